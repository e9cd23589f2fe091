//! Hydrostatic tank (docs/theory.md §12; Antuono et al. 2010): after t·sqrt(g/H) = 20 the
//! δ-SPH pressure matches p = ρ0 g (H - y) everywhere, including the top layers,
//! while the Molteni-Colagrossi diffusion leaves a clearly larger error near the
//! free surface (it has no hydrostatic solution there).

use deltasph_suite::example_case;
use sph_core::{Kind, Simulation};

struct Errors {
    /// L2 error of p over all fluid, relative to ρ0 g H.
    all: f64,
    /// L2 error over the top three layers (y > H - 3Δx).
    top: f64,
    max_speed: f64,
}

fn run(diffusion: &str, dx: f64) -> Errors {
    let case = example_case(
        "hydrostatic_2d.toml",
        &[
            &format!("particles.spacing = {dx}"),
            &format!("scheme.diffusion = \"{diffusion}\""),
            "time.end = 6.39",
        ],
    );
    let (rho0, g, depth) = (1000.0, 9.81, 1.0);
    let mut sim = Simulation::<2>::new(case).unwrap();
    while sim.time() < 6.39 * (1.0 - 1e-12) {
        sim.step().unwrap();
    }
    sim.sync_pressure();
    let p = sim.particles();
    let (mut all, mut n_all, mut top, mut n_top, mut umax) = (0.0, 0, 0.0, 0, 0.0f64);
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid) {
        let y = p.x[i][1];
        let err = (p.p[i] - rho0 * g * (depth - y)) / (rho0 * g * depth);
        all += err * err;
        n_all += 1;
        if y > depth - 3.0 * dx {
            top += err * err;
            n_top += 1;
        }
        umax = umax.max(p.u[i].norm());
    }
    Errors {
        all: (all / n_all as f64).sqrt(),
        top: (top / n_top as f64).sqrt(),
        max_speed: umax,
    }
}

#[test]
fn delta_sph_keeps_the_hydrostatic_pressure_and_molteni_colagrossi_does_not() {
    let dx = 0.05; // H/Δx = 20
    let delta = run("delta_sph", dx);
    let mc = run("molteni_colagrossi", dx);
    println!(
        "δ-SPH: L2 {:.4}, top {:.4}, |u|max {:.2e};  MC: L2 {:.4}, top {:.4}",
        delta.all, delta.top, delta.max_speed, mc.all, mc.top
    );
    // Measured at H/Δx = 20: L2 0.56% of ρ0 g H, 1.28% in the top layers (where the
    // kernel is truncated by the surface), spurious currents 1.3e-3 m/s; the bounds
    // keep about twice that (4× for the currents, which vary most between machines).
    assert!(delta.all < 0.012, "δ-SPH L2 error {:.4}", delta.all);
    assert!(delta.top < 0.02, "δ-SPH top-layer error {:.4}", delta.top);
    // Spurious currents: a thousandth of the free-fall speed sqrt(2gH) = 4.4 m/s.
    assert!(delta.max_speed < 5e-3, "|u|max {:.3e}", delta.max_speed);
    // The talk's claim, measured: Molteni-Colagrossi is clearly worse near the surface.
    assert!(
        mc.top > 2.0 * delta.top,
        "MC top {:.4} vs δ-SPH top {:.4}",
        mc.top,
        delta.top
    );
}

/// The wall pressure of Adami et al. (2012), extrapolated from fluid at rest, is the
/// hydrostatic pressure at the wall particle's own depth, p_w = ρ0 g (H - y_w): below
/// the floor and along the side walls alike, the gravity term carries it past the
/// fluid into the wall layers. On the initial hydrostatic state every wall particle
/// with fluid in reach below the surface is within 1% of ρ0 g (H - y_w) (measured
/// 0.05%); walls above the surface read zero. After the tank has settled
/// (t·sqrt(g/H) = 10) the fluid itself is off by up to 2.2% of ρ0 g H at the floor
/// (its weakly-compressible settling), and the walls follow it within 3% of ρ0 g H.
#[test]
fn wall_pressure_is_hydrostatic_at_the_wall_particles_depth() {
    let case = example_case("hydrostatic_2d.toml", &["particles.spacing = 0.05"]);
    let (rho0, g, depth) = (1000.0, 9.81, 1.0);
    let mut sim = Simulation::<2>::new(case).unwrap();
    let mut worst = Vec::new();
    for t in [0.0, 3.19] {
        while sim.time() < t * (1.0 - 1e-12) {
            sim.step().unwrap();
        }
        sim.sync_pressure();
        let p = sim.particles();
        let reach = sim.case().support();
        let (mut relative, mut of_scale, mut checked) = (0.0f64, 0.0f64, 0);
        for w in (0..p.len()).filter(|&i| p.kind[i] == Kind::Wall) {
            let near_fluid =
                (0..p.len()).any(|f| p.kind[f] == Kind::Fluid && (p.x[f] - p.x[w]).norm() < reach);
            let y = p.x[w][1];
            if !near_fluid {
                continue;
            }
            if y > depth {
                assert_eq!(p.p[w], 0.0, "wall above the surface at {:?}", p.x[w]);
                continue;
            }
            let exact = rho0 * g * (depth - y);
            relative = relative.max((p.p[w] - exact).abs() / exact);
            of_scale = of_scale.max((p.p[w] - exact).abs() / (rho0 * g * depth));
            checked += 1;
        }
        println!("t = {t}: {checked} wall particles, worst error {relative:.4} of ρ0 g (H - y_w), {of_scale:.4} of ρ0 g H");
        assert!(checked > 100);
        worst.push((relative, of_scale));
    }
    // measured: 0.07% at the start, 1.2% of ρ0 g H at t·sqrt(g/H) = 10
    assert!(worst[0].0 < 0.002, "{worst:?}");
    assert!(worst[1].1 < 0.03, "{worst:?}");
}
