#!/usr/bin/env python3
"""Work-precision of the kernel and its support: the error each kernel reaches against
the wall time it takes, on validation cases, with the default scheme (δ-SPH, RK4; δ+-SPH
for the Taylor-Green vortex, which needs shifting).

Kernels: Wendland C2 at h/Δx = 1.33, 1.6 and 2, Wendland C4 at h/Δx = 2, the quintic
spline at h/Δx = 1 (support 3Δx). The wall layers are the default, enough to cover each
support. Writes docs/validation/kernel_study.md and .csv; prints the table as it goes.

Usage: python3 examples/validation/kernel_study.py [--full] [--report]   (2 threads,
quiet machine)
"""
import argparse
import csv
import math
import os
import pathlib
import sys
import time

import deltasph as ds

HERE = pathlib.Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))
import cases  # noqa: E402

OUT = HERE.parents[1] / "docs" / "validation"
KERNELS = [
    ("Wendland C2", "wendland_c2", 1.33),
    ("Wendland C2", "wendland_c2", 1.6),
    ("Wendland C2", "wendland_c2", 2.0),
    ("Wendland C4", "wendland_c4", 2.0),
    ("quintic spline", "quintic_spline", 1.0),
]
#: (case, variant, resolutions quick, resolutions full, measure)
STUDY = [
    ("poiseuille_2d", ("δ-SPH", "RK4"), [10, 20, 30], [10, 20, 40],
     lambda s: cases.poiseuille(s, 0.3)),
    ("couette_2d", ("δ-SPH", "RK4"), [10, 20, 30], [10, 20, 40],
     lambda s: cases.couette(s, 0.1)),
    ("hydrostatic", ("δ-SPH", "RK4"), [10, 20, 30], [10, 20, 40], None),
    ("taylor_green_re100", ("δ+-SPH", "RK4"), [25, 50], [25, 50, 75], None),
    ("standing_wave", ("δ-SPH", "RK4"), [10, 20, 40], [10, 20, 40, 60], None),
    ("dam_break_p1", ("δ-SPH", "RK4"), [15, 20, 30], [15, 20, 30, 50], None),
]
#: cases of the study outside the validation suite
EXTRA = [
    cases.Case("couette_2d", "Start-up Couette flow (ν t/L² = 0.1)", "couette_2d.toml",
               {}, 1e-3, "RMS error of u / U", None),
    cases.Case("standing_wave", "Standing wave in a closed tank (4 periods): "
               "|Δω + iΔγ|/ω against linear theory", "standing_wave.toml", {}, 0.5,
               "complex frequency error", cases.standing_wave),
    cases.Case("dam_break_p1", "Dam break, P1 at y = 0.2H against Marrone et al. (2011)'s "
               "δ-SPH at H/Δx = 320: RMS of p/ρ0gH over t* 2.3-7", "dam_break.toml", {}, 0.6,
               "RMS of p/ρ0gH", cases.dam_break_marrone),
]


def case_of(name):
    return next(c for c in EXTRA + cases.CASES if c.name == name)


def run_one(case, variant, n, kernel, h_over_dx, measure):
    config = case.config(n, *variant)
    config["particles"]["kernel"] = kernel
    config["particles"]["h_over_dx"] = h_over_dx
    for tank in config.get("tank", []):
        tank.pop("layers", None)
    sim = ds.Simulation(config)
    start = time.perf_counter()
    try:
        metrics = (measure or case.measure)(sim)
    except ds.InstabilityError as e:
        print(f"  unstable: {str(e).splitlines()[0]}")
        metrics = {"error": math.nan}
    details = "; ".join(f"{k} = {v:.4g}" for k, v in metrics.items()
                        if k != "error" and isinstance(v, float))
    return metrics["error"], time.perf_counter() - start, details


def equal_time_error(points, budget):
    """The error at wall time `budget`, interpolated in log-log between the runs around it
    (None outside the runs' span)."""
    points = sorted((t, e) for t, e in points if e > 0)  # NaN (unstable) drops out
    for (t0, e0), (t1, e1) in zip(points, points[1:]):
        if t0 <= budget <= t1:
            w = math.log(budget / t0) / math.log(t1 / t0) if t1 > t0 else 0.0
            return math.exp(math.log(e0) + w * (math.log(e1) - math.log(e0)))
    return None


