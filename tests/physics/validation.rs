//! The fast subset of the validation suite (docs/validation): the cases of
//! `examples/validation/` at coarse resolution, each against its analytic reference.
//! Tolerances come from the measured errors at this and the next finer resolution
//! (quoted at each assertion); the full resolution studies are `examples/validation/run_all.py`.

use deltasph_suite::{example_case, read_csv, refdata};
use sph_core::{Kind, Simulation, Vector};

fn run_to<const D: usize>(sim: &mut Simulation<D>, t: f64) {
    while sim.time() < t * (1.0 - 1e-12) {
        sim.step_until(t).unwrap();
    }
}

/// Semi-axes `a = R sqrt(<x²>(t)/<x²>(0))` from the second moments of the particle
/// cloud, exact for any cloud carried by a linear velocity field, and the kinetic
/// energy change, at `t` for the elliptic drop with `overrides`.
fn elliptic_drop(overrides: &[&str], t: f64) -> (f64, f64, f64) {
    let case = example_case("validation/elliptic_drop.toml", overrides);
    let mut sim = Simulation::<2>::new(case).unwrap();
    let moments = |sim: &Simulation<2>| {
        let p = sim.particles();
        let n = p.len() as f64;
        let m: Vector<2> = p.x.iter().map(|x| x.component_mul(x)).sum();
        m / n
    };
    let (m0, e0) = (moments(&sim), sim.energies().kinetic);
    run_to(&mut sim, t);
    let m = moments(&sim);
    let ek = sim.energies().kinetic / e0 - 1.0;
    ((m[0] / m0[0]).sqrt(), (m[1] / m0[1]).sqrt(), ek)
}

/// Elliptic drop (Monaghan 1994) at A0 t = 0.75, against the ODE solution of the
/// reference CSV: both semi-axes and the area a·b = R² of the incompressible drop.
///
/// The strain stretches the particle lattice 3.8 : 1 by then (x spacing about Δx/2,
/// y spacing about 1.9Δx). Without shifting the SPH divergence of that anisotropic
/// cloud under-reads the area's growth: the particles come to cover an ellipse 10%
/// too large (δ-SPH, h/Δx = 1.33; 4-7% without diffusion, 1.3% at h/Δx = 2, flat from
/// R/Δx = 25 to 100) while Σ m/ρ stays within 0.7% of πR². The second moments, the
/// volume-weighted moments and the extent of the cloud all show the same excess, so
/// the diagnostic is sound and the Lagrangian dynamics is not. δ+-SPH shifting keeps
/// the distribution isotropic, and with it the drop converges: a·b within 0.30%,
/// 0.45%, 0.40% of R² at R/Δx = 25, 50, 100 (a 0.05/0.49/0.39%, b 0.36/0.03/0.01%).
/// Asserted at R/Δx = 25 within 1%, and the error of the drop without shifting is
/// asserted to be what shifting removes.
#[test]
fn elliptic_drop_follows_the_exact_ellipse() {
    let (_, rows) = read_csv(&refdata("elliptic_drop_exact.csv"));
    let exact = rows.iter().find(|r| (r[0] - 0.75).abs() < 1e-9).unwrap();
    let (a, b, ek) = elliptic_drop(&["scheme.shifting = \"delta_plus\""], 0.0075);
    let (a_plain, b_plain, _) = elliptic_drop(&[], 0.0075);
    let area = |a: f64, b: f64| a * b - 1.0;
    println!(
        "δ+-SPH: a {:+.4}, b {:+.4}, a·b {:+.4}, E_k change {ek:+.2e}; δ-SPH: a {:+.4}, b {:+.4}, a·b {:+.4}",
        a / exact[1] - 1.0,
        b / exact[2] - 1.0,
        area(a, b),
        a_plain / exact[1] - 1.0,
        b_plain / exact[2] - 1.0,
        area(a_plain, b_plain),
    );
    assert!((a / exact[1] - 1.0).abs() < 0.01, "a = {a}");
    assert!((b / exact[2] - 1.0).abs() < 0.01, "b = {b}");
    assert!(area(a, b).abs() < 0.01, "a·b = {}", a * b);
    assert!(area(a_plain, b_plain) > 0.05, "the unshifted drop grows");
    // E_k is an invariant of the exact flow; measured change -8.1e-4 with shifting
    assert!(ek.abs() < 2e-3, "E_k change {ek}");
}

