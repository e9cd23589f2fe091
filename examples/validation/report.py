"""Plots, tables and the README of the validation report (written by run_all.py)."""

import math

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cases import MARRONE_RUNS, buchner, marrone, smooth  # noqa: E402
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


def plot_p1(out, signals):
    fig, ax = plt.subplots(figsize=(10, 4.2), constrained_layout=True)
    t_exp, p_exp = buchner()
    ax.plot(t_exp, p_exp, "k.", ms=3, label="Buchner (2002), digitised")
    ref = marrone()
    ax.plot(ref[:, 0], ref[:, MARRONE_RUNS[320]], "k-", lw=1.6,
            label="Marrone et al. (2011), δ-SPH H/Δx = 320, y = 0.2H")
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
    ax.set_ylabel("p / ρ0 g H at P1 (y = 0.2H)")
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


def best_at_finest(rows):
    """The finest resolution run and the run with the lowest error there (or None)."""
    finest = max(r["resolution"] for r in rows)
    at_finest = usable([r for r in rows if r["resolution"] == finest])
    return finest, min(at_finest, key=lambda r: r["error"], default=None)


def summary(rows):
    finest, best = best_at_finest(rows)
    parts = []
    if best:
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


def closing_table(cases, rows):
    """One line per case: best error at the finest resolution, that variant's observed
    order, and the variant with the lowest error within the budget."""
    lines = ["| case | finest resolution | best error there | variant | its order in Δx "
             f"| lowest error within {BUDGET_S:.0f} s |", "|---|---|---|---|---|---|"]
    for case in cases:
        case_rows = [r for r in rows if r["case"] == case.name]
        if not case_rows:
            continue
        finest, best = best_at_finest(case_rows)
        winner = budget_winner(case_rows)
        cells = [f"[{case.title}](#{anchor(case.title)})", f"{finest:g}"]
        if best:
            p = order(by_variant(case_rows)[variant(best)])
            cells += [f"{best['error']:.3g}", variant(best), f"{p:.2f}"]
        else:
            cells += ["—", "—", "—"]
        cells.append(f"{variant(winner)} at {winner['resolution']:g}: {winner['error']:.3g} "
                     f"in {winner['wall_s']:.0f} s" if winner else "—")
        lines.append("| " + " | ".join(cells) + " |")
    return "\n".join(lines)


def anchor(title):
    """GitHub's heading anchor: lower case, punctuation dropped, spaces to hyphens."""
    kept = "".join(c for c in title.lower() if c.isalnum() or c in " -")
    return kept.replace(" ", "-")


def skipped_note(skipped):
    if not skipped:
        return ""
    items = ", ".join(f"{d} {i} at {n:g} ({t:.0f} s predicted)" for _, d, i, n, t, _ in skipped)
    return (f"Not run, over the per-run cap of {skipped[0][5]:g} s (predicted from the same "
            f"variant at the previous resolution): {items}.\n")


def write(out, mode, cases, rows, signals, skipped, total):
    text = [INTRO.format(mode=mode, total_min=total / 60, runs=len(rows)),
            "## Summary\n", closing_table(cases, rows) + "\n"]
    for case in cases:
        case_rows = [r for r in rows if r["case"] == case.name]
        if case.name == "dam_break":
            plot_p1(out, signals)
        plot_case(out, case, case_rows)
        text.append(f"## {case.title}\n")
        text.append(READING.get(case.name, "").strip() + "\n")
        text.append(f"![{case.name}]({case.name}.png)\n")
        if case.name == "dam_break":
            text.append("![P1 signals](dam_break_p1.png)\n")
        text.append(summary(case_rows) + "\n")
        text.append(skipped_note([s for s in skipped if s[0] == case.name]))
        text.append(table(case_rows) + "\n")
    (out / "README.md").write_text("\n".join(text))
