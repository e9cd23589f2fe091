#!/usr/bin/env python3
"""NACA0010 at 30° incidence, Re = 10 000 (examples/validation/airfoil.toml), with δ+-SPH,
with and without tensile instability control (TIC, Sun et al. 2018): the talk's finding
that without TIC the particles tear apart in the negative-pressure region behind the
profile, as numbers.

The outline is the NACA four-digit thickness law with a closed trailing edge,
y_t = 5t(0.2969√x − 0.1260x − 0.3516x² + 0.2843x³ − 0.1036x⁴), t = 0.10, at 120 points
per side on a cosine spacing, turned nose up by α about the mid-chord; the script writes
it to examples/validation/naca0010_a30.txt (a vertex list) before it runs.

At the samples t = 2, 3, ..., 6 c/U, in the negative-pressure region behind the profile
(points within 1.5c of the mid-chord, downstream of the leading edge, more than 2Δx from
the wall, whose nearest particle has p < 0), the script measures:
- the nearest-neighbour spread: the standard deviation of the particles' nearest-
  neighbour distances over their mean (0 on a lattice);
- the largest empty disc: the largest distance from a point of the region (a Δx/4 grid)
  to its nearest particle, in Δx (≈ 0.7 on a lattice);
- the empty cells: the fraction of 2Δx cells of the region holding no particle (0 on a
  lattice);
and over t = 2-6 c/U the mean lift and drag coefficients (pressure and viscous loads on
the profile, ½ρ0U²c). Writes docs/validation/airfoil.csv, airfoil_table.md,
airfoil_forces.png and airfoil_fields.png.

Each run writes its record (docs/validation/airfoil_tic_<off|on>.json) and its last
fields (.npz); a run that goes unstable stops there and its record says when and where.
The two runs can go to separate processes (`--tic off`, `--tic on`, RAYON_NUM_THREADS=1
each); `--summary` then builds the table and the plots.

Usage: python3 examples/validation/airfoil.py [--n 50] [--end 6] [--tic off on] [--summary]
"""
import argparse
import json
import math
import pathlib
import tomllib

import matplotlib
import numpy as np
from scipy.spatial import cKDTree

import deltasph as ds
from records import plot_forces, write_csv, write_table
from cylinder import vorticity
from sampling import Sampler, body_force

matplotlib.use("Agg")

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
OUTLINE = HERE / "naca0010_a30.txt"
ALPHA = math.radians(30.0)
THICKNESS = 0.10
Q = 0.5  # ½ρ0U²c
U = 1.0
RAMP = 1.0  # the start's ramp time [c/U]
SAMPLES = [2.0, 3.0, 4.0, 5.0, 6.0]
FROM = 2.0


def naca_outline(points=120):
    """The turned NACA00tt outline, counter-clockwise from the trailing edge."""
    beta = np.linspace(0.0, math.pi, points)
    x = 0.5 * (1 - np.cos(beta))
    y = 5 * THICKNESS * (0.2969 * np.sqrt(x) - 0.1260 * x - 0.3516 * x**2
                         + 0.2843 * x**3 - 0.1036 * x**4)
    # upper side from the trailing edge to the leading edge, then the lower side back
    xs = np.concatenate([x[::-1], x[1:-1]])
    ys = np.concatenate([y[::-1], -y[1:-1]])
    xc = xs - 0.5
    turned_x = xc * math.cos(ALPHA) + ys * math.sin(ALPHA)
    turned_y = -xc * math.sin(ALPHA) + ys * math.cos(ALPHA)
    return np.column_stack([turned_x, turned_y])


def write_outline():
    lines = [f"# NACA0010, closed trailing edge, chord 1, {math.degrees(ALPHA):.0f}° nose up "
             "about the mid-chord (examples/validation/airfoil.py)"]
    lines += [f"{x:.8f} {y:.8f}" for x, y in naca_outline()]
    OUTLINE.write_text("\n".join(lines) + "\n")


def config(n, end, tic):
    with open(HERE / "airfoil.toml", "rb") as f:
        cfg = tomllib.load(f)
    cfg["particles"]["spacing"] = 1.0 / n
    cfg["shape"][0]["file"] = str(OUTLINE)
    cfg["scheme"]["tensile_control"] = tic
    cfg["time"]["end"] = end
    cfg["time"]["output_interval"] = 0.0
    return cfg


