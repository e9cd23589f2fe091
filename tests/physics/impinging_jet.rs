//! A plane jet impinging normally on a flat plate, fed by an inlet and leaving the
//! domain along the plate: the steady stagnation pressure, plate force and outgoing
//! fluxes of free-streamline theory (examples/validation/impinging_jet.py runs the
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
/// c0 = 10U, δ-SPH, the inlet's inner face 3b above the plate, the plate 6b long,
/// started from [`START`].
fn jet(n: usize) -> Simulation<2> {
    let dx = B / n as f64;
    let (width, depth) = (5.0 * dx, 4.0 * dx);
    let top = 3.0 * B + width;
    let text = format!(
        "dimension = 2\n[particles]\nspacing = {dx}\n[fluid]\ndensity = {RHO0}\n\
         sound_speed = 10.0\n[[fluid_block]]\nlo = [-0.05, 0.0]\nhi = [0.05, {top}]\n\
         hydrostatic = false\n{START}[[wall]]\nname = \"plate\"\n\
         lo = [-0.3, -{depth}]\nhi = [0.3, 0.0]\n[domain]\nlo = [-0.3, -{depth}]\n\
         hi = [0.3, {top}]\n[scheme]\ndiffusion = \"delta_sph\"\n[[open_boundary]]\n\
         type = \"inlet\"\naxis = 1\nside = \"hi\"\nsection = [[-0.05, 0.05]]\n\
         width = {width}\nvelocity = [0.0, -{U}]\n[time]\nend = 1.0\n"
    );
    let case = Case::from_toml_str(&text).unwrap_or_else(|e| panic!("{e}"));
    Simulation::<2>::new(case).unwrap_or_else(|e| panic!("{e}"))
}

/// (mass, x-momentum) fluxes through x = x0 per unit depth, hat-weighted over the
/// columns on either side (exact for a lattice at any offset).
fn fluxes(sim: &Simulation<2>, x0: f64) -> (f64, f64) {
    let (p, dx) = (sim.particles(), sim.case().dx());
    (0..p.len())
        .filter(|&i| p.kind[i] == Kind::Fluid)
        .map(|i| {
            let hat = (1.0 - (p.x[i][0] - x0).abs() / dx).max(0.0) / dx;
            let m = p.mass[i] * p.u[i][0] * hat;
            (m, m * p.u[i][0])
        })
        .fold((0.0, 0.0), |a, b| (a.0 + b.0, a.1 + b.1))
}

/// The steady figures of the jet at b/Δx = n, averaged every 0.005 s over t = 5-10 b/U (as the study script):
/// stagnation pressure [½ρ0U²], plate force (pressure and viscous) [ρ0U²b], and the
/// mass [ρ0Ub/2] and x-momentum [ρ0U²b/2] fluxes of the right and left wall jets
/// through x = ±2b.
struct Figures {
    stagnation: f64,
    force: f64,
    mass: [f64; 2],
    momentum: [f64; 2],
}

fn measure(n: usize) -> Figures {
    let mut sim = jet(n);
    let (mut stagnation, mut force, mut right, mut left, mut samples) =
        (0.0, 0.0, (0.0, 0.0), (0.0, 0.0), 0.0);
    let mut t = 0.0;
    while t < 1.0 - 1e-9 {
        t += 0.005;
        while sim.time() < t * (1.0 - 1e-12) {
            sim.step().unwrap();
        }
        if t < 0.5 - 1e-9 {
            continue;
        }
        sim.sync_pressure();
        stagnation += sim.probe_pressure(&Vector::<2>::zeros()).unwrap();
        let plate = sim.bodies().iter().position(|b| b.name == "plate").unwrap();
        let load = &sim.loads()[plate];
        force -= load.pressure[1] + load.viscous[1];
        let (r, l) = (fluxes(&sim, 2.0 * B), fluxes(&sim, -2.0 * B));
        right = (right.0 + r.0, right.1 + r.1);
        left = (left.0 - l.0, left.1 + l.1);
        samples += 1.0;
    }
    let half = |f: f64, scale: f64| f / samples / (scale * B / 2.0);
    let figures = Figures {
        stagnation: stagnation / samples / (0.5 * RHO0 * U * U),
        force: force / samples / (RHO0 * U * U * B),
        mass: [half(right.0, RHO0 * U), half(left.0, RHO0 * U)],
        momentum: [half(right.1, RHO0 * U * U), half(left.1, RHO0 * U * U)],
    };
    println!(
        "impinging jet, b/Δx = {n}: p(0) {:.4} ½ρU², force {:.4} ρU²b, mass fluxes {:.4?} \
         ρUb/2, momentum fluxes {:.4?} ρU²b/2",
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
    let (coarse, fine) = (measure(10), measure(20));
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
