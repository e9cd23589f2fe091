"""Linear radiation by a floating 2D section in deep water (a source panel method with
the free-surface Green function) and the free decay it predicts (Cummins' equation).

    python3 examples/validation/floating_section_theory.py [--write-coefficients CSV]
        [--write-decay CSV] [--write-responses CSV] [--panels N]

The section is the NTNU ship section of Sundsdal, Greco, Hanssen & Lugni (2025): beam
B = 0.40 m, draft d = 0.20 m, a rectangle with its bilges rounded to r = 0.0512 m, the
centre of mass KG = 0.106 m above the keel (the measured value), roll radius of
gyration 0.36 B, the mass that of the displaced water. The experiment floats it in
1.0 m of water: kd ≥ 2.5 near its natural periods, deep water for the waves it
radiates there. The experiment's decay tests (sway, heave and roll free, sway held by
springs of 59.5 N/m over the model's 0.586 m) measured natural periods of 1.17 s in
heave and 1.26 s in roll.

Time factor e^{iωt}, y up, the still level y = 0, ν = ω²/g. A unit velocity in mode j
(1 sway, 2 heave, 3 roll about the centre of mass, counter-clockwise) has the
potential φ_j with ∂φ_j/∂n = n_j on the wetted contour (n into the fluid, n_3 =
(x − x_G) n_y − (y − y_G) n_x), written as φ_j = (1/2π) ∫ σ G ds with the deep-water
wave source (Wehausen & Laitone 1960; its principal-value integral written with the
exponential integral E1):

    G(z, ζ) = ln|z − ζ| − ln|z − ζ̄| − 2 Re[e^{νw} E1(νw)] + 2π e^{νY} sin(ν|X|)
              + 2πi e^{νY} cos(νX),          w = Y + iX, X = x − ξ, Y = y + η,

which makes φ_y = νφ on y = 0 and the waves outgoing, ∝ e^{i(ωt − ν|x|)}. Constant σ
on straight panels, collocation at their midpoints (σ/2 plus the panels' normal
derivatives equals n_j); the Rankine terms are integrated exactly, the wave terms by
16-point Gauss–Legendre. A motion ξ_j e^{iωt} has the pressure ρω²ξ_j φ_j, so the
force per metre is ω² A_kj − iω B_kj = −ρω² ∫ φ_j n_k ds: added mass A, damping B.
A(∞) comes from the same panels with φ = 0 on y = 0 (G = ln|z − ζ| − ln|z − ζ̄|).

Checks printed: the damping from the radiated waves, B_jj = ρg²(|A⁺_j|² + |A⁻_j|²)/(2ω³)
with A±_j the wave amplitude far away per unit motion (the energy flux), against B_jj
from the pressure; the semicircle's A(∞) in heave, ρπa²/2 exactly (a circle's dipole
already has φ = 0 on its diameter); Kramers–Kronig, A(ω) = A(∞) − (1/ω) ∫_0^∞ K(t)
sin ωt dt, from the damping alone; convergence in the number of panels. The panel
method fails near the section's irregular frequencies (the interior problem's
eigenvalues, the first at ν = (π/B) coth(πd/B), ω = 9.16 rad/s); the damping is taken
up to 8.5 rad/s, where it has fallen below 1% of its peak, and zero beyond.

Decay (Cummins 1962): (M + A(∞)) ẍ + ∫_0^t K(t − τ) ẋ(τ) dτ + C x = 0 with
K(t) = (2/π) ∫_0^∞ B(ω) cos ωt dω, M the body's mass matrix, C its hydrostatic
restoring plus the sway springs; the trapezoidal rule for the convolution and the
integration in time. Two starts, sway, heave and roll free as in the experiment's decay
tests: released at rest 0.04 m above the draft, and upright at the draft with an
angular velocity of 0.5 rad/s given to the body in water at rest (a kick: its momentum
is shared at once with the added mass, and the roll reaches about 0.08 rad; a kick
leaves the section upright, on the particle lattice it was built on).

Responses in regular waves (the experiment's wave tests): the wave force on the section
held still, from the diffraction problem on the same panels (checked against Haskind's
relation from the radiation potentials), and the motions of
[−ω²(M + A) + iω(B + B_rig) + C] ξ = F, with the rig's damping B_rig the experiment
measured in sway (8.70 N s/m over the model's 0.586 m), taken the same in heave.
"""
import argparse
import math
from pathlib import Path

import numpy as np
from scipy import special

