//! A plane jet impinging on a flat plate, normally and at 60°, fed by an inlet and
//! leaving the domain along the plate: the steady stagnation pressure, plate force and
//! outgoing fluxes of free-streamline theory and of momentum and Bernoulli (examples/validation/impinging_jet.py runs the
//! resolution study; docs/validation/impinging_jet.md).

use sph_core::{Case, Kind, Simulation, Vector};

const RHO0: f64 = 1000.0;
const U: f64 = 1.0;
const B: f64 = 0.1;

/// The start of examples/validation/impinging_jet.toml: the stagnation flow
/// ψ = U x tanh(y/l), l = b/2, with its Bernoulli pressure (no impact).
const START: &str = "[initial]\ntype = \"expressions\"\nconstants = { l = 0.05 }\n\
    u = [\"x/l*(1 - tanh(y/l)^2)\", \"-tanh(y/l)\"]\n\
    p = \"0.5*rho0*(1 - (x/l*(1 - tanh(y/l)^2))^2 - tanh(y/l)^2)\"\n";

/// The jet of examples/validation/impinging_jet.toml at b/Δx = `n`: no gravity,
/// δ-SPH, the inlet's inner face 3b above the plate, the plate 6b long, started from
/// [`START`]; the case's sound speed 10U and artificial viscosity α = 0.02 unless
/// `sound` gives others.
fn jet(n: usize, sound: Sound) -> Simulation<2> {
    let dx = B / n as f64;
    let depth = 4.0 * dx;
    let plate = format!(
        "[[fluid_block]]\nlo = [-0.05, 0.0]\nhi = [0.05, {top}]\nhydrostatic = false\n\
         {START}[[wall]]\nname = \"plate\"\nlo = [-0.3, -{depth}]\nhi = [0.3, 0.0]\n",
        top = top(dx)
    );
    build(dx, &plate, -depth, sound)
}

/// The sound speed c0 [U] and the artificial viscosity's α of a run.
#[derive(Clone, Copy)]
struct Sound {
    c0: f64,
    alpha: f64,
}

/// The case's: c0 = 10U (Mach 0.1), α = 0.02.
const CASE_SOUND: Sound = Sound {
    c0: 10.0,
    alpha: 0.02,
};

/// The jet of [`jet`] on a plate through the origin tilted by 30°, so that the jet
/// meets it at θ = 60°: a wall polygon 5Δx thick, the column started at U down to it.
fn oblique(n: usize) -> Simulation<2> {
    let dx = B / n as f64;
    let (rise, thick) = (0.3 * TILT.tan(), 5.0 * dx / TILT.cos());
    let column = -(0.5 * B * TILT.tan() / dx).ceil() * dx;
    let plate = format!(
        "[[fluid_block]]\nlo = [-0.05, {column}]\nhi = [0.05, {top}]\nhydrostatic = false\n\
         velocity = [0.0, -{U}]\n[[shape]]\nrole = \"wall\"\nname = \"plate\"\n\
         polygon = [[-0.3, {lo}], [0.3, {rise}], [0.3, {}], [-0.3, {}]]\n",
        rise - thick,
        -rise - thick,
        top = top(dx),
        lo = -rise,
    );
    build(dx, &plate, -rise - thick - dx, CASE_SOUND)
}

/// The top of the domain: 3b above the plate, plus the inlet buffer's 5Δx.
fn top(dx: f64) -> f64 {
    3.0 * B + 5.0 * dx
}

/// The jet's case around `plate` (its fluid and wall), the domain from `bottom` up.
fn build(dx: f64, plate: &str, bottom: f64, sound: Sound) -> Simulation<2> {
    let text = format!(
        "dimension = 2\n[particles]\nspacing = {dx}\n[fluid]\ndensity = {RHO0}\n\
         sound_speed = {c0}\n{plate}[domain]\nlo = [-0.3, {bottom}]\nhi = [0.3, {top}]\n\
         [scheme]\ndiffusion = \"delta_sph\"\nalpha = {alpha}\n[[open_boundary]]\ntype = \"inlet\"\naxis = 1\n\
         side = \"hi\"\nsection = [[-0.05, 0.05]]\nwidth = {width}\nvelocity = [0.0, -{U}]\n\
         [time]\nend = 1.0\n",
        top = top(dx),
        width = 5.0 * dx,
        c0 = sound.c0 * U,
        alpha = sound.alpha,
    );
    let case = Case::from_toml_str(&text).unwrap_or_else(|e| panic!("{e}\n{text}"));
    Simulation::<2>::new(case).unwrap_or_else(|e| panic!("{e}"))
}

/// The tilted plate's angle to the horizontal.
const TILT: f64 = std::f64::consts::FRAC_PI_6;

