"""Plots, tables and the README of the validation report (written by run_all.py)."""

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cases import buchner  # noqa: E402
from reading import INTRO, READING  # noqa: E402

BUDGET_S = 60.0


def variant(row):
    return f"{row['diffusion']} {row['integrator']}"


def by_variant(rows):
    groups = {}
    for r in rows:
        groups.setdefault(variant(r), []).append(r)
    return groups


def usable(runs):
    return [r for r in runs if r["stable"] and np.isfinite(r["error"]) and r["error"] > 0]


def order(runs):
    """Least-squares slope of log(error) against log(Δx): the observed order."""
    ok = usable(runs)
    if len(ok) < 2:
        return math.nan
    x = np.log([r["spacing"] for r in ok])
    y = np.log([r["error"] for r in ok])
    return float(np.polyfit(x, y, 1)[0])


def plot_case(out, case, rows):
    fig, (ax_t, ax_dx) = plt.subplots(1, 2, figsize=(11, 4.2), constrained_layout=True)
    for label, runs in by_variant(rows).items():
        ok = usable(runs)
        if not ok:
            continue
        line, = ax_t.loglog([r["wall_s"] for r in ok], [r["error"] for r in ok], "o-",
                            label=label)
        p = order(runs)
        ax_dx.loglog([r["spacing"] for r in ok], [r["error"] for r in ok], "o-",
                     color=line.get_color(),
                     label=f"{label} (order {p:.2f})" if np.isfinite(p) else label)
    ax_t.set_xlabel("wall time of the run [s] (2 cores)")
    ax_dx.set_xlabel("particle spacing Δx [m]")
    for ax in (ax_t, ax_dx):
        ax.set_ylabel(case.error_label)
        ax.grid(True, which="both", alpha=0.3)
    ax_t.legend(fontsize=8)
    ax_dx.legend(fontsize=8)
    fig.suptitle(case.title)
    fig.savefig(out / f"{case.name}.png", dpi=110)
    plt.close(fig)


def smooth(t, p, width=0.1):
    """Moving average over `width` in t* (the experimental sensor and noise scale)."""
    step = t[1] - t[0]
    k = max(1, int(round(width / step)))
    return np.convolve(p, np.ones(k) / k, mode="same")


def dam_break_against_fine(rows, signals):
    """RMS difference of smoothed P1 over t* in [2.3, 7] against the finest δ-SPH RK4 run."""
    fine_key = max((k for k in signals if k[1] == "δ-SPH" and k[2] == "RK4"),
                   key=lambda k: k[3], default=None)
    if fine_key is None:
        return None
    t, ref = signals[fine_key]
    ref = smooth(t, ref)
    window = (t >= 2.3) & (t <= 7.0)
    for r in rows:
        key = (r["case"], r["diffusion"], r["integrator"], r["resolution"])
        if key in signals and key != fine_key:
            diff = smooth(t, signals[key][1]) - ref
            r["details"] += f"; vs_fine={np.sqrt(np.mean(diff[window] ** 2)):.4g}"
    return fine_key


def plot_p1(out, signals):
    fig, ax = plt.subplots(figsize=(10, 4.2), constrained_layout=True)
    t_exp, p_exp = buchner()
    ax.plot(t_exp, p_exp, "k.", ms=3, label="Buchner (2002), digitised")
    finest = {}
    for key in signals:
        label = f"{key[1]} {key[2]}"
        if label not in finest or key[3] > finest[label][3]:
            finest[label] = key
    for label, key in finest.items():
        t, p = signals[key]
        ax.plot(t, smooth(t, p), lw=1, label=f"{label}, H/Δx = {key[3]:g} (0.1 t* average)")
    ax.set_xlim(2.0, 7.0)
    ax.set_xlabel("t·sqrt(g/H)")
    ax.set_ylabel("p / ρ0 g H at P1")
    ax.legend(fontsize=8)
    fig.savefig(out / "dam_break_p1.png", dpi=110)
    plt.close(fig)


def budget_winner(rows):
    """Per variant the run with the largest wall time within the budget; the lowest error."""
    best = {}
    for label, runs in by_variant(rows).items():
        fits = [r for r in usable(runs) if r["wall_s"] <= BUDGET_S]
        if fits:
            best[label] = max(fits, key=lambda r: r["wall_s"])
    if not best:
        return None
    return min(best.values(), key=lambda r: r["error"])


def table(rows):
    lines = ["| variant | resolution | fluid particles | steps | wall [s] | particle-steps/s "
             "| error | details |", "|---|---|---|---|---|---|---|---|"]
    for r in rows:
        err = f"{r['error']:.3e}" if r["stable"] else "blew up"
        lines.append(f"| {variant(r)} | {r['resolution']:g} | {r['particles']} | {r['steps']} "
                     f"| {r['wall_s']:.2f} | {r['particle_steps_per_s']:.3g} | {err} "
                     f"| {r['details']} |")
    return "\n".join(lines)


def summary(rows):
    finest = max(r["resolution"] for r in rows)
    at_finest = usable([r for r in rows if r["resolution"] == finest])
    parts = []
    if at_finest:
        best = min(at_finest, key=lambda r: r["error"])
        parts.append(f"best error at the finest resolution ({finest:g}): "
                     f"**{best['error']:.3e}** ({variant(best)})")
    orders = [f"{label} {order(runs):.2f}" for label, runs in by_variant(rows).items()
              if np.isfinite(order(runs))]
    if orders:
        parts.append("observed order in Δx: " + ", ".join(orders))
    winner = budget_winner(rows)
    if winner:
        parts.append(f"lowest error within {BUDGET_S:.0f} s: **{variant(winner)}** at "
                     f"{winner['resolution']:g} ({winner['error']:.3e} in {winner['wall_s']:.1f} s)")
    unstable = [f"{variant(r)} at {r['resolution']:g}" for r in rows if not r["stable"]]
    if unstable:
        parts.append("blew up: " + ", ".join(unstable))
    return "\n".join(f"- {p}" for p in parts)


def write(out, mode, cases, rows, signals, total):
    text = [INTRO.format(mode=mode, total=total, runs=len(rows))]
    for case in cases:
        case_rows = [r for r in rows if r["case"] == case.name]
        if case.name == "dam_break":
            fine = dam_break_against_fine(case_rows, signals)
            plot_p1(out, signals)
        plot_case(out, case, case_rows)
        text.append(f"## {case.title}\n")
        text.append(READING.get(case.name, "").strip() + "\n")
        text.append(f"![{case.name}]({case.name}.png)\n")
        if case.name == "dam_break":
            text.append("![P1 signals](dam_break_p1.png)\n")
            if fine:
                text.append(f"`vs_fine`: RMS difference of the 0.1 t*-averaged P1 signal over "
                            f"t* ∈ [2.3, 7] from the {fine[1]} {fine[2]} run at H/Δx = "
                            f"{fine[3]:g}, in ρ0gH.\n")
        text.append(summary(case_rows) + "\n")
        text.append(table(case_rows) + "\n")
    (out / "README.md").write_text("\n".join(text))