/// Start-up Poiseuille flow (Morris et al. 1997), the series solution with the signs
/// corrected as in `docs/validation/data/README.md`.
fn poiseuille_exact(y: f64, t: f64) -> f64 {
    let (l, nu, f) = (1e-3, 1e-6, 2e-4);
    let mut u = f / (2.0 * nu) * y * (l - y);
    for n in 0..50 {
        let k = (2 * n + 1) as f64;
        let pi = std::f64::consts::PI;
        u -= 4.0 * f * l * l / (nu * pi.powi(3) * k.powi(3))
            * (k * pi * y / l).sin()
            * (-k * k * pi * pi * nu * t / (l * l)).exp();
    }
    u
}

/// Start-up Couette flow, the lid started at t = 0:
/// `u = U y/L - Σ_n 2U (-1)^(n+1)/(nπ) sin(nπy/L) e^(-n²π²νt/L²)`.
fn couette_exact(y: f64, t: f64) -> f64 {
    let (l, nu, u_lid) = (1e-3, 1e-6, 2.5e-5);
    let pi = std::f64::consts::PI;
    let mut u = u_lid * y / l;
    for n in 1..200 {
        let k = n as f64;
        let sign = if n % 2 == 1 { 1.0 } else { -1.0 };
        u -= 2.0 * u_lid * sign / (k * pi)
            * (k * pi * y / l).sin()
            * (-k * k * pi * pi * nu * t / (l * l)).exp();
    }
    u
}

/// RMS error of u_x over the fluid at t against `exact(y, t)`, relative to 2.5e-5 m/s
/// (the steady centre speed of the Poiseuille case, the lid speed of the Couette case).
fn profile_error<const D: usize>(
    name: &str,
    spacing: f64,
    t: f64,
    exact: impl Fn(f64, f64) -> f64,
) -> f64 {
    let case = example_case(name, &[&format!("particles.spacing = {spacing}")]);
    let mut sim = Simulation::<D>::new(case).unwrap();
    run_to(&mut sim, t);
    let p = sim.particles();
    let (sum, n) = (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| (p.u[i][0] - exact(p.x[i][1], t)).powi(2))
        .fold((0.0, 0), |(s, n), e| (s + e, n + 1));
    (sum / n as f64).sqrt() / 2.5e-5
}

fn poiseuille_error<const D: usize>(name: &str, spacing: f64, t: f64) -> f64 {
    profile_error::<D>(name, spacing, t, poiseuille_exact)
}

#[test]
fn couette_start_up_matches_the_series_solution() {
    // ν t/L² = 0.1. Measured with Wendland C2 at h/Δx = 2 (the case's): 0.93%, 0.78%,
    // 0.78% of U at L/Δx = 10, 20, 30 (flat: the viscous operator's error at fixed
    // h/Δx); at h/Δx = 1.33 the same runs are 3.4% off.
    let e = profile_error::<2>("validation/couette_2d.toml", 5e-5, 0.1, couette_exact);
    println!("start-up Couette, L/Δx = 20: RMS error {e:.4} of U");
    assert!(e < 0.012, "error {e}");
}

#[test]
fn poiseuille_2d_matches_the_series_solution() {
    // ν t/L² = 0.1125 (Morris et al.'s first profile). Measured at L/Δx = 10, 20, 40:
    // 1.45%, 1.02%, 1.05%. With Wendland C2 at h/Δx = 1.33 the same run is 17% off:
    // the physical viscous term needs h/Δx = 2 (see docs/validation).
    let e = poiseuille_error::<2>("validation/poiseuille_2d.toml", 1e-4, 0.1125);
    println!("2D Poiseuille, L/Δx = 10: RMS error {e:.4} of u_max");
    assert!(e < 0.025, "error {e}");
}

#[test]
fn poiseuille_3d_confirms_the_viscous_constant() {
    // K = 2(n+2)μ with n = 3; the 2D constant 2(2+2)μ would make ν 20% too small and
    // the profile about 15% off at this time. Measured at L/Δx = 15: 0.62%.
    let e = poiseuille_error::<3>("validation/poiseuille_3d.toml", 1e-3 / 15.0, 0.1125);
    println!("3D Poiseuille, L/Δx = 15: RMS error {e:.4} of u_max");
    assert!(e < 0.025, "error {e}");
}

