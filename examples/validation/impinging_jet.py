#!/usr/bin/env python3
"""Plane jet impinging normally on a flat plate (examples/validation/impinging_jet.toml),
against free-streamline theory, at b/Δx = 10, 20, 40 and 80 with δ-SPH and with standard
SPH (no density diffusion), RK4, artificial viscosity α = 0.02; and the same jet on a
plate tilted by 30° (the jet 60° to the plate) with δ-SPH at b/Δx = 20, 40 and 80.

The jet (width b = 0.1 m, U = 1 m/s, c0 = 10U, no gravity) enters through an inlet
buffer whose inner face stands 3b above the plate; the two wall jets leave the domain
at x = ±3b. Over t = 5-10 b/U (steady) the script averages:
- the stagnation pressure p(0) against ½ρ0U²;
- the plate's load (the fluid's force on the wall body, pressure and viscous)
  against ρ0U²b;
- the mass and x-momentum fluxes of each outgoing jet through x = ±2b against ρ0Ub/2
  and ρ0U²b/2 (hat-weighted sums over particles, exact for a lattice);
- the plate pressure p(x) at 51 probes on the plate, |x| <= 2.5b, against the free-
  streamline solution p/(½ρ0U²) = 1 - s², x/b = (2/π)(artanh s + arctan s), s = q/U
  (hodograph of the jet from infinity; derivation in docs/validation/impinging_jet.md):
  RMS over |x| <= 2b, and its observed order between resolutions.
On the tilted plate, momentum along the plate and Bernoulli give the split of the jet
(b(1 ± cos θ)/2 for the jet at θ to the plate, the wider one down the slope) and the
plate's normal force ρ0U²b sin θ; the script measures the fluxes through sections
across the plate 2b from the jet's axis, the normal and tangential loads, and the
largest plate pressure (½ρ0U² at the stagnation point).
The sound-speed study (`--only c0`) runs the normal jet with δ-SPH at b/Δx = 20 and 40
with c0 = 10, 20 and 40 U, holding either the artificial viscosity's α (its viscosity
α h c0/8 grows with c0, as a user who only raises c0 gets) or α c0 (the same viscosity:
what is left is compressibility, whose share of the stagnation pressure is
Ma²/4 + O(Ma⁴) under the linear equation of state).
Writes docs/validation/impinging_jet{.csv,_table.md,_oblique.csv,_oblique_table.md,
_profiles.csv,_c0.csv,_c0_table.md} and the plots impinging_jet_plate.png, impinging_jet_field.png and
impinging_jet_oblique_field.png;
docs/validation/impinging_jet.md reads them.

Usage: python3 examples/validation/impinging_jet.py [--quick] [--only normal|oblique|c0]
(2 threads, quiet machine)
"""
import argparse
import csv
import math
import pathlib
import tomllib

import matplotlib
import numpy as np

import deltasph as ds
from records import write_csv, write_table
from sampling import Sampler, body_force

matplotlib.use("Agg")

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
RHO0, U, B = 1000.0, 1.0, 0.1
SCHEMES = {"δ-SPH": "delta_sph", "SPH": "none"}
T_END, WINDOW = 1.0, (0.5, 1.0)
SAMPLE = 0.005
#: the inlet's inner face above the plate: theory puts p = 0.003 ½ρ0U² there (0.035 at 2b)
NOZZLE = 3 * B
PROBE_X = np.linspace(-2.5 * B, 2.5 * B, 51)
FLUX_X = 2.0 * B
Q = 0.5 * RHO0 * U**2
#: the tilted plate's angle to the horizontal (the jet meets it at 90° - TILT)
TILT = math.radians(30.0)
#: probes on the tilted plate, at distances s along it from the jet's axis
OBLIQUE_PROBE_S = np.linspace(-1.5 * B, 1.5 * B, 61)


def config(n, diffusion, c0=None, alpha=None):
    """The case at b/Δx = n: the wall 4Δx deep (the kernel support), the buffer 5Δx wide
    (R plus a spacing), its inner face 3b above the plate; the case's sound speed and
    artificial viscosity unless `c0` or `alpha` is given."""
    with open(HERE / "impinging_jet.toml", "rb") as f:
        cfg = tomllib.load(f)
    dx = B / n
    width = 5 * dx
    top = NOZZLE + width
    cfg["particles"]["spacing"] = dx
    cfg["wall"][0]["lo"][1] = -4 * dx
    cfg["domain"]["lo"][1] = -4 * dx
    cfg["domain"]["hi"][1] = top
    cfg["fluid_block"][0]["hi"][1] = top
    cfg["open_boundary"][0]["width"] = width
    cfg["scheme"]["diffusion"] = diffusion
    if c0 is not None:
        cfg["fluid"]["sound_speed"] = c0
    if alpha is not None:
        cfg["scheme"]["alpha"] = alpha
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


