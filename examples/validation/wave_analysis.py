"""Regular-wave signals: the wavenumber, harmonics fitted over a window, and the split of
gauges' first harmonics into the waves running either way."""
import math

import numpy as np

import deltasph as ds

G = 9.81


def wavenumber(omega, depth):
    """The root k of ω² = g k tanh(k d), from deltasph's own wave theory."""
    # the height only scales the other entries
    wave = ds.regular_wave(height=1.0, period=2.0 * math.pi / omega, depth=depth, gravity=G)
    return wave["wavenumber"]


def group_velocity(omega, k, depth):
    return 0.5 * omega / k * (1.0 + 2.0 * k * depth / math.sinh(2.0 * k * depth))


def harmonics(t, y, omega, n=3, drift=False):
    """Complex amplitudes A_m, m = 1..n, of y ≈ a0 (+ a1 t) + Re Σ A_m e^{-imωt}, least
    squares (with `drift`, a linear drift fitted too)."""
    cols = [np.ones_like(t)] + ([t - t.mean()] if drift else [])
    for m in range(1, n + 1):
        cols += [np.cos(m * omega * t), np.sin(m * omega * t)]
    coef, *_ = np.linalg.lstsq(np.array(cols).T, y, rcond=None)
    first = len(cols) - 2 * n
    return [complex(coef[first + 2 * m - 2], coef[first + 2 * m - 1]) for m in range(1, n + 1)]


def split(amplitudes, positions, k):
    """Incident (running toward +x) and reflected complex amplitudes at x = 0 of the
    first harmonics a_p ≈ A e^{ikx_p} + B e^{-ikx_p} at gauges x_p, least squares
    (Mansard & Funke 1980 at one frequency)."""
    m = np.array([[np.exp(1j * k * x), np.exp(-1j * k * x)] for x in positions])
    (incident, reflected), *_ = np.linalg.lstsq(m, np.asarray(amplitudes), rcond=None)
    return incident, reflected
