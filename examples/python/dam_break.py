"""2D dam break (δ-SPH benchmark) driven from Python.

Runs examples/dam_break_2d.toml, then plots the pressure field coloured on the
particles at a few instants and the wall-pressure signal at probe P1, saving PNGs
into a new folder (never over an existing one).

    python examples/python/dam_break.py                 # H/Δx = 50, t·sqrt(g/H) to 7
    python examples/python/dam_break.py --spacing 0.02  # coarser and quicker
"""

from __future__ import annotations

import argparse
import datetime
import pathlib
import sys
from typing import Any, List, Optional

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import deltasph as ds  # noqa: E402
from deltasph import plot  # noqa: E402

if sys.version_info >= (3, 11):
    import tomllib
else:  # 3.9 and 3.10: pip install tomli
    import tomli as tomllib

HERE = pathlib.Path(__file__).resolve().parent
CASE = HERE.parent / "dam_break_2d.toml"
#: Marrone et al. (2011)'s P1 figure, digitised (experiment and δ-SPH), where present
MARRONE = HERE.parents[1] / "docs" / "validation" / "data" / "dambreak2d_marrone2011_P1.csv"
H, G, RHO0 = 0.6, 9.81, 1000.0
P1 = (3.2196, 0.12)


def arguments() -> argparse.Namespace:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--spacing", type=float, help="particle spacing Δx [m] (case: 0.012)")
    parser.add_argument("--until", type=float, default=7.0, help="end time in t·sqrt(g/H)")
    parser.add_argument("--out", type=pathlib.Path, help="new folder for the PNGs")
    return parser.parse_args()


def new_folder(out: Optional[pathlib.Path]) -> pathlib.Path:
    stamp = datetime.datetime.now().strftime("%Y%m%d-%H%M%S")
    out = out or pathlib.Path("out") / f"python_dam_break-{stamp}"
    out.mkdir(parents=True, exist_ok=False)
    return out


def main() -> None:
    args = arguments()
    out = new_folder(args.out)
    sim = ds.Simulation.from_toml(CASE)
    if args.spacing:
        config = tomllib.loads(sim.to_toml())
        config["particles"]["spacing"] = args.spacing
        sim = ds.Simulation(config)
    print(sim)
    t_ref = np.sqrt(H / G)
    frames = [1.5, 4.0, 6.0]
    times: List[float] = []
    p1: List[float] = []
    fig, axes = plt.subplots(len(frames), 1, figsize=(8, 8.5), constrained_layout=True)
    frame = 0
    for t_star in np.arange(0.02, args.until + 1e-9, 0.02):
        sim.run(until=t_star * t_ref, progress=False)
        times.append(float(t_star))
        p1.append(float(sim.probe_pressure(P1)[0]) / (RHO0 * G * H))
        if frame < len(frames) and t_star >= frames[frame] - 1e-9:
            draw_pressure(axes[frame], sim, t_star)
            frame += 1
    for ax in axes[frame:]:
        ax.set_visible(False)
    fig.savefig(out / "pressure_field.png", dpi=130)
    plot_p1(times, p1, out / "p1_pressure.png")
    print(f"{sim.n_steps} steps; PNGs in {out}")


def draw_pressure(ax: Any, sim: ds.Simulation, t_star: float) -> None:
    plot.snapshot(sim, "pressure", ax=ax, scale=1.0 / (RHO0 * G * H), label="p / ρ0 g H",
                  vmin=0.0, vmax=1.0)
    ax.set_title(f"t·sqrt(g/H) = {t_star:.1f}")


def plot_p1(times: List[float], p1: List[float], path: pathlib.Path) -> None:
    fig, ax = plt.subplots(figsize=(8, 4), constrained_layout=True)
    if MARRONE.exists():
        ref = np.loadtxt(MARRONE, delimiter=",", comments="#", skiprows=5)
        ax.plot(ref[:, 0], ref[:, 1], "k.", ms=2, label="Buchner (2002), as in Marrone et al.")
        ax.plot(ref[:, 0], ref[:, 4], "k-", lw=0.8, label="Marrone et al. (2011), H/Δx = 320")
    ax.plot(times, p1, label="deltasph, P1 (Shepard probe)")
    ax.set_xlabel("t·sqrt(g/H)")
    ax.set_ylabel("p / ρ0 g H")
    ax.set_title("Dam break: pressure on the right wall at y = 0.2H = 0.12 m")
    ax.legend()
    fig.savefig(path, dpi=130)


if __name__ == "__main__":
    main()