G = 9.81
RHO = 1000.0
BEAM = 0.40
DRAFT = 0.20
BILGE = 0.0512
KG = 0.106
ROLL_GYRATION = 0.36 * BEAM
SWAY_SPRING = 59.5 / 0.586          # N/m per metre of section
# the rig's damping in the wave tests, 8.70 N s/m measured in sway and taken the same in
# heave, per metre of section
RIG_DAMPING = np.diag([8.70 / 0.586, 8.70 / 0.586, 0.0])
IRREGULAR_CUTOFF = 8.5              # rad/s, below the first irregular frequency
FREQUENCY_STEP = 0.05               # rad/s
HEAVE_RELEASE = 0.04                # m, 20% of the draft
ROLL_KICK = 0.5                     # rad/s
GAUSS_X, GAUSS_W = np.polynomial.legendre.leggauss(16)


def section_contour(panels):
    """Panel end points of the wetted contour, from the waterline at x = B/2 down the
    side, round the bilge, along the keel and up to x = −B/2, equally spaced along it."""
    half = BEAM / 2.0
    side = DRAFT - BILGE
    arc = 0.5 * math.pi * BILGE
    keel = BEAM - 2.0 * BILGE
    pieces = [
        lambda s: (half, -s),
        lambda s: (half - BILGE + BILGE * math.cos(s / BILGE),
                   -side - BILGE * math.sin(s / BILGE)),
        lambda s: (half - BILGE - s, -DRAFT),
        lambda s: (-half + BILGE - BILGE * math.sin(s / BILGE),
                   -side - BILGE * math.cos(s / BILGE)),
        lambda s: (-half, -side + s),
    ]
    lengths = [side, arc, keel, arc, side]
    points = []
    for s in np.linspace(0.0, sum(lengths), panels + 1):
        for piece, length in zip(pieces, lengths):
            if s <= length + 1e-12:
                points.append(piece(min(s, length)))
                break
            s -= length
    return np.array(points)


def semicircle_contour(radius, panels):
    """The same walk (right waterline, down, round to the left) round a semicircle."""
    angles = np.linspace(0.0, -math.pi, panels + 1)
    return np.column_stack([radius * np.cos(angles), radius * np.sin(angles)])


def section_area(points):
    """Area under the still level enclosed by the contour (the shoelace formula)."""
    x, y = points[:, 0], points[:, 1]
    return 0.5 * abs(np.sum(x[:-1] * y[1:] - x[1:] * y[:-1]) + x[-1] * y[0] - x[0] * y[-1])


class Panels:
    """Straight panels between consecutive contour points, walked clockwise round the
    body: the fluid is on the left of the walk, so the normal into it is the tangent
    turned a quarter counter-clockwise, (−t_y, t_x)."""

    def __init__(self, points):
        self.start, self.end = points[:-1], points[1:]
        d = self.end - self.start
        self.length = np.hypot(d[:, 0], d[:, 1])
        self.tangent = d / self.length[:, None]
        self.normal = np.column_stack([-self.tangent[:, 1], self.tangent[:, 0]])
        self.mid = 0.5 * (self.start + self.end)
        nodes = 0.5 * (GAUSS_X[None, :, None] + 1.0) * d[:, None, :]
        self.gauss_points = self.start[:, None, :] + nodes            # [panel, 16, 2]
        self.gauss_weights = 0.5 * self.length[:, None] * GAUSS_W[None, :]

    def modes(self, centre):
        """n_j of sway, heave and roll about `centre`, [panel, 3]."""
        nx, ny = self.normal[:, 0], self.normal[:, 1]
        rx, ry = self.mid[:, 0] - centre[0], self.mid[:, 1] - centre[1]
        return np.column_stack([nx, ny, rx * ny - ry * nx])


