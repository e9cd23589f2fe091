"""The validation cases: how each is set up at a given resolution and scheme variant,
how it is run, and how its error is measured against its reference.

Every case is a TOML file beside this module; a run overrides the particle spacing and
the scheme (diffusion, integrator, Courant number). `measure` drives the simulation to
the case's comparison time and returns the error (the number plotted) and extra figures.
References: analytic solutions, or `docs/validation/data/` (its README gives sources and grades).
"""

import math
import pathlib
import tomllib
from dataclasses import dataclass, field
from typing import Callable

import numpy as np

HERE = pathlib.Path(__file__).resolve().parent
REFDATA = HERE.parents[1] / "docs" / "validation" / "data"


@dataclass
class Case:
    name: str
    title: str
    toml: str
    #: particles across the reference length, per mode
    resolutions: dict
    #: the reference length over which `resolutions` count particles [m]
    length: float
    error_label: str
    measure: Callable
    #: variants per mode: (diffusion label, integrator label)
    variants: dict = field(default_factory=dict)
    #: extra overrides (dotted keys) applied to every run
    fixed: dict = field(default_factory=dict)
    #: space dimension: a run's cost grows as resolution^(dim + 1) (particles × steps)
    dim: int = 2
    #: per-run wall-time cap of `--full` for this case [s], where it differs from the default
    cap: float | None = None
    #: whether `measure` returns a time signal (kept for the report and for --resume)
    records_signal: bool = False

    def config(self, n, diffusion, integrator):
        with open(HERE / self.toml, "rb") as f:
            config = tomllib.load(f)
        scheme = config.setdefault("scheme", {})
        scheme.update(DIFFUSIONS[diffusion])
        scheme["integrator"], scheme["cfl"] = INTEGRATORS[integrator]
        config["particles"]["spacing"] = self.length / n
        for dotted, value in self.fixed.items():
            table, key = dotted.split(".")
            config.setdefault(table, {})[key] = value
        return config


def variant(diffusion, shifting="none", turbulence="none"):
    return {"diffusion": diffusion, "shifting": shifting, "turbulence": turbulence}


#: density diffusion, particle shifting and turbulence closure of each variant
DIFFUSIONS = {
    "SPH": variant("none"),
    "MC": variant("molteni_colagrossi"),
    "Ferrari": variant("ferrari"),
    "δ-SPH": variant("delta_sph"),
    "δ+-SPH": variant("delta_sph", "delta_plus"),
    "δ-LES-SPH": variant("delta_sph", turbulence="delta_les"),
}
#: integrator and its largest stable Courant number (docs/accuracy.md: stability findings)
INTEGRATORS = {"RK4": ("rk4", 1.5), "SE2": ("symplectic", 0.15)}
QUICK = [("δ-SPH", "RK4"), ("δ-SPH", "SE2"), ("MC", "RK4"), ("SPH", "RK4")]
#: every diffusion with both integrators; shifting only where particle disorder matters
FULL = [(d, i) for d in DIFFUSIONS if d not in ("δ+-SPH", "δ-LES-SPH") for i in INTEGRATORS]
FULL_SHIFTED = FULL + [("δ+-SPH", i) for i in INTEGRATORS]


def fluid(sim):
    return sim.kind == 0


# 1. Hydrostatic tank -----------------------------------------------------------------

def hydrostatic(sim):
    """p against ρ0 g (H - y) at t·sqrt(g/H) = 20: L2 and max over the fluid, L2 in the top 3Δx."""
    rho0, g, depth = 1000.0, 9.81, 1.0
    sim.run(until=20.0 * math.sqrt(depth / g))
    f = fluid(sim)
    y, p = sim.positions[f, 1], sim.pressure[f]
    err = (p - rho0 * g * (depth - y)) / (rho0 * g * depth)
    top = y > depth - 3.0 * sim.spacing
    return {
        "error": float(np.sqrt(np.mean(err**2))),
        "max_error": float(np.max(np.abs(err))),
        "top_error": float(np.sqrt(np.mean(err[top] ** 2))),
        "max_speed": float(np.max(np.linalg.norm(sim.velocities[f], axis=1))),
    }


# 2. Dam break, δ-SPH benchmark: P1 at 0.2H against Marrone et al. (2011) and Buchner ---

