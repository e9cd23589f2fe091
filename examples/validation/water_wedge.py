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
    args = parser.parse_args()
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


def write_report(rows, convergence, resolutions):
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "water_wedge.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    q = 0.5 * RHO0 * U**2
    lines = [
        "# Water-wedge impact: wall pressure at the apex",
        "",
        "Command: `python3 examples/validation/water_wedge.py` (2 threads). Case: "
        "`examples/validation/water_wedge.toml` (H = 0.5 m, flanks at 45°, U = 1 m/s, "
        "no gravity, RK4, Wendland C2 h/Δx = 2, α = 0.02).",
        "",
        "| scheme | H/Δx | c0 [m/s] | particles | steps | wall [s] | first peak / ρ0c0U | "
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
    (OUT / "water_wedge.md").write_text("\n".join(lines) + "\n")


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
