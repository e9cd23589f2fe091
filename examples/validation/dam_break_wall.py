#!/usr/bin/env python3
"""Wall pressure in the δ-SPH dam break (examples/validation/dam_break_wall.toml): the
probe P1 at y = 0.2H against Marrone et al. (2011)'s δ-SPH at equal H/Δx and the
experiment, the face sensors at 6, 30, 60 and 160 mm against De Courcy et al. (2024),
and the horizontal load on the right wall, from `sph-cli run` (build it first:
cargo build --release).

For each resolution (H/Δx = 40 and 80; 160 with --fine) it reports, in p* = p/(ρ0 g H)
against t* = t sqrt(g/H):
- P1: the RMS difference from Marrone's δ-SPH at the same H/Δx over t* 2-7 (raw, and
  after a 0.1 t* running mean), the means over the plateau (t* 3.3-5.2) and the first
  impact (t* 2.5-3.0), the first peak (t* < 3.2) and its time, the rise (p* > 0.1);
- the sensors: face-averaged means over the same two windows, against De Courcy's;
- the right wall: the mean horizontal load over the plateau, in ρ0 g H².
Writes docs/validation/dam_break_wall.{md,csv} and the plots dam_break_wall_p1.png,
dam_break_wall_profile.png and dam_break_wall_force.png.

Usage: python3 examples/validation/dam_break_wall.py [--fine] [--h-over-dx 2]
       [--resolutions 40 80]   (2 threads)
"""
import argparse
import csv
import math
import pathlib
import re
import subprocess
import tempfile
import time

import numpy as np

from sampling import running_mean

HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parents[1]
OUT = ROOT / "docs" / "validation"
REFDATA = OUT / "data"
CLI = ROOT / "target" / "release" / "sph-cli"
H, G, RHO0, LENGTH = 0.6, 9.81, 1000.0, 3.2196
SENSORS = {"s6mm": 0.006, "s30mm": 0.030, "s60mm": 0.060, "s160mm": 0.160}
#: De Courcy et al. (2024), means over t* 3.3-5.2 / 2.5-3.0 (docs/validation/data/README.md)
DE_COURCY = {"s6mm": (0.985, 1.705), "s30mm": (0.915, 1.555), "s60mm": (0.815, 1.113),
             "s160mm": (0.366, 0.062)}
PLATEAU, IMPACT, COMPARE = (3.3, 5.2), (2.5, 3.0), (2.0, 7.0)


def case_text(n, h_over_dx):
    """The case at H/Δx = n, its right wall continuing the tank's lattice: the tank's
    lattice runs from -pad, its last column inside the tank sits below the face, and
    the right wall's first column one spacing on, half a spacing past the wall face.
    Walls are as many layers thick as cover the Wendland support 2h."""
    text = (HERE / "dam_break_wall.toml").read_text()
    layers = math.ceil(2 * h_over_dx - 1e-9)
    text = re.sub(r"(?m)^h_over_dx = .*$", f"h_over_dx = {h_over_dx!r}", text)
    text = re.sub(r"(?m)^layers = .*$", f"layers = {layers}", text)
    dx = H / n
    pad = layers * dx
    face = -pad + (math.floor((LENGTH + pad) / dx - 0.5) + 1) * dx
    text = re.sub(r"(?m)^spacing = .*$", f"spacing = {dx!r}", text)
    text = re.sub(r"(?m)^lo = \[3\.2196, .*$", f"lo = [{face!r}, {-pad!r}]", text)
    text = re.sub(r"(?m)^hi = \[3\.2421, .*$", f"hi = [{face + pad!r}, 1.8]", text)
    # the probes and the sensors' centres move onto the wall face
    return text.replace("[3.2196, 0.", f"[{face!r}, 0.")


def run(n, h_over_dx, work):
    case = work / f"dam_break_wall_{n}.toml"
    case.write_text(case_text(n, h_over_dx))
    out = work / f"out_{n}"
    start = time.perf_counter()
    subprocess.run([str(CLI), "run", str(case), "--out", str(out), "--force", "-q"],
                   check=True, stdout=subprocess.DEVNULL)
    wall = time.perf_counter() - start
    data = np.genfromtxt(out / "timeseries.csv", delimiter=",", names=True)
    # the probe reads NaN while no fluid is in reach: zero gauge pressure there
    data["probe0_pressure"] = np.nan_to_num(data["probe0_pressure"])
    return data, wall


def mean_over(t, p, window):
    w = (t >= window[0]) & (t <= window[1])
    return float(np.trapezoid(p[w], t[w]) / (t[w][-1] - t[w][0]))




