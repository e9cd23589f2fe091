"""The measuring tools of the decaying-turbulence comparison
(examples/validation/decaying_turbulence.py): spectra, the gridding filter and the cached
spectral reference."""
import pathlib
import sys
from types import SimpleNamespace

import numpy as np
import pytest

sys.path.insert(0, str(pathlib.Path(__file__).resolve().parents[2] / "examples" / "validation"))
import decaying_turbulence as dt  # noqa: E402
import turbulence_field as tf  # noqa: E402


def grid(n):
    g = (np.arange(n) + 0.5) / n
    return np.meshgrid(g, g)


def test_the_spectrum_sums_to_the_kinetic_energy_and_gives_the_enstrophy():
    """Parseval on the initial field (band-limited, |n| <= 6, so 64² resolves it): the
    shells sum to ½⟨|u|²⟩, and ½⟨ω²⟩ from the spectral derivative is the analytic
    vorticity's."""
    x, y = grid(64)
    u, v = tf.velocity(x, y)
    e = tf.spectrum(u, v)[1]
    assert np.sum(e) == pytest.approx(0.5 * np.mean(u * u + v * v), rel=1e-12)
    assert tf.enstrophy(u, v) == pytest.approx(0.5 * np.mean(tf.vorticity(x, y) ** 2),
                                               rel=1e-10)


def lattice_sim(n, u):
    """Particles on a lattice offset from the grid of cell centres, carrying u(x, y)."""
    g = (np.arange(n) + 0.5) / n
    x, y = (c.ravel() for c in np.meshgrid(g + 0.27 / n, g + 0.11 / n))
    return SimpleNamespace(positions=np.column_stack([x, y]), mass=np.full(n * n, n**-2.0),
                           density=np.ones(n * n), velocities=np.column_stack(u(x, y)))


@pytest.mark.parametrize("k", [2, 10, 20])
def test_gridding_damps_a_mode_by_the_kernel_transfer_function(k):
    """The Shepard-normalised kernel interpolation of a sine mode onto the grid keeps
    F(k) of its amplitude, F the continuum transfer function that the comparison applies
    to the reference (measured within 0.05% at L/Δx = 100 up to k = n/5)."""
    n = 100
    sim = lattice_sim(n, lambda x, y: (np.sin(2 * np.pi * k * x), 0.0 * x))
    u, _ = dt.gridded_velocity(sim, n)
    exact = np.sin(2 * np.pi * k * grid(n)[0])
    amplitude = np.sum(u * exact) / np.sum(exact * exact)
    assert amplitude == pytest.approx(dt.gridding_transfer(k, n)[0], rel=3e-3)
    assert dt.gridding_transfer(k, n)[0] < 1.0 - 2e-3 * k


def test_the_cached_reference_obeys_the_energy_equation():
    """The cached spectral reference against the laws of 2D Navier-Stokes, not against
    another file: it starts from the analytic field's energy and enstrophy, and its energy
    falls as dE/dt = -2ν Z at every stored interval (trapezoidal rule; measured within
    7.7·10⁻⁵, and a reference from the wrong viscosity, or an under-resolved one that
    piles enstrophy at the grid scale, misses by far more than the 3·10⁻⁴ allowed)."""
    ref = dt.load(dt.REFERENCE)
    x, y = grid(256)
    u, v = tf.velocity(x, y)
    assert ref["energy"][0] == pytest.approx(0.5 * np.mean(u * u + v * v), rel=1e-9)
    assert ref["enstrophy"][0] == pytest.approx(0.5 * np.mean(tf.vorticity(x, y) ** 2),
                                                rel=1e-6)
    t, e, z = ref["time"], ref["energy"], ref["enstrophy"]
    nu = 1.0 / float(ref["re"])
    rate = np.diff(e) / np.diff(t)
    law = -2.0 * nu * 0.5 * (z[1:] + z[:-1])
    assert np.max(np.abs(rate / law - 1.0)) < 3e-4
    assert e[-1] < 0.65 * e[0]


def test_the_reference_vorticity_is_filtered_onto_the_cell_centres():
    """A single mode stored as the reference stores vorticity (point values at i/256)
    comes out on a run's cell centres ((i + ½)/n) damped by F(k): the half-cell shift
    and the filter within 10⁻³ of the amplitude (measured 3·10⁻⁴; F is interpolated
    between integer shells)."""
    m, n = 256, 100
    x, y = np.meshgrid(np.arange(m) / m, np.arange(m) / m)
    mode = lambda x, y: np.sin(2 * np.pi * (20 * x + 3 * y) + 0.3)  # noqa: E731
    ref = {"vorticity": np.array([mode(x, y)])}
    xc, yc = grid(n)
    exact = mode(xc, yc) * dt.gridding_transfer(np.hypot(20, 3), n)[0]
    assert np.max(np.abs(dt.filtered_reference_vorticity(ref, 0, n) - exact)) < 1e-3
