#!/usr/bin/env python3
"""In-line oscillating cylinder at Re = 100, KC = 5 (examples/validation/oscillating_cylinder.toml)
against Dütsch, Durst, Becker & Lienhart 1998 (J. Fluid Mech. 360:249).

The cylinder (D = 1, U_m = 1, ρ0 = 1, T = 5) moves as x_c = -A sin(2πt/T) in a closed tank of
water at rest, its motion ramped up over the first half period. Over the fourth cycle
(t = 15-20 s, the periodic state) the script samples the in-line force F_x/(ρ0 U_m² D) every
0.01 T, and at phases 180°, 210° and 330° the velocity on the vertical lines x/D = -0.6, 0,
0.6, 1.2 where the experiment measured it (docs/validation/data/oscillating_cylinder_*.csv,
grade C digitisations). It reports
- the force's RMS difference from the eleven digitised points, relative to their peak 1.61;
- the velocity's RMS difference over all measured points, relative to U_m, per component;
- C_D and C_I of Morison's equation F = -½ρD C_D u|u| - ρ(πD²/4) C_I du/dt fitted to the
  sampled cycle (the experiment's points give 2.25 and 1.43).

Each run writes docs/validation/oscillating_cylinder_n<D/Δx>.json; the figure of all runs
written so far is oscillating_cylinder.png and the table oscillating_cylinder_table.md.

Usage: python3 examples/validation/oscillating_cylinder.py [--n 10 20] [--summary]
"""
import argparse
import json
import math
import pathlib
import tomllib

import numpy as np

import deltasph as ds
from records import write_table
from sampling import body_force

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
DATA = OUT / "data"
D, U, T = 1.0, 1.0, 5.0
CYCLE = 3  # the fourth cycle: t = 15-20 s
PHASES = (180, 210, 330)
FORCE_PEAK = 1.6063


def reference(name):
    """Rows of a reference CSV, its `#` lines and its header skipped."""
    lines = [line for line in (DATA / name).read_text().splitlines() if not line.startswith("#")]
    return np.loadtxt(lines[1:], delimiter=",", ndmin=2)


def morison(t, force):
    """C_D, C_I of Morison's equation fitted by least squares to `force` at times `t`,
    the cylinder's velocity -U cos ωt."""
    phase = 2 * math.pi * t / T
    c = np.cos(phase)
    basis = np.c_[c * np.abs(c), -np.sin(phase) * math.pi**2 * D / (2 * U * T)]
    (half_cd, ci), *_ = np.linalg.lstsq(basis, force, rcond=None)
    return 2 * half_cd, ci


def probe(sim, rows, comp):
    """The fluid's velocity component `comp` at the points (x/D, y/D) of reference `rows`."""
    points = np.c_[rows[:, 1], rows[:, 2]] * D
    return sim.probe_velocity(points)[:, "uv".index(comp)] / U


def run(n):
    config = tomllib.loads((HERE / "oscillating_cylinder.toml").read_text())
    config["particles"]["spacing"] = D / n
    sim = ds.Simulation(config)
    sim.run(CYCLE * T)
    velocity = {"u": reference("oscillating_cylinder_dutsch1998_u.csv"),
                "v": reference("oscillating_cylinder_dutsch1998_v.csv")}
    grid = [CYCLE * T + k * T / 100 for k in range(101)]
    at_phase = {(CYCLE + phase / 360) * T: phase for phase in PHASES}
    t, force, sampled = [], [], {}
    for time in sorted(set(grid) | set(at_phase)):
        sim.run(time)
        if time in at_phase:
            sampled[at_phase[time]] = {
                comp: probe(sim, rows[rows[:, 0] == at_phase[time]], comp)
                for comp, rows in velocity.items()}
        if time in grid:
            t.append(time)
            force.append(body_force(sim, "cylinder")[0])
    t, force = np.array(t), np.array(force)
    ref = reference("oscillating_cylinder_dutsch1998_force.csv")
    at = np.interp(CYCLE * T + ref[:, 0] * T, t, force)
    errors = {}
    for comp, rows in velocity.items():
        ours = np.concatenate([sampled[p][comp] for p in PHASES])
        theirs = np.concatenate([rows[rows[:, 0] == p, 3] for p in PHASES])
        keep = np.isfinite(ours)
        errors[comp] = float(np.sqrt(np.mean((ours[keep] - theirs[keep]) ** 2)))
    cd, ci = morison(t[:-1], force[:-1])
    result = {
        "n": n, "particles": sim.n_particles,
        "force_rms": float(np.sqrt(np.mean((at - ref[:, 1]) ** 2)) / FORCE_PEAK),
        "u_rms": errors["u"], "v_rms": errors["v"], "cd": float(cd), "ci": float(ci),
        "t": (t / T - CYCLE).tolist(), "force": force.tolist(),
        "profiles": {str(p): {c: v.tolist() for c, v in s.items()} for p, s in sampled.items()},
    }
    (OUT / f"oscillating_cylinder_n{n}.json").write_text(json.dumps(result))
    print(f"D/Δx = {n}: force RMS {result['force_rms']:.3f} of the peak, u {errors['u']:.3f}, "
          f"v {errors['v']:.3f} of U_m; C_D {cd:.2f}, C_I {ci:.2f}")
    return result


