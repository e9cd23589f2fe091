#!/usr/bin/env python3
"""Flow past a circular cylinder (examples/validation/cylinder.toml) at Re = 100 and 200,
D/Δx = 20 and 30, with δ+-SPH and physical viscosity, against the unconfined cylinder of
the literature.

The stream (U = 1, D = 1, ρ0 = 1, c0 = 10U) enters through an inlet 4D upstream of the
cylinder and leaves through an outlet 10D downstream; the domain is periodic across with
period H = 8D. For the time-mean flow of a symmetric body a periodic row is the same as
free-slip walls H apart (the walls' mirror images are the row), so the usual closed-tunnel
blockage correction applies: the body's and wake's images speed the stream at the body by
ε = (π²/12)(D/H)² + (D/4H) C_D (solid blockage of a doublet row, and wake blockage of a
source of strength ½ U D C_D; Allen & Vincenti 1944), and the coefficients are reported
raw and scaled to the corrected speed U(1 + ε): C_D/(1 + ε)², C_L/(1 + ε)², St/(1 + ε).

From the cylinder's load (pressure and viscous), sampled every 0.05 D/U:
The lift is first low-passed (zero-phase Butterworth at 1 U/D, five times the shedding
frequency) to remove the loads' acoustic noise. Then:
- St = f D/U from the lift's upward zero crossings over the window (the last 25 D/U of
  a run to 60 D/U by default), f the mean of their rate;
- C_D, the drag coefficient averaged over whole lift periods in the window;
- C_L', the lift amplitude: half the mean peak-to-peak of the lift over those periods.
References (unconfined): Re = 100: C_D 1.33-1.35, C_L' 0.33, St 0.164-0.167; Re = 200:
C_D 1.33-1.37, C_L' 0.65-0.70, St 0.195-0.20 (Liu, Zheng & Sung 1998, J. Comput. Phys.
139:35, Table: 1.350, 0.339, 0.164 at 100 and 1.31, 0.69, 0.192 at 200; Braza, Chassaing
& Ha Minh 1986, J. Fluid Mech. 165:79; Williamson 1996, Annu. Rev. Fluid Mech. 28:477, for
the Strouhal number).

Each run writes its series docs/validation/cylinder_re<Re>_n<D/Δx>.csv, its figures
(.json) and its last vorticity field (cylinder_vorticity_re<Re>_n<D/Δx>.png); the summary
of all runs written so far is cylinder.csv, cylinder_table.md and cylinder_lift.png;
docs/validation/cylinder.md reads them. Runs of different cases may go in parallel
processes (RAYON_NUM_THREADS=1 each); --summary then rebuilds the table.

Usage: python3 examples/validation/cylinder.py [--re 100 200] [--n 20 30] [--end 60]
       [--window 25] [--summary]
"""
import argparse
import json
import math
import pathlib
import tomllib

import numpy as np
from scipy.signal import butter, filtfilt
from scipy.spatial import cKDTree

import deltasph as ds
from records import plot_forces, write_csv, write_table
from sampling import Sampler, body_force

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
D, U, RHO0, H = 1.0, 1.0, 1.0, 8.0
SAMPLE = 0.05
#: the lift's low-pass cut-off [U/D]
SMOOTHING = 1.0
Q = 0.5 * RHO0 * U**2 * D
REFERENCE = {100: (1.350, 0.339, 0.164), 200: (1.31, 0.69, 0.192)}


def config(re, n, end):
    with open(HERE / "cylinder.toml", "rb") as f:
        cfg = tomllib.load(f)
    cfg["particles"]["spacing"] = D / n
    cfg["scheme"]["dynamic_viscosity"] = RHO0 * U * D / re
    cfg["time"]["end"] = end
    cfg["time"]["output_interval"] = 0.0
    return cfg