def fluxes(sim, x0, e=(1.0, 0.0)):
    """(mass, momentum) fluxes along the unit vector e through the section x·e = x0,
    per unit depth (hat-weighted sums over particles, exact for a lattice)."""
    dx = sim.spacing
    fluid = sim.kind == ds.FLUID
    x, u, m = sim.positions[fluid], sim.velocities[fluid], sim.mass[fluid]
    hat = np.maximum(0.0, 1 - np.abs(x @ np.asarray(e) - x0) / dx)
    ue = u @ np.asarray(e)
    return np.sum(m * ue * hat) / dx, np.sum(m * ue * ue * hat) / dx


def sample(sim, measure):
    """Steps to T_END and calls measure(sim) every SAMPLE over the window: the list of
    what it returned, the wall time and the particle-steps per second."""
    sampler = Sampler(sim, T_END, SAMPLE)
    rows = [measure(sim) for t in sampler if t >= WINDOW[0] - 1e-9]
    return rows, sampler.wall, sampler.rate


def run(n, scheme, c0=None, alpha=None):
    sim = ds.Simulation(config(n, SCHEMES[scheme], c0, alpha))
    probes = np.column_stack([PROBE_X, np.zeros_like(PROBE_X)])

    def measure(sim):
        p = np.nan_to_num(sim.probe_pressure(probes))
        return p, -body_force(sim, "plate")[1], fluxes(sim, FLUX_X), fluxes(sim, -FLUX_X)

    rows, wall, rate = sample(sim, measure)
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
        "particle_steps_per_s": rate,
        "profile": p / Q,
        "sim": sim,
    }


def oblique_config(n):
    """The jet of `config` with δ-SPH on a plate through the origin tilted by TILT: a
    wall polygon 5Δx thick across the domain, whose bottom moves down to hold it; the
    column starts at U down to the plate (an impact, over before the window)."""
    cfg = config(n, "delta_sph")
    dx = B / n
    half = 3 * B
    rise, thick = half * math.tan(TILT), 5 * dx / math.cos(TILT)
    del cfg["wall"], cfg["initial"]
    cfg["shape"] = [{"role": "wall", "name": "plate", "polygon": [
        [-half, -rise], [half, rise], [half, rise - thick], [-half, -rise - thick]]}]
    block = cfg["fluid_block"][0]
    block["lo"][1] = -math.ceil(0.5 * B * math.tan(TILT) / dx) * dx
    block["velocity"] = [0.0, -U]
    cfg["domain"]["lo"][1] = -rise - thick - dx
    return cfg


def run_oblique(n):
    """The tilted plate's figures, each over its theoretical value."""
    sim = ds.Simulation(oblique_config(n))
    along = np.array([math.cos(TILT), math.sin(TILT)])
    normal = np.array([-math.sin(TILT), math.cos(TILT)])
    probes = np.outer(OBLIQUE_PROBE_S, along)

    def measure(sim):
        p = np.nan_to_num(sim.probe_pressure(probes))
        load = body_force(sim, "plate")
        return p, load, fluxes(sim, FLUX_X, along), fluxes(sim, -FLUX_X, along)

    rows, wall, rate = sample(sim, measure)
    p = np.mean([r[0] for r in rows], axis=0)
    load = np.mean([r[1] for r in rows], axis=0)
    up = np.mean([r[2] for r in rows], axis=0)
    down = np.mean([r[3] for r in rows], axis=0)
    theta = math.pi / 2 - TILT
    return {
        "n": n,
        "p_max": p.max() / Q,
        "s_max": OBLIQUE_PROBE_S[np.argmax(p)] / B,
        "normal_force": -(load @ normal) / (RHO0 * U**2 * B * math.sin(theta)),
        "tangential_force": (load @ along) / (RHO0 * U**2 * B),
        "mass_down": -down[0] / (RHO0 * U * B * (1 + math.cos(theta)) / 2),
        "mass_up": up[0] / (RHO0 * U * B * (1 - math.cos(theta)) / 2),
        "steps": sim.n_steps,
        "wall_s": wall,
        "particle_steps_per_s": rate,
        "sim": sim,
    }