def buchner():
    data = np.loadtxt(REFDATA / "dambreak2d_buchner2002_P1.csv", delimiter=",",
                      comments="#", skiprows=3)
    return data[:, 0], data[:, 1]


def smooth(t, p, width=0.1):
    """Moving average over `width` in t* (the experimental sensor and noise scale)."""
    step = t[1] - t[0]
    k = max(1, int(round(width / step)))
    return np.convolve(p, np.ones(k) / k, mode="same")


def p1_signal(sim, height):
    """P1 (right wall, y = `height`) as p/ρ0gH every 0.01 t* to t* = 7 (zero while the
    probe is dry)."""
    H, g, rho0 = 0.6, 9.81, 1000.0
    t_ref = math.sqrt(H / g)
    times = np.arange(0.01, 7.0 + 1e-9, 0.01)
    signal = []
    for t_star in times:
        sim.run(until=t_star * t_ref)
        signal.append(sim.probe_pressure([3.2196, height])[0] / (rho0 * g * H))
    return times, np.nan_to_num(np.array(signal))


def marrone():
    """Marrone et al. (2011)'s P1 figure: t*, experiment, δ-SPH at H/Δx = 40, 80, 320."""
    return np.loadtxt(REFDATA / "dambreak2d_marrone2011_P1.csv", delimiter=",",
                      comments="#", skiprows=5)


#: the columns of `marrone()` holding their δ-SPH signal at each H/Δx
MARRONE_RUNS = {40: 2, 80: 3, 320: 4}
#: t* windows: the plateau, and the span the signals are compared over
PLATEAU, COMPARED = (3.3, 5.2), (2.0, 7.0)


def mean_over(t, p, window):
    return float(np.mean(p[(t >= window[0]) & (t <= window[1])]))


def rms_against_marrone(times, signal, n, window):
    """RMS over `window` of the 0.1 t* moving average of P1 less Marrone's δ-SPH at
    H/Δx = n."""
    ref = marrone()
    diff = smooth(times, signal) - np.interp(times, ref[:, 0], ref[:, MARRONE_RUNS[n]])
    kept = (times >= window[0]) & (times <= window[1])
    return float(np.sqrt(np.mean(diff[kept] ** 2)))


def dam_break(sim):
    """P1 at y = 0.2H = 0.12 m, the probe of the published δ-SPH runs (docs/validation/data/README.md),
    to t* = 7. The error: RMS difference over t* 2-7 from Marrone et al.'s δ-SPH at
    H/Δx = 320, their converged signal; also against their run at the same H/Δx (40,
    80), the plateau against theirs and Buchner's, the first peak and its time."""
    times, signal = p1_signal(sim, 0.12)
    ref = marrone()
    t_exp, p_exp = buchner()
    first = (times >= 2.3) & (times <= 3.2)
    k = int(np.argmax(signal[first]))
    metrics = {
        "error": rms_against_marrone(times, signal, 320, COMPARED),
        "plateau": mean_over(times, signal, PLATEAU),
        "marrone_plateau": mean_over(ref[:, 0], ref[:, MARRONE_RUNS[320]], PLATEAU),
        "experiment_plateau": mean_over(t_exp, p_exp, PLATEAU),
        "first_peak": float(signal[first][k]),
        "first_peak_time": float(times[first][k]),
        "rise_time": float(times[np.argmax(signal > 0.1)]),
        "signal": (times, signal),
    }
    n = round(0.6 / sim.spacing)
    if n in (40, 80):
        metrics["vs_marrone_same"] = rms_against_marrone(times, signal, n, COMPARED)
    return metrics


def dam_break_marrone(sim):
    """P1 at y = 0.2H against Marrone et al. (2011)'s δ-SPH at H/Δx = 320: RMS over t*
    2.3-7 of the 0.1 t* moving average (the kernel study's measure)."""
    times, signal = p1_signal(sim, 0.12)
    return {"error": rms_against_marrone(times, signal, 320, (2.3, 7.0)),
            "plateau": mean_over(times, signal, PLATEAU)}


# 2b. Dam break, Martin & Moyce column: surge front ------------------------------------------

