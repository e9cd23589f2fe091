#!/usr/bin/env python3
"""Plane jet impinging normally on a flat plate (examples/validation/impinging_jet.toml),
against free-streamline theory, at b/Δx = 10, 20, 40 and 80 with δ-SPH and with standard
SPH (no density diffusion), RK4, artificial viscosity α = 0.02.

The jet (width b = 0.1 m, U = 1 m/s, c0 = 10U, no gravity) enters through an inlet
buffer whose inner face stands 2b above the plate; the two wall jets leave the domain
at x = ±3b. Over t = 5-10 b/U (steady) the script averages:
- the stagnation pressure p(0) against ½ρ0U²;
- the plate's load (the fluid's force on the wall body) against ρ0U²b;
- the mass and x-momentum fluxes of each outgoing jet through x = ±2b against ρ0Ub/2
  and ρ0U²b/2 (hat-weighted sums over particles, exact for a lattice);
- the plate pressure p(x) at 51 probes on the plate, |x| <= 2.5b, against the free-
  streamline solution p/(½ρ0U²) = 1 - s², x/b = (2/π)(artanh s + arctan s), s = q/U
  (hodograph of the jet from infinity; derivation in docs/validation/impinging_jet.md):
  RMS over |x| <= 2b, and its observed order between resolutions.
Writes docs/validation/impinging_jet.{md,csv} and the plots impinging_jet_plate.png and
impinging_jet_field.png.

Usage: python3 examples/validation/impinging_jet.py [--quick]   (2 threads, quiet machine)
"""
import argparse
import csv
import math
import pathlib
import time
import tomllib

import numpy as np

import deltasph as ds

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
RHO0, U, B = 1000.0, 1.0, 0.1
SCHEMES = {"δ-SPH": "delta_sph", "SPH": "none"}
T_END, WINDOW = 1.0, (0.5, 1.0)
SAMPLE = 0.005
PROBE_X = np.linspace(-2.5 * B, 2.5 * B, 51)
FLUX_X = 2.0 * B
Q = 0.5 * RHO0 * U**2


def config(n, diffusion):
    """The case at b/Δx = n: the wall 4Δx deep (the kernel support), the buffer 5Δx wide
    (R plus a spacing), its inner face 2b above the plate."""
    with open(HERE / "impinging_jet.toml", "rb") as f:
        cfg = tomllib.load(f)
    dx = B / n
    width = 5 * dx
    top = 2 * B + width
    cfg["particles"]["spacing"] = dx
    cfg["wall"][0]["lo"][1] = -4 * dx
    cfg["domain"]["lo"][1] = -4 * dx
    cfg["domain"]["hi"][1] = top
    cfg["fluid_block"][0]["hi"][1] = top
    cfg["open_boundary"][0]["width"] = width
    cfg["scheme"]["diffusion"] = diffusion
    cfg["time"]["end"] = T_END
    cfg["time"]["output_interval"] = 0.0
    cfg["diagnostics"] = {"loads": True}
    return cfg


def free_streamline(x):
    """p/(½ρ0U²) on the plate at x for the jet of width B from infinity."""
    target = np.abs(x) / B * math.pi / 2
    lo, hi = np.zeros_like(target), np.ones_like(target)
    for _ in range(60):
        s = 0.5 * (lo + hi)
        low = np.arctanh(np.minimum(s, 1 - 1e-16)) + np.arctan(s) < target
        lo, hi = np.where(low, s, lo), np.where(low, hi, s)
    s = 0.5 * (lo + hi)
    return 1 - s**2


def fluxes(sim, x0):
    """(mass, x-momentum) fluxes through the section x = x0, per unit depth."""
    dx = sim.spacing
    fluid = sim.kind == ds.FLUID
    x, u, m = sim.positions[fluid], sim.velocities[fluid], sim.mass[fluid]
    hat = np.maximum(0.0, 1 - np.abs(x[:, 0] - x0) / dx)
    ux = u[:, 0]
    return np.sum(m * ux * hat) / dx, np.sum(m * ux * ux * hat) / dx