struct Impact {
    /// Mean contact-point pressure over 0.2 to 0.8 of the acoustic plateau, / ρ0 c0 U.
    plateau: f64,
    /// RMS of p_i minus its Shepard-smoothed value over the patch interiors, / ρ0 c0 U.
    noise: f64,
}

fn patch_impact(diffusion: &str) -> Impact {
    let case = example_case(
        "validation/patch_impact.toml",
        &[&format!("scheme.diffusion = \"{diffusion}\"")],
    );
    let mut sim = Simulation::<2>::new(case).unwrap();
    let scale = 1000.0 * 20.0 * 1.0;
    let (release, origin) = (0.025, Vector::<2>::zeros());
    let (mut sum, mut n) = (0.0, 0);
    while sim.time() < 0.05 * (1.0 - 1e-12) {
        sim.step().unwrap();
        if (0.2 * release..0.8 * release).contains(&sim.time()) {
            sim.sync_pressure();
            sum += sim
                .probe_pressure(&origin)
                .expect("the patch centre is wet");
            n += 1;
        }
    }
    sim.sync_pressure();
    let p = sim.particles();
    let inner: Vec<usize> = (0..p.len())
        .filter(|&i| p.x[i].iter().all(|c| c.abs() < 0.45))
        .collect();
    let noise = inner
        .iter()
        .map(|&i| (p.p[i] - sim.probe_pressure(&p.x[i]).expect("a fluid particle")).powi(2))
        .sum::<f64>()
        / inner.len() as f64;
    Impact {
        plateau: sum / n as f64 / scale,
        noise: noise.sqrt() / scale,
    }
}

#[test]
fn patch_impact_reaches_the_acoustic_pressure_and_delta_sph_removes_the_noise() {
    let delta = patch_impact("delta_sph");
    let standard = patch_impact("none");
    println!(
        "δ-SPH: plateau {:.4}, noise {:.4}; standard SPH: plateau {:.4}, noise {:.4}",
        delta.plateau, delta.noise, standard.plateau, standard.noise
    );
    // Water hammer p = ρ0 c0 U (U/c0 = 0.05). Measured plateau at L/Δx = 50 and 100:
    // 0.994, 1.019 (δ-SPH; the case's h/Δx = 1.33); at h/Δx = 2 1.049, 1.018.
    assert!((delta.plateau - 1.0).abs() < 0.05);
    assert!((standard.plateau - 1.0).abs() < 0.05);
    // At t = 2(h/2)/c0 standard SPH carries checkerboard noise; measured 0.082 against
    // 0.019 for δ-SPH here, 0.186 against 0.025 at twice the resolution.
    assert!(standard.noise > 3.0 * delta.noise);
    assert!(delta.noise < 0.03);
}

/// Wendland C2 Shepard average of the fluid velocity at `point` (support 2h).
fn velocity_at(sim: &Simulation<2>, point: Vector<2>) -> Vector<2> {
    let (p, h) = (sim.particles(), sim.case().h());
    let (mut sum, mut weight) = (Vector::<2>::zeros(), 0.0);
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid) {
        let q = (p.x[i] - point).norm() / h;
        if q < 2.0 {
            let w = (1.0 - q / 2.0).powi(4) * (2.0 * q + 1.0);
            sum += p.u[i] * w;
            weight += w;
        }
    }
    sum / weight
}

