#!/usr/bin/env python3
"""Free decay of the NTNU ship section (examples/validation/floating_section.toml)
against linear theory and the experiment's natural periods.

Two starts, sway, heave and roll free (sway held by the experiment's weak springs):
released at rest 0.04 m (20% of the draft) above the draft (the case file), and
upright at the draft with a roll velocity of 0.5 rad/s given to the body in water at
rest (a kick to about 0.08 rad that leaves the section on the particle lattice it was
built on). Linear theory: Cummins'
equation with the section's added mass and damping from the panel method of
examples/validation/floating_section_theory.py
(docs/validation/data/floating_section_decay.csv). Compared:
- the natural period, the mean of the first three periods between up-crossings of the
  motion about its final mean (theory: heave 1.157 s, roll 1.261 s; the experiment's
  decay tests 1.17 s and 1.26 s, Sundsdal et al. 2025);
- the decay: the first positive peak after half a period, over the release (heave) or
  0.1 rad (roll), and the ratio of the next positive peak to it;
- the whole curve: the RMS difference over the first four periods, over the same scale;
- the equilibrium: the draft at rest (the mean over the last two seconds) against the
  still level the gauges 1 m either side measure (the level rises by the water the
  section pushes down), and the roll angle at rest.

Usage: python3 examples/validation/floating_section.py [--quick] [--scratch DIR]
[--reuse] [--set SECTION.KEY=VALUE ...] (2 threads: draft/Δx = 5, 10 and 15, about
25 min; --quick the coarsest only). Writes docs/validation/floating_section{.csv,
_table.md,_decay.png}.
"""
import pathlib

import numpy as np

import floating_section_theory as theory
import variants
from records import write_csv, write_table
from variants import load_case

HERE = pathlib.Path(__file__).resolve().parent
OUT = HERE.parents[1] / "docs" / "validation"
# the scale of each motion: the heave release, and about the roll the kick gives
SCALES = {"heave": theory.HEAVE_RELEASE, "roll": 0.1}
SETTLE = 2.0                       # s over which the final mean is taken
REFERENCE = OUT / "data" / "floating_section_decay.csv"


def config(dx, release, changes=()):
    """The case at spacing `dx` for the `release` ("heave": the case file; "roll": the
    section upright at its draft with the theory's roll kick), with `changes`
    ("section.key=value", the value in TOML) applied."""
    cfg = load_case(HERE / "floating_section.toml", changes)
    cfg["particles"]["spacing"] = dx
    cfg["time"]["output_interval"] = 0.0
    if release == "roll":
        body = cfg["shape"][0]
        lift = theory.HEAVE_RELEASE
        body["polygon"] = [[x, y - lift] for x, y in body["polygon"]]
        body["free"]["centre_of_mass"][1] -= lift
        body["free"]["angular_velocity"] = [theory.ROLL_KICK]
        for spring in body["free"]["springs"]:
            spring["point"][1] -= lift
            spring["anchor"][1] -= lift
    return cfg


def motion(series, release):
    """The released degree of freedom: the centre of mass's height or the angle."""
    return series["section_y"] if release == "heave" else series["section_angle"]


def positive_peaks(t, x):
    inner = (x[1:-1] > x[:-2]) & (x[1:-1] >= x[2:]) & (x[1:-1] > 0.0)
    return t[1:-1][inner], x[1:-1][inner]


def decay_measures(t, x, amplitude, period):
    """Mean of the first three up-crossing periods, the ratio of the second positive
    peak to the first after release, and the RMS of x over the first four periods (to
    compare curves, x less the theory's)."""
    periods = theory.crossing_periods(t, x)
    _, peaks = positive_peaks(t[t > 0.5 * period], x[t > 0.5 * period])
    return {"period": float(np.mean(periods[:3])), "peak_ratio": float(peaks[1] / peaks[0]),
            "first_peak": float(peaks[0] / amplitude)}


def analyse(series, release, predicted):
    """Measures of one run against the theory's curve `predicted` (t, x)."""
    t = series["time"]
    raw = motion(series, release)
    late = t >= t[-1] - SETTLE
    final = float(np.mean(raw[late]))
    x = raw - final
    amplitude = SCALES[release]
    period = 1.157 if release == "heave" else 1.261
    r = decay_measures(t, x, amplitude, period)
    early = t <= 4.0 * period
    expected = np.interp(t, predicted[0], predicted[1])
    r["rms"] = float(np.sqrt(np.mean((x[early] - expected[early]) ** 2)) / amplitude)
    level = np.mean(0.5 * (series["left_elevation"][late] + series["right_elevation"][late]))
    if release == "heave":
        # the draft at rest: the still level plus the gauges' rise less the keel's height
        keel = final - theory.KG
        r["draft_offset"] = float((1.0 + level - keel) / theory.DRAFT - 1.0)
    else:
        r["draft_offset"] = float(final)
    return r, t, x


