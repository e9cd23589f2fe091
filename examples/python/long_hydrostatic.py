"""A hydrostatic tank held for a long time: t·sqrt(g/H) = 200 with δ-SPH.

Runs examples/hydrostatic_2d.toml (water of depth H = 1 m at rest in a tank 2H wide,
δ = 0.1, α = 0.02, RK4 at CFL 1.5) and every Δt* = 1 records:
- the drift of the free surface: the mean height of the top particle layer minus its
  initial value, in Δx;
- the spurious currents: the largest fluid speed, in sqrt(gH);
- the pressure error: the L2 norm over the fluid of p − ρ0 g (H − y), in ρ0 g H.
Prints the worst of each after t* = 20 (the initial acoustic transient; half the run
when it is shorter) and plots the three against time.

    python examples/python/long_hydrostatic.py                  # H/Δx = 20, about a minute on 2 cores
    python examples/python/long_hydrostatic.py --spacing 0.025  # H/Δx = 40, about 8 minutes
"""

from __future__ import annotations

import argparse
import datetime
import pathlib
import sys
from typing import Any, List, Tuple

if sys.version_info >= (3, 11):
    import tomllib
else:  # 3.9 and 3.10: pip install tomli
    import tomli as tomllib

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import deltasph as ds  # noqa: E402

CASE = pathlib.Path(__file__).resolve().parent.parent / "hydrostatic_2d.toml"
RHO0, G, H = 1000.0, 9.81, 1.0


def arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spacing", type=float, default=0.05, help="Δx [m]")
    parser.add_argument("--until", type=float, default=200.0, help="end, in t·sqrt(g/H)")
    parser.add_argument("--out", type=pathlib.Path, help="new folder for the PNG")
    return parser.parse_args()


def top_layer(y: Any, dx: float) -> float:
    """Mean height of the particles within Δx/2 of the highest one."""
    return float(y[y > y.max() - 0.5 * dx].mean())


def main() -> None:
    args = arguments()
    with open(CASE, "rb") as f:
        config = tomllib.load(f)
    dx = args.spacing
    config["particles"]["spacing"] = dx
    config["time"]["end"] = args.until * np.sqrt(H / G)
    sim = ds.Simulation(config)
    fluid = sim.kind == ds.FLUID
    top0 = top_layer(sim.positions[fluid, 1], dx)
    history: List[Tuple[float, float, float, float]] = []
    for t_star in np.arange(1.0, args.until + 1e-9, 1.0):
        sim.run(until=t_star * np.sqrt(H / G))
        x, p = sim.positions[fluid], sim.pressure[fluid]
        speed = np.linalg.norm(sim.velocities[fluid], axis=1).max()
        error = np.sqrt(np.mean((p - RHO0 * G * (H - x[:, 1])) ** 2)) / (RHO0 * G * H)
        history.append((t_star, (top_layer(x[:, 1], dx) - top0) / dx, speed / np.sqrt(G * H),
                     error))
    rows = np.array(history)
    settled = 20.0 if args.until > 20.0 else 0.5 * args.until  # past the first transient
    late = rows[rows[:, 0] >= settled]
    print(f"H/Δx = {H / dx:g}, {sim.n_fluid} fluid particles, {sim.n_steps} steps to "
          f"t·sqrt(g/H) = {args.until:g}. After t* = {settled:g}: surface drift at most "
          f"{np.abs(late[:, 1]).max():.3f} Δx (at the end {rows[-1, 1]:+.3f}), largest speed "
          f"{late[:, 2].max():.2e} sqrt(gH), L2 pressure error at most "
          f"{late[:, 3].max():.4f} ρ0gH (at the end {rows[-1, 3]:.4f})")
    stamp = datetime.datetime.now().strftime("%Y%m%d-%H%M%S")
    out = args.out or pathlib.Path("out") / f"python_long_hydrostatic-{stamp}"
    out.mkdir(parents=True, exist_ok=False)
    fig, axes = plt.subplots(3, 1, figsize=(8, 7), sharex=True, constrained_layout=True)
    labels = ["surface drift / Δx", "max |u| / sqrt(gH)", "L2 error of p / ρ0gH"]
    for ax, col, label in zip(axes, (1, 2, 3), labels):
        ax.plot(rows[:, 0], rows[:, col])
        ax.set_ylabel(label)
    axes[1].set_yscale("log")
    axes[-1].set_xlabel("t·sqrt(g/H)")
    fig.suptitle(f"Hydrostatic tank, δ-SPH, H/Δx = {H / dx:g}")
    fig.savefig(out / "long_hydrostatic.png", dpi=130)
    print(f"PNG in {out}")


if __name__ == "__main__":
    main()