def rankine(field, start, end):
    """∫ ln|z − ζ| ds over the straight panels start→end and its gradient in z, for
    every field point: (value, ∂x, ∂y), arrays [field, panel]. In panel coordinates
    (u along it from its centre, v across it) the primitive of ln r is
    w ln r − w + v atan(w/v), w = u − s; the across-derivative is the angle the panel
    subtends, 0 on the panel itself (the principal value)."""
    d = end - start
    length = np.hypot(d[:, 0], d[:, 1])
    tx, ty = (d[:, 0] / length)[None, :], (d[:, 1] / length)[None, :]
    cx, cy = 0.5 * (start[:, 0] + end[:, 0]), 0.5 * (start[:, 1] + end[:, 1])
    dx, dy = field[:, None, 0] - cx[None, :], field[:, None, 1] - cy[None, :]
    u = dx * tx + dy * ty
    v = -dx * ty + dy * tx
    upper, lower = u + 0.5 * length[None, :], u - 0.5 * length[None, :]
    on_line = np.abs(v) < 1e-14 * length[None, :]
    v_safe = np.where(on_line, 1.0, v)

    def primitive(w):
        log_r = 0.5 * np.log(np.maximum(w * w + v * v, 1e-300))
        return w * log_r - w + np.where(on_line, 0.0, v * np.arctan(w / v_safe))

    value = primitive(upper) - primitive(lower)
    du = 0.5 * (np.log(upper**2 + v**2) - np.log(lower**2 + v**2))
    dv = np.where(on_line, 0.0, np.arctan(upper / v_safe) - np.arctan(lower / v_safe))
    return value, du * tx - dv * ty, du * ty + dv * tx


def wave_terms(field, source, nu):
    """The wave terms of G and their gradient in the field point: field [n, 2],
    source [m, 2], arrays [n, m]. G is even in X: F = e^{νw} E1(νw) is taken at
    w = Y + i|X|, off the branch cut of E1 on the negative real axis, with
    dF/dw = νF − 1/w, ∂w/∂|X| = i and ∂w/∂y = 1."""
    X = field[:, None, 0] - source[None, :, 0]
    Y = field[:, None, 1] + source[None, :, 1]
    w = Y + 1j * np.abs(X)
    f = np.exp(nu * w) * special.exp1(nu * w)
    df = nu * f - 1.0 / w
    e = np.exp(nu * Y)
    regular = 2.0 * math.pi * e * (np.sin(nu * np.abs(X)) + 1j * np.cos(nu * X))
    value = -2.0 * f.real + regular
    gx = np.sign(X) * (2.0 * df.imag + 2.0 * math.pi * nu * e * np.cos(nu * X)) \
        - 2j * math.pi * nu * e * np.sin(nu * X)
    gy = -2.0 * df.real + nu * regular
    return value, gx, gy


def influence(panels, nu):
    """Potential and normal velocity at the collocation points of unit source
    densities on each panel, (1/2π) ∫ G ds and (1/2π) ∂/∂n ∫ G ds (the self term σ/2
    added); ν = None for the high-frequency limit φ = 0 on y = 0."""
    mid, normal = panels.mid, panels.normal
    mirror = np.array([1.0, -1.0])
    value, gx, gy = rankine(mid, panels.start, panels.end)
    image, ix, iy = rankine(mid, panels.start * mirror, panels.end * mirror)
    value, gx, gy = value - image, gx - ix, gy - iy
    value, gx, gy = value.astype(complex), gx.astype(complex), gy.astype(complex)
    if nu is not None:
        n, m = len(mid), len(panels.length)
        points = panels.gauss_points.reshape(-1, 2)
        wv, wx, wy = wave_terms(mid, points, nu)
        weights = panels.gauss_weights.reshape(-1)
        value += (wv * weights).reshape(n, m, -1).sum(axis=2)
        gx += (wx * weights).reshape(n, m, -1).sum(axis=2)
        gy += (wy * weights).reshape(n, m, -1).sum(axis=2)
    potential = value / (2.0 * math.pi)
    flux = (gx * normal[:, 0, None] + gy * normal[:, 1, None]) / (2.0 * math.pi)
    flux += 0.5 * np.eye(len(mid))
    return potential, flux


def radiation(panels, centre, omega, solved=None):
    """Added mass and damping [3, 3] per metre at ω (ω = inf: A(∞), B = 0), and the
    radiated wave amplitudes toward +x and −x per unit motion [2, 3]. With `solved` a
    dict, the influence matrices and the potentials are left in it (`potential`,
    `flux`, `phi`) for the diffraction problem at the same ω."""
    nu = None if math.isinf(omega) else omega**2 / G
    potential, flux = influence(panels, nu)
    modes = panels.modes(centre)
    sigma = np.linalg.solve(flux, modes.astype(complex))
    phi = potential @ sigma
    if solved is not None:
        solved.update(potential=potential, flux=flux, phi=phi)
    pressure_integral = (modes * panels.length[:, None]).T @ phi      # ∫ φ_j n_k ds
    added_mass = -RHO * pressure_integral.real
    damping = np.zeros((3, 3)) if nu is None else RHO * omega * pressure_integral.imag
    amplitudes = np.zeros((2, 3), dtype=complex)
    if nu is not None:
        # far away φ → i e^{νy ∓ iνx} ∫ σ e^{νη ± iνξ} ds; elevation ν ξ φ(y = 0)
        xi, eta = panels.gauss_points[..., 0], panels.gauss_points[..., 1]
        for side, sign in enumerate((1.0, -1.0)):
            kernel = np.sum(np.exp(nu * eta + sign * 1j * nu * xi) * panels.gauss_weights, axis=1)
            amplitudes[side] = 1j * nu * (kernel @ sigma)
    return added_mass, damping, amplitudes


