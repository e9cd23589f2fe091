//! δ-LES-SPH against docs/theory.md §13's analytic cases.
//!
//! V1, the Taylor-Green vortex at Re = 100 (examples/les_taylor_green.toml, c0 = 20U):
//! the kinetic energy against the exact exp(-16π²νt), the closure's own effect
//! (ν_T/ν ≈ 0.2-0.7% here) and the total momentum. Measured, the largest
//! |E/E_exact - 1| over t ∈ [0, 1] (default shifting a = 8): 3.0% at L/Δx = 50 and 1.14%
//! at 100 (the windows of docs/theory.md §13: 5% and 2%). The error is the start's transient, while the
//! lattice first deforms at the saddle points; the decay rate after t = 0.3 is the exact
//! one within 1%.
//!
//! V2, the forced 8 × 8 cell array at Re = 10⁴ (examples/les_forced_cells.toml): the
//! energy against the mode's ODE without (C_S = 0) and with the eddy viscosity, whose
//! difference pins the LES length l.

use deltasph_suite::example_case;
use sph_core::Simulation;
use std::f64::consts::PI;

/// The forced cell array (examples/les_forced_cells.toml): ν, wavenumber, amplitude and
/// ramp time of the forcing `A r(t)`, r = (1 - cos(π t/T))/2 until T, then 1.
const CELLS_NU: f64 = 1e-4;
const CELLS_K: f64 = 8.0 * PI;
const CELLS_A: f64 = 1.3;
const CELLS_RAMP: f64 = 0.1;

/// E/E_exact at t = 0.1, 0.2, ..., 1, and the largest |P|/(M U) of the run.
fn run(spacing: f64, extra: &[&str]) -> (Vec<f64>, f64) {
    let spacing = format!("particles.spacing = {spacing}");
    let mut overrides = vec![spacing.as_str()];
    overrides.extend_from_slice(extra);
    let case = example_case("les_taylor_green.toml", &overrides);
    let mut sim = Simulation::<2>::new(case).unwrap();
    let nu = 0.01;
    let e0 = sim.energies().kinetic;
    let mass: f64 = sim.particles().mass.iter().sum();
    let (mut ratios, mut momentum) = (vec![], 0.0f64);
    for k in 1..=10 {
        let t = 0.1 * k as f64;
        while sim.time() < t - 1e-12 {
            sim.step_until(t).unwrap();
            let p = sim.particles();
            let total = (0..p.len()).fold(nalgebra::Vector2::zeros(), |acc, i| {
                acc + p.u[i] * p.mass[i]
            });
            momentum = momentum.max(total.norm() / mass);
        }
        let exact = (-16.0 * PI * PI * nu * t).exp();
        ratios.push(sim.energies().kinetic / e0 / exact);
    }
    (ratios, momentum)
}

fn largest_error(ratios: &[f64]) -> f64 {
    ratios.iter().map(|r| (r - 1.0).abs()).fold(0.0, f64::max)
}

fn largest_change(a: &[f64], b: &[f64]) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x / y - 1.0).abs())
        .fold(0.0, f64::max)
}

/// V1 at L/Δx = 50: the energy within the 5% target of the exact decay (measured 3.0%),
/// the eddy viscosity's effect (against C_S = 0) within 1%, the momentum within
/// 10⁻³ M U. (Switching the diffusion off as well, C_δ = 0, changes E by 1.07% at this
/// resolution, just outside the 1% target; `v1_taylor_green_converges` checks that window
/// at L/Δx = 100.)
#[test]
fn v1_taylor_green_energy_follows_the_exact_decay() {
    let (on, momentum) = run(0.02, &[]);
    let (no_eddy, _) = run(0.02, &["scheme.smagorinsky_constant = 0.0"]);
    let (error, eddy) = (largest_error(&on), largest_change(&on, &no_eddy));
    println!(
        "L/Δx = 50: E/E_exact {on:.4?}; largest error {error:.4}, eddy viscosity's effect \
         {eddy:.5}, |P|/MU ≤ {momentum:.2e}"
    );
    assert!(error < 0.05, "energy error {error}");
    assert!(eddy < 0.01, "the eddy viscosity changes E by {eddy}");
    assert!(momentum < 1e-3, "momentum {momentum}");
}