def drive(sim):
    """The stream, driven by a uniform body force: after every step, every fluid particle
    gets the same velocity increment that brings the fluid's mean velocity to
    U min(t/RAMP, 1). This is the frame of a profile accelerated smoothly from rest
    through still water and then towed at U; in the doubly periodic domain the mean
    pressure is held by the fluid's mass, as in a closed tank, so a void cannot open
    at no cost. Returns the after-step hook for `Sampler`."""
    def accelerate(before):
        u = sim.velocities
        fluid = sim.kind == ds.FLUID
        target = U * min(sim.time / RAMP, 1.0)
        u[fluid, 0] += target - u[fluid, 0].mean()
        sim.set_velocities(u)
    return accelerate


def disorder(sim):
    """(nearest-neighbour spread, largest empty disc [Δx], empty 2Δx cells) in the
    negative-pressure region behind the profile."""
    dx = sim.spacing
    fluid = sim.kind == ds.FLUID
    x, p = sim.positions[fluid], sim.pressure[fluid]
    walls = cKDTree(sim.positions[sim.kind == ds.WALL])
    tree = cKDTree(x)
    leading = naca_outline()[:, 0].min()

    def in_region(points):
        dist, nearest = tree.query(points)
        behind = (np.hypot(points[:, 0], points[:, 1]) < 1.5) & (points[:, 0] > leading)
        clear = walls.query(points)[0] > 2 * dx
        return behind & clear & (p[nearest] < 0), dist

    mine, _ = in_region(x)
    if mine.sum() < 10:
        return float("nan"), float("nan"), float("nan"), int(mine.sum())
    nn = tree.query(x[mine], k=2)[0][:, 1]
    g = np.arange(-1.5, 1.5, dx / 4)
    grid = np.array(np.meshgrid(g, g)).reshape(2, -1).T
    inside, dist = in_region(grid)
    cells = np.arange(-1.5, 1.5, 2 * dx) + dx
    centres = np.array(np.meshgrid(cells, cells)).reshape(2, -1).T
    held, _ = in_region(centres)
    counts = tree.query_ball_point(centres[held], r=dx * math.sqrt(2), p=np.inf,
                                   return_length=True)
    return (float(nn.std() / nn.mean()), float(dist[inside].max() / dx),
            float(np.mean(counts == 0)), int(mine.sum()))


def run(n, end, tic):
    """One run; a run that goes unstable ends there, and its record says when and where."""
    sim = ds.Simulation(config(n, end, tic))
    forces, measures, at, stopped = [], [], [], ""
    sampler = Sampler(sim, end, 0.02, after_step=drive(sim))
    try:
        for t in sampler:
            force = body_force(sim, "airfoil")
            forces.append((sim.time, force[0] / Q, force[1] / Q))
            if any(abs(t - s) < 1e-9 for s in SAMPLES):
                measures.append(disorder(sim))
                at.append(sim.time)
                print(f"  TIC {tic}: t = {sim.time:.1f}, C_D {force[0] / Q:.3f}, "
                      f"C_L {force[1] / Q:.3f}, disorder {measures[-1]}, "
                      f"{sampler.wall:.0f} s", flush=True)
    except ds.errors.InstabilityError as e:
        stopped = str(e)
        print(f"  TIC {tic}: {stopped}", flush=True)
    forces = np.array(forces)
    late = forces[:, 0] >= FROM - 1e-9
    m = np.nanmean(np.array(measures, dtype=float), axis=0)
    fluid = (sim.kind == ds.FLUID) & np.isfinite(sim.positions[:, 0])
    np.savez_compressed(OUT / f"airfoil_tic_{label(tic)}.npz", forces=forces,
                        x=sim.positions[fluid], p=sim.pressure[fluid],
                        omega=vorticity(sim)[fluid], time=sim.time)
    record = {
        "tic": tic, "n": n, "particles": sim.n_particles, "steps": sim.n_steps,
        "wall_s": sampler.wall, "particle_steps_per_s": sampler.particle_steps / max(sampler.wall, 1e-9),
        "cd": float(forces[late, 1].mean()), "cl": float(forces[late, 2].mean()),
        "spread": m[0], "empty_disc": m[1], "empty_cells": m[2], "region": m[3],
        "samples": len(measures), "end": sim.time, "stopped": stopped,
        "disorder_by_time": [[t, *m] for t, m in zip(at, measures)],
    }
    (OUT / f"airfoil_tic_{label(tic)}.json").write_text(json.dumps(record, indent=1))


def label(tic):
    return "on" if tic else "off"


COLUMNS = ["tic", "n", "particles", "cd", "cl", "cd_common", "cl_common", "common_end",
           "spread", "empty_disc", "empty_cells",
           "region", "samples", "end", "steps", "wall_s", "particle_steps_per_s", "stopped"]


