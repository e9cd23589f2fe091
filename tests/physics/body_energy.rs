//! The energy budget with moving bodies: the fluid's energy, the free bodies' and the
//! work of prescribed walls close (docs/theory.md §10).

use deltasph_suite::example_case;
use sph_core::{Case, Simulation};

/// The budget at a step's start.
struct Row {
    /// `E_f + E_b + removed - ∫P dt`, constant when the budget closes.
    closure: f64,
    /// `E_b`, the free bodies' energy.
    bodies: f64,
}

/// The budget at every step's start of `case` up to `end`, each taken when the next
/// step has closed the integral of the powers through it by the trapezoidal rule.
fn closure(case: Case, end: f64) -> Vec<Row> {
    let mut sim = Simulation::<2>::new(case).unwrap();
    let caveats = sim.budget_caveats();
    assert!(caveats.is_empty(), "{caveats:?}");
    let energy = |sim: &Simulation<2>| {
        let bodies = sim.motions().map_or(0.0, |m| m.free_energy());
        let b = sim.budget().unwrap();
        (sim.energies().total() + bodies + b.removed_energy, bodies)
    };
    let mut rows = Vec::new();
    let mut last = energy(&sim);
    while sim.time() < end * (1.0 - 1e-12) {
        sim.step().unwrap();
        let work = sim.budget().unwrap().dissipated;
        rows.push(Row {
            closure: last.0 - work,
            bodies: last.1,
        });
        last = energy(&sim);
    }
    rows
}

/// A piston wave maker at the end of a flume, depth d = 0.2 m: a `[[wall]]` moving by
/// `a sin ωt` after a one-period ramp (ω = 2π rad/s, kd = 0.9), at spacing `dx`.
fn piston_flume(dx: f64, stroke: f64, extra: &str) -> Case {
    let text = format!(
        "dimension = 2\n[particles]\nspacing = {dx}\n[fluid]\ndensity = 1000.0\n\
         gravity = [0.0, -9.81]\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [2.0, 0.2]\n\
         [[tank]]\nlo = [-0.3, 0.0]\nhi = [2.0, 0.4]\n\
         [[wall]]\nname = \"paddle\"\nlo = [-0.1, 0.0]\nhi = [0.0, 0.4]\nmotion = \"prescribed\"\n\
         [wall.prescribed]\ndisplacement = [\"a*sin(w*t)\", \"0\"]\n\
         constants = {{ a = {stroke}, w = 6.283185307179586 }}\nramp = 1.0\n\
         [diagnostics]\nenergy_budget = true\n{extra}"
    );
    Case::from_toml_str(&text).unwrap()
}

/// The floating box of `examples/floating_box_2d.toml` (B = 0.2 m, draft 0.05 m)
/// released 20% of its draft (z0 = 0.01 m) above it, at spacing `dx`, to `end`; the
/// largest closure error over the run relative to the energy the release sets free,
/// `k z0²/2` (`k = ρ g B` the heave stiffness), and the largest swing of the box's own
/// energy, likewise.
fn heave_decay_closure(dx: f64, end: f64, integrator: &str) -> (f64, f64) {
    let lines = [
        format!("particles.spacing = {dx}"),
        format!("time.end = {end}"),
        format!("scheme.integrator = \"{integrator}\""),
        "shape.0.box.lo = [0.4, 0.26]".into(),
        "shape.0.box.hi = [0.6, 0.36]".into(),
        "diagnostics.energy_budget = true".into(),
    ];
    let lines: Vec<&str> = lines.iter().map(String::as_str).collect();
    let rows = closure(example_case("floating_box_2d.toml", &lines), end);
    let released = 0.5 * 1000.0 * 9.81 * 0.2 * 0.01f64.powi(2);
    let most = |f: &dyn Fn(&Row) -> f64| {
        let start = f(&rows[0]);
        rows.iter()
            .map(|r| (f(r) - start).abs())
            .fold(0.0, f64::max)
            / released
    };
    (most(&|r| r.closure), most(&|r| r.bodies))
}