def run(n, scheme):
    sim = ds.Simulation(config(n, SCHEMES[scheme]))
    probes = np.column_stack([PROBE_X, np.zeros_like(PROBE_X)])
    rows = []
    start = time.perf_counter()
    particle_steps, steps = 0.0, 0
    t = 0.0
    while t < T_END - 1e-9:
        t += SAMPLE
        while sim.time < t * (1 - 1e-12):
            sim.step()
            particle_steps += sim.n_particles
        if t >= WINDOW[0] - 1e-9:
            p = np.nan_to_num(sim.probe_pressure(probes))
            force = -sim.loads()["plate"]["pressure"][1]
            right, left = fluxes(sim, FLUX_X), fluxes(sim, -FLUX_X)
            rows.append((p, force, right, left))
    wall = time.perf_counter() - start
    p = np.mean([r[0] for r in rows], axis=0)
    # the mirror images averaged: the flow is symmetric about x = 0
    p = 0.5 * (p + p[::-1])
    force = np.mean([r[1] for r in rows])
    right = np.mean([r[2] for r in rows], axis=0)
    left = np.mean([r[3] for r in rows], axis=0)
    inner = np.abs(PROBE_X) <= 2 * B + 1e-12
    rms = np.sqrt(np.mean((p[inner] / Q - free_streamline(PROBE_X[inner])) ** 2))
    return {
        "n": n,
        "scheme": scheme,
        "p_stag": p[len(p) // 2] / Q,
        "force": force / (RHO0 * U**2 * B),
        "mass_right": right[0] / (RHO0 * U * B / 2),
        "mass_left": -left[0] / (RHO0 * U * B / 2),
        "momentum_right": right[1] / (RHO0 * U**2 * B / 2),
        "momentum_left": left[1] / (RHO0 * U**2 * B / 2),
        "plate_rms": rms,
        "steps": sim.n_steps,
        "wall_s": wall,
        "particle_steps_per_s": particle_steps / wall,
        "created": sim.n_created,
        "removed": sim.n_removed,
        "profile": p / Q,
        "sim": sim,
    }


COLUMNS = ["scheme", "n", "p_stag", "force", "mass_right", "mass_left", "momentum_right",
           "momentum_left", "plate_rms", "order", "steps", "wall_s", "particle_steps_per_s"]


def orders(results):
    for scheme in SCHEMES:
        runs = [r for r in results if r["scheme"] == scheme]
        runs.sort(key=lambda r: r["n"])
        for coarse, fine in zip(runs, runs[1:]):
            fine["order"] = math.log2(coarse["plate_rms"] / fine["plate_rms"])


def write(results):
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "impinging_jet.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in results:
            w.writerow([r.get(c, "") if not isinstance(r.get(c), float) else f"{r[c]:.5g}"
                        for c in COLUMNS])
    lines = ["| scheme | b/Δx | p(0)/½ρU² | F/ρU²b | ṁ right, left [ρUb/2] | "
             "momentum flux right, left [ρU²b/2] | plate RMS [½ρU²] | order | steps | "
             "wall [s] | particle-steps/s |", "|" + "---|" * 12]
    for r in results:
        order = f"{r['order']:.2f}" if "order" in r else "—"
        lines.append(
            f"| {r['scheme']} | {r['n']} | {r['p_stag']:.4f} | {r['force']:.4f} | "
            f"{r['mass_right']:.4f}, {r['mass_left']:.4f} | "
            f"{r['momentum_right']:.4f}, {r['momentum_left']:.4f} | {r['plate_rms']:.4f} | "
            f"{order} | {r['steps']} | {r['wall_s']:.1f} | {r['particle_steps_per_s']:.3g} |")
    (OUT / "impinging_jet_table.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


def plot(results):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7, 4))
    fine = np.linspace(-2.5 * B, 2.5 * B, 501)
    ax.plot(fine / B, free_streamline(fine), "k-", lw=2, label="free-streamline theory")
    for r in results:
        style = "-" if r["scheme"] == "δ-SPH" else ":"
        ax.plot(PROBE_X / B, r["profile"], style, label=f"{r['scheme']}, b/Δx = {r['n']}")
    ax.set_xlabel("x / b")
    ax.set_ylabel("p / (½ρ₀U²)")
    ax.set_title("Normal jet on a plate: plate pressure, mean over t = 5–10 b/U")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(OUT / "impinging_jet_plate.png", dpi=120)
    plt.close(fig)

    shown = [r for r in results if r["n"] == max(q["n"] for q in results)]
    fig, axes = plt.subplots(1, len(shown), figsize=(6 * len(shown), 3.2), squeeze=False)
    for ax, r in zip(axes[0], shown):
        sim = r["sim"]
        fluid = sim.kind == ds.FLUID
        x, p = sim.positions[fluid], sim.pressure[fluid]
        sc = ax.scatter(x[:, 0] / B, x[:, 1] / B, c=p / Q, s=0.3, cmap="viridis",
                        vmin=-0.1, vmax=1.1)
        ax.set_aspect("equal")
        ax.set_title(f"{r['scheme']}, b/Δx = {r['n']}, t = {sim.time:.2f} s")
        ax.set_xlabel("x / b")
        ax.set_ylabel("y / b")
        fig.colorbar(sc, ax=ax, label="p / (½ρ₀U²)")
    fig.tight_layout()
    fig.savefig(OUT / "impinging_jet_field.png", dpi=120)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="b/Δx = 10 and 20 only")
    args = parser.parse_args()
    resolutions = [10, 20] if args.quick else [10, 20, 40, 80]
    results = []
    for scheme in SCHEMES:
        for n in resolutions:
            r = run(n, scheme)
            print(f"{scheme} b/Δx = {n}: p(0) {r['p_stag']:.4f}, F {r['force']:.4f}, "
                  f"RMS {r['plate_rms']:.4f}, {r['wall_s']:.1f} s", flush=True)
            results.append(r)
    orders(results)
    write(results)
    plot(results)


if __name__ == "__main__":
    main()
