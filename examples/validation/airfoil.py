#!/usr/bin/env python3
"""NACA0010 at 30° incidence, Re = 10 000 (examples/validation/airfoil.toml), with δ+-SPH,
with and without tensile instability control (TIC, Sun et al. 2018): the talk's finding
that without TIC the particles tear apart in the negative-pressure region behind the
profile, as numbers.

The outline is the NACA four-digit thickness law with a closed trailing edge,
y_t = 5t(0.2969√x − 0.1260x − 0.3516x² + 0.2843x³ − 0.1036x⁴), t = 0.10, at 120 points
per side on a cosine spacing, turned nose up by α about the mid-chord; the script writes
it to examples/validation/naca0010_a30.txt (a vertex list) before it runs.

At the samples t = 4, 5, ..., 10 c/U, in the negative-pressure region behind the profile
(points within 1.5c of the mid-chord, downstream of the leading edge, more than 2Δx from
the wall, whose nearest particle has p < 0), the script measures:
- the nearest-neighbour spread: the standard deviation of the particles' nearest-
  neighbour distances over their mean (0 on a lattice);
- the largest empty disc: the largest distance from a point of the region (a Δx/4 grid)
  to its nearest particle, in Δx (≈ 0.7 on a lattice);
- the empty cells: the fraction of 2Δx cells of the region holding no particle (0 on a
  lattice);
and over t = 4-10 c/U the mean lift and drag coefficients (pressure and viscous loads on
the profile, ½ρ0U²c). Writes docs/validation/airfoil.csv, airfoil_table.md,
airfoil_forces.png and airfoil_fields.png.

Usage: python3 examples/validation/airfoil.py [--n 50] [--end 10]
"""
import argparse
import math
import pathlib
import tomllib

import matplotlib
import numpy as np
from scipy.spatial import cKDTree

import deltasph as ds
from records import plot_forces, write_csv, write_table
from sampling import Sampler, body_force

matplotlib.use("Agg")

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
OUTLINE = HERE / "naca0010_a30.txt"
ALPHA = math.radians(30.0)
THICKNESS = 0.10
Q = 0.5  # ½ρ0U²c
SAMPLES = [4.0, 5.0, 6.0, 7.0, 8.0, 9.0, 10.0]
FROM = 4.0


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
    sim = ds.Simulation(config(n, end, tic))
    forces, measures = [], []
    sampler = Sampler(sim, end, 0.02)
    for t in sampler:
        force = body_force(sim, "airfoil")
        forces.append((sim.time, force[0] / Q, force[1] / Q))
        if any(abs(t - s) < 1e-9 for s in SAMPLES):
            measures.append(disorder(sim))
            print(f"  TIC {tic}: t = {sim.time:.1f}, C_D {force[0] / Q:.3f}, "
                  f"C_L {force[1] / Q:.3f}, disorder {measures[-1]}, {sampler.wall:.0f} s",
                  flush=True)
    forces = np.array(forces)
    late = forces[:, 0] >= FROM - 1e-9
    m = np.nanmean(np.array(measures, dtype=float), axis=0)
    return {
        "tic": tic, "n": n, "particles": sim.n_particles, "steps": sim.n_steps,
        "wall_s": sampler.wall, "particle_steps_per_s": sampler.rate,
        "cd": float(forces[late, 1].mean()), "cl": float(forces[late, 2].mean()),
        "spread": m[0], "empty_disc": m[1], "empty_cells": m[2], "region": m[3],
        "forces": forces, "sim": sim,
    }


COLUMNS = ["tic", "n", "particles", "cd", "cl", "spread", "empty_disc", "empty_cells",
           "region", "steps", "wall_s", "particle_steps_per_s"]


def write(results):
    write_csv(OUT / "airfoil.csv", COLUMNS, results)
    header = ["TIC", "c/Δx", "particles", "C_D", "C_L", "nearest-neighbour spread",
              "largest empty disc [Δx]", "empty 2Δx cells", "region particles", "steps",
              "wall [s]", "particle-steps/s"]
    rows = [["on" if r["tic"] else "off", f"{r['n']}", f"{r['particles']}", f"{r['cd']:.3f}",
             f"{r['cl']:.3f}", f"{r['spread']:.3f}", f"{r['empty_disc']:.2f}",
             f"{r['empty_cells']:.3f}", f"{r['region']:.0f}", f"{r['steps']}",
             f"{r['wall_s']:.0f}", f"{r['particle_steps_per_s']:.3g}"] for r in results]
    write_table(OUT / "airfoil_table.md", header, rows)


def plot(results):
    import matplotlib.pyplot as plt
    from cylinder import vorticity

    curves = [(f"TIC {'on' if r['tic'] else 'off'}", *r["forces"].T) for r in results]
    plot_forces(OUT / "airfoil_forces.png", curves,
                "NACA0010, α = 30°, Re = 10⁴: drag and lift (pressure + viscous)", "t U/c")

    fig, axes = plt.subplots(len(results), 2, figsize=(12, 3.4 * len(results)),
                             squeeze=False)
    for row, r in zip(axes, results):
        sim = r["sim"]
        fluid = sim.kind == ds.FLUID
        x = sim.positions[fluid]
        near = (x[:, 0] > -1) & (x[:, 0] < 3) & (np.abs(x[:, 1]) < 1.5)
        fields = [(sim.pressure[fluid] / Q, "p / ½ρ₀U²", "viridis", (-2.0, 1.0)),
                  (vorticity(sim)[fluid], "ω c/U", "RdBu_r", (-20.0, 20.0))]
        for ax, (value, label, cmap, (lo, hi)) in zip(row, fields):
            sc = ax.scatter(x[near, 0], x[near, 1], c=value[near], s=0.3, cmap=cmap,
                            vmin=lo, vmax=hi)
            outline = naca_outline()
            ax.fill(outline[:, 0], outline[:, 1], color="0.3")
            ax.set_aspect("equal")
            ax.set_title(f"TIC {'on' if r['tic'] else 'off'}, c/Δx = {r['n']}, "
                         f"t U/c = {sim.time:.0f}")
            fig.colorbar(sc, ax=ax, label=label)
    fig.tight_layout()
    fig.savefig(OUT / "airfoil_fields.png", dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--n", type=int, default=50, help="c/Δx")
    parser.add_argument("--end", type=float, default=10.0, help="end time [c/U]")
    args = parser.parse_args()
    write_outline()
    OUT.mkdir(parents=True, exist_ok=True)
    results = [run(args.n, args.end, tic) for tic in (False, True)]
    write(results)
    plot(results)


if __name__ == "__main__":
    main()