def read_refdata(name):
    """A reference CSV (leading `#` lines, then a header) as a structured array."""
    lines = [l for l in (REFDATA / name).read_text().splitlines() if not l.startswith("#")]
    names = lines[0].strip().split(",")
    values = np.array([[float(v) for v in l.split(",")] for l in lines[1:] if l.strip()])
    return np.rec.fromarrays(values.T, names=names)


def marrone():
    return read_refdata("dambreak2d_marrone2011_P1.csv")


def p1_figures(t, p, n):
    ref = marrone()
    column = f"dsph_H{n}"
    w = (t >= COMPARE[0]) & (t <= COMPARE[1])
    figures = {}
    if column in ref.dtype.names:
        r = np.interp(t, ref["t_star"], ref[column])
        figures["rms_vs_marrone"] = float(np.sqrt(np.mean((p[w] - r[w]) ** 2)))
        smooth = running_mean(t, p, 0.1)
        figures["rms_vs_marrone_smoothed"] = float(np.sqrt(np.mean((smooth[w] - r[w]) ** 2)))
        figures["marrone_plateau"] = mean_over(ref["t_star"], ref[column], PLATEAU)
        figures["marrone_impact"] = mean_over(ref["t_star"], ref[column], IMPACT)
    first = (t >= 2.3) & (t <= 3.2)
    k = int(np.argmax(p[first]))
    figures.update({
        "plateau": mean_over(t, p, PLATEAU),
        "impact": mean_over(t, p, IMPACT),
        "first_peak": float(p[first][k]),
        "first_peak_time": float(t[first][k]),
        "rise_time": float(t[np.argmax(p > 0.1)]),
    })
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--fine", action="store_true", help="also H/Δx = 160")
    parser.add_argument("--h-over-dx", type=float, default=1.33,
                        help="smoothing length over spacing (default 1.33, as dam_break.toml)")
    parser.add_argument("--resolutions", type=int, nargs="*", help="H/Δx values to run")
    args = parser.parse_args()
    resolutions = args.resolutions or ([40, 80, 160] if args.fine else [40, 80])
    scale_t, scale_p = math.sqrt(G / H), RHO0 * G * H
    runs, rows = {}, []
    with tempfile.TemporaryDirectory() as tmp:
        for n in resolutions:
            data, wall = run(n, args.h_over_dx, pathlib.Path(tmp))
            t = data["time"] * scale_t
            row = {"H/dx": n, "h/dx": args.h_over_dx, "wall_s": round(wall, 1)}
            row.update({f"p1_{k}": v for k, v in
                        p1_figures(t, data["probe0_pressure"] / scale_p, n).items()})
            for name in SENSORS:
                face = data[f"{name}_pressure"] / scale_p
                row[f"{name}_plateau"] = mean_over(t, face, PLATEAU)
                row[f"{name}_impact"] = mean_over(t, face, IMPACT)
            force = (data["right_wall_pressure_fx"] + data["right_wall_viscous_fx"]) / (RHO0 * G * H**2)
            row["force_plateau"] = mean_over(t, force, PLATEAU)
            row["force_peak"] = float(force.max())
            row["force_peak_time"] = float(t[int(np.argmax(force))])
            runs[n] = (t, data)
            rows.append(row)
            print({k: (round(v, 4) if isinstance(v, float) else v) for k, v in row.items()},
                  flush=True)
    suffix = "" if args.h_over_dx == 1.33 else f"_h{args.h_over_dx:g}"
    write_report(rows, suffix)
    plots(runs, suffix)


