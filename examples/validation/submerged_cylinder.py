#!/usr/bin/env python3
"""Regular waves over a fixed, submerged horizontal cylinder in deep water
(examples/validation/submerged_cylinder.toml) against linear theory: the multipole
solution of examples/validation/submerged_cylinder_theory.py (Ursell 1950), which
gives no reflection (Dean 1948), |T| = 1 with a shift of phase, and a force whose
horizontal and vertical amplitudes are equal (Ogilvie 1963).

Each resolution runs twice, with the cylinder and without it (the same flume, the
same gauges). Over the last four periods a mean and three harmonics of the wave
frequency are fitted at each gauge and to the cylinder's force:
- the incident wave at the cylinder: the elevation at x = 2.5 m without the cylinder,
  A_c (the phase reference of the force);
- reflection: the first harmonic at r1-r3 (0, L/10, L/4 apart, 1 L before the
  cylinder) split into incident and reflected waves (Mansard & Funke 1980), with the
  cylinder and, for the flume's own background (absorber and paddle), without it;
- transmission: the first harmonic at t1-t3 (1 L past the cylinder) with the cylinder
  over the same without it, whose mean is T (modulus and phase);
- force: the first harmonic of the pressure plus viscous force over A_c, against the
  theory's F/A, modulus and phase, horizontal and vertical.

Usage: python3 examples/validation/submerged_cylinder.py [--quick]
(2 threads: Δx = 0.025 m and 0.0125 m, about 25 min; --quick the coarse pair only)
Writes docs/validation/submerged_cylinder{.csv,_table.md,_signals.png}.
"""
import cmath
import math
import pathlib
import tomllib

import numpy as np

import deltasph as ds
import variants
import wave_analysis
from records import write_csv, write_table
from variants import load_case
from submerged_cylinder_theory import solve

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
G, DEPTH, PERIOD, HEIGHT = 9.81, 0.75, 0.8, 0.03
RADIUS, SUBMERGENCE = 0.1, 0.25
OMEGA = 2 * math.pi / PERIOD


def config(dx, cylinder, changes=()):
    """The case at spacing `dx`, with or without the cylinder, with `changes`
    ("section.key=value", the value in TOML) applied."""
    cfg = load_case(HERE / "submerged_cylinder.toml", changes)
    cfg["particles"]["spacing"] = dx
    # the paddle at least the kernel support thick
    cfg["wall"][0]["lo"][0] = -max(0.1, 6 * dx)
    cfg["time"]["output_interval"] = 0.0
    if not cylinder:
        del cfg["shape"]
    return cfg


def run(dx, cylinder, folder, reuse, changes=()):
    """Runs the case into `folder` or reads it back (variants.run)."""
    return variants.run(config(dx, cylinder, changes), folder, reuse)


def harmonics(t, y):
    """Complex amplitudes A_m of y ≈ a0 + Re Σ_{m≤3} A_m e^{-imωt}."""
    return wave_analysis.harmonics(t, y, OMEGA)


def window(series):
    t = series["time"]
    keep = t >= t[-1] - 4 * PERIOD
    return {name: values[keep] for name, values in series.items()}


def first(series, name):
    return harmonics(series["time"], series[name])[0]


def split(series, names, positions, k):
    """Incident and reflected first-harmonic amplitudes at x = 0 (least squares)."""
    a = [first(series, f"{n}_elevation") for n in names]
    return wave_analysis.split(a, positions, k)


def analyse(with_cyl, without, gauges, k):
    w, o = window(with_cyl), window(without)
    reflect = ["r1", "r2", "r3"]
    xr = [gauges[n] for n in reflect]
    inc, ref = split(w, reflect, xr, k)
    inc0, ref0 = split(o, reflect, xr, k)
    a_c = first(o, "c_elevation")
    ratios = [first(w, f"{n}_elevation") / first(o, f"{n}_elevation") for n in ("t1", "t2", "t3")]
    fx = first(w, "cylinder_pressure_fx") + first(w, "cylinder_viscous_fx")
    fy = first(w, "cylinder_pressure_fy") + first(w, "cylinder_viscous_fy")
    mean_fx = np.mean(w["cylinder_pressure_fx"] + w["cylinder_viscous_fx"])
    return {
        "incident_height": 2 * abs(inc),
        "height_at_cylinder": 2 * abs(a_c),
        "kr": abs(ref) / abs(inc),
        "kr_empty": abs(ref0) / abs(inc0),
        "T": np.mean(ratios),
        "T_spread": max(abs(r - np.mean(ratios)) for r in ratios),
        "Fx": fx / a_c,
        "Fy": fy / a_c,
        "mean_fx": mean_fx,
    }