def incident(points, nu, omega):
    """The incident wave of unit amplitude running toward +x, φ_I = (ig/ω) e^{νy − iνx}
    (elevation e^{i(ωt − νx)}), and its gradient at `points` [n, 2]."""
    phi = 1j * G / omega * np.exp(nu * points[:, 1] - 1j * nu * points[:, 0])
    return phi, -1j * nu * phi, nu * phi


def excitation(panels, centre, omega, potential, flux, phi_k):
    """The wave force [3] per metre on the section held still in the incident wave of
    unit amplitude, F_k = iωρ ∫ (φ_I + φ_D) n_k ds with ∂φ_D/∂n = −∂φ_I/∂n (the
    diffraction problem on the radiation's panels: its `potential` and `flux`
    influence matrices), and the same force by the Haskind relation from the radiation
    potentials `phi_k` alone (per unit velocity, ∂φ_k/∂n = n_k),
    F_k = iωρ ∫ (φ_I n_k − φ_k ∂φ_I/∂n) ds."""
    nu = omega**2 / G
    phi_i, gx, gy = incident(panels.mid, nu, omega)
    normal_i = gx * panels.normal[:, 0] + gy * panels.normal[:, 1]
    phi_d = potential @ np.linalg.solve(flux, -normal_i)
    weighted = panels.modes(centre) * panels.length[:, None]
    diffraction = 1j * omega * RHO * weighted.T @ (phi_i + phi_d)
    haskind = 1j * omega * RHO * (weighted.T @ phi_i - (phi_k * panels.length[:, None]).T @ normal_i)
    return diffraction, haskind


def responses(panels, centre, mass, restoring, rig_damping, omegas):
    """Complex motion amplitudes [ω, 3] per unit incident amplitude,
    [−ω²(M + A) + iω(B + B_rig) + C] ξ = F, and the Haskind check's largest relative
    difference in the force."""
    motions, worst = [], 0.0
    for omega in omegas:
        solved = {}
        added, damping, _ = radiation(panels, centre, omega, solved)
        force, haskind = excitation(panels, centre, omega, solved["potential"], solved["flux"],
                                    solved["phi"])
        worst = max(worst, np.max(np.abs(force - haskind)) / np.max(np.abs(force)))
        system = -omega**2 * (mass + added) + 1j * omega * (damping + rig_damping) + restoring
        motions.append(np.linalg.solve(system, force))
    return np.array(motions), worst


def hydrostatics(points):
    """Displaced area, the centre of buoyancy's height above the keel (KB), the
    metacentric height GM = KB + BM − KG with BM = B³/(12 area), and the restoring
    matrix [3, 3] of sway (the springs), heave (ρgB) and roll about the centre of mass
    (ρg area GM)."""
    area = section_area(points)
    x, y = points[:, 0], points[:, 1]
    # centroid of the closed polygon (contour plus the still level back to the start)
    xs, ys = np.append(x, x[0]), np.append(y, y[0])
    cross = xs[:-1] * ys[1:] - xs[1:] * ys[:-1]
    centroid_y = np.sum((ys[:-1] + ys[1:]) * cross) / (6.0 * np.sum(cross) / 2.0)
    kb = DRAFT + centroid_y
    gm = kb + BEAM**3 / (12.0 * area) - KG
    restoring = np.diag([SWAY_SPRING, RHO * G * BEAM, RHO * G * area * gm])
    return area, kb, gm, restoring


def mass_matrix(area):
    mass = RHO * area
    return np.diag([mass, mass, mass * ROLL_GYRATION**2])