def cell(error):
    return "unstable" if math.isnan(error) else f"{error:.3g}"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--full", action="store_true")
    ap.add_argument("--report", action="store_true",
                    help="rewrite kernel_study.md from kernel_study.csv without running")
    ap.add_argument("--only", nargs="+", metavar="CASE",
                    help="run only these cases; the other cases' rows stay from the csv")
    args = ap.parse_args()
    kept = stored_rows() if args.report or args.only else []
    if args.report:
        write(kept)
        return
    os.environ.setdefault("RAYON_NUM_THREADS", "2")
    rows = [r for r in kept if r["case"] not in args.only] if args.only else []
    print(f"{'case':<20} {'kernel':<15} {'h/dx':>5} {'n':>4} {'error':>10} {'wall s':>8}")
    for name, variant, quick, full, measure in STUDY:
        if args.only and name not in args.only:
            continue
        case = case_of(name)
        for label, kernel, h_dx in KERNELS:
            for n in full if args.full else quick:
                error, wall, details = run_one(case, variant, n, kernel, h_dx, measure)
                rows.append({"case": name, "kernel": label, "h_over_dx": h_dx, "n": n,
                             "error": error, "wall_s": wall, "details": details})
                print(f"{name:<20} {label:<15} {h_dx:>5} {n:>4} {error:>10.4g} {wall:>8.2f}"
                      f"  {details}", flush=True)
    order = [s[0] for s in STUDY]
    write(sorted(rows, key=lambda r: order.index(r["case"])))


def stored_rows():
    with open(OUT / "kernel_study.csv", newline="") as f:
        return [{**r, "h_over_dx": float(r["h_over_dx"]), "n": int(r["n"]),
                 "error": float(r["error"]), "wall_s": float(r["wall_s"]),
                 "details": r.get("details") or ""}
                for r in csv.DictReader(f)]


def write(rows):
    OUT.mkdir(parents=True, exist_ok=True)
    with open(OUT / "kernel_study.csv", "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    lines = ["# Kernel and support: work-precision", "",
             "Written by `python3 examples/validation/kernel_study.py` (2 threads). Error "
             "against wall time for each kernel; the last columns give the error each "
             "reaches at equal wall time (log-log interpolation between its runs; "
             "— where its runs do not span that time). A run the stability guard stopped "
             "reads unstable.", "",
             "The default taken from these tables is Wendland C2 at h/Δx = 2. Among the "
             "kernels stable in every case (Wendland C4 is not, next to no-slip walls) it has "
             "the lowest error in the viscous flows, by 2.2× or more; it is within 1.2× of the "
             "lowest in the Taylor-Green vortex and the dam break, within 1.2-1.8× in the "
             "hydrostatic tank and 1.3-1.4× in the standing wave, where the quintic spline "
             "leads (4× worse than Wendland C2 at 2 in the viscous flows). The README's "
             "Validation section gives the comparison.", ""]
    for name in dict.fromkeys(r["case"] for r in rows):
        mine = [r for r in rows if r["case"] == name]
        budgets = sorted(r["wall_s"] for r in mine
                         if r["kernel"] == "Wendland C2" and r["h_over_dx"] == 1.33)[1:]
        lines += [f"## {case_of(name).title}", "",
                  "| kernel | h/Δx | runs (n: error, wall s) | "
                  + " | ".join(f"error at {b:.2f} s" for b in budgets) + " |",
                  "|---|---|---|" + "---|" * len(budgets)]
        for label, _, h_dx in KERNELS:
            runs = [r for r in mine if r["kernel"] == label and r["h_over_dx"] == h_dx]
            points = [(r["wall_s"], r["error"]) for r in runs]
            at = [equal_time_error(points, b) for b in budgets]
            lines.append(f"| {label} | {h_dx} | "
                         + "; ".join(f"{r['n']}: {cell(r['error'])}, {r['wall_s']:.1f}"
                                     for r in runs) + " | "
                         + " | ".join("—" if e is None else f"{e:.3g}" for e in at) + " |")
        lines.append("")
        if any(r["details"] for r in mine):
            lines += ["| kernel | h/Δx | finest run: n, other figures |", "|---|---|---|"]
            for label, _, h_dx in KERNELS:
                runs = [r for r in mine if r["kernel"] == label and r["h_over_dx"] == h_dx]
                if runs:
                    r = max(runs, key=lambda r: r["n"])
                    lines.append(f"| {label} | {h_dx} | {r['n']}: {r['details'] or '—'} |")
            lines.append("")
    (OUT / "kernel_study.md").write_text("\n".join(lines))


if __name__ == "__main__":
    main()