COLUMNS = ["scheme", "n", "p_stag", "force", "mass_right", "mass_left", "momentum_right",
           "momentum_left", "plate_rms", "order_theory", "change", "order", "steps",
           "wall_s", "particle_steps_per_s"]


def orders(results):
    """Per run, the RMS change of the plate pressure from the next coarser run over
    |x| <= 2b (`change`), and the observed order of those changes (`order`); and the
    order of the error against theory (`order_theory`)."""
    inner = np.abs(PROBE_X) <= 2 * B + 1e-12
    for scheme in SCHEMES:
        runs = sorted((r for r in results if r["scheme"] == scheme), key=lambda r: r["n"])
        for coarse, fine in zip(runs, runs[1:]):
            diff = fine["profile"][inner] - coarse["profile"][inner]
            fine["change"] = float(np.sqrt(np.mean(diff**2)))
            fine["order_theory"] = math.log2(coarse["plate_rms"] / fine["plate_rms"])
        for coarse, fine in zip(runs[1:], runs[2:]):
            fine["order"] = math.log2(coarse["change"] / fine["change"])


def write(results):
    write_csv(OUT / "impinging_jet.csv", COLUMNS, results)
    with open(OUT / "impinging_jet_profiles.csv", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x_over_b", "theory"] + [f"{r['scheme']} {r['n']}" for r in results])
        for k, x in enumerate(PROBE_X):
            w.writerow([f"{x / B:.3f}", f"{free_streamline(np.array([x]))[0]:.5f}"]
                       + [f"{r['profile'][k]:.5f}" for r in results])

    def fmt(r, key, digits):
        return f"{r[key]:.{digits}f}" if key in r else "—"

    header = ["scheme", "b/Δx", "p(0)/½ρU²", "F/ρU²b", "ṁ right, left [ρUb/2]",
              "momentum flux right, left [ρU²b/2]", "plate RMS vs theory [½ρU²]",
              "its order", "RMS change from b/Δx/2", "its order", "steps", "wall [s]",
              "particle-steps/s"]
    rows = [[r["scheme"], f"{r['n']}", f"{r['p_stag']:.4f}", f"{r['force']:.4f}",
             f"{r['mass_right']:.4f}, {r['mass_left']:.4f}",
             f"{r['momentum_right']:.4f}, {r['momentum_left']:.4f}", f"{r['plate_rms']:.4f}",
             fmt(r, "order_theory", 2), fmt(r, "change", 4), fmt(r, "order", 2),
             f"{r['steps']}", f"{r['wall_s']:.1f}", f"{r['particle_steps_per_s']:.3g}"]
            for r in results]
    write_table(OUT / "impinging_jet_table.md", header, rows)


def plot(results):
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

    plot_fields([r for r in results if r["n"] == max(q["n"] for q in results)],
                "impinging_jet_field.png")


def plot_fields(shown, name):
    """The pressure fields of the runs `shown`, side by side, into OUT/name."""
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(shown), figsize=(6 * len(shown), 3.2), squeeze=False)
    for ax, r in zip(axes[0], shown):
        sim = r["sim"]
        fluid = sim.kind == ds.FLUID
        x, p = sim.positions[fluid], sim.pressure[fluid]
        sc = ax.scatter(x[:, 0] / B, x[:, 1] / B, c=p / Q, s=0.3, cmap="viridis",
                        vmin=-0.1, vmax=1.1)
        wall = sim.kind == ds.WALL
        ax.scatter(sim.positions[wall, 0] / B, sim.positions[wall, 1] / B, s=0.3, c="0.6")
        ax.set_aspect("equal")
        ax.set_title(f"{r.get('scheme', 'δ-SPH')}, b/Δx = {r['n']}, t = {sim.time:.2f} s")
        ax.set_xlabel("x / b")
        ax.set_ylabel("y / b")
        fig.colorbar(sc, ax=ax, label="p / (½ρ₀U²)")
    fig.tight_layout()
    fig.savefig(OUT / name, dpi=120)
    plt.close(fig)


