"""The 2D decaying-turbulence flow shared by the spectral reference and the SPH runs.

Initial field: the unforced 8 × 8 Taylor-Green cell array of the periodic unit square
(Di Mascio et al. 2017, J. Comput. Phys. 330; Antuono et al. 2021, J. Comput. Phys. 433),
plus a small divergence-free perturbation that breaks its symmetry, both given by a
stream function so that every solver evaluates the same field at its own points:

    ψ0 = (U/k) cos kx cos ky,  k = 8π/L        (u = ∂ψ/∂y, v = -∂ψ/∂x)
    ψ1 = Σ_n a_n cos(2π n·x/L + φ_n),  1 ≤ |n| ≤ N_P

with random a_n, φ_n from a fixed seed, scaled so that the perturbation's kinetic energy
is ε² times the cell array's. The cell array's velocity is u = U(-cos kx sin ky,
sin kx cos ky), the deltasph `taylor_green` initial field with wavelength L/4, and its
vorticity ω = 2Uk cos kx cos ky.

Spectra and enstrophy are taken on a uniform grid of the unit square, from FFTs of the
velocity: E(k) sums ½|û|² over the shells |n| ∈ [k - ½, k + ½) (k in units of 2π/L), so
that Σ_k E(k) is the mean kinetic energy per unit mass.
"""

import numpy as np

#: cells per side of the square
CELLS = 8
#: the cell array's wavenumber k = 8π/L for L = 1
K0 = np.pi * CELLS
#: perturbation modes: integer wave vectors n with 1 <= |n| <= N_P
N_P = 6
#: perturbation energy relative to the cell array's (ε = 0.05 in velocity)
EPSILON = 0.05
SEED = 2017


def _modes():
    rng = np.random.default_rng(SEED)
    n = np.array([(i, j) for i in range(-N_P, N_P + 1) for j in range(0, N_P + 1)
                  if (j > 0 or i > 0) and 0 < i * i + j * j <= N_P * N_P], dtype=float)
    amplitude = rng.standard_normal(len(n))
    phase = rng.uniform(0.0, 2.0 * np.pi, len(n))
    # kinetic energy of ψ1 per unit area: ½ Σ a² |2πn|² · ½
    energy = 0.25 * np.sum(amplitude**2 * (2.0 * np.pi) ** 2 * np.sum(n * n, axis=1))
    cell_energy = 0.25  # ½⟨u²+v²⟩ of the cell array with U = 1
    amplitude *= EPSILON * np.sqrt(cell_energy / energy)
    return n, amplitude, phase


def velocity(x, y, amplitude=1.0):
    """(u, v) of the initial field at the points (x, y) (arrays of one shape), L = 1."""
    u = -amplitude * np.cos(K0 * x) * np.sin(K0 * y)
    v = amplitude * np.sin(K0 * x) * np.cos(K0 * y)
    n, a, phi = _modes()
    for (nx, ny), an, p in zip(n, a, phi):
        s = -amplitude * an * np.sin(2.0 * np.pi * (nx * x + ny * y) + p) * 2.0 * np.pi
        u += s * ny
        v -= s * nx
    return u, v


def vorticity(x, y, amplitude=1.0):
    """ω = ∂v/∂x - ∂u/∂y = -∇²ψ of the initial field."""
    w = 2.0 * amplitude * K0 * np.cos(K0 * x) * np.cos(K0 * y)
    n, a, phi = _modes()
    for (nx, ny), an, p in zip(n, a, phi):
        k2 = (2.0 * np.pi) ** 2 * (nx * nx + ny * ny)
        w += amplitude * an * k2 * np.cos(2.0 * np.pi * (nx * x + ny * y) + p)
    return w


def wavenumbers(n):
    """Integer wavenumbers (kx, ky) of an n × n grid in numpy's FFT order, indexing [iy, ix]."""
    k = np.fft.fftfreq(n, 1.0 / n)
    return np.meshgrid(k, k)


def spectrum(u, v):
    """Shell-summed energy spectrum of a velocity field on an n × n grid of the unit
    square (indexing [iy, ix]): returns (k, E(k)) for k = 1 .. n/2."""
    n = u.shape[0]
    density = 0.5 * (np.abs(np.fft.fft2(u)) ** 2 + np.abs(np.fft.fft2(v)) ** 2) / n**4
    kx, ky = wavenumbers(n)
    shell = np.rint(np.hypot(kx, ky)).astype(int)
    e = np.bincount(shell.ravel(), weights=density.ravel())
    k = np.arange(1, n // 2 + 1)
    return k, e[1:n // 2 + 1]


def enstrophy(u, v):
    """½⟨ω²⟩ of a gridded velocity field, from spectral derivatives."""
    n = u.shape[0]
    kx, ky = wavenumbers(n)
    w = 2.0 * np.pi * 1j * (kx * np.fft.fft2(v) - ky * np.fft.fft2(u))
    return 0.5 * np.sum(np.abs(w) ** 2) / n**4


def shell_enstrophy(e, k_max):
    """Σ_{k=1}^{k_max} (2πk)² E(k): the enstrophy of the shells up to k_max, from a
    shell-summed spectrum E(k), k = 1, 2, ... (each shell counted at its nominal
    radius, the same for every field it is applied to)."""
    k = np.arange(1, k_max + 1)
    return np.sum((2.0 * np.pi * k) ** 2 * np.asarray(e)[..., :k_max], axis=-1)


def vorticity_on_grid(u, v):
    """ω of a gridded velocity field, from spectral derivatives."""
    n = u.shape[0]
    kx, ky = wavenumbers(n)
    w = 2.0 * np.pi * 1j * (kx * np.fft.fft2(v) - ky * np.fft.fft2(u))
    return np.real(np.fft.ifft2(w))