def surge_front(sim):
    """Front Z = x/a against T = t sqrt(2g/a), RMS over the MM (both columns) and KO points
    with T in [0.5, 2.5], after the time shift τ in [0, 0.5] that fits best (the
    experiments' gate release is not instantaneous; τ is reported; the SPH front leads)."""
    a = 0.1
    scale = math.sqrt(2 * 9.81 / a)
    t_sph, z_sph = [0.0], [1.0]
    while sim.time * scale < 3.0:
        sim.step()
        t_sph.append(sim.time * scale)
        z_sph.append(sim.positions[fluid(sim), 0].max() / a)
    mm = np.loadtxt(REFDATA / "dambreak2d_martin_moyce_1952_surge_front.csv", delimiter=",",
                    comments="#", skiprows=3)[:, 1:]
    ko = np.loadtxt(REFDATA / "dambreak2d_koshizuka_oka_1996_surge_front.csv", delimiter=",",
                    comments="#", skiprows=3)
    points = np.vstack([mm, ko])
    points = points[(points[:, 0] >= 0.5) & (points[:, 0] <= 2.5)]
    fits = []
    for tau in np.arange(0.0, 0.501, 0.01):
        z = np.interp(points[:, 0] - tau, t_sph, z_sph)
        fits.append((float(np.sqrt(np.mean((z - points[:, 1]) ** 2))), float(tau)))
    rms, tau = min(fits)
    return {"error": rms, "shift": tau, "error_without_shift": fits[0][0]}


# Rotating square patch ----------------------------------------------------------------------

def rotating_square(sim):
    """Spread of the nearest-neighbour distance at t ω = 2 (0 on a regular lattice; voids
    and line-up raise it) and the angular momentum change."""
    def lz():
        x, u, m = sim.positions, sim.velocities, sim.mass
        return float(np.sum(m * (x[:, 0] * u[:, 1] - x[:, 1] * u[:, 0])))
    lz0 = lz()
    sim.run(until=2.0)
    x = sim.positions
    d2 = np.sum((x[:, None, :] - x[None, :, :]) ** 2, axis=2)
    np.fill_diagonal(d2, np.inf)
    nearest = np.sqrt(d2.min(axis=1))
    return {"error": float(nearest.std() / nearest.mean()), "Lz_change": lz() / lz0 - 1.0}


# 3. Elliptic drop ---------------------------------------------------------------------

def elliptic_drop(sim):
    """Semi-axes from second moments at A0 t = 0.75 against the ODE (docs/validation/data)."""
    ref = np.loadtxt(REFDATA / "elliptic_drop_exact.csv", delimiter=",", comments="#",
                     skiprows=2)
    exact = ref[np.argmin(np.abs(ref[:, 0] - 0.75))]
    m0, e0 = np.mean(sim.positions**2, axis=0), sim.energies()["kinetic"]
    sim.run(until=0.0075)
    a, b = np.sqrt(np.mean(sim.positions**2, axis=0) / m0)
    return {
        "error": abs(b / exact[2] - 1.0),
        "a_error": abs(a / exact[1] - 1.0),
        "area_error": abs(a * b - 1.0),
        "kinetic_energy_change": abs(sim.energies()["kinetic"] / e0 - 1.0),
    }


# 4. Taylor-Green vortex -------------------------------------------------------------------

def taylor_green(sim, nu, until=1.0):
    """L2 velocity error at t against the analytic field, relative to U e^{bt}; E_k decay error."""
    k = 2.0 * math.pi
    decay = math.exp(-8.0 * math.pi**2 * nu * until)
    e0 = sim.energies()["kinetic"]
    sim.run(until=until)
    x, u = sim.positions, sim.velocities
    exact = decay * np.column_stack([-np.cos(k * x[:, 0]) * np.sin(k * x[:, 1]),
                                     np.sin(k * x[:, 0]) * np.cos(k * x[:, 1])])
    err = np.sqrt(np.mean(np.sum((u - exact) ** 2, axis=1))) / decay
    return {
        "error": float(err),
        "energy_decay_error": abs(sim.energies()["kinetic"] / e0 / decay**2 - 1.0),
    }


# 5. Impact of two patches -------------------------------------------------------------------