def reference():
    """The theory's decay curves (examples/validation/floating_section_theory.py
    --write-decay): release → (t, x)."""
    with open(REFERENCE) as f:
        table = np.genfromtxt([line for line in f if not line.startswith("#")], delimiter=",", names=True)
    return {"heave": (table["t"], table["heave_release_heave"]),
            "roll": (table["t"], table["roll_kick_roll"])}


def plot(path, curves, predicted):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(2, 1, figsize=(8, 6), constrained_layout=True)
    for axis, release in zip(axes, ("heave", "roll")):
        amplitude = SCALES[release]
        t, x = predicted[release]
        keep = t <= 6.0
        axis.plot(t[keep], x[keep] / amplitude, "k--", lw=1.2, label="linear theory (Cummins)")
        for dx, (ts, xs) in sorted(curves[release].items(), reverse=True):
            keep = ts <= 6.0
            axis.plot(ts[keep], xs[keep] / amplitude, lw=1.0, label=f"SPH, d/Δx = {theory.DRAFT / dx:.0f}")
        axis.set_ylabel("heave / 0.04 m" if release == "heave" else "roll / 0.1 rad")
        axis.axhline(0.0, color="0.7", lw=0.5)
        axis.legend(fontsize=8, loc="upper right")
    axes[0].set_title("NTNU section: free decay after a 0.04 m heave release and a 0.5 rad/s roll kick")
    axes[1].set_xlabel("t [s]")
    fig.savefig(path, dpi=120)


def main():
    args = variants.study_arguments(__doc__.splitlines()[0], "floating_section",
                                    "the coarsest resolution only")
    predicted = reference()
    results, curves = [], {"heave": {}, "roll": {}}
    for dx in (0.04,) if args.quick else (0.04, 0.02, 0.04 / 3):
        for release in ("heave", "roll"):
            folder = args.scratch / f"{release}_{theory.DRAFT / dx:.0f}"
            series, wall, n = variants.run(config(dx, release, args.set), folder, args.reuse)
            r, t, x = analyse(series, release, predicted[release])
            r.update(dx=dx, release=release, particles=n, wall=wall)
            results.append(r)
            curves[release][dx] = (t, x)
            print(f"{release} Δx = {dx}: period {r['period']:.4f} s, second/first peak "
                  f"{r['peak_ratio']:.3f}, first peak {r['first_peak']:.3f} of the release, "
                  f"RMS {r['rms']:.3f} of the release, offset {r['draft_offset']:+.4f}, wall {wall:.0f} s")
    if args.set:
        return
    t_ref = {}
    for release, (t, x) in predicted.items():
        amplitude = SCALES[release]
        t_ref[release] = decay_measures(t, x, amplitude, 1.2)
    rows = []
    for r in results:
        ref = t_ref[r["release"]]
        rows.append([r["release"], f"{theory.DRAFT / r['dx']:.0f}", f"{r['particles']}",
                     f"{r['period']:.3f} s ({r['period'] / ref['period'] - 1:+.1%})",
                     f"{r['peak_ratio']:.3f}", f"{r['first_peak']:.3f}", f"{r['rms']:.3f}",
                     f"{r['draft_offset']:+.2%}" if r["release"] == "heave" else f"{r['draft_offset']:+.1e} rad",
                     f"{r['wall']:.0f} s"])
    for release, ref in t_ref.items():
        measured = "1.17 s" if release == "heave" else "1.26 s"
        rows.append([f"{release}: linear theory (experiment)", "", "",
                     f"{ref['period']:.3f} s ({measured})", f"{ref['peak_ratio']:.3f}",
                     f"{ref['first_peak']:.3f}", "0", "", ""])
    write_table(OUT / "floating_section_table.md",
                ["release", "d/Δx", "particles", "period", "2nd/1st peak", "1st peak / release",
                 "RMS vs theory / release", "offset at rest", "wall"], rows)
    write_csv(OUT / "floating_section.csv",
              ["release", "dx", "particles", "period", "peak_ratio", "first_peak", "rms",
               "draft_offset", "wall"], results)
    plot(OUT / "floating_section_decay.png", curves, predicted)


if __name__ == "__main__":
    main()
