"""Runs the validation suite and writes the work-precision report.

Every case of `cases.py` at each resolution and scheme variant: wall time of the
stepping, particle-steps/s, the error against the reference, and whether it stayed
stable. Writes `results.csv`, one PNG per case (error against wall time; error against
Δx with the fitted order) and `README.md` into the output folder.

    python3 examples/validation/run_all.py --quick    # < 10 min on 2 cores
    python3 examples/validation/run_all.py --full     # the record (about an hour)
    python3 examples/validation/run_all.py --quick --cases hydrostatic elliptic_drop
    python3 examples/validation/run_all.py --full --resume   # run only what is missing
"""

import argparse
import csv
import math
import pathlib
import sys
import json
import time

import deltasph as ds
import numpy as np

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
    parser.add_argument("--resume", action="store_true",
                        help="keep the runs already in the folder's results.csv (and their "
                             "signals) and run only the missing ones")
    parser.add_argument("--max-run-s", type=float,
                        help="skip a run whose wall time, predicted from the same variant at "
                             "the previous resolution, exceeds this many seconds (default: "
                             f"none with --quick, {FULL_CAP_S:g} s with --full; a case may "
                             "set its own)")
    args = parser.parse_args()
    args.mode = args.mode or "quick"
    return args


#: P1 signals of the dam-break runs, kept beside results.csv for --resume
SIGNALS = "signals.json"
#: per-run wall-time cap of --full [s]: keeps the record run near an hour on 2 cores
FULL_CAP_S = 90.0


def cap_for(case, args):
    if args.max_run_s is not None:
        return args.max_run_s
    if args.mode == "full":
        return case.cap or FULL_CAP_S
    return math.inf


def predicted_wall(case, previous, n):
    """Wall time of the run at resolution n from the previous run of the same variant:
    particles grow as n^dim and steps as n (fixed Courant number, h ∝ Δx)."""
    return previous["wall_s"] * (n / previous["resolution"]) ** (case.dim + 1)


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


def parse_row(raw):
    """A row of an earlier results.csv, with the types run_one gives."""
    row = dict(raw)
    for key in ("resolution", "spacing", "wall_s", "error"):
        row[key] = float(row[key])
    for key in ("particles", "steps", "particle_steps_per_s"):
        row[key] = int(row[key])
    row["stable"] = row["stable"] == "True"
    return row


def key_of(row):
    return (row["case"], row["diffusion"], row["integrator"], row["resolution"])


def earlier_results(out):
    """Rows and signals kept from an earlier run into the same folder (for --resume)."""
    rows, signals = {}, {}
    if (out / "results.csv").exists():
        with open(out / "results.csv", newline="") as f:
            rows = {key_of(r): r for r in map(parse_row, csv.DictReader(f))}
    if (out / SIGNALS).exists():
        stored = json.loads((out / SIGNALS).read_text())
        signals = {tuple(k.split("|")[:3]) + (float(k.split("|")[3]),): tuple(map(np.array, v))
                   for k, v in stored.items()}
    return rows, signals


def save_signals(out, signals):
    stored = {"|".join(map(str, k)): [t.tolist(), p.tolist()] for k, (t, p) in signals.items()}
    (out / SIGNALS).write_text(json.dumps(stored))


def write_csv(out, rows):
    """`results.csv`: every row so far (rewritten after each run, so that an
    interrupted record keeps what it ran for --resume)."""
    with open(out / "results.csv", "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=COLUMNS)
        writer.writeheader()
        writer.writerows(rows)


def main():
    args = arguments()
    args.out.mkdir(parents=True, exist_ok=True)
    chosen = [c for c in CASES if not args.cases or c.name in args.cases]
    done, signals = earlier_results(args.out) if args.resume else ({}, {})
    rows, skipped = [], []
    for case in chosen:
        cap = cap_for(case, args)
        for diffusion, integrator in case.variants[args.mode]:
            previous = None
            for n in case.resolutions[args.mode]:
                predicted = predicted_wall(case, previous, n) if previous else 0.0
                if predicted > cap:
                    skipped.append((case.name, diffusion, integrator, n, predicted, cap))
                    print(f"{case.name:20s} {diffusion:8s} {integrator:4s} {n:>6} skipped: "
                          f"predicted {predicted:.0f} s > {cap:g} s", flush=True)
                    break
                key = (case.name, diffusion, integrator, float(n))
                if key in done and (not case.records_signal or key in signals):
                    row = done[key]
                else:
                    row, metrics = run_one(case, n, diffusion, integrator)
                    if "signal" in metrics:
                        signals[key] = metrics["signal"]
                        save_signals(args.out, signals)
                rows.append(row)
                write_csv(args.out, rows)
                if row["stable"]:
                    previous = row
                print(f"{case.name:20s} {diffusion:8s} {integrator:4s} {n:>6} "
                      f"{row['particles']:>7} particles {row['wall_s']:8.2f} s "
                      f"error {row['error']:.4g} {'' if row['stable'] else '(blew up)'}",
                      flush=True)
    stepping = sum(r["wall_s"] for r in rows)
    report.write(args.out, args.mode, chosen, rows, signals, skipped, stepping)
    print(f"{len(rows)} runs, {stepping:.0f} s of stepping; report in {args.out / 'README.md'}")


if __name__ == "__main__":
    main()