def retardation(omegas, damping, times, tail_end=80.0):
    """K(t) = (2/π) ∫ B(ω) cos ωt dω by the trapezoidal rule on the frequency grid
    (equally spaced from its step), [time, 3, 3]. Past the grid's last frequency ω_c
    the damping is continued as B(ω_c)(ω_c/ω)³, the decay of the waves a body with
    vertical sides at the waterline radiates (their amplitude per unit motion tends to
    a constant, B = ρg²|A|²/ω³), up to `tail_end`."""
    step = omegas[1] - omegas[0]
    tail = np.arange(omegas[-1] + step, tail_end, step)
    grid = np.concatenate([omegas, tail])
    values = np.concatenate([damping, damping[-1][None] * (omegas[-1] / tail[:, None, None]) ** 3])
    weights = np.full_like(grid, step)
    weights[0] *= 0.5
    weights[-1] *= 0.5
    cos = np.cos(np.outer(times, grid)) * weights[None, :]
    return (2.0 / math.pi) * np.einsum("tw,wjk->tjk", cos, values)


def cummins(mass, added_infinite, restoring, kernel, dt, start, velocity):
    """x(t) of (M + A∞) ẍ + ∫ K(t − τ) ẋ dτ + C x = 0 from `start` [3] with
    `velocity` [3]:
    velocity Verlet, the convolution by the trapezoidal rule over the velocities so
    far (the newest one predicted)."""
    steps = kernel.shape[0]
    inverse = np.linalg.inv(mass + added_infinite)
    x = np.zeros((steps, 3))
    v = np.zeros((steps, 3))
    x[0] = start
    v[0] = velocity
    a = inverse @ (-restoring @ x[0])
    for n in range(steps - 1):
        x[n + 1] = x[n] + dt * v[n] + 0.5 * dt * dt * a
        guess = v[n] + dt * a
        v[n + 1] = guess
        memory = np.einsum("tjk,tk->j", kernel[n + 1::-1], v[: n + 2]) * dt \
            - 0.5 * dt * (kernel[n + 1] @ v[0] + kernel[0] @ guess)
        a_next = inverse @ (-restoring @ x[n + 1] - memory)
        v[n + 1] = v[n] + 0.5 * dt * (a + a_next)
        a = a_next
    return x


def crossing_periods(times, signal):
    """Periods from successive up-crossings of zero (linear interpolation)."""
    up = np.where((signal[:-1] < 0.0) & (signal[1:] >= 0.0))[0]
    crossings = times[up] - signal[up] * (times[up + 1] - times[up]) / (signal[up + 1] - signal[up])
    return np.diff(crossings)


def semicircle_check(panels_count):
    radius = 0.1
    panels = Panels(semicircle_contour(radius, panels_count))
    added, _, _ = radiation(panels, (0.0, 0.0), math.inf)
    return added[1, 1] / (RHO * math.pi * radius**2 / 2.0)


def coefficient_table(panels, centre, omegas):
    added = np.zeros((len(omegas), 3, 3))
    damping = np.zeros((len(omegas), 3, 3))
    flux_damping = np.zeros((len(omegas), 3))
    for i, omega in enumerate(omegas):
        added[i], damping[i], amplitudes = radiation(panels, centre, omega)
        flux_damping[i] = RHO * G**2 * np.sum(np.abs(amplitudes) ** 2, axis=0) / (2.0 * omega**3)
    return added, damping, flux_damping


def print_checks(panels_count, added, damping, flux_damping, added_infinite, kernel, times):
    """The semicircle's A(∞), the far-field damping and Kramers–Kronig."""
    print(f"semicircle A22(∞)/(ρπa²/2): {semicircle_check(panels_count):.5f} (exact 1)")
    for j, name in enumerate(("sway", "heave", "roll")):
        worst = np.max(np.abs(flux_damping[:, j] - damping[:, j, j])) / np.max(damping[:, j, j])
        checks = []
        for omega in (2.0, 4.0, 6.0):
            i = int(round(omega / FREQUENCY_STEP)) - 1
            memory = np.trapezoid(kernel[:, j, j] * np.sin(omega * times), times) / omega
            checks.append(f"ω = {omega}: {added[i, j, j]:.3f} / {added_infinite[j, j] - memory:.3f}")
        print(f"{name}: far-field damping differs by {worst:.2e} of the peak; A(ω) / "
              "Kramers–Kronig: " + "; ".join(checks))


