//! δ-LES-SPH on the Taylor-Green vortex at Re = 100 (LES.md §2, V1;
//! examples/les_taylor_green.toml, c0 = 20U): the kinetic energy against the exact
//! exp(-16π²νt), the closure's own effect (ν_T/ν ≈ 0.2-0.7% here) and the total momentum.
//!
//! Measured, the largest |E/E_exact - 1| over t ∈ [0, 1] (default shifting a = 8):
//! 3.0% at L/Δx = 50 and 1.14% at 100 (LES.md's windows: 5% and 2%). The error is the
//! start's transient, while the lattice first deforms at the saddle points; the decay
//! rate after t = 0.3 is the exact one within 1%.

use deltasph_suite::example_case;
use sph_core::Simulation;
use std::f64::consts::PI;

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

/// V1 at L/Δx = 50: the energy within LES.md's 5% of the exact decay (measured 3.0%),
/// the eddy viscosity's effect (against C_S = 0) within 1%, the momentum within
/// 10⁻³ M U. (Switching the diffusion off as well, C_δ = 0, changes E by 1.07% at this
/// resolution, just outside LES.md's 1%; `v1_taylor_green_converges` checks that window
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