def summary():
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    runs = sorted((json.loads(p.read_text()) for p in OUT.glob("oscillating_cylinder_n*.json")),
                  key=lambda r: r["n"])
    write_table(OUT / "oscillating_cylinder_table.md",
                ["D/Δx", "particles", "force RMS / peak", "u RMS / U_m", "v RMS / U_m", "C_D", "C_I"],
                [[str(r["n"]), str(r["particles"]), f"{r['force_rms']:.3f}", f"{r['u_rms']:.3f}",
                  f"{r['v_rms']:.3f}", f"{r['cd']:.2f}", f"{r['ci']:.2f}"] for r in runs])
    fig = plt.figure(figsize=(11, 10))
    grid = fig.add_gridspec(4, 2, height_ratios=[1.1, 1, 1, 1])
    ax = fig.add_subplot(grid[0, :])
    ref = reference("oscillating_cylinder_dutsch1998_force.csv")
    for r in runs:
        ax.plot(r["t"], r["force"], lw=1, label=f"deltasph D/Δx = {r['n']}")
    ax.plot(ref[:, 0], ref[:, 1], "ko", mfc="none", label="Dütsch et al. 1998")
    ax.set_xlabel("t/T (fourth cycle)")
    ax.set_ylabel("F_x / (ρ U_m² D)")
    ax.legend(fontsize=8, ncol=3)
    ax.grid(alpha=0.3)
    finest = runs[-1]
    for row, phase in enumerate(PHASES):
        for col, comp in enumerate("uv"):
            ax = fig.add_subplot(grid[row + 1, col])
            rows = reference(f"oscillating_cylinder_dutsch1998_{comp}.csv")
            rows = rows[rows[:, 0] == phase]
            ours = np.array(finest["profiles"][str(phase)][comp])
            for i, x in enumerate((-0.6, 0.0, 0.6, 1.2)):
                on = rows[:, 1] == x
                ax.plot(rows[on, 3], rows[on, 2], "o", color=f"C{i}", mfc="none", ms=4)
                y, line = rows[on, 2], ours[on]
                cut = np.flatnonzero(np.diff(y) > 0.25) + 1  # across the cylinder: no line
                ax.plot(np.insert(line, cut, np.nan), np.insert(y, cut, np.nan), "-",
                        color=f"C{i}", label=f"x/D = {x}")
            ax.set_xlabel(f"{comp}/U_m")
            ax.set_ylabel("y/D")
            ax.set_title(f"φ = {phase}°, D/Δx = {finest['n']} (lines), experiment (circles)", fontsize=9)
            ax.grid(alpha=0.3)
            if row == 0 and col == 1:
                ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(OUT / "oscillating_cylinder.png", dpi=110)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, nargs="*", default=[10, 20])
    parser.add_argument("--summary", action="store_true", help="only rebuild the table and figure")
    args = parser.parse_args()
    if not args.summary:
        for n in args.n:
            run(n)
    summary()


if __name__ == "__main__":
    main()
