#!/usr/bin/env python3
"""Constant-speed water entry of a 30° wedge (examples/validation/wedge_entry.toml)
against Zhao & Faltinsen's (1993) similarity solution: the pressure along the flank and
the vertical force, converging in Δx, with δ-SPH beside standard SPH.

Without gravity the flow is self-similar: Cp = p/(½ρ0V²) on the flank is a function of
ζ = z/(Vt) alone (z the height above the still level) and the vertical force per unit
length is C_F ρ0V³t with a constant C_F. Every step the pressure is read on the flanks
(Shepard interpolation of the fluid at points on the wall's surface, both flanks
averaged) at fixed ζ, and the force from the wedge's load. Over t = 0.05-0.1 s the
profiles are averaged; the study reports the largest averaged Cp and its ζ against the
similarity solution's 6.927 at ζ = 0.4243, the mean C_F, the apex Cp, and the noise (the
RMS of C_F about its running mean over 20 acoustic times of a spacing).

The peak is looked for below ζ = 0.6: above it the flank holds the jet, a film a few
particles thick whose Shepard readings are noise (the similarity solution's pressure there
is near zero).

Runs: δ-SPH at Δx = 0.01, 0.005, 0.0025 m (V t/Δx = 10, 20, 40 at the end) with
c0 = 20 V; δ-SPH with c0 = 40 V (Δx = 0.01 and 0.005 m) and 80 V (Δx = 0.01 m), the tank
scaled with c0 (the acoustic waves of the impact must not come back before the end);
standard SPH (no density diffusion) at Δx = 0.005 m, c0 = 20 V. Writes docs/validation/wedge_entry.{md,csv} and the figures
wedge_entry_profiles.png and wedge_entry_field.png.

Usage: python3 examples/validation/wedge_entry.py [--quick]   (2 threads, quiet machine;
--quick leaves out Δx = 0.0025 m)
"""
import argparse
import csv
import math
import pathlib
import time
import tomllib

import numpy as np

import deltasph as ds
from records import pressure_field, write_csv, write_table
from sampling import running_mean

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
RHO0, V, BETA = 1000.0, 1.0, math.radians(30.0)
#: Zhao & Faltinsen 1993, similarity solution for β = 30°: the largest Cp and its height
#: above the still level over Vt (docs/validation/data/README.md)
with open(OUT / "data" / "wedge_entry_zhao_faltinsen1993.csv") as _f:
    _ROW = next(r for r in csv.DictReader(line for line in _f if not line.startswith("#"))
                if float(r["beta_deg"]) == 30.0)
CP_MAX, ZETA_MAX = float(_ROW["cp_max"]), float(_ROW["z_max_over_vt"])
ZETA = np.round(np.arange(-0.98, 1.0, 0.01), 2)
WINDOW = (0.05, 0.1)
#: the peak is looked for below this ζ (above it: the jet)
JET = 0.6


def config(dx, c0=20.0, diffusion="delta_sph"):
    """The case at spacing `dx` and sound speed `c0`, its tank c0/(20 V) times as large."""
    scale = c0 / (20.0 * V)
    with open(HERE / "wedge_entry.toml", "rb") as f:
        cfg = tomllib.load(f)
    cfg["particles"]["spacing"] = dx
    cfg["fluid"]["sound_speed"] = c0
    cfg["scheme"]["diffusion"] = diffusion
    for region in (cfg["fluid_block"][0], cfg["tank"][0]):
        region["lo"] = [scale * x for x in region["lo"]]
        region["hi"][0] *= scale
    cfg["time"]["output_interval"] = 0.0
    return cfg


def flank_points(t):
    """Points on both flanks at the heights ζ Vt above the still level, right flank
    first."""
    s = (ZETA + 1.0) * V * t / math.sin(BETA)
    right = np.array([0.0, -V * t]) + s[:, None] * np.array([math.cos(BETA), math.sin(BETA)])
    return np.concatenate([right, right * np.array([-1.0, 1.0])])


def run(dx, c0=20.0, diffusion="delta_sph"):
    """Per step: the time, C_F and the flanks' mean Cp at each ζ; the wall time and the
    simulation at its end."""
    cfg = config(dx, c0, diffusion)
    sim = ds.Simulation(cfg)
    end = cfg["time"]["end"]
    q = 0.5 * RHO0 * V**2
    t, force, cp = [], [], []
    start = time.perf_counter()
    while sim.time < end * (1 - 1e-12):
        sim.step()
        t.append(sim.time)
        # the loads refresh the pressures the probes read
        force.append(sim.loads()["wedge"]["pressure"][1] / (RHO0 * V**3 * sim.time))
        p = np.nan_to_num(sim.probe_pressure(flank_points(sim.time)))
        cp.append(p.reshape(2, -1).mean(axis=0) / q)
    return np.array(t), np.array(force), np.array(cp), time.perf_counter() - start, sim