/// V1 converges: within 2% at L/Δx = 100 (measured 1.14%), below the error at 50, and
/// there the closure (C_S = C_δ = 0 against the defaults) changes E by at most 1%.
/// About 2 minutes on 2 cores: `cargo test --release --test physics les -- --ignored`.
#[test]
#[ignore]
fn v1_taylor_green_converges() {
    let (coarse, _) = run(0.02, &[]);
    let (fine, _) = run(0.01, &[]);
    let (off, _) = run(
        0.01,
        &[
            "scheme.smagorinsky_constant = 0.0",
            "scheme.diffusion_constant = 0.0",
        ],
    );
    let (e50, e100) = (largest_error(&coarse), largest_error(&fine));
    let closure = largest_change(&fine, &off);
    println!(
        "largest error: {e50:.4} at L/Δx = 50, {e100:.4} at 100 (closure off {:.4}, \
         closure effect {closure:.4}); E/E_exact at 100: {fine:.4?}",
        largest_error(&off)
    );
    assert!(e100 < 0.02 && e100 < e50, "errors {e50} and {e100}");
    assert!(
        closure < 0.01,
        "the closure changes E by {closure} at L/Δx = 100"
    );
}

/// E = a²/4 of the forced mode at `times` (increasing), from the ODE of docs/theory.md §13
/// `da/dt = A r(t) - 2νk²a - 2.88 (C_S l)² k³ a²` (the last term the exact projection of
/// ν_T‖D‖² onto the mode), by RK4 with 10⁻⁴ steps (converged to 10⁻¹²).
fn cells_ode_energy(cs_l: f64, times: &[f64]) -> Vec<f64> {
    let ramp = |t: f64| 0.5 * (1.0 - (PI * (t / CELLS_RAMP).min(1.0)).cos());
    let rate = |t: f64, a: f64| {
        CELLS_A * ramp(t)
            - 2.0 * CELLS_NU * CELLS_K * CELLS_K * a
            - 2.88 * cs_l * cs_l * CELLS_K.powi(3) * a * a
    };
    let (mut t, mut a, step) = (0.0f64, 0.0f64, 1e-4f64);
    times
        .iter()
        .map(|&end| {
            while t < end - 1e-12 {
                let h = step.min(end - t);
                let k1 = rate(t, a);
                let k2 = rate(t + 0.5 * h, a + 0.5 * h * k1);
                let k3 = rate(t + 0.5 * h, a + 0.5 * h * k2);
                let k4 = rate(t + h, a + h * k3);
                a += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                t += h;
            }
            0.25 * a * a
        })
        .collect()
}

/// Steps `sim` to time `t` and returns its kinetic energy there.
fn kinetic_energy_at(sim: &mut Simulation<2>, t: f64) -> f64 {
    while sim.time() < t - 1e-12 {
        sim.step_until(t).unwrap();
    }
    sim.energies().kinetic
}

/// The kinetic energy of the forced cell array at t = 0.5 and 0.9 (E = ½Σm|u|²,
/// ρ0 = U = L = 1), at spacing `spacing`, Smagorinsky constant `cs`.
fn cells_energy(spacing: f64, cs: f64) -> [f64; 2] {
    let case = example_case(
        "les_forced_cells.toml",
        &[
            &format!("particles.spacing = {spacing}"),
            &format!("scheme.smagorinsky_constant = {cs:?}"),
        ],
    );
    let mut sim = Simulation::<2>::new(case).unwrap();
    [0.5, 0.9].map(|t| kinetic_energy_at(&mut sim, t))
}

/// V2 at `spacing` (l = Δx): the relative error of run A (C_S = 0) against the ODE at
/// t = 0.5 and 0.9, and E_A - E_B at 0.9 (run B: C_S = 0.12) over the ODE's difference.
fn v2(spacing: f64) -> ([f64; 2], f64) {
    let times = [0.5, 0.9];
    let (ode_a, ode_b) = (
        cells_ode_energy(0.0, &times),
        cells_ode_energy(0.12 * spacing, &times),
    );
    let (a, b) = (cells_energy(spacing, 0.0), cells_energy(spacing, 0.12));
    let errors = [a[0] / ode_a[0] - 1.0, a[1] / ode_a[1] - 1.0];
    let ratio = (a[1] - b[1]) / (ode_a[1] - ode_b[1]);
    println!(
        "V2 L/Δx = {:.0}: E_A {a:.5?} (ODE {ode_a:.5?}), E_B {b:.5?} (ODE {ode_b:.5?}); \
         errors {errors:.4?}, ΔE {:.5} = {ratio:.3} × the ODE's {:.5}",
        1.0 / spacing,
        a[1] - b[1],
        ode_a[1] - ode_b[1]
    );
    (errors, ratio)
}

