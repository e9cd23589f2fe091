#!/usr/bin/env python3
"""The NTNU ship section's measured responses in regular waves (Sundsdal, Greco, Hanssen
& Lugni 2025; raw data at github.com/KRSundsdal1/2D-ship-cross-section-in-regular-waves),
reduced to response amplitude operators for docs/validation/data.

Scenario B (files data/3PPH/3PPH_R.csv: free in sway, heave and roll; PP the period's
index, H 1 for 0.024 m and 2 for 0.04 m) in the 13.63 m flume, 1.0 m deep, the section 7 m
off the flap. For each run:
- the window: the wave maker's steady stretch (its stroke within 3% of the largest),
  carried to the probes and the section at the group velocity, less a period of
  build-up at each end, cut to whole periods (at least three; two at the probes, where the
  longest wave's reflection from the section leaves only two);
- the first harmonic of every signal over it, by least squares on a constant, a linear
  drift and cos/sin ωt;
- the incident wave: the three-probe split (probes 2, 3, 4 at 4.95, 5.20, 5.50 m) of the
  first harmonics into a wave running toward the section and one running back, with the
  finite-depth wavenumber, least squares (Mansard & Funke 1980 at one frequency);
  the second estimate, the calibration without the model (data/1PPH, the same PPH), is
  the mean of probes 4 and 6 (5.50 and 8.50 m) either side of where the section floats;
- the amplitudes of sway and heave over the incident amplitude ζ_a, roll over k ζ_a.

Usage: python3 examples/validation/floating_section_experiment.py DATA_DIR
(DATA_DIR the repository's data folder). Writes
docs/validation/data/floating_section_experiment.csv.
"""
import argparse
import pathlib

import numpy as np

import wave_analysis
from records import write_csv

OUT = pathlib.Path(__file__).resolve().parents[2] / "docs" / "validation" / "data"
DEPTH = 1.0
HEIGHTS = {"1": 0.024, "2": 0.04}
# the experiment's periods by index (its table of ξ_B = ω² B / (2 g))
PERIODS = {1: 1.516, 2: 1.269, 3: 1.238, 4: 1.210, 5: 1.183, 6: 1.158, 7: 1.113,
           8: 1.072, 9: 1.036, 10: 0.897, 11: 0.802, 12: 0.733, 13: 0.678, 14: 0.634}
PROBES = {"WP_2": 4.95, "WP_3": 5.20, "WP_4": 5.50}
SECTION_AT = 7.0
STEADY = 0.97


def steady_stretch(t, stroke, period):
    """When the wave maker's stroke envelope (the largest |stroke| over a period) is
    within 3% of its largest."""
    n = max(1, int(round(period / (t[1] - t[0]))))
    envelope = np.lib.stride_tricks.sliding_window_view(np.abs(stroke), n).max(axis=1)
    on = np.flatnonzero(envelope > STEADY * envelope.max())
    return t[on[0]], t[min(on[-1] + n, len(t) - 1)]


def first_harmonic(t, x, omega):
    """The first harmonic's complex amplitude over a constant and a linear drift."""
    return wave_analysis.harmonics(t, x, omega, n=1, drift=True)[0]


def window(t, start, end, period, least=3):
    """Whole periods from start + T to end − T, at least `least`."""
    n = int(np.floor((end - start - 2.0 * period) / period))
    if n < least:
        return None
    lo = start + period
    return (t >= lo) & (t < lo + n * period)


def read(path):
    """The columns of a run's file by name without the unit ("Time", "WP_2", ...; the
    calibration files lead with an unnamed index column)."""
    with open(path) as f:
        names = [n.split(" [")[0] for n in f.readline().strip().split(",")]
    values = np.loadtxt(path, delimiter=",", skiprows=1)
    return {n: values[:, i] for i, n in enumerate(names) if n}


def calibration(data, index, height_digit, omega, k):
    """Incident amplitude from the calibration without the model: probes 4 and 6's
    first harmonics in their steady windows, averaged."""
    name = f"1{index:02d}{height_digit}.csv"
    if not (data / "1PPH" / name).exists():
        return np.nan
    d = read(data / "1PPH" / name)
    t, period = d["Time"], 2.0 * np.pi / omega
    on, off = steady_stretch(t, d["WM_Position"], period)
    cg = wave_analysis.group_velocity(omega, k, DEPTH)
    amplitudes = []
    for probe, x in (("WP_4", 5.50), ("WP_6", 8.50)):
        w = window(t, on + x / cg, off + x / cg, period)
        amplitudes.append(abs(first_harmonic(t[w], d[probe][w], omega)))
    return float(np.mean(amplitudes))


def reduce_run(path, data):
    """One run's row: period, height, incident amplitudes, RAOs and the window."""
    index, height_digit = int(path.stem[1:3]), path.stem[3]
    period = PERIODS[index]
    omega = 2.0 * np.pi / period
    k = wave_analysis.wavenumber(omega, DEPTH)
    cg = wave_analysis.group_velocity(omega, k, DEPTH)
    d = read(path)
    t = d["Time"]
    on, off = steady_stretch(t, d["WM_Position"], period)
    # at the probes: the incident steady from on + x/cg, the reflection from the section
    # steady once the section is and its waves have come back
    back = (SECTION_AT + (SECTION_AT - min(PROBES.values()))) / cg
    probes = window(t, on + back, off + min(PROBES.values()) / cg, period, least=2)
    motions = window(t, on + SECTION_AT / cg, off + SECTION_AT / cg, period)
    if probes is None or motions is None or np.ptp(d["Heave"][motions]) == 0.0:
        return None
    first = [first_harmonic(t[probes], d[p][probes], omega) for p in PROBES]
    incident, reflected = wave_analysis.split(first, list(PROBES.values()), k)
    zeta = abs(incident)
    test, _, repetition = path.stem.partition("_")
    row = {"test": int(test), "repetition": int(repetition or 0), "period": period, "height": HEIGHTS[height_digit],
           "omega": omega, "k": k, "incident": zeta,
           "incident_calibration": calibration(data, index, height_digit, omega, k),
           "reflected": abs(reflected)}
    for name, column, scale in (("sway", "Sway", zeta), ("heave", "Heave", zeta),
                                ("roll", "Roll", k * zeta)):
        row[name] = abs(first_harmonic(t[motions], d[column][motions], omega)) / scale
    row["periods"] = int(round(motions.sum() * (t[1] - t[0]) / period))
    return row


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("data", type=pathlib.Path, help="the repository's data folder")
    args = parser.parse_args()
    rows = []
    for path in sorted((args.data / "3PPH").glob("3*.csv")):
        row = reduce_run(path, args.data)
        if row is None:
            print(f"{path.name}: no steady window or no tracked motion")
            continue
        rows.append(row)
        print(", ".join(f"{k} {v:.4g}" if isinstance(v, float) else f"{k} {v}"
                        for k, v in row.items()))
    write_csv(OUT / "floating_section_experiment.csv", list(rows[0]), rows, comments=[
        "NTNU ship section in regular beam-sea waves, free in sway, heave and roll (scenario B):",
        "Sundsdal, Greco, Hanssen & Lugni 2025, raw data at",
        "github.com/KRSundsdal1/2D-ship-cross-section-in-regular-waves (data/3PPH, data/1PPH),",
        "first harmonics over the steady window by examples/validation/floating_section_experiment.py"])


if __name__ == "__main__":
    main()