def measure(t, force, cp, dx, c0):
    """The window's mean profile and its peak, C_F's mean, its change from the first
    half of the window to the second, and its noise."""
    w = (t >= WINDOW[0]) & (t <= WINDOW[1])
    profile = cp[w].mean(axis=0)
    k = int(np.argmax(np.where(ZETA <= JET, profile, -np.inf)))
    first = t[w] < 0.5 * sum(WINDOW)
    noise = force[w] - running_mean(t, force, 20 * dx / c0)[w]
    return profile, {
        "cp_max": profile[k],
        "zeta_max": float(ZETA[k]),
        "cp_apex": profile[0],
        "c_f": force[w].mean(),
        "c_f_drift": force[w][~first].mean() / force[w][first].mean() - 1.0,
        "c_f_noise": math.sqrt(np.mean(noise**2)),
    }


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--quick", action="store_true", help="leave out Δx = 0.0025 m")
    args = parser.parse_args()
    runs = [("δ-SPH", 0.01, 20.0, "delta_sph"), ("δ-SPH", 0.005, 20.0, "delta_sph")]
    if not args.quick:
        runs.append(("δ-SPH", 0.0025, 20.0, "delta_sph"))
    runs += [("δ-SPH", 0.01, 40.0, "delta_sph"), ("SPH", 0.005, 20.0, "none")]
    if not args.quick:
        runs += [("δ-SPH", 0.005, 40.0, "delta_sph"), ("δ-SPH", 0.01, 80.0, "delta_sph")]
    results, profiles, histories, fields = [], {}, {}, {}
    for label, dx, c0, diffusion in runs:
        t, force, cp, wall, sim = run(dx, c0, diffusion)
        profile, m = measure(t, force, cp, dx, c0)
        name = f"{label}, Δx = {dx:g} m, c0 = {c0:g} V"
        profiles[name], histories[name] = profile, (t, force)
        if dx == 0.005 and c0 == 20.0:
            fields[label] = (sim.positions, sim.pressure, sim.kind)
        results.append({"scheme": label, "dx": dx, "c0": c0, "particles": sim.n_fluid,
                        "steps": sim.n_steps, "wall_s": round(wall, 1), **m})
        print(f"{name}: Cp max {m['cp_max']:.3f} at ζ = {m['zeta_max']:.2f}, apex "
              f"{m['cp_apex']:.3f}, C_F {m['c_f']:.3f} (drift {100 * m['c_f_drift']:+.1f}%, "
              f"noise {m['c_f_noise']:.3f}), {wall:.0f} s", flush=True)
    columns = ["scheme", "dx", "c0", "particles", "steps", "wall_s", "cp_max", "zeta_max",
               "cp_apex", "c_f", "c_f_drift", "c_f_noise"]
    write_csv(OUT / "wedge_entry.csv", columns, results)
    header = ["scheme", "Δx [m]", "c0/V", "particles", "steps", "wall [s]", "Cp max",
              "its ζ", "Cp at the apex", "C_F", "C_F change", "C_F noise"]
    rows = [[r["scheme"], f"{r['dx']:g}", f"{r['c0']:g}", str(r["particles"]), str(r["steps"]),
             f"{r['wall_s']:.1f}", f"{r['cp_max']:.3f}", f"{r['zeta_max']:.2f}",
             f"{r['cp_apex']:.3f}", f"{r['c_f']:.2f}", f"{100 * r['c_f_drift']:+.1f}%",
             f"{r['c_f_noise']:.2f}"] for r in results]
    rows.append(["similarity solution", "", "∞", "", "", "", f"{CP_MAX}", f"{ZETA_MAX}",
                 "", "", "", ""])
    write_table(OUT / "wedge_entry_table.md", header, rows)
    plot_profiles(profiles, histories)
    plot_fields(fields)


def plot_profiles(profiles, histories):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, (left, right) = plt.subplots(1, 2, figsize=(12, 4.5))
    for name, profile in profiles.items():
        left.plot(ZETA, profile, label=name)
        t, force = histories[name]
        right.plot(t, force, label=name, lw=0.8)
    left.plot([ZETA_MAX], [CP_MAX], "k*", ms=12, label="similarity solution: largest Cp")
    left.set_xlabel("ζ = z / (Vt)")
    left.set_ylabel("Cp = p / (½ρ0V²), mean over t = 0.05-0.1 s")
    left.set_ylim(-2, 10)
    left.legend(fontsize=7)
    left.grid(alpha=0.3)
    right.set_xlabel("t [s]")
    right.set_ylabel("C_F = F / (ρ0V³t)")
    right.set_ylim(0, 30)
    right.grid(alpha=0.3)
    fig.suptitle("30° wedge entering water at constant speed V, no gravity")
    fig.tight_layout()
    fig.savefig(OUT / "wedge_entry_profiles.png", dpi=110)


def plot_fields(fields):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, len(fields), figsize=(6 * len(fields), 3.6))
    for ax, (label, (x, p, kind)) in zip(np.atleast_1d(axes), fields.items()):
        s = pressure_field(ax, x, p / (0.5 * RHO0 * V**2), kind == ds.FLUID, 8, (-0.4, 0.4),
                           (-0.2, 0.15), f"{label}, Δx = 0.005 m, t = 0.1 s: p / ½ρ0V²")
        fig.colorbar(s, ax=ax, shrink=0.8)
    fig.tight_layout()
    fig.savefig(OUT / "wedge_entry_field.png", dpi=110)


if __name__ == "__main__":
    main()