def run(re, n, end):
    """Runs the case to `end` and returns its time series (t, C_D, C_L) and the
    simulation."""
    sim = ds.Simulation(config(re, n, end))
    series = []
    sampler = Sampler(sim, end, SAMPLE)
    for _ in sampler:
        force = body_force(sim, "cylinder")
        series.append((sim.time, force[0] / Q, force[1] / Q))
        if len(series) % 200 == 0:
            print(f"  Re {re} D/Δx {n}: t = {sim.time:.1f}, C_D {force[0] / Q:.3f}, "
                  f"C_L {force[1] / Q:.3f}, {sampler.wall:.0f} s", flush=True)
    return np.array(series), sim, sampler.wall, sampler.rate


def upward_crossings(t, c):
    """Times where c crosses its mean upwards, linearly interpolated."""
    c = c - c.mean()
    k = np.nonzero((c[:-1] < 0) & (c[1:] >= 0))[0]
    return t[k] - c[k] * (t[k + 1] - t[k]) / (c[k + 1] - c[k])


def coefficients(series, end, window):
    """St, mean C_D and C_L' over whole lift periods of the last `window` D/U; the lift
    low-passed first (SMOOTHING)."""
    t, cd, cl = series.T
    cl = smooth(cl, t[1] - t[0])
    keep = t >= end - window - 1e-9
    t, cd, cl = t[keep], cd[keep], cl[keep]
    up = upward_crossings(t, cl)
    if len(up) < 3:
        return {"st": float("nan"), "cd": float(cd.mean()), "cl": float("nan"), "periods": 0}
    period = np.diff(up)
    inside = (t >= up[0]) & (t < up[-1])
    swings = [np.ptp(cl[(t >= a) & (t < b)]) for a, b in zip(up, up[1:])]
    return {
        "st": float(D / (U * period.mean())),
        "cd": float(cd[inside].mean()),
        "cl": float(0.5 * np.mean(swings)),
        "periods": len(period),
    }


def smooth(signal, dt):
    """The signal through a zero-phase 4th-order Butterworth low-pass at SMOOTHING U/D:
    five times the shedding frequency, far below the acoustic noise of the loads."""
    b, a = butter(4, SMOOTHING, fs=1.0 / dt)
    return filtfilt(b, a, signal)


def corrected(figures):
    """The coefficients scaled to the stream speed at the body, U(1 + ε)."""
    eps = math.pi**2 / 12 * (D / H) ** 2 + D / (4 * H) * figures["cd"]
    return {"eps": eps, "cd_c": figures["cd"] / (1 + eps) ** 2,
            "cl_c": figures["cl"] / (1 + eps) ** 2, "st_c": figures["st"] / (1 + eps)}


COLUMNS = ["re", "n", "particles", "steps", "wall_s", "particle_steps_per_s", "periods",
           "cd", "cl", "st", "eps", "cd_c", "cl_c", "st_c"]


def write(results):
    OUT.mkdir(parents=True, exist_ok=True)
    write_csv(OUT / "cylinder.csv", COLUMNS, results)
    header = ["Re", "D/Δx", "particles", "C_D", "C_L'", "St", "ε", "C_D corr.", "C_L' corr.",
              "St corr.", "reference C_D, C_L', St", "periods", "steps", "wall [s]",
              "particle-steps/s"]
    rows = [[f"{r['re']}", f"{r['n']}", f"{r['particles']}", f"{r['cd']:.3f}",
             f"{r['cl']:.3f}", f"{r['st']:.3f}", f"{r['eps']:.3f}", f"{r['cd_c']:.3f}",
             f"{r['cl_c']:.3f}", f"{r['st_c']:.3f}",
             ", ".join(f"{v:g}" for v in REFERENCE[r["re"]]), f"{r['periods']}",
             f"{r['steps']}", f"{r['wall_s']:.0f}", f"{r['particle_steps_per_s']:.3g}"]
            for r in results]
    write_table(OUT / "cylinder_table.md", header, rows)


def plot_series(results):
    curves = []
    for r in results:
        t, cd, cl = np.loadtxt(series_file(r["re"], r["n"]), delimiter=",", skiprows=1).T
        curves.append((f"Re {r['re']}, D/Δx {r['n']}", t, cd, cl))
    plot_forces(OUT / "cylinder_lift.png", curves,
                "Cylinder: drag and lift coefficients (pressure + viscous), raw", "t U/D",
                drag_limits=(0.8, 2.5))