def plot(path, series, theory, a_c, dx):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    w = window(series)
    t = w["time"]
    fig, (top, bottom) = plt.subplots(2, 1, figsize=(8, 6), sharex=True, constrained_layout=True)
    for n, style in (("r1", "C0"), ("c", "C1"), ("t1", "C2")):
        top.plot(t, w[f"{n}_elevation"] * 1e3, style, lw=1, label=f"gauge {n}")
    top.set_ylabel("η [mm]")
    top.legend(fontsize=8, ncol=3, loc="upper right", framealpha=0.9)
    top.set_title(f"Submerged cylinder, Δx = {dx} m: elevations and force over the last four periods")
    for axis, key, colour in (("x", "Fx", "C3"), ("y", "Fy", "C4")):
        f = w[f"cylinder_pressure_f{axis}"] + w[f"cylinder_viscous_f{axis}"]
        mean = f.mean()
        bottom.plot(t, f - mean, colour, lw=1.0, label=f"F{axis} − mean (SPH)")
        linear = (theory[key] * a_c * np.exp(-1j * OMEGA * t)).real
        bottom.plot(t, linear, "k", lw=1.0, ls="--", label="linear theory" if axis == "x" else None)
    bottom.set_xlabel("t [s]")
    bottom.set_ylabel("F [N/m]")
    bottom.legend(fontsize=8, ncol=3, loc="upper right", framealpha=0.9)
    fig.savefig(path, dpi=120)


def degrees(z):
    return math.degrees(cmath.phase(z))


def main():
    args = variants.study_arguments(__doc__.splitlines()[0], "submerged_cylinder",
                                    "the coarse pair only")
    theory = solve(RADIUS, SUBMERGENCE, OMEGA)
    k = ds.regular_wave(height=HEIGHT, period=PERIOD, depth=DEPTH, gravity=G)["wavenumber"]
    with open(HERE / "submerged_cylinder.toml", "rb") as f:
        gauges = {g["name"]: g["position"][0] for g in tomllib.load(f)["diagnostics"]["gauges"]}
    print(f"theory: |R| = {abs(theory['R']):.1e}, T = {abs(theory['T']):.4f} at "
          f"{degrees(theory['T']):.2f}°, F/A = {abs(theory['Fx']):.1f} N/m² "
          f"(x at {degrees(theory['Fx']):.1f}°, y at {degrees(theory['Fy']):.1f}°)")
    results, last = [], None
    for dx in (0.025,) if args.quick else (0.025, 0.0125):
        with_cyl, wall, n = run(dx, True, args.scratch / f"cylinder_{dx}", args.reuse, args.set)
        without, wall0, _ = run(dx, False, args.scratch / f"empty_{dx}", args.reuse, args.set)
        r = analyse(with_cyl, without, gauges, k)
        r.update(dx=dx, particles=n, wall=wall, wall_empty=wall0)
        results.append(r)
        last = (with_cyl, without, r)
        print(f"Δx = {dx}: H at r-gauges {r['incident_height']:.5f} m, at the cylinder "
              f"{r['height_at_cylinder']:.5f} m; K_r = {r['kr']:.4f} (empty flume {r['kr_empty']:.4f}); "
              f"T = {abs(r['T']):.4f} at {degrees(r['T']):.2f}° (spread {r['T_spread']:.4f}); "
              f"|Fx|/A = {abs(r['Fx']):.1f} at {degrees(r['Fx']):.1f}°, "
              f"|Fy|/A = {abs(r['Fy']):.1f} at {degrees(r['Fy']):.1f}°; mean Fx {r['mean_fx']:.3f} N/m; "
              f"wall {wall:.0f} s + {wall0:.0f} s")
    if args.set:
        return
    rows = [[
        f"{r['dx']}", f"{RADIUS / r['dx']:.0f}", f"{r['particles']}", f"{r['kr']:.2%}",
        f"{r['kr_empty']:.2%}", f"{abs(r['T']):.3f}", f"{degrees(r['T']):.1f}°",
        f"{abs(r['Fx']):.0f} ({abs(r['Fx']) / abs(theory['Fx']) - 1:+.1%})",
        f"{abs(r['Fy']):.0f} ({abs(r['Fy']) / abs(theory['Fy']) - 1:+.1%})",
        f"{degrees(r['Fx']):.1f}° / {degrees(r['Fy']):.1f}°", f"{r['wall']:.0f} s",
    ] for r in results]
    rows.append(["linear theory", "", "", "0", "", f"{abs(theory['T']):.3f}",
                 f"{degrees(theory['T']):.1f}°", f"{abs(theory['Fx']):.0f}",
                 f"{abs(theory['Fy']):.0f}", f"{degrees(theory['Fx']):.1f}° / {degrees(theory['Fy']):.1f}°", ""])
    write_table(OUT / "submerged_cylinder_table.md",
                ["Δx [m]", "a/Δx", "particles", "K_r", "K_r without cylinder", "\\|T\\|", "arg T",
                 "\\|Fx\\|/A [N/m²]", "\\|Fy\\|/A [N/m²]", "phase Fx / Fy", "wall (with cylinder)"], rows)
    columns = ["dx", "particles", "kr", "kr_empty", "abs_T", "arg_T_deg", "abs_Fx", "arg_Fx_deg",
               "abs_Fy", "arg_Fy_deg", "mean_fx", "wall"]
    write_csv(OUT / "submerged_cylinder.csv", columns, [
        {**r, "abs_T": abs(r["T"]), "arg_T_deg": degrees(r["T"]), "abs_Fx": abs(r["Fx"]),
         "arg_Fx_deg": degrees(r["Fx"]), "abs_Fy": abs(r["Fy"]), "arg_Fy_deg": degrees(r["Fy"])}
        for r in results])
    series, without, r = last
    a_c = first(window(without), "c_elevation")
    plot(OUT / "submerged_cylinder_signals.png", series, theory, a_c, r["dx"])


if __name__ == "__main__":
    main()