def write_report(rows, suffix):
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / f"dam_break_wall{suffix}.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=list(rows[0]))
        writer.writeheader()
        writer.writerows(rows)
    lines = [
        "# Dam break: wall pressure and the right wall's load",
        "",
        "Command: `python3 examples/validation/dam_break_wall.py` (after `cargo build "
        "--release`; 2 threads). Case: `examples/validation/dam_break_wall.toml` (δ-SPH, "
        f"RK4, CFL 1.5, Wendland C2 h/Δx = {rows[0]['h/dx']:g}, α = 0.02, δ = 0.1). "
        "p* = p/(ρ0gH), "
        "t* = t sqrt(g/H).",
        "",
        "## P1 at y = 0.2H against Marrone et al. (2011)'s δ-SPH at the same H/Δx",
        "",
        "| H/Δx | wall [s] | RMS t* 2-7 (raw / 0.1 t* mean) | plateau (Marrone) | first impact "
        "(Marrone) | first peak at t* | rise t* |",
        "|---|---|---|---|---|---|---|",
    ]
    for r in rows:
        rms = (f"{r['p1_rms_vs_marrone']:.3f} / {r['p1_rms_vs_marrone_smoothed']:.3f}"
               if "p1_rms_vs_marrone" in r else "(no curve)")
        ref_p = f" ({r['p1_marrone_plateau']:.3f})" if "p1_marrone_plateau" in r else ""
        ref_i = f" ({r['p1_marrone_impact']:.3f})" if "p1_marrone_impact" in r else ""
        lines.append(
            f"| {r['H/dx']} | {r['wall_s']} | {rms} | {r['p1_plateau']:.3f}{ref_p} | "
            f"{r['p1_impact']:.3f}{ref_i} | {r['p1_first_peak']:.3f} at "
            f"{r['p1_first_peak_time']:.2f} | {r['p1_rise_time']:.2f} |")
    lines += ["", "Experiment (Buchner 2002, as plotted by Marrone): plateau 0.540, first "
              "impact 0.566, first maximum 0.69 at t* 2.74-2.77, rise at t* 2.45-2.50.", "",
              "## Face sensors (8.4 mm, face-averaged) against De Courcy et al. (2024, "
              "H/Δx = 400)", "",
              "| sensor | De Courcy plateau / impact | " +
              " | ".join(f"H/Δx {r['H/dx']}" for r in rows) + " |",
              "|---|---|" + "---|" * len(rows)]
    for name, (plateau, impact) in DE_COURCY.items():
        cells = " | ".join(f"{r[f'{name}_plateau']:.3f} / {r[f'{name}_impact']:.3f}" for r in rows)
        lines.append(f"| {name} | {plateau:.3f} / {impact:.3f} | {cells} |")
    lines += ["", "## Right wall: horizontal load (pressure + viscous), in ρ0 g H² per unit "
              "width", "", "| H/Δx | plateau mean | peak at t* |", "|---|---|---|"]
    for r in rows:
        lines.append(f"| {r['H/dx']} | {r['force_plateau']:.3f} | {r['force_peak']:.3f} at "
                     f"{r['force_peak_time']:.2f} |")
    (OUT / f"dam_break_wall{suffix}.md").write_text("\n".join(lines) + "\n")


def plots(runs, suffix):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    scale_p = RHO0 * G * H
    ref = marrone()
    fig, ax = plt.subplots(figsize=(10, 4.5))
    ax.plot(ref["t_star"], ref["experiment"], "k.", ms=2, label="Buchner (2002)")
    for n, (t, data) in runs.items():
        ax.plot(t, data["probe0_pressure"] / scale_p, lw=0.8, label=f"deltasph H/Δx = {n}")
        if f"dsph_H{n}" in ref.dtype.names:
            ax.plot(ref["t_star"], ref[f"dsph_H{n}"], "--", lw=0.8,
                    label=f"Marrone et al. 2011, H/Δx = {n}")
    ax.plot(ref["t_star"], ref["dsph_H320"], "k--", lw=0.8, label="Marrone et al. 2011, H/Δx = 320")
    ax.set(xlim=(2, 7), ylim=(-0.2, 1.6), xlabel="t sqrt(g/H)", ylabel="p / ρ0gH",
           title="Dam break: P1 at y = 0.2H on the right wall")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(OUT / f"dam_break_wall_p1{suffix}.png", dpi=110)

    fig, axes = plt.subplots(2, 2, figsize=(12, 7), sharex=True)
    n_top = max(runs)
    t, data = runs[n_top]
    for ax, (name, height) in zip(axes.flat, SENSORS.items()):
        ref_s = read_refdata(f"dambreak2d_decourcy2024_wall_{int(height * 1000)}mm.csv")
        ax.plot(ref_s["t_star"], ref_s["p_star"], "k-", lw=0.8, label="De Courcy et al. 2024")
        ax.plot(t, data[f"{name}_point"] / scale_p, lw=0.5, alpha=0.5, label="point value")
        ax.plot(t, data[f"{name}_pressure"] / scale_p, lw=0.8, label="face average")
        ax.plot(t, data[f"{name}_filtered"] / scale_p, lw=1.0, label="face, 100 Hz low-pass")
        ax.set(xlim=(2, 7), title=f"sensor at {height * 1000:.0f} mm, H/Δx = {n_top}")
        ax.grid(alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    for ax in axes[-1]:
        ax.set_xlabel("t sqrt(g/H)")
    fig.tight_layout()
    fig.savefig(OUT / f"dam_break_wall_profile{suffix}.png", dpi=110)

    fig, ax = plt.subplots(figsize=(10, 4))
    for n, (t, data) in runs.items():
        force = (data["right_wall_pressure_fx"] + data["right_wall_viscous_fx"]) / (RHO0 * G * H**2)
        ax.plot(t, force, lw=0.8, label=f"H/Δx = {n}")
    ax.set(xlim=(2, 7), xlabel="t sqrt(g/H)", ylabel="F_x / ρ0gH²",
           title="Dam break: horizontal load on the right wall")
    ax.legend(fontsize=8)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(OUT / f"dam_break_wall_force{suffix}.png", dpi=110)


if __name__ == "__main__":
    main()