def patch_impact(sim):
    """Contact-point pressure on the acoustic plateau against ρ0 c0 U; noise at 2 (h/2)/c0."""
    scale, release = 1000.0 * 20.0 * 1.0, 0.025
    plateau = []
    while sim.time < 0.05 * (1 - 1e-12):
        sim.step()
        if 0.2 * release <= sim.time < 0.8 * release:
            plateau.append(sim.probe_pressure([0.0, 0.0])[0])
    x, p = sim.positions, sim.pressure
    inner = np.all(np.abs(x) < 0.45, axis=1)
    noise = np.sqrt(np.mean((p[inner] - sim.probe_pressure(x[inner])) ** 2)) / scale
    peak = float(np.mean(plateau)) / scale
    return {"error": abs(peak - 1.0), "plateau": peak, "noise": float(noise)}


# 6. Poiseuille flow ---------------------------------------------------------------------------

def poiseuille_exact(y, t, L=1e-3, nu=1e-6, F=2e-4):
    """Morris et al. (1997), signs corrected (docs/validation/data/README.md §7c)."""
    u = F / (2 * nu) * y * (L - y)
    for n in range(50):
        k = 2 * n + 1
        u = u - 4 * F * L**2 / (nu * math.pi**3 * k**3) * np.sin(k * math.pi * y / L) \
            * np.exp(-(k**2) * math.pi**2 * nu * t / L**2)
    return u


def profile_error(sim, until, exact, scale):
    """RMS of u_x(y) against `exact(y, t)` at t = `until`, relative to `scale`."""
    sim.run(until=until)
    f = fluid(sim)
    y, u = sim.positions[f, 1], sim.velocities[f, 0]
    return {"error": float(np.sqrt(np.mean((u - exact(y, until)) ** 2)) / scale)}


def poiseuille(sim, until):
    """RMS of u_x against the series at t (ν t/L² = t here), relative to F L²/(8ν)."""
    return profile_error(sim, until, poiseuille_exact, 2.5e-5)


# 6b. Start-up Couette flow --------------------------------------------------------------------

def couette_exact(y, t, L=1e-3, nu=1e-6, U=2.5e-5):
    """u = U y/L - Σ_n 2U (-1)^(n+1)/(nπ) sin(nπy/L) exp(-n²π²νt/L²), from rest at t = 0."""
    u = U * y / L
    for n in range(1, 200):
        u = u - 2 * U * (-1) ** (n + 1) / (n * math.pi) * np.sin(n * math.pi * y / L) \
            * np.exp(-(n**2) * math.pi**2 * nu * t / L**2)
    return u


def couette(sim, until):
    """RMS of u_x against the series at t (ν t/L² = t here), relative to the lid speed U."""
    return profile_error(sim, until, couette_exact, 2.5e-5)


# 6c. Standing wave in a closed tank ------------------------------------------------------------