/// The ODE reproduces the table of docs/theory.md §13 (E at t = 0.5 / 0.9: C_S = 0 0.0808 / 0.2744; C_S =
/// 0.12 with l = 1/100: 0.0799 / 0.2640, with l = 1/200: 0.0806 / 0.2717) within a unit of
/// the last digit (the largest difference 0.6 units, 0.27176 for 0.2717),
/// so the table's predictions and windows apply to this forcing.
#[test]
fn v2_ode_matches_the_published_table() {
    for (cs_l, expected) in [
        (0.0, [0.0808, 0.2744]),
        (0.0012, [0.0799, 0.2640]),
        (0.0006, [0.0806, 0.2717]),
    ] {
        let e = cells_ode_energy(cs_l, &[0.5, 0.9]);
        for (got, want) in e.iter().zip(expected) {
            assert!(
                (got - want).abs() <= 1e-4,
                "C_S l = {cs_l}: {e:?} against {expected:?}"
            );
        }
    }
}

/// V2 at L/Δx = 70, with the windows docs/theory.md §13 sets for L/Δx = 100: |E_A/ODE - 1|
/// ≤ 3% at t = 0.5 and ≤ 4% at 0.9 (measured -0.9% and -3.7%), E_A - E_B within [0.6,
/// 1.6] × the ODE's 0.0205 (measured 0.65 ×; at L/Δx = 100 the window rejects l = h, 3.1 ×).
/// The example's L/Δx = 100 (-0.8%, -1.9%, 0.78 ×) and 200 are the ignored
/// `v2_forced_cells_converge`; at L/Δx = 50 E_A(0.9) is 9.4% low (docs/validation/les.md).
/// About 70 s on 2 cores.
#[test]
fn v2_forced_cells_follow_the_ode() {
    let ([e05, e09], ratio) = v2(1.0 / 70.0);
    assert!(e05.abs() <= 0.03, "E_A(0.5) off the ODE by {e05}");
    assert!(e09.abs() <= 0.04, "E_A(0.9) off the ODE by {e09}");
    assert!((0.6..=1.6).contains(&ratio), "ΔE = {ratio} × the ODE's");
}

/// V2 at the example's L/Δx = 100 and at 200, the windows of docs/theory.md §13:
/// |E_A/ODE - 1| ≤ 3% (t = 0.5) and 4% (0.9) at 100, ≤ 2% at 200, the error falling
/// with Δx, and ΔE within [0.6, 1.6] × the ODE's (0.0104, 0.0027). About 20 minutes on 2
/// cores: `cargo test --release --test physics v2_forced_cells_converge -- --ignored --nocapture`.
#[test]
#[ignore]
fn v2_forced_cells_converge() {
    let ([c05, c09], coarse_ratio) = v2(0.01);
    assert!(
        c05.abs() <= 0.03 && c09.abs() <= 0.04,
        "L/Δx = 100: {c05}, {c09}"
    );
    let ([e05, e09], ratio) = v2(0.005);
    assert!(
        e05.abs() <= 0.02 && e09.abs() <= 0.02,
        "errors {e05}, {e09}"
    );
    assert!(
        e09.abs() < c09.abs(),
        "E_A(0.9): {c09} at 100, {e09} at 200"
    );
    for r in [coarse_ratio, ratio] {
        assert!((0.6..=1.6).contains(&r), "ΔE = {r} × the ODE's");
    }
}

/// V3, forced until t = 1, then decaying through 2D turbulence (the same case to t = 3):
/// the windows of docs/theory.md §13 at L/Δx = 100, E(1) ≥ 0.285, E(2) ∈ [0.195, 0.245], E(2.85) ∈
/// [0.160, 0.200] (measured 0.3175, 0.2053, 0.1703; the laminar mode would keep 0.339,
/// 0.263, 0.212). About 6 minutes on 2 cores:
/// `cargo test --release --test physics v3_forced_then_decaying -- --ignored --nocapture`.
#[test]
#[ignore]
fn v3_forced_then_decaying() {
    let case = example_case("les_forced_cells.toml", &["time.end = 3.0"]);
    let mut sim = Simulation::<2>::new(case).unwrap();
    let energy = [1.0, 2.0, 2.85].map(|t| kinetic_energy_at(&mut sim, t));
    println!("V3 L/Δx = 100: E(1, 2, 2.85) = {energy:.4?}");
    let [e1, e2, e3] = energy;
    assert!(e1 >= 0.285, "E(1) = {e1}");
    assert!((0.195..=0.245).contains(&e2), "E(2) = {e2}");
    assert!((0.160..=0.200).contains(&e3), "E(2.85) = {e3}");
}