/// (mass, momentum) fluxes along the unit vector `e` through the section x·e = s0 per
/// unit depth, hat-weighted over the particles on either side (exact for a lattice).
fn fluxes(sim: &Simulation<2>, s0: f64, e: Vector<2>) -> (f64, f64) {
    let (p, dx) = (sim.particles(), sim.case().dx());
    (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| {
            let hat = (1.0 - (p.x[i].dot(&e) - s0).abs() / dx).max(0.0) / dx;
            let m = p.mass[i] * p.u[i].dot(&e) * hat;
            (m, m * p.u[i].dot(&e))
        })
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// The fluid's force on the plate, pressure and viscous.
fn plate_load(sim: &mut Simulation<2>) -> Vector<2> {
    let plate = sim.bodies().iter().position(|b| b.name == "plate").unwrap();
    let load = &sim.loads()[plate];
    load.pressure + load.viscous
}

/// Runs `sim` to t = 10 b/U and returns the mean of `measure` (with the pressure
/// synchronised) every 0.005 s over t = 5-10 b/U, as the study script samples.
fn window_mean(
    sim: &mut Simulation<2>,
    mut measure: impl FnMut(&mut Simulation<2>) -> Vec<f64>,
) -> Vec<f64> {
    let (mut sum, mut samples): (Vec<f64>, f64) = (Vec::new(), 0.0);
    let mut t = 0.0;
    while t < 1.0 - 1e-9 {
        t += 0.005;
        while sim.time() < t * (1.0 - 1e-12) {
            sim.step().unwrap();
        }
        if t >= 0.5 - 1e-9 {
            sim.sync_pressure();
            let m = measure(sim);
            sum.resize(m.len(), 0.0);
            sum.iter_mut().zip(m).for_each(|(s, m)| *s += m);
            samples += 1.0;
        }
    }
    sum.into_iter().map(|s| s / samples).collect()
}

/// The steady figures of the normal jet at b/Δx = n: stagnation pressure [½ρ0U²],
/// plate force (pressure and viscous) [ρ0U²b], and the mass [ρ0Ub/2] and x-momentum
/// [ρ0U²b/2] fluxes of the right and left wall jets through x = ±2b.
struct Figures {
    stagnation: f64,
    force: f64,
    mass: [f64; 2],
    momentum: [f64; 2],
}

fn measure(n: usize, sound: Sound) -> Figures {
    let x = Vector::<2>::new(1.0, 0.0);
    let m = window_mean(&mut jet(n, sound), |sim| {
        let (r, l) = (fluxes(sim, 2.0 * B, x), fluxes(sim, -2.0 * B, x));
        let p0 = sim.probe_pressure(&Vector::<2>::zeros()).unwrap();
        vec![p0, -plate_load(sim)[1], r.0, -l.0, r.1, l.1]
    });
    let (q, half_mass, half_momentum) = (
        0.5 * RHO0 * U * U,
        RHO0 * U * B / 2.0,
        RHO0 * U * U * B / 2.0,
    );
    let figures = Figures {
        stagnation: m[0] / q,
        force: m[1] / (RHO0 * U * U * B),
        mass: [m[2] / half_mass, m[3] / half_mass],
        momentum: [m[4] / half_momentum, m[5] / half_momentum],
    };
    println!(
        "impinging jet, b/Δx = {n}, c0 = {} U, α = {}: p(0) {:.4} ½ρU², force {:.4} ρU²b, mass fluxes {:.4?} \
         ρUb/2, momentum fluxes {:.4?} ρU²b/2",
        sound.c0,
        sound.alpha,
        figures.stagnation, figures.force, figures.mass, figures.momentum
    );
    figures
}

/// At b/Δx = 10 and 20 (the resolution study, to b/Δx = 80, is in
/// docs/validation/impinging_jet.md):
/// - the stagnation pressure is ½ρ0U² within 3% at 20 (measured 2.4% low; 0.1% at 40,
///   where the 2% is met);
/// - the plate force falls short of ρ0U²b at first order: by less than 6% at 20
///   (measured 5.2%; 2.6% at 40, 1.0% at 80), and by at least 1.6 times less than at
///   10 (measured 1.98);
/// - each wall jet carries ρ0Ub/2 of mass within 2% (measured 1.4% short: the wall jets
///   still thicken slowly) and x-momentum ρ0U²b/2 within 4% (measured 3.2% short;
///   viscosity slows them), the two sides equal to 1e-9.
#[test]
fn a_normal_jet_on_a_plate_has_the_stagnation_pressure_force_and_split_of_theory() {
    let (coarse, fine) = (measure(10, CASE_SOUND), measure(20, CASE_SOUND));
    assert!((fine.stagnation - 1.0).abs() < 0.03, "{}", fine.stagnation);
    assert!((fine.force - 1.0).abs() < 0.06, "{}", fine.force);
    let ratio = (1.0 - coarse.force) / (1.0 - fine.force);
    assert!(
        ratio > 1.6,
        "force deficit {} then {}",
        1.0 - coarse.force,
        1.0 - fine.force
    );
    for m in fine.mass {
        assert!((m - 1.0).abs() < 0.02, "{:?}", fine.mass);
    }
    for m in fine.momentum {
        assert!((m - 1.0).abs() < 0.04, "{:?}", fine.momentum);
    }
    assert!(
        (fine.mass[0] - fine.mass[1]).abs() < 1e-9,
        "{:?}",
        fine.mass
    );
}

/// The sound speed acts through the artificial viscosity α h c0/8 (docs/validation/
/// impinging_jet.md, the c0 study): at b/Δx = 20, c0 = 20U with α halved (the same
/// viscosity) carries the wall jets' x-momentum of c0 = 10U within 1% (measured
/// −0.4%), its plate force within 2% (−0.9%) and its stagnation pressure within 1.5%
/// (−0.5%); c0 = 20U with α kept (twice the viscosity) slows the wall jets by more than
/// 1% (measured 1.9%). Compressibility's own share, Ma²/4 of ½ρ0U² in p(0), is 0.25%
/// at c0 = 10U.
#[test]
fn doubling_c0_at_equal_viscosity_keeps_the_jet_and_doubling_the_viscosity_slows_it() {
    let case = measure(20, CASE_SOUND);
    let same_viscosity = measure(
        20,
        Sound {
            c0: 20.0,
            alpha: 0.01,
        },
    );
    let twice = measure(
        20,
        Sound {
            c0: 20.0,
            alpha: 0.02,
        },
    );
    let change = |a: f64, b: f64| b / a - 1.0;
    let momentum = change(case.momentum[0], same_viscosity.momentum[0]);
    assert!(momentum.abs() < 0.01, "momentum flux {momentum}");
    let force = change(case.force, same_viscosity.force);
    assert!(force.abs() < 0.02, "plate force {force}");
    let stagnation = change(case.stagnation, same_viscosity.stagnation);
    assert!(stagnation.abs() < 0.015, "stagnation pressure {stagnation}");
    let slowed = change(case.momentum[0], twice.momentum[0]);
    assert!(slowed < -0.01, "momentum flux with α kept {slowed}");
}

/// On the plate tilted by 30° (the jet at θ = 60° to it) at b/Δx = 20 (the study
/// script runs 40 and 80 too):
/// - the normal force is ρ0U²b sin θ within 2.5% (measured 1.5% above; 0.9% at 40, 0.5%
///   at 80);
/// - the largest plate pressure is ½ρ0U² within 2.5% (measured 1.1% above);
/// - the wall jet down the slope carries ρ0U b(1 + cos θ)/2 within 2.5% (measured 1.2%
///   short, as at 40 and 80), and the one up the slope, five particles thick, more than
///   0.75 of ρ0U b(1 - cos θ)/2 (measured 0.81; 1.00 at 40);
/// - the force along the plate is under 1% of ρ0U²b (measured 0.4%: the artificial
///   viscosity's drag).
#[test]
fn an_oblique_jet_splits_and_loads_the_plate_as_momentum_and_bernoulli_say() {
    let along = Vector::<2>::new(TILT.cos(), TILT.sin());
    let normal = Vector::<2>::new(-TILT.sin(), TILT.cos());
    let probes: Vec<Vector<2>> = (-30..=30).map(|k| along * (0.05 * B * k as f64)).collect();
    let m = window_mean(&mut oblique(20), |sim| {
        let load = plate_load(sim);
        let (up, down) = (fluxes(sim, 2.0 * B, along), fluxes(sim, -2.0 * B, along));
        let mut row = vec![-load.dot(&normal), load.dot(&along), -down.0, up.0];
        row.extend(probes.iter().map(|x| sim.probe_pressure(x).unwrap()));
        row
    });
    let (sin, cos) = (TILT.cos(), TILT.sin());
    let normal_force = m[0] / (RHO0 * U * U * B * sin);
    let along_force = m[1] / (RHO0 * U * U * B);
    let down = m[2] / (RHO0 * U * B * (1.0 + cos) / 2.0);
    let up = m[3] / (RHO0 * U * B * (1.0 - cos) / 2.0);
    let p_max = m[4..].iter().fold(f64::MIN, |a, &b| a.max(b)) / (0.5 * RHO0 * U * U);
    println!(
        "oblique jet, b/Δx = 20: F_n {normal_force:.4} ρU²b sin θ, F_t {along_force:.4} ρU²b, \
         down {down:.4}, up {up:.4} of theory, max p {p_max:.4} ½ρU²"
    );
    assert!((normal_force - 1.0).abs() < 0.025, "{normal_force}");
    assert!((p_max - 1.0).abs() < 0.025, "{p_max}");
    assert!((down - 1.0).abs() < 0.025, "{down}");
    assert!(up > 0.75 && up < 1.025, "{up}");
    assert!(along_force.abs() < 0.01, "{along_force}");
}