/// Fluid and body exchange energy through the wall pair terms alone: in the heave
/// decay of a floating box, `E_k + E_p + E_c + E_b - ∫(P_V + P_D + P_W + P_B) dt`
/// stays within 1% of the energy the release sets free, over 10 heave periods
/// (8.7 s). Measured with RK4 (largest error over the run): 0.52% at draft/Δx = 2.5,
/// 0.23% at 5, almost all of it in the first 0.05 s after the release; the symplectic
/// scheme 0.037% at 2.5. The box's own energy swings by twelve times that scale, so a
/// budget without it would be off by 1000%.
#[test]
fn a_heaving_box_and_its_water_keep_their_energy() {
    let (error, swing) = heave_decay_closure(0.02, 8.7, "rk4");
    println!(
        "heave decay, RK4, draft/Δx = 2.5, 10 periods: closure within {:.3}% of kz0²/2, \
         E_b swings {:.0}%",
        100.0 * error,
        100.0 * swing
    );
    assert!(error < 0.01, "{error}");
    assert!(swing > 5.0, "{swing}");
    let (error, _) = heave_decay_closure(0.02, 2.0, "symplectic");
    println!(
        "symplectic, 2 s: closure within {:.3}% of kz0²/2",
        100.0 * error
    );
    assert!(error < 0.01, "{error}");
}

/// A prescribed paddle's work `∫P_M dt` (pressure and viscous pairs at the walls'
/// velocity) equals the water's energy change plus what it dissipated,
/// `∫(P_V + P_D + P_W) dt`: a piston wave maker of stroke 0.02 m for 3 s. Measured:
/// the largest residual 0.011% of the largest work at d/Δx = 10, 0.004% at 20,
/// against a dissipation of 11–22% of it (the budget without `P_M` would be off by
/// 100%).
#[test]
fn a_paddles_work_is_the_waters_energy_change_and_dissipation() {
    let end = 3.0;
    let case = piston_flume(0.02, 0.02, &format!("[time]\nend = {end}\n"));
    let mut sim = Simulation::<2>::new(case).unwrap();
    let e0 = sim.energies().total();
    let (mut residual, mut work, mut dissipated) = (0.0f64, 0.0f64, 0.0f64);
    let mut change = 0.0;
    while sim.time() < end * (1.0 - 1e-12) {
        sim.step().unwrap();
        // the integrals through the last step's start, closed by the trapezoidal rule
        let b = sim.budget().unwrap();
        let w = b.moving_work;
        let rest = b.dissipated - w;
        residual = residual.max((change - w - rest).abs());
        (work, dissipated) = (work.max(w.abs()), dissipated.min(rest));
        change = sim.energies().total() - e0;
    }
    println!(
        "paddle, d/Δx = 10: largest residual {residual:.3e} J, {:.4}% of the largest work \
         {work:.3} J; dissipated {dissipated:.3} J",
        100.0 * residual / work
    );
    assert!(work > 1.0, "{work}");
    assert!(dissipated < -0.05 * work, "{dissipated}");
    assert!(residual < 1e-3 * work, "{residual} of {work}");
}

/// A sliding lid is a moving wall too: the lid-driven cavity's energy closes with the
/// lid's work `∫P_M dt` (no-slip pairs), the case says nothing is missing, and the lid
/// put in what the water holds plus what it dissipated. Measured at L/Δx = 25 to
/// t = 0.5 s: residual 0.013% of the lid's work (0.07% at 50 to 2 s).
#[test]
fn a_sliding_lids_work_closes_the_cavitys_budget() {
    let end = 0.5;
    let case = example_case(
        "validation/cavity.toml",
        &[
            "particles.spacing = 0.04",
            &format!("time.end = {end}"),
            "diagnostics.energy_budget = true",
        ],
    );
    let mut sim = Simulation::<2>::new(case).unwrap();
    let caveats = sim.budget_caveats().join("; ");
    assert!(!caveats.contains("lid"), "{caveats}");
    let e0 = sim.energies().total();
    let mut change = 0.0;
    while sim.time() < end * (1.0 - 1e-12) {
        sim.step().unwrap();
        if sim.time() < end * (1.0 - 1e-12) {
            change = sim.energies().total() - e0;
        }
    }
    // through the last step's start (the trapezoidal rule's closed integrals)
    let b = sim.budget().unwrap();
    let (work, rest) = (b.moving_work, b.dissipated - b.moving_work);
    let residual = change - work - rest;
    println!(
        "cavity, L/Δx = 25: lid's work {work:.4e} J, held {change:.4e} J, dissipated \
         {:.4e} J, residual {residual:.2e} J ({:.3}% of the work)",
        -rest,
        100.0 * residual.abs() / work
    );
    assert!(work > 0.0 && change > 0.0 && rest < 0.0);
    assert!(residual.abs() < 0.005 * work, "{residual} of {work}");
}