def plot_vorticity(sim, re, n):
    """The run's last vorticity field, cylinder_vorticity_re<Re>_n<D/Δx>.png."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(9, 4))
    fluid = sim.kind == ds.FLUID
    x = sim.positions[fluid]
    w = vorticity(sim)[fluid]
    sc = ax.scatter(x[:, 0], x[:, 1], c=w, s=0.2, cmap="RdBu_r", vmin=-3, vmax=3)
    ax.add_patch(plt.Circle((0, 0), 0.5 * D, color="0.3"))
    ax.set_aspect("equal")
    ax.set_title(f"Re {re}, D/Δx {n}, t U/D = {sim.time:.0f}")
    ax.set_xlabel("x / D")
    ax.set_ylabel("y / D")
    fig.colorbar(sc, ax=ax, label="ω D/U")
    fig.tight_layout()
    fig.savefig(OUT / f"cylinder_vorticity_re{re}_n{n}.png", dpi=120)
    plt.close(fig)


def series_file(re, n):
    return OUT / f"cylinder_re{re}_n{n}.csv"


def vorticity(sim, k=12):
    """ω = ∂v/∂x - ∂u/∂y at each particle: the least-squares velocity gradient over its
    k nearest neighbours (walls included), G = (Σ Δu Δxᵀ)(Σ Δx Δxᵀ)⁻¹, exact for a
    linear field; NaN on the rows of removed particles."""
    here = np.isfinite(sim.positions[:, 0])
    x, u = sim.positions[here], sim.velocities[here]
    near = cKDTree(x).query(x, k=k + 1)[1][:, 1:]
    dx, du = x[near] - x[:, None, :], u[near] - u[:, None, :]
    moment = np.einsum("nki,nkj->nij", dx, dx)
    grad = np.einsum("nki,nkj->nij", du, dx) @ np.linalg.inv(moment)
    out = np.full(len(here), np.nan)
    out[here] = grad[:, 1, 0] - grad[:, 0, 1]
    return out


def summary():
    """The table and the lift plot from every run's files in docs/validation."""
    results = []
    for meta in sorted(OUT.glob("cylinder_re*_n*.json")):
        r = json.loads(meta.read_text())
        series = np.loadtxt(series_file(r["re"], r["n"]), delimiter=",", skiprows=1)
        r.update(coefficients(series, r["end"], r["window"]))
        r.update(corrected(r))
        results.append(r)
    results.sort(key=lambda r: (r["re"], r["n"]))
    write(results)
    plot_series(results)


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--re", type=int, nargs="+", default=[100, 200], choices=[100, 200])
    parser.add_argument("--n", type=int, nargs="+", default=[20, 30])
    parser.add_argument("--end", type=float, default=60.0, help="end time [D/U]")
    parser.add_argument("--window", type=float, default=25.0,
                        help="the averaging window at the run's end [D/U]")
    parser.add_argument("--summary", action="store_true",
                        help="only the table and plot from the runs already written")
    args = parser.parse_args()
    OUT.mkdir(parents=True, exist_ok=True)
    for re in [] if args.summary else args.re:
        for n in args.n:
            series, sim, wall, rate = run(re, n, args.end)
            np.savetxt(series_file(re, n), series, delimiter=",", header="t,cd,cl",
                       comments="", fmt="%.6g")
            meta = {"re": re, "n": n, "end": args.end, "window": args.window,
                    "particles": sim.n_particles, "steps": sim.n_steps, "wall_s": wall,
                    "particle_steps_per_s": rate}
            (OUT / f"cylinder_re{re}_n{n}.json").write_text(json.dumps(meta, indent=1))
            plot_vorticity(sim, re, n)
            print(meta, coefficients(series, args.end, args.window), flush=True)
    summary()


if __name__ == "__main__":
    main()
