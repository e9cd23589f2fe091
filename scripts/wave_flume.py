"""Wave heights, periods and second harmonics at the gauges of a wave-flume run,
against linear and second-order theory (docs/validation/wave_flume.md).

    python3 scripts/wave_flume.py RUN_FOLDER [--window T0 T1] [--plot PNG]

Reads RUN_FOLDER/timeseries.csv and the case's wave maker from RUN_FOLDER/case.toml.
At each gauge `<name>_elevation` it fits a mean and three harmonics of the wave
frequency by least squares over a whole number of periods in the window (default:
the last 4 periods of the run), and prints the height 2|A1| against H and the mean
zero-up-crossing period against T; with three or more gauges `g*` the second
harmonic split into its bound part (c A1(x)²) and its free part (the wavenumber of
2ω); with two or more gauges `r*` (L/10 and about L/4 apart) the first harmonic split
into incident and reflected waves, and the reflection coefficient. For an irregular
sea (a `spectrum` wave maker) it gives H_s = 4√m0 and T_p at each gauge over one
repeat period of the paddle's signal (the last of the run). --plot draws the
elevations against Stokes's crest and trough (regular waves) or the measured spectra
over the target (irregular seas).
"""
import argparse
import csv
import math
import sys
import tomllib
from pathlib import Path

import numpy as np

G = 9.81


def wavenumber(omega, depth):
    """Root of ω² = g k tanh(kd) by Newton from Eckart's estimate."""
    k0d = omega * omega * depth / G
    kd = k0d / math.sqrt(math.tanh(k0d))
    for _ in range(50):
        t = math.tanh(kd)
        step = (kd * t - k0d) / (t + kd * (1 - t * t))
        kd -= step
        if abs(step) < 1e-15 * kd:
            break
    return kd / depth


def bound_second_harmonic(height, k, depth):
    kd = k * depth
    return k * height**2 / 16 * math.cosh(kd) * (2 + math.cosh(2 * kd)) / math.sinh(kd) ** 3


def harmonics(t, eta, omega, n=3):
    """Complex amplitudes A_m of eta ≈ a0 + Re Σ A_m exp(-i m ω t)."""
    cols = [np.ones_like(t)]
    for m in range(1, n + 1):
        cols += [np.cos(m * omega * t), np.sin(m * omega * t)]
    coef, *_ = np.linalg.lstsq(np.array(cols).T, eta, rcond=None)
    return [complex(coef[2 * m - 1], coef[2 * m]) for m in range(1, n + 1)]


def up_crossing_period(t, eta):
    mean = eta.mean()
    s = eta - mean
    ups = [t[i] - s[i] * (t[i + 1] - t[i]) / (s[i + 1] - s[i])
           for i in range(len(s) - 1) if s[i] < 0 <= s[i + 1]]
    return (ups[-1] - ups[0]) / (len(ups) - 1) if len(ups) > 1 else float("nan")


def jonswap(f, hs, tp, gamma, band):
    """The JONSWAP density [m²/Hz] at f, scaled so that 4√m0 = H_s over `band`."""
    def shape(f):
        fp = 1 / tp
        sigma = np.where(f <= fp, 0.07, 0.09)
        r = np.exp(-((f - fp) ** 2) / (2 * sigma**2 * fp**2))
        return f**-5.0 * np.exp(-1.25 * (fp / f) ** 4) * gamma**r
    fine = np.linspace(band[0], band[1], 20001)
    m0 = np.trapezoid(shape(fine), fine)
    return shape(f) * (hs / 4) ** 2 / m0


