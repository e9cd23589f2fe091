"""Runs the validation suite and writes the work-precision report.

Every case of `cases.py` at each resolution and scheme variant: wall time of the
stepping, particle-steps/s, the error against the reference, and whether it stayed
stable. Writes `results.csv`, one PNG per case (error against wall time; error against
Δx with the fitted order) and `README.md` into the output folder.

    python3 examples/validation/run_all.py --quick    # < 10 min on 2 cores
    python3 examples/validation/run_all.py --full     # the record (hours)
    python3 examples/validation/run_all.py --quick --cases hydrostatic elliptic_drop
"""

import argparse
import csv
import math
import pathlib
import sys
import time

import deltasph as ds

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parent))
from cases import CASES  # noqa: E402
import report  # noqa: E402

ROOT = pathlib.Path(__file__).resolve().parents[2]
COLUMNS = ["case", "diffusion", "integrator", "resolution", "spacing", "particles", "steps",
           "wall_s", "particle_steps_per_s", "stable", "error", "details"]


def arguments():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    mode = parser.add_mutually_exclusive_group()
    mode.add_argument("--quick", action="store_const", dest="mode", const="quick")
    mode.add_argument("--full", action="store_const", dest="mode", const="full")
    parser.add_argument("--cases", nargs="+", choices=[c.name for c in CASES])
    parser.add_argument("--out", type=pathlib.Path, default=ROOT / "docs" / "validation")
    args = parser.parse_args()
    args.mode = args.mode or "quick"
    return args


def run_one(case, n, diffusion, integrator):
    """One run; returns the CSV row and the measured extras (signals included)."""
    sim = ds.Simulation(case.config(n, diffusion, integrator))
    start = time.perf_counter()
    try:
        metrics, stable = case.measure(sim), True
    except ds.InstabilityError as err:
        metrics, stable = {"error": math.nan, "blew_up_at": err.time}, False
    wall = time.perf_counter() - start
    details = {k: v for k, v in metrics.items() if k not in ("error", "signal")}
    row = {
        "case": case.name, "diffusion": diffusion, "integrator": integrator,
        "resolution": n, "spacing": sim.spacing, "particles": sim.n_fluid,
        "steps": sim.n_steps, "wall_s": round(wall, 3),
        "particle_steps_per_s": round(sim.n_fluid * sim.n_steps / wall) if wall > 0 else 0,
        "stable": stable, "error": metrics["error"],
        "details": "; ".join(f"{k}={v:.4g}" for k, v in details.items()),
    }
    return row, metrics


def main():
    args = arguments()
    args.out.mkdir(parents=True, exist_ok=True)
    chosen = [c for c in CASES if not args.cases or c.name in args.cases]
    rows, signals = [], {}
    begin = time.perf_counter()
    for case in chosen:
        for diffusion, integrator in case.variants[args.mode]:
            for n in case.resolutions[args.mode]:
                row, metrics = run_one(case, n, diffusion, integrator)
                rows.append(row)
                if "signal" in metrics:
                    signals[(case.name, diffusion, integrator, n)] = metrics["signal"]
                print(f"{case.name:20s} {diffusion:8s} {integrator:4s} {n:>6} "
                      f"{row['particles']:>7} particles {row['wall_s']:8.2f} s "
                      f"error {row['error']:.4g} {'' if row['stable'] else '(blew up)'}",
                      flush=True)
    total = time.perf_counter() - begin
    with open(args.out / "results.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)
    report.write(args.out, args.mode, chosen, rows, signals, total)
    print(f"{len(rows)} runs in {total:.0f} s; report in {args.out / 'README.md'}")


if __name__ == "__main__":
    main()