/// Lid-driven cavity, Re = 100 (Ghia, Ghia & Shin 1982, Table I): the sliding lid drives
/// the primary vortex; u on the vertical centre line after t U/L = 10.
#[test]
fn lid_driven_cavity_approaches_ghia() {
    let case = example_case("validation/cavity.toml", &["particles.spacing = 0.05"]);
    let mut sim = Simulation::<2>::new(case).unwrap();
    let lid: Vec<(u32, Vector<2>)> = (0..sim.particles().len())
        .filter(|&i| sim.particles().u[i][0] == 1.0)
        .map(|i| (sim.particles().id[i], sim.particles().x[i]))
        .collect();
    run_to(&mut sim, 10.0);
    // The lid slides in its own plane: its particles keep their places and velocity.
    let p = sim.particles();
    for &(id, x0) in &lid {
        let i = p.id.iter().position(|&j| j == id).unwrap();
        assert_eq!((p.x[i], p.u[i]), (x0, Vector::<2>::new(1.0, 0.0)));
    }
    let (_, rows) = read_csv(&refdata(
        "lid_driven_cavity_ghia1982_u_on_vertical_centreline.csv",
    ));
    let inner: Vec<&Vec<f64>> = rows.iter().filter(|r| r[0] > 0.0 && r[0] < 1.0).collect();
    let rms = (inner
        .iter()
        .map(|r| (velocity_at(&sim, Vector::<2>::new(0.5, r[0]))[0] - r[1]).powi(2))
        .sum::<f64>()
        / inner.len() as f64)
        .sqrt();
    let scale = (inner.iter().map(|r| r[1] * r[1]).sum::<f64>() / inner.len() as f64).sqrt();
    println!("cavity, L/Δx = 20, t = 10: RMS u error {rms:.4} (profile RMS {scale:.3})");
    // Measured 0.088 here with c0 = 20 U (0.071 with 10 U), 0.087 and 0.037 at L/Δx = 20
    // and 30 at t = 20 with 10 U (the Δx-convergence of the report); a lid that does not
    // drive leaves the fluid at rest and the error at the profile's own RMS, 0.41.
    assert!(rms < 0.12, "RMS error {rms}");
}

/// Frequency and amplitude decay rate of the first sloshing mode of
/// `validation/standing_wave.toml` at `d/Δx = depth_over_dx`, from the kinetic energy,
/// which peaks twice a period (t = nT/2) and whose peaks decay as exp(-2γt): ω is π
/// over the spacing of the peaks (a line through their times), γ half the log-slope
/// of their heights. Each peak is placed by a parabola through the largest sample
/// near nT/2 and its neighbours (T/80 apart).
fn standing_wave(depth_over_dx: f64, periods: usize) -> (f64, f64) {
    use sph_core::geometry::initial_field::standing_wave_frequency;
    let spacing = format!("particles.spacing = {}", 0.5 / depth_over_dx);
    let mut sim =
        Simulation::<2>::new(example_case("validation/standing_wave.toml", &[&spacing])).unwrap();
    let half = std::f64::consts::PI / standing_wave_frequency(1.0, 0.5, 9.81);
    let samples = 40;
    let dt = half / samples as f64;
    let mut energy = Vec::new();
    for k in 1..=2 * periods * samples + samples / 2 {
        run_to(&mut sim, k as f64 * dt);
        energy.push(sim.energies().kinetic.ln());
    }
    let (mut times, mut heights) = (Vec::new(), Vec::new());
    for n in 1..=2 * periods {
        let near = n * samples - 1 - samples / 4..n * samples + samples / 4;
        let j = near
            .max_by(|&a, &b| energy[a].total_cmp(&energy[b]))
            .unwrap();
        let (a, b, c) = (energy[j - 1], energy[j], energy[j + 1]);
        let shift = 0.5 * (a - c) / (a - 2.0 * b + c);
        times.push((j + 1) as f64 * dt + shift * dt);
        heights.push(b - 0.25 * (a - c) * shift);
    }
    let index: Vec<f64> = (1..=2 * periods).map(|n| n as f64).collect();
    let omega = std::f64::consts::PI / slope(&index, &times);
    (omega, -0.5 * slope(&times, &heights))
}

/// Least-squares slope of y against x.
fn slope(x: &[f64], y: &[f64]) -> f64 {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(y).map(|(a, b)| (a - mx) * (b - my)).sum();
    let sxx: f64 = x.iter().map(|a| (a - mx).powi(2)).sum();
    sxy / sxx
}

#[test]
fn standing_wave_keeps_the_linear_frequency_and_the_viscous_damping() {
    use sph_core::geometry::initial_field::standing_wave_frequency;
    let (omega, decay) = standing_wave(20.0, 4);
    let exact = standing_wave_frequency(1.0, 0.5, 9.81);
    let viscous = 2.0 * 1e-3 * std::f64::consts::PI.powi(2);
    println!(
        "standing wave, d/Δx = 20: ω/ω_linear = {:.4}, γ/2νk² = {:.3}",
        omega / exact,
        decay / viscous
    );
    assert!(
        (omega / exact - 1.0).abs() < 0.02,
        "ω/ω_linear = {}",
        omega / exact
    );
    assert!(
        (decay / viscous - 1.0).abs() < 0.5,
        "γ/2νk² = {}",
        decay / viscous
    );
}