def write(results):
    write_csv(OUT / "airfoil.csv", COLUMNS, results)
    header = ["TIC", "c/Δx", "particles", "C_D", "C_L", "C_D, C_L over the common window",
              "nearest-neighbour spread",
              "largest empty disc [Δx]", "empty 2Δx cells", "region particles", "samples",
              "reached t U/c", "steps", "wall [s]", "particle-steps/s"]
    rows = [[label(r["tic"]), f"{r['n']}", f"{r['particles']}", f"{r['cd']:.3f}",
             f"{r['cl']:.3f}",
             f"{r['cd_common']:.3f}, {r['cl_common']:.3f} (t = {FROM:.0f}-{r['common_end']:.2f})",
             f"{r['spread']:.3f}", f"{r['empty_disc']:.2f}",
             f"{r['empty_cells']:.3f}", f"{r['region']:.0f}", f"{r['samples']}",
             f"{r['end']:.2f}" + (" (unstable)" if r["stopped"] else ""), f"{r['steps']}",
             f"{r['wall_s']:.0f}", f"{r['particle_steps_per_s']:.3g}"] for r in results]
    write_table(OUT / "airfoil_table.md", header, rows)


def plot(results):
    import matplotlib.pyplot as plt

    fields_of = [np.load(OUT / f"airfoil_tic_{label(r['tic'])}.npz") for r in results]
    curves = [(f"TIC {label(r['tic'])}", *f["forces"].T) for r, f in zip(results, fields_of)]
    plot_forces(OUT / "airfoil_forces.png", curves,
                "NACA0010, α = 30°, Re = 10⁴: drag and lift (pressure + viscous)", "t U/c")

    fig, axes = plt.subplots(len(results), 2, figsize=(12, 3.4 * len(results)),
                             squeeze=False)
    for row, r, f in zip(axes, results, fields_of):
        x = f["x"]
        near = (x[:, 0] > -1) & (x[:, 0] < 3) & (np.abs(x[:, 1]) < 1.5)
        fields = [(f["p"] / Q, "p / ½ρ₀U²", "viridis", (-2.0, 1.0)),
                  (f["omega"], "ω c/U", "RdBu_r", (-20.0, 20.0))]
        for ax, (value, name, cmap, (lo, hi)) in zip(row, fields):
            sc = ax.scatter(x[near, 0], x[near, 1], c=value[near], s=0.3, cmap=cmap,
                            vmin=lo, vmax=hi)
            outline = naca_outline()
            ax.fill(outline[:, 0], outline[:, 1], color="0.3")
            ax.set_aspect("equal")
            ax.set_title(f"TIC {label(r['tic'])}, c/Δx = {r['n']}, "
                         f"t U/c = {float(f['time']):.2f}")
            fig.colorbar(sc, ax=ax, label=name)
    fig.tight_layout()
    fig.savefig(OUT / "airfoil_fields.png", dpi=120)
    plt.close(fig)


def summary():
    """The table and plots from the runs' records; the force means also over the window
    both runs reached (from FROM to the earlier end)."""
    results = [json.loads((OUT / f"airfoil_tic_{label(tic)}.json").read_text())
               for tic in (False, True)]
    common = min(r["end"] for r in results)
    for r in results:
        forces = np.load(OUT / f"airfoil_tic_{label(r['tic'])}.npz")["forces"]
        window = (forces[:, 0] >= FROM - 1e-9) & (forces[:, 0] <= common + 1e-9)
        r["cd_common"], r["cl_common"] = forces[window, 1:].mean(axis=0)
        r["common_end"] = common
    write(results)
    plot(results)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=50, help="c/Δx")
    parser.add_argument("--end", type=float, default=6.0, help="end time [c/U]")
    parser.add_argument("--tic", choices=["off", "on"], nargs="*", default=["off", "on"],
                        help="the runs to make (each can go to its own process)")
    parser.add_argument("--summary", action="store_true",
                        help="only rebuild the table and plots from the runs' records")
    args = parser.parse_args()
    write_outline()
    OUT.mkdir(parents=True, exist_ok=True)
    for tic in [] if args.summary else args.tic:
        run(args.n, args.end, tic == "on")
    missing = [t for t in ("off", "on") if not (OUT / f"airfoil_tic_{t}.json").exists()]
    if missing:
        print(f"the table waits for the run with TIC {', '.join(missing)} (then --summary)")
    else:
        summary()


if __name__ == "__main__":
    main()