OBLIQUE_COLUMNS = ["n", "p_max", "s_max", "normal_force", "tangential_force", "mass_down",
                   "mass_up", "steps", "wall_s", "particle_steps_per_s"]


def write_oblique(results):
    """impinging_jet_oblique.csv and its table."""
    write_csv(OUT / "impinging_jet_oblique.csv", OBLIQUE_COLUMNS, results)
    header = ["b/Δx", "max p / ½ρU²", "at s/b", "F_n / ρU²b sin θ", "F_t / ρU²b",
              "ṁ down / ρUb(1+cos θ)/2", "ṁ up / ρUb(1-cos θ)/2", "steps", "wall [s]",
              "particle-steps/s"]
    rows = [[f"{r['n']}", f"{r['p_max']:.4f}", f"{r['s_max']:.2f}", f"{r['normal_force']:.4f}",
             f"{r['tangential_force']:.4f}", f"{r['mass_down']:.4f}", f"{r['mass_up']:.4f}",
             f"{r['steps']}", f"{r['wall_s']:.1f}", f"{r['particle_steps_per_s']:.3g}"]
            for r in results]
    write_table(OUT / "impinging_jet_oblique_table.md", header, rows)


C0_COLUMNS = ["n", "c0", "alpha", "viscosity", "p_stag", "compressibility", "force",
              "mass_right", "momentum_right", "plate_rms", "steps", "wall_s"]


def sound_speed_study(resolutions):
    """The normal jet with δ-SPH at c0 = 10, 20, 40 U: α held (the case's 0.02) and α c0
    held (the viscosity α h c0/8 of c0 = 10U); into impinging_jet_c0{.csv,_table.md}."""
    with open(HERE / "impinging_jet.toml", "rb") as f:
        cfg = tomllib.load(f)
    alpha0, c00 = cfg["scheme"]["alpha"], cfg["fluid"]["sound_speed"]
    results = []
    for n in resolutions:
        for c0, alpha in [(c00, alpha0), (2 * c00, alpha0), (4 * c00, alpha0),
                          (2 * c00, alpha0 / 2), (4 * c00, alpha0 / 4)]:
            r = run(n, "δ-SPH", c0, alpha)
            r.update(c0=c0 / U, alpha=alpha,
                     viscosity=alpha * 2 * (B / n) * c0 / 8 / (U * B),
                     compressibility=(U / c0) ** 2 / 4)
            print(f"b/Δx = {n}, c0 = {c0:g} U, α = {alpha:g}: p(0) {r['p_stag']:.4f}, "
                  f"F {r['force']:.4f}, RMS {r['plate_rms']:.4f}, {r['wall_s']:.1f} s",
                  flush=True)
            results.append(r)
    write_csv(OUT / "impinging_jet_c0.csv", C0_COLUMNS, results)
    header = ["b/Δx", "c0/U", "α", "ν_α/(Ub)", "p(0)/½ρU²", "Ma²/4", "F/ρU²b",
              "ṁ right [ρUb/2]", "momentum flux right [ρU²b/2]", "plate RMS vs theory [½ρU²]",
              "steps", "wall [s]"]
    rows = [[f"{r['n']}", f"{r['c0']:g}", f"{r['alpha']:g}", f"{r['viscosity']:.2e}",
             f"{r['p_stag']:.4f}", f"{r['compressibility']:.4f}", f"{r['force']:.4f}",
             f"{r['mass_right']:.4f}", f"{r['momentum_right']:.4f}", f"{r['plate_rms']:.4f}",
             f"{r['steps']}", f"{r['wall_s']:.1f}"] for r in results]
    write_table(OUT / "impinging_jet_c0_table.md", header, rows)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="b/Δx = 10 and 20 only")
    parser.add_argument("--only", choices=["normal", "oblique", "c0"],
                        help="one of the three studies")
    args = parser.parse_args()
    resolutions = [10, 20] if args.quick else [10, 20, 40, 80]
    OUT.mkdir(parents=True, exist_ok=True)
    if args.only == "c0" or args.only is None:
        sound_speed_study([10, 20] if args.quick else [20, 40])
    if args.only == "c0":
        return
    if args.only != "oblique":
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
    if args.only != "normal":
        oblique = [run_oblique(n) for n in resolutions if n >= 20]
        write_oblique(oblique)
        plot_fields(oblique[-1:], "impinging_jet_oblique_field.png")


if __name__ == "__main__":
    main()
