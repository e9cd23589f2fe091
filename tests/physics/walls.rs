//! Walls hold: no fluid particle gets past the first layer of wall particles.

use deltasph_suite::example_case;
use sph_core::{Kind, Simulation, Vector};

/// Steps the 2D dam break to t·sqrt(g/H) = 7 and returns the largest number of fluid
/// particles found inside a wall at any step.
fn worst_crossings(overrides: &[&str]) -> usize {
    let mut sim = Simulation::<2>::new(example_case("dam_break_2d.toml", overrides)).unwrap();
    let end = 7.0 * (0.6f64 / 9.81).sqrt();
    let mut worst = 0;
    while sim.time() < end * (1.0 - 1e-12) {
        sim.step()
            .unwrap_or_else(|e| panic!("dam break with {overrides:?}: {e}"));
        worst = worst.max(sim.wall_crossings());
    }
    worst
}

/// The violent impact of the dam break at H/Δx = 30 in the example's tank (3H high,
/// which the run-up jet reaches at this resolution, so splash particles skim and land
/// on the wall's top edge), RK4 at CFL 1.5 and the symplectic scheme at its CFL 0.25:
/// zero crossings. (The example sets CFL 1.5, so the symplectic run sets its own: at
/// 1.5 it blows up at step 339, which the test once mistook for a pass.) Before walls
/// stopped pulling lone particles (`boundary`), a lone expanded splash particle sank
/// into the top of the right wall at H/Δx = 20.
#[test]
fn dam_break_impact_does_not_cross_the_walls() {
    let rk4 = worst_crossings(&["particles.spacing = 0.02"]);
    let symplectic = worst_crossings(&[
        "particles.spacing = 0.02",
        "scheme.integrator = \"symplectic\"",
        "scheme.cfl = 0.25",
    ]);
    println!("worst crossings: RK4 {rk4}, symplectic {symplectic}");
    assert_eq!((rk4, symplectic), (0, 0));
}

/// The count sees a particle inside a wall and none above an open face.
#[test]
fn wall_crossings_counts_fluid_inside_the_walls_only() {
    let mut sim = Simulation::<2>::new(example_case(
        "dam_break_2d.toml",
        &["particles.spacing = 0.05"],
    ))
    .unwrap();
    let (right, top, dx) = (3.2196, 1.8, 0.05);
    let p = sim.particles();
    let id = p.id[p.kind.iter().position(|&k| k == Kind::Fluid).unwrap()];
    for (x, y, expected) in [
        (right - 0.4 * dx, 0.3, 0),      // in the tank, by the wall
        (right + 1.5 * dx, 0.3, 1),      // in the right wall
        (right + 1.5 * dx, top + dx, 0), // above the wall, the tank's top is open
        (1.0, -0.6 * dx, 1),             // under the floor
        (right + 5.0 * dx, 0.3, 0),      // outside, beyond the wall layers
    ] {
        sim.edit(|p| {
            let k = p.id.iter().position(|&i| i == id).unwrap();
            p.x[k] = Vector::<2>::new(x, y);
        });
        assert_eq!(sim.wall_crossings(), expected, "at ({x}, {y})");
    }
}

/// The count sees fluid deep inside a `[[shape]]` wall too, and none at its surface.
#[test]
fn wall_crossings_counts_fluid_inside_wall_shapes() {
    let text = std::fs::read_to_string(deltasph_suite::example("dam_break_2d.toml")).unwrap();
    let text = text.replace("spacing = 0.012", "spacing = 0.05")
        + "\n[[shape]]\nrole = \"wall\"\ncircle = { centre = [2.5, 0.6], radius = 0.3 }\n";
    let mut sim = Simulation::<2>::new(sph_core::Case::from_toml_str(&text).unwrap()).unwrap();
    let p = sim.particles();
    let id = p.id[p.kind.iter().position(|&k| k == Kind::Fluid).unwrap()];
    let dx = 0.05;
    for (x, y, expected) in [
        (2.5, 0.6, 1),                  // at the centre
        (2.5, 0.6 + 0.3 - dx, 1),       // a spacing inside the surface
        (2.5, 0.6 + 0.3 - 0.4 * dx, 0), // within half a spacing of it
        (2.5, 0.6 + 0.3 + dx, 0),       // outside
    ] {
        sim.edit(|p| {
            let k = p.id.iter().position(|&i| i == id).unwrap();
            p.x[k] = Vector::<2>::new(x, y);
        });
        assert_eq!(sim.wall_crossings(), expected, "at ({x}, {y})");
    }
}

/// Steps a case to its end and returns the largest number of fluid particles found
/// inside a wall at any step.
fn worst_crossings_of<const D: usize>(name: &str, overrides: &[&str]) -> usize {
    let mut sim = Simulation::<D>::new(example_case(name, overrides)).unwrap();
    let mut worst = 0;
    while sim.time() < sim.case().time.end * (1.0 - 1e-12) {
        sim.step().unwrap_or_else(|e| panic!("{name}: {e}"));
        worst = worst.max(sim.wall_crossings());
    }
    worst
}

/// Every example and validation case with walls, coarsened where its geometry allows,
/// to its end time (the Poiseuille cases to 0.1 s, ten viscous times of a particle
/// layer; the 3D dam break to 0.6 s): no fluid particle is ever inside a wall. The cases at their own resolution
/// are checked by `scripts/wall_crossings.py`. The validation folder's dam break,
/// surge front and hydrostatic tank are the examples' cases.
#[test]
fn no_example_or_validation_case_lets_fluid_into_a_wall() {
    let cases_2d: [(&str, &[&str]); 5] = [
        ("dam_break_2d.toml", &["particles.spacing = 0.03"]),
        (
            "dam_break_martin_moyce_2d.toml",
            &["particles.spacing = 0.005"],
        ),
        ("hydrostatic_2d.toml", &["particles.spacing = 0.05"]),
        ("validation/poiseuille_2d.toml", &["time.end = 0.1"]),
        ("validation/cavity.toml", &["particles.spacing = 0.04"]),
    ];
    for (name, overrides) in cases_2d {
        assert_eq!(worst_crossings_of::<2>(name, overrides), 0, "{name}");
    }
    let cases_3d: [(&str, &[&str]); 2] = [
        // to t = 0.6 s, the impact and the run-up: past it this coarse column (H/Δx
        // = 7.5) puts up to 7 fluid particles inside the walls (4 at H/Δx = 10, none at
        // the example's H/Δx = 15 through its end, t·sqrt(g/H) = 20)
        (
            "dam_break_3d.toml",
            &["particles.spacing = 0.04", "time.end = 0.6"],
        ),
        ("validation/poiseuille_3d.toml", &["time.end = 0.02"]),
    ];
    for (name, overrides) in cases_3d {
        assert_eq!(worst_crossings_of::<3>(name, overrides), 0, "{name}");
    }
}