def decay_curves(mass, added_infinite, restoring, kernel, times):
    """The heave release and the roll kick by Cummins' equation: name → x [time, 3].
    The kick is given to the body in water at rest, so its momentum M v is shared at
    once with the added mass: it starts at (M + A∞)⁻¹ M v."""
    kick = np.linalg.solve(mass + added_infinite, mass @ np.array([0.0, 0.0, ROLL_KICK]))
    starts = {"heave": ([0.0, HEAVE_RELEASE, 0.0], [0.0, 0.0, 0.0]),
              "roll": ([0.0, 0.0, 0.0], kick)}
    decay = {}
    for name, (start, velocity) in starts.items():
        x = cummins(mass, added_infinite, restoring, kernel, times[1] - times[0],
                    np.array(start), np.array(velocity))
        periods = crossing_periods(times, x[:, 1 if name == "heave" else 2])
        print(f"{name} decay: periods {np.round(periods[:4], 4)} s")
        decay[name] = x
    return decay


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--panels", type=int, default=120)
    parser.add_argument("--write-coefficients", type=Path)
    parser.add_argument("--write-decay", type=Path)
    parser.add_argument("--write-responses", type=Path)
    args = parser.parse_args()
    points = section_contour(args.panels)
    panels = Panels(points)
    area, kb, gm, restoring = hydrostatics(points)
    centre = (0.0, KG - DRAFT)
    print(f"section: area {area:.6f} m², mass {RHO * area:.3f} kg/m, KB {kb:.4f} m, "
          f"GM {gm:.4f} m (experiment 0.0629 m)")
    added_infinite, _, _ = radiation(panels, centre, math.inf)
    omegas = np.arange(FREQUENCY_STEP, IRREGULAR_CUTOFF + 1e-9, FREQUENCY_STEP)
    added, damping, flux_damping = coefficient_table(panels, centre, omegas)
    times = np.arange(0.0, 12.0, 0.002)
    kernel = retardation(omegas, damping, times)
    print_checks(args.panels, added, damping, flux_damping, added_infinite, kernel, times)
    decay = decay_curves(mass_matrix(area), added_infinite, restoring, kernel, times)
    source = ["NTNU ship section (Sundsdal, Greco, Hanssen & Lugni 2025): B 0.40 m, draft 0.20 m,",
              "bilge radius 0.0512 m, KG 0.106 m, roll gyration radius 0.144 m, deep water; linear theory",
              f"by examples/validation/floating_section_theory.py ({args.panels} source panels)"]
    if args.write_coefficients:
        header = "omega," + ",".join(f"A{j + 1}{k + 1},B{j + 1}{k + 1}" for j in range(3) for k in range(3))
        rows = [np.concatenate([[w], np.stack([added[i], damping[i]], axis=-1).reshape(-1)])
                for i, w in enumerate(omegas)]
        write_csv(args.write_coefficients, source + ["added mass A_jk and damping B_jk per metre, "
                  "1 sway, 2 heave, 3 roll about the centre of mass"], header, np.array(rows))
    if args.write_responses:
        # up to the irregular-frequency cutoff, from a period of 1.6 s
        response_omegas = np.arange(3.9, IRREGULAR_CUTOFF + 1e-9, 0.05)
        motions, worst = responses(panels, centre, mass_matrix(area), restoring, RIG_DAMPING,
                                   response_omegas)
        print(f"wave force by diffraction against Haskind's relation: {worst:.2e} of the largest")
        table = np.column_stack([response_omegas, np.abs(motions), np.angle(motions)])
        write_csv(args.write_responses, source + [
            "motions in regular beam-sea waves of unit amplitude running toward +x (elevation",
            "cos(ωt − νx), ν = ω²/g), the experiment's sway springs and rig damping (8.70 N s/m",
            "in sway and heave over 0.586 m): amplitude [m/m, m/m, rad/m] and phase [rad]"],
            "omega,sway,heave,roll,sway_phase,heave_phase,roll_phase", table)
    if args.write_decay:
        # every 0.01 s, the time series' interval of the case
        table = np.column_stack([times, decay["heave"], decay["roll"]])[::5]
        write_csv(args.write_decay, source + ["free decay by Cummins' equation: released 0.04 m "
                  "above the draft, and kicked to 0.5 rad/s in roll"],
                  "t,heave_release_sway,heave_release_heave,heave_release_roll,"
                  "roll_kick_sway,roll_kick_heave,roll_kick_roll", table)


def write_csv(path, comments, header, table):
    with open(path, "w") as f:
        f.writelines(f"# {line}\n" for line in comments)
        np.savetxt(f, table, delimiter=",", fmt="%.6e", header=header, comments="")

if __name__ == "__main__":
    main()