def irregular(args, case, sea, t, data, header, gauges):
    """H_s = 4√m0 and T_p (peak of the periodogram smoothed over 3 bins) at each gauge
    over one repeat period of the paddle's signal, against the target; with --plot a
    figure of the measured spectra over the target's."""
    tp, hs = sea["peak_period"], sea["significant_height"]
    n = sea.get("components", 200)
    band = sea.get("frequencies", [0.5 / tp, 2.5 / tp])
    repeat = n / (band[1] - band[0])
    t0, t1 = args.window if args.window else (t[-1] - repeat, t[-1])
    dt = np.median(np.diff(t))
    grid = np.arange(t0, t1, dt)
    print(f"H_s = {hs} m, T_p = {tp} s, {n} components over [{band[0]:.3f}, {band[1]:.3f}] Hz "
          f"(repeat {repeat:.2f} s); window [{t0:.2f}, {t1:.2f}] s")
    spectra = {}
    for name in gauges:
        eta = np.interp(grid, t, data[:, header.index(f"{name}_elevation")])
        eta = eta - eta.mean()
        spec = np.abs(np.fft.rfft(eta)) ** 2 * 2 * dt / len(eta)
        f = np.fft.rfftfreq(len(eta), dt)
        smooth = np.convolve(spec, np.ones(3) / 3, mode="same")
        inside = (f >= band[0]) & (f <= band[1])
        fp = f[inside][np.argmax(smooth[inside])]
        m0 = eta.var()
        print(f"{name} x = {gauges[name]:.3f} m: H_s = {4 * math.sqrt(m0):.5f} m "
              f"({4 * math.sqrt(m0) / hs - 1:+.2%}), T_p = {1 / fp:.4f} s ({1 / fp / tp - 1:+.2%})")
        spectra[name] = (f, smooth)
    if args.plot:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        fig, ax = plt.subplots(figsize=(7, 4), constrained_layout=True)
        for name, (f, smooth) in spectra.items():
            ax.plot(f, smooth, lw=1, label=f"{name} (x = {gauges[name]} m), 3-bin mean")
        ff = np.linspace(band[0], band[1], 400)
        ax.plot(ff, jonswap(ff, hs, tp, sea.get("gamma", 3.3), band), "k--", lw=1.2,
                label="target JONSWAP")
        ax.set_xlim(0, 1.2 * band[1])
        ax.set_xlabel("f [Hz]")
        ax.set_ylabel("S(f) [m²/Hz]")
        ax.set_title(f"{Path(args.run).name}: H_s = {hs} m, T_p = {tp} s")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        fig.savefig(args.plot, dpi=120)
        print(f"wrote {args.plot}")