def standing_wave(sim, periods=4, nu=1e-3, length=1.0, depth=0.5, g=9.81):
    """Frequency and damping of the first sloshing mode against linear theory: the kinetic
    energy peaks twice a period and its peaks decay as exp(-4νk²t), so ω is π over the
    spacing of the peaks (a line through their times) and the amplitude decay γ half the log-slope of their
    heights. The error is the complex frequency's, |Δω + iΔγ|/ω, against ω² = g k tanh kd
    and γ = 2νk²."""
    k = math.pi / length
    omega = math.sqrt(g * k * math.tanh(k * depth))
    period = 2.0 * math.pi / omega
    samples = 40  # per half period
    times = np.arange(1, periods * 2 * samples + samples // 2) * (period / 2 / samples)
    energy = []
    for t in times:
        sim.run(until=t)
        energy.append(sim.energies()["kinetic"])
    energy = np.array(energy)
    peaks_t, peaks_e = [], []
    for n in range(1, 2 * periods + 1):
        i = n * samples - 1  # the sample nearest t = n T/2
        w = energy[i - samples // 4:i + samples // 4 + 1]
        j = i - samples // 4 + int(np.argmax(w))
        a, b, c = np.log(energy[j - 1:j + 2])
        shift = 0.5 * (a - c) / (a - 2 * b + c)  # parabola through the three samples
        peaks_t.append(times[j] + shift * (times[1] - times[0]))
        peaks_e.append(b - 0.25 * (a - c) * shift)
    peaks_t = np.array(peaks_t)
    slope, _ = np.polyfit(peaks_t, peaks_e, 1)
    half_period, _ = np.polyfit(np.arange(1, 2 * periods + 1), peaks_t, 1)
    got_omega = math.pi / float(half_period)
    got_decay = -0.5 * float(slope)
    viscous = 2.0 * nu * k**2
    return {
        "error": math.hypot(got_omega - omega, got_decay - viscous) / omega,
        "period_error": omega / got_omega - 1.0,
        "decay_over_viscous": got_decay / viscous,
    }


# 7. Lid-driven cavity -------------------------------------------------------------------------

def ghia(name):
    return np.loadtxt(REFDATA / name, delimiter=",", comments="#", skiprows=3)


def velocity_at(sim, points):
    """Shepard-interpolated fluid velocity at points (Wendland C2 weights over 2h)."""
    f = fluid(sim)
    x, u, h = sim.positions[f], sim.velocities[f], sim.smoothing_length
    out = []
    for p in points:
        q = np.linalg.norm(x - p, axis=1) / h
        w = np.where(q < 2.0, (1.0 - q / 2.0) ** 4 * (2.0 * q + 1.0), 0.0)
        out.append(w @ u / w.sum())
    return np.array(out)


def cavity(sim, until=20.0):
    """Centre-line profiles at t U/L = 20 against Ghia et al. (1982), Re = 100: RMS of u on
    x = 0.5 and of v on y = 0.5 over the tabulated interior points."""
    sim.run(until=until)
    gu = ghia("lid_driven_cavity_ghia1982_u_on_vertical_centreline.csv")
    gv = ghia("lid_driven_cavity_ghia1982_v_on_horizontal_centreline.csv")
    gu, gv = gu[(gu[:, 0] > 0) & (gu[:, 0] < 1)], gv[(gv[:, 0] > 0) & (gv[:, 0] < 1)]
    u = velocity_at(sim, np.column_stack([np.full(len(gu), 0.5), gu[:, 0]]))[:, 0]
    v = velocity_at(sim, np.column_stack([gv[:, 0], np.full(len(gv), 0.5)]))[:, 1]
    eu = float(np.sqrt(np.mean((u - gu[:, 1]) ** 2)))
    ev = float(np.sqrt(np.mean((v - gv[:, 1]) ** 2)))
    return {"error": max(eu, ev), "u_error": eu, "v_error": ev}


# 8. Decaying turbulence ---------------------------------------------------------------------

def decaying_turbulence(sim, until=1.0):
    """The Re = 10⁴ decaying cell array of decaying_turbulence.py (perturbed here) against
    its spectral reference at t: |E/E_ref − 1| of the particles' kinetic energy, and the
    error of the enstrophy of the resolved band through the gridding filter."""
    import decaying_turbulence as dt

    n = round(math.sqrt(sim.n_fluid))
    dt.perturb(sim)
    sim.run(until=until)
    ref = dt.load(dt.REFERENCE)
    i = int(np.argmin(np.abs(ref["time"] - until)))
    spectrum = dt.tf.spectrum(*dt.gridded_velocity(sim, n))[1]
    enstrophy = dt.tf.shell_enstrophy(spectrum, n // 4)
    return {
        "error": abs(dt.kinetic_energy(sim) / ref["energy"][i] - 1.0),
        "enstrophy_error": abs(enstrophy / dt.filtered_reference(ref, n)[1][i] - 1.0),
    }


RK4_ONLY = {"quick": [("δ-SPH", "RK4"), ("MC", "RK4"), ("SPH", "RK4")], "full": FULL}
VISCOUS = {"quick": [("δ-SPH", "RK4"), ("δ-SPH", "SE2"), ("MC", "RK4"), ("SPH", "RK4")],
           "full": FULL}
SHIFTED = {"quick": VISCOUS["quick"] + [("δ+-SPH", "RK4")], "full": FULL_SHIFTED}
ALL = {"quick": QUICK, "full": FULL}

CASES = [
    Case("hydrostatic", "Hydrostatic tank (t·sqrt(g/H) = 20)", "hydrostatic.toml",
         {"quick": [10, 20, 30], "full": [10, 20, 30, 40, 60]}, 1.0,
         "L2 error of p / ρ0gH", hydrostatic, RK4_ONLY),
    Case("dam_break", "Dam break, P1 at 0.2H against Marrone et al. (2011)", "dam_break.toml",
         {"quick": [15, 20, 30], "full": [15, 20, 40, 80]}, 0.6,
         "RMS of p/ρ0gH − Marrone's δ-SPH (H/Δx 320), t* 2-7", dam_break, ALL, cap=240.0,
         records_signal=True),
    Case("surge_front", "Dam break, surge front against Martin & Moyce and Koshizuka & Oka",
         "surge_front.toml", {"quick": [10, 20, 40], "full": [10, 20, 40, 80]}, 0.1,
         "RMS of Z = x/a (after the fitted shift)", surge_front, ALL),
    Case("rotating_square", "Rotating square patch (t ω = 2), particle regularity",
         "../rotating_square_patch.toml", {"quick": [25, 40], "full": [25, 40, 60, 80]}, 1.0,
         "spread of nearest-neighbour distance (std/mean)", rotating_square,
         {"quick": [("δ-SPH", "RK4"), ("δ+-SPH", "RK4")],
          "full": [(d, i) for d in ("δ-SPH", "δ+-SPH") for i in INTEGRATORS]}),
    Case("elliptic_drop", "Elliptic drop (A0 t = 0.75)", "elliptic_drop.toml",
         {"quick": [12.5, 25, 50], "full": [12.5, 25, 50, 100]}, 1.0,
         "|b/b_exact − 1|", elliptic_drop, SHIFTED),
    Case("taylor_green_re100", "Taylor-Green vortex, Re = 100 (t = 1)", "taylor_green.toml",
         {"quick": [25, 50, 75], "full": [25, 50, 75, 100]}, 1.0,
         "L2 velocity error / U e^{bt}", lambda s: taylor_green(s, 0.01), SHIFTED),
    Case("taylor_green_re1000", "Taylor-Green vortex, Re = 1000 (t = 1)", "taylor_green.toml",
         {"quick": [25, 50, 75], "full": [25, 50, 75, 100]}, 1.0,
         "L2 velocity error / U e^{bt}", lambda s: taylor_green(s, 0.001), SHIFTED,
         {"scheme.dynamic_viscosity": 0.001}),
    Case("patch_impact", "Impact of two patches (ρ0 c0 U)", "patch_impact.toml",
         {"quick": [25, 50, 100], "full": [25, 50, 100, 200]}, 1.0,
         "|plateau/ρ0c0U − 1|", patch_impact, ALL),
    Case("poiseuille_2d", "Poiseuille 2D (ν t/L² = 0.3)", "poiseuille_2d.toml",
         {"quick": [10, 20, 40], "full": [10, 20, 40, 80]}, 1e-3,
         "RMS error of u / u_max", lambda s: poiseuille(s, 0.3), VISCOUS),
    Case("poiseuille_3d", "Poiseuille 3D slab (ν t/L² = 0.1125)", "poiseuille_3d.toml",
         {"quick": [15], "full": [15, 20, 30]}, 1e-3,
         "RMS error of u / u_max", lambda s: poiseuille(s, 0.1125),
         {"quick": [("δ-SPH", "RK4")], "full": [("δ-SPH", "RK4"), ("δ-SPH", "SE2")]}, dim=3),
    Case("cavity", "Lid-driven cavity, Re = 100 (t U/L = 20)", "cavity.toml",
         {"quick": [20, 30], "full": [20, 30, 40, 60]}, 1.0,
         "RMS centre-line velocity error / U (max of u, v)", cavity, RK4_ONLY),
    Case("decaying_turbulence", "2D decaying turbulence, Re = 10⁴ (t U/L = 1)",
         "decaying_turbulence.toml", {"quick": [50], "full": [50, 100]}, 1.0,
         "|E/E_ref − 1| against the spectral reference", decaying_turbulence,
         {"quick": [("δ+-SPH", "RK4"), ("δ-LES-SPH", "RK4")],
          "full": [("δ+-SPH", "RK4"), ("δ-LES-SPH", "RK4")]}, cap=300.0),
]
