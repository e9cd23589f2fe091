"""docs/theory.md §13 V3 from a finished run: the forced-then-decaying cell array at Re = 10⁴.

Run the case first (t = 3, snapshots every 0.1; about 9 minutes on 2 cores):

    sph-cli run examples/les_forced_cells.toml --until 3 --out v3_out

then `python3 examples/validation/les_forced_cells.py v3_out` prints E at t = 1, 2 and
2.85 against the windows of docs/theory.md §13 and writes docs/validation/les_v3.png: E(t) against the
forced mode's ODE (with the run's eddy viscosity, and laminar), and the vorticity at
t = 1, 1.5, 2 and 3 (the velocity gridded onto the 100² cell centres by the kernel, as
in decaying_turbulence.py, and differentiated spectrally).
"""

import argparse
import csv
import pathlib
import sys
import tomllib

import h5py
import matplotlib
import numpy as np
from scipy.integrate import solve_ivp

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(pathlib.Path(__file__).parent))
import decaying_turbulence as dt  # noqa: E402

DOCS = pathlib.Path(__file__).resolve().parents[2] / "docs" / "validation"
#: docs/theory.md §13 V3's windows at L/Δx = 100: (t, lowest, highest)
WINDOWS = [(1.0, 0.285, np.inf), (2.0, 0.195, 0.245), (2.85, 0.160, 0.200)]


def mode_energy(case, cs_l, until):
    """E = a²/4 of the forced mode, da/dt = A r(t) − 2νk²a − 2.88 (C_S l)² k³ a², with
    the case's forcing constants (A, k, T, t_off) and viscosity."""
    c = case["forcing"]["constants"]
    nu = case["scheme"]["dynamic_viscosity"] / case["fluid"]["density"]

    def rate(t, a):
        ramp = 0.5 * (1.0 - np.cos(np.pi * min(t / c["T"], 1.0))) if t < c["t_off"] else 0.0
        return [c["A"] * ramp - 2 * nu * c["k"] ** 2 * a[0] - 2.88 * cs_l**2 * c["k"] ** 3 * a[0] ** 2]

    sol = solve_ivp(rate, (0.0, until), [0.0], rtol=1e-10, atol=1e-12, max_step=1e-3,
                    dense_output=True)
    return lambda t: sol.sol(t)[0] ** 2 / 4.0


def snapshot_at(folder, t):
    """Positions, volumes and velocities of the snapshot nearest time t (XDMF index)."""
    index = (folder / "particles.xmf").read_text()
    times = [float(v) for v in index.split('<Time Value="')[1:] for v in [v.split('"')[0]]]
    i = int(np.argmin(np.abs(np.array(times) - t)))
    with h5py.File(folder / f"particles_{i:06d}.h5") as f:
        x, u, rho = f["position"][:], f["velocity"][:], f["density"][:]
    return x, rho, u


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("folder", type=pathlib.Path, help="the run's output folder")
    args = parser.parse_args()
    case = tomllib.loads((args.folder / "case.toml").read_text())
    rows = list(csv.DictReader(open(args.folder / "timeseries.csv")))
    t = np.array([float(r["time"]) for r in rows])
    e = np.array([float(r["kinetic"]) for r in rows])
    dx = case["particles"]["spacing"]
    cs_l = case["scheme"].get("smagorinsky_constant", 0.12) * case["scheme"].get("les_length", dx)
    closure, laminar = mode_energy(case, cs_l, t[-1]), mode_energy(case, 0.0, t[-1])
    for when, lo, hi in WINDOWS:
        got = np.interp(when, t, e)
        verdict = "pass" if lo <= got <= hi else "FAIL"
        print(f"E({when}) = {got:.4f}, window [{lo}, {hi}]: {verdict} "
              f"(forced mode with closure {closure(when):.4f}, laminar {laminar(when):.4f})")
    fig = plt.figure(figsize=(13, 7))
    ax = fig.add_subplot(2, 3, (1, 4))
    ax.plot(t, e, "k", label=f"δ-LES-SPH, L/Δx = {1 / dx:.0f}")
    s = np.linspace(0.0, t[-1], 600)
    ax.plot(s, closure(s), "C0--", label="forced mode, ODE with ν_T")
    ax.plot(s, laminar(s), "C1:", label="forced mode, laminar")
    for when, lo, hi in WINDOWS:
        ax.plot([when, when], [lo, min(hi, 0.4)], "C3", lw=4, alpha=0.5)
    ax.set_xlabel("t U/L")
    ax.set_ylabel("E / (ρ0 U² L²)")
    ax.set_title("V3 energy (red bars: the windows of docs/theory.md §13)")
    ax.legend(fontsize=8)
    n = round(1.0 / dx)
    for slot, when in zip([2, 3, 5, 6], [1.0, 1.5, 2.0, 3.0]):
        x, rho, u = snapshot_at(args.folder, when)
        volumes = dx**2 * case["fluid"]["density"] / rho
        w = dt.tf.vorticity_on_grid(*dt.gridded(x, volumes, u, n))
        a = fig.add_subplot(2, 3, slot)
        a.imshow(w, origin="lower", extent=[0, 1, 0, 1], cmap="RdBu_r", vmin=-40, vmax=40)
        a.set_title(f"ω at t = {when}")
        a.set_xticks([])
        a.set_yticks([])
    fig.tight_layout()
    DOCS.mkdir(parents=True, exist_ok=True)
    fig.savefig(DOCS / "les_v3.png", dpi=80)
    print(f"wrote {DOCS / 'les_v3.png'}")


if __name__ == "__main__":
    main()