def plot_regular(args, run, t, data, header, gauges, main, height, k, depth, window):
    """The elevation at the first, middle and last `g` gauge over the run, with the
    Stokes crest and trough (±H/2 + A2) and the analysis window."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    names = list(gauges)
    picks = sorted({main[0], main[len(main) // 2], main[-1]})
    fig, axes = plt.subplots(len(picks), 1, figsize=(8, 2.2 * len(picks)), sharex=True,
                             constrained_layout=True)
    a2 = bound_second_harmonic(height, k, depth)
    for ax, i in zip(np.atleast_1d(axes), picks):
        name = names[i]
        ax.plot(t, data[:, header.index(f"{name}_elevation")], lw=0.8, label=name)
        for level in (0.5 * height + a2, -0.5 * height + a2):
            ax.axhline(level, color="k", ls="--", lw=0.7)
        ax.axvspan(*window, color="0.9", zorder=-1)
        ax.set_ylabel("η [m]")
        ax.set_title(f"{name}, x = {gauges[name]} m ({gauges[name] * k / (2 * math.pi):.2f} L); "
                     "dashed: Stokes II crest and trough; grey: analysis window", fontsize=9)
    np.atleast_1d(axes)[-1].set_xlabel("t [s]")
    fig.savefig(args.plot, dpi=120)
    print(f"wrote {args.plot}")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("run")
    ap.add_argument("--window", nargs=2, type=float)
    ap.add_argument("--plot", help="a PNG: gauges against the target (regular waves) or "
                    "the spectra (irregular seas)")
    args = ap.parse_args()
    run = Path(args.run)
    case = tomllib.loads((run / "case.toml").read_text())
    walls = case.get("wall", []) + case.get("shape", [])
    waves = next(w["prescribed"]["waves"] for w in walls if "waves" in w.get("prescribed", {}))
    gauges = {g["name"]: g["position"][0] for g in case["diagnostics"]["gauges"]}
    with open(run / "timeseries.csv") as f:
        rows = list(csv.reader(f))
    header, data = rows[0], np.array(rows[1:], dtype=float)
    t = data[:, header.index("time")]
    if "spectrum" in waves:
        return irregular(args, case, waves["spectrum"], t, data, header, gauges)
    depth, height = waves["depth"], waves["height"]
    omega = 2 * math.pi / waves["period"]
    k = wavenumber(omega, depth)
    k2 = wavenumber(2 * omega, depth)
    period = 2 * math.pi / omega
    t0, t1 = args.window if args.window else (t[-1] - 4 * period, t[-1])
    t1 = t0 + period * math.floor((t1 - t0) / period + 1e-9)
    sel = (t >= t0) & (t <= t1)
    print(f"kd = {k * depth:.4f}, L = {2 * math.pi / k:.4f} m, H = {height} m, T = {period:.4f} s; "
          f"window [{t0:.3f}, {t1:.3f}] s")
    a1, a2 = [], []
    for name, x in gauges.items():
        eta = data[sel, header.index(f"{name}_elevation")]
        a = harmonics(t[sel], eta, omega)
        a1.append(a[0])
        a2.append(a[1])
        tz = up_crossing_period(t[sel], eta)
        print(f"{name} x = {x:.3f} m ({x * k / (2 * math.pi):.2f} L): H = {2 * abs(a[0]):.5f} m "
              f"({2 * abs(a[0]) / height - 1:+.2%}), T_z = {tz:.4f} s ({tz / period - 1:+.2%}), "
              f"|A2| = {abs(a[1]):.5f} m")
    xs, a1, a2 = np.array(list(gauges.values())), np.array(a1), np.array(a2)
    main = [i for i, n in enumerate(gauges) if not n.startswith("r")]
    if len(main) >= 3:
        # the bound harmonic is c A1(x)² (it follows the first harmonic's height and
        # phase as both decay); the free one is F e^{i k2 x}
        b1 = a1[main]
        m = np.array([b1**2, np.exp(1j * k2 * xs[main])]).T
        (c, free), *_ = np.linalg.lstsq(m, a2[main], rcond=None)
        bound = abs(c) * np.mean(abs(b1)) ** 2
        theory = bound_second_harmonic(2 * np.mean(abs(b1)), k, depth)
        print(f"second harmonic: bound {bound:.5f} m (Stokes at the mean height {theory:.5f} m), "
              f"free {abs(free):.5f} m ({abs(free) / bound:.1%} of the bound)")
    if main:
        # the free part at each gauge with the bound one from Stokes: A2 - c A1²,
        # c = A2_Stokes/a² (a real, positive ratio: the bound crest rides on the crest)
        c = bound_second_harmonic(2.0, k, depth) / 1.0
        for i in main:
            f = a2[i] - c * a1[i] ** 2
            print(f"  {list(gauges)[i]}: free second harmonic (A2 - Stokes) {abs(f):.5f} m, "
                  f"{abs(f) / (c * abs(a1[i]) ** 2):.1%} of Stokes's bound")
    if args.plot:
        plot_regular(args, run, t, data, header, gauges, main, height, k, depth, (t0, t1))
    close = [n for n in gauges if n.startswith("r")]
    if len(close) >= 2:
        # the first harmonic at the r gauges as incident and reflected waves (Mansard &
        # Funke 1980: gauges L/10 and about L/4 apart)
        idx = [list(gauges).index(n) for n in close]
        xr, ar = xs[idx], a1[idx]
        m = np.array([np.exp(1j * k * xr), np.exp(-1j * k * xr)]).T
        (inc, ref), *_ = np.linalg.lstsq(m, ar, rcond=None)
        print(f"reflection: incident {2 * abs(inc):.5f} m, reflected {2 * abs(ref):.5f} m, "
              f"K_r = {abs(ref) / abs(inc):.2%}")


if __name__ == "__main__":
    sys.exit(main())
