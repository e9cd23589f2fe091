"""Walls hold: runs every example and validation case that has walls, at its own
resolution and to its end time, and counts the fluid particles inside a wall after
every step (`Simulation.wall_crossings`: past the first layer of wall particles of a
closed face). Prints one line per case and exits with status 1 if any step of any case
had a crossing.

    python3 scripts/wall_crossings.py                    # every case (the 3D Poiseuille slab,
                                                         # to t = 1 s at viscous time steps,
                                                         # alone takes over ten minutes)
    python3 scripts/wall_crossings.py dam_break_2d cavity  # about 4 minutes on 2 cores
"""

import pathlib
import sys
import time
import tomllib

import deltasph as ds

ROOT = pathlib.Path(__file__).resolve().parent.parent


def cases(names):
    files = sorted((ROOT / "examples").glob("*.toml"))
    files += sorted((ROOT / "examples" / "validation").glob("*.toml"))
    for path in files:
        with open(path, "rb") as f:
            config = tomllib.load(f)
        if not (config.get("tank") or config.get("wall")):
            continue
        if names and path.stem not in names:
            continue
        yield path, config


def worst_crossings(config):
    sim = ds.Simulation(config)
    end = config["time"]["end"]
    worst, first, steps_with = 0, None, 0
    while sim.time < end * (1.0 - 1e-12):
        sim.step(1)
        n = sim.wall_crossings()
        if n:
            steps_with += 1
            first = sim.time if first is None else first
        worst = max(worst, n)
    return sim, worst, first, steps_with


def main():
    failed = False
    for path, config in cases(set(sys.argv[1:])):
        start = time.perf_counter()
        sim, worst, first, steps_with = worst_crossings(config)
        where = "" if first is None else f", first at t = {first:.4f} s, in {steps_with} steps"
        print(f"{path.relative_to(ROOT)}: {sim.n_fluid} fluid particles, {sim.n_steps} steps "
              f"to t = {sim.time:.4g} s: at most {worst} inside a wall{where} "
              f"({time.perf_counter() - start:.0f} s)", flush=True)
        failed |= worst > 0
    sys.exit(1 if failed else 0)


if __name__ == "__main__":
    main()
