//! Initial fields from expressions (`[initial] type = "expressions"`): the same
//! particles as the analytic fields they spell out, and one-line errors naming the key
//! and, for a value that is not finite, the particle.

use sph_core::{Case, Kind, Simulation};

/// The Taylor-Green case of the validation suite's form: a periodic unit square.
fn taylor_green(initial: &str) -> String {
    format!(
        "dimension = 2\n[particles]\nspacing = 0.05\n[fluid]\ndensity = 1.0\n\
         sound_speed = 10.0\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\n\
         hydrostatic = false\n[domain]\nlo = [0.0, 0.0]\nhi = [1.0, 1.0]\n\
         periodic = [true, true]\n[time]\nend = 0.1\n{initial}"
    )
}

fn build(text: &str) -> Simulation<2> {
    Simulation::<2>::new(Case::from_toml_str(text).unwrap_or_else(|e| panic!("{e}")))
        .unwrap_or_else(|e| panic!("{e}"))
}

fn error_of(text: &str) -> String {
    let e = match Case::from_toml_str(text) {
        Err(e) => e.to_string(),
        Ok(case) => match Simulation::<2>::new(case) {
            Err(e) => e.to_string(),
            Ok(_) => panic!("built: {text}"),
        },
    };
    assert_eq!(e.lines().count(), 1, "{e}");
    e
}

/// The Taylor-Green vortex written as expressions gives the particles of the built-in
/// field: u = U(-cos kx sin ky, sin kx cos ky), p = -ρ0 U²/4 (cos 2kx + cos 2ky).
#[test]
fn expressions_give_the_particles_of_the_analytic_field() {
    let builtin = build(&taylor_green(
        "[initial]\ntype = \"taylor_green\"\namplitude = 1.0\nwavelength = 1.0\n",
    ));
    let written = build(&taylor_green(
        "[initial]\ntype = \"expressions\"\nconstants = { U = 1.0, k = 6.283185307179586 }\n\
         u = [\"-U*cos(k*x)*sin(k*y)\", \"U*sin(k*x)*cos(k*y)\"]\n\
         p = \"-rho0*U^2/4*(cos(2*k*x) + cos(2*k*y))\"\n",
    ));
    let (a, b) = (builtin.particles(), written.particles());
    assert_eq!(a.len(), b.len());
    let mut worst: f64 = 0.0;
    for i in 0..a.len() {
        assert_eq!(a.x[i], b.x[i]);
        worst = worst
            .max((a.u[i] - b.u[i]).norm())
            .max((a.rho[i] - b.rho[i]).abs());
    }
    assert!(worst < 1e-12, "largest difference {worst}");
    // the field moves: its kinetic energy is that of the vortex, U²/4 per unit mass
    let e: f64 = (0..b.len())
        .map(|i| 0.5 * b.mass[i] * b.u[i].norm_squared())
        .sum();
    assert!((e - 0.25).abs() < 1e-3, "{e}");
}

/// A density field, and a 3D rotation about y.
#[test]
fn density_and_3d_velocity_expressions() {
    let sim = build(&taylor_green(
        "[initial]\ntype = \"expressions\"\nrho = \"rho0*(1 + 0.001*y)\"\n",
    ));
    let p = sim.particles();
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid) {
        assert!((p.rho[i] - (1.0 + 0.001 * p.x[i][1])).abs() < 1e-15);
    }
    let text = "dimension = 3\n[particles]\nspacing = 0.1\n[fluid]\ndensity = 1000.0\n\
                sound_speed = 10.0\n[[fluid_block]]\nlo = [-0.5, -0.5, -0.5]\n\
                hi = [0.5, 0.5, 0.5]\nhydrostatic = false\n[time]\nend = 0.1\n\
                [initial]\ntype = \"expressions\"\nconstants = { w = 2.0 }\n\
                u = [\"w*z\", \"0\", \"-w*x\"]\n";
    let sim = Simulation::<3>::new(Case::from_toml_str(text).unwrap()).unwrap();
    let p = sim.particles();
    for i in 0..p.len() {
        let (x, u) = (p.x[i], p.u[i]);
        assert!(
            (u[0] - 2.0 * x[2]).abs() < 1e-15 && u[1] == 0.0 && (u[2] + 2.0 * x[0]).abs() < 1e-15
        );
    }
}

#[test]
fn bad_expressions_are_refused_in_one_line() {
    let with =
        |initial: &str| taylor_green(&format!("[initial]\ntype = \"expressions\"\n{initial}\n"));
    for (initial, expected) in [
        (
            "u = [\"q*x\", \"0\"]",
            "initial.u[0] = \"q*x\": expected an expression of known variables (unknown: q; known: x, y, rho0, g",
        ),
        ("p = \"2*(x\"", "initial.p = \"2*(x\": expected an expression ("),
        (
            "p = \"1/(x - 0.025)\"",
            "initial.p = \"1/(x - 0.025)\": expected an expression finite at every fluid particle (it gives inf at x = [0.025, 0.025])",
        ),
        ("u = [\"0\", \"0\", \"0\"]", "initial.u = [\"0\", \"0\", \"0\"]: expected 2 expressions"),
        ("constants = { x = 1.0 }\np = \"x\"", "initial.constants.x = 1: expected a constant whose name is not x"),
        ("p = \"0\"\nrho = \"rho0\"", "initial.rho = (set with initial.p): expected either a pressure"),
    ] {
        let e = error_of(&with(initial));
        assert!(e.starts_with(expected), "{e}\n expected: {expected}");
    }
}
