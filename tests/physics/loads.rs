//! Body loads: the fluid's force and moment on each tank and wall, from the wall pair
//! terms of the momentum equation (`sph_core::boundary::bodies`).

use deltasph_suite::example_case;
use sph_core::{Case, Kind, Simulation, Vector};

const G: f64 = 9.81;

/// The hydrostatic tank of `examples/hydrostatic_2d.toml` (H = 1 m of water, 2 m wide),
/// its walls as five bodies: floor, left and right walls, and the two corner blocks
/// below the side walls and beside the floor, at H/Δx = 20, four wall layers (0.2 m).
/// The corner blocks mirror both walls: their vertical load is the floor's, their
/// horizontal load the side wall's.
fn tank_of_five_walls() -> Case {
    let text = "
        name = \"tank_walls\"
        dimension = 2
        [particles]
        spacing = 0.05
        [fluid]
        density = 1000.0
        gravity = [0.0, -9.81]
        [[fluid_block]]
        lo = [0.0, 0.0]
        hi = [2.0, 1.0]
        [[wall]]
        name = \"floor\"
        lo = [0.0, -0.2]
        hi = [2.0, 0.0]
        [[wall]]
        name = \"left\"
        lo = [-0.2, 0.0]
        hi = [0.0, 1.3]
        [[wall]]
        name = \"right\"
        lo = [2.0, 0.0]
        hi = [2.2, 1.3]
        [[wall]]
        name = \"left_corner\"
        lo = [-0.2, -0.2]
        hi = [0.0, 0.0]
        [[wall]]
        name = \"right_corner\"
        lo = [2.0, -0.2]
        hi = [2.2, 0.0]
        [scheme]
        diffusion = \"delta_sph\"
        viscosity = \"artificial\"
        alpha = 0.02
        [time]
        end = 3.2
        [diagnostics]
        loads = true
        moment_point = [1.0, 0.0]
        [[diagnostics.sensors]]
        name = \"side\"
        centre = [0.0, 0.4]
        normal = [1.0, 0.0]
        size = 0.2
    ";
    Case::from_toml_str(text).unwrap()
}

/// At rest the floor carries the water's weight, ρ0 g H L, and each side wall the
/// hydrostatic thrust ρ0 g H²/2 (per unit width), after the start-up oscillation has
/// decayed (t·sqrt(g/H) = 10). The floor's moment about the tank's centre line
/// vanishes by symmetry, and the side walls' thrust acts at H/3.
#[test]
fn the_hydrostatic_tank_carries_the_weight_and_the_thrust_of_its_water() {
    let mut sim = Simulation::<2>::new(tank_of_five_walls()).unwrap();
    let names: Vec<&str> = sim.bodies().iter().map(|b| b.name.as_str()).collect();
    assert_eq!(
        names,
        ["floor", "left", "right", "left_corner", "right_corner"]
    );
    let (rho0, h, l) = (1000.0, 1.0, 2.0);
    let (weight, thrust) = (rho0 * G * h * l, 0.5 * rho0 * G * h * h);
    while sim.time() < 10.0 * (h / G).sqrt() {
        sim.step().unwrap();
    }
    let loads = sim.loads();
    let f: Vec<Vector<2>> = loads.iter().map(|l| l.force()).collect();
    let floor = f[0][1] + f[3][1] + f[4][1];
    let (left, right) = (f[1][0] + f[3][0], f[2][0] + f[4][0]);
    // about (1, 0) a thrust F_x < 0 at height y has the moment -y F_x
    let height = loads[1].moment[2] / -f[1][0];
    println!(
        "floor {floor:.1} (-ρ0gHL = {:.1}), left {left:.1}, right {right:.1} (ρ0gH²/2 = \
         {thrust:.1}); floor moment {:.2}; left wall thrust at y = {height:.4}",
        -weight, loads[0].moment[2],
    );
    // Measured: floor 1.0038 ρ0gHL (the water is 0.25% denser than ρ0 under its own
    // weight), side walls 1.0055 ρ0gH²/2 at y = 0.345 H.
    assert!((-floor / weight - 1.0).abs() < 0.01, "floor {floor}");
    assert!((-left / thrust - 1.0).abs() < 0.01, "left {left}");
    assert!((right / thrust - 1.0).abs() < 0.01, "right {right}");
    assert!(loads[0].moment[2].abs() < 1e-3 * weight * l, "floor moment");
    assert!(
        (height - h / 3.0).abs() < 0.02 * h,
        "left thrust acts at y = {height}"
    );
    // a face sensor 0.2 m high on the left wall, centred 0.6 m deep, reads ρ0 g 0.6 m
    // averaged over its face, as its centre does (measured 1.0047 ρ0 g 0.6 m)
    let header = sim.series_header();
    let row = sim.series_values();
    let column = |name: &str| row[header.iter().position(|c| c == name).unwrap()];
    let (face, point) = (column("side_pressure"), column("side_point"));
    println!("side sensor: face {face:.1} Pa, centre {point:.1} Pa");
    assert!((face / (rho0 * G * 0.6) - 1.0).abs() < 0.01, "face {face}");
    assert!(
        (face / point - 1.0).abs() < 0.005,
        "face {face} centre {point}"
    );
}

/// A fixed block 0.4 m × 0.2 m submerged in the hydrostatic tank, its centre 0.6 m
/// deep, carries the buoyancy ρ0 g V upward and no net horizontal force, once the
/// start-up oscillation has decayed (t·sqrt(g/H) = 10). The water is laid around it in
/// four blocks sharing the free surface at y = 1 m.
#[test]
fn a_submerged_block_carries_its_buoyancy() {
    let blocks = [
        ([0.0, 0.0], [2.0, 0.3]),
        ([0.0, 0.3], [0.8, 0.5]),
        ([1.2, 0.3], [2.0, 0.5]),
        ([0.0, 0.5], [2.0, 1.0]),
    ];
    let mut text = String::from(
        "name = \"buoyancy\"\ndimension = 2\n[particles]\nspacing = 0.05\n[fluid]\n\
         density = 1000.0\ngravity = [0.0, -9.81]\n",
    );
    for (lo, hi) in blocks {
        text += &format!("[[fluid_block]]\nlo = {lo:?}\nhi = {hi:?}\nsurface = 1.0\n");
    }
    text += "[[tank]]\nlo = [0.0, 0.0]\nhi = [2.0, 1.3]\n\
             [[wall]]\nname = \"block\"\nlo = [0.8, 0.3]\nhi = [1.2, 0.5]\n\
             [scheme]\ndiffusion = \"delta_sph\"\nviscosity = \"artificial\"\nalpha = 0.02\n\
             [time]\nend = 3.2\n";
    let mut sim = Simulation::<2>::new(Case::from_toml_str(&text).unwrap()).unwrap();
    assert_eq!(sim.bodies()[1].name, "block");
    while sim.time() < 10.0 * (1.0 / G).sqrt() {
        sim.step().unwrap();
    }
    let block = sim.loads()[1].force();
    let buoyancy = 1000.0 * G * 0.4 * 0.2;
    println!(
        "block {:.2?} against ρ0 g V = {buoyancy:.2}",
        block.as_slice()
    );
    // Measured 1.0013 ρ0 g V, horizontal 1e-13 of it.
    assert!((block[1] / buoyancy - 1.0).abs() < 0.01, "block {block:?}");
    assert!(block[0].abs() < 1e-3 * buoyancy, "block {block:?}");
}

/// Newton's third law: whatever the flow, the bodies' loads sum to minus the walls'
/// force on the fluid, Σ_i m_i (g - du_i/dt), since the fluid pairs cancel. The dam
/// break during its impact on the right wall, with no-slip walls (so the viscous part
/// is in play) and the lone particles of the splash.
#[test]
fn the_loads_balance_the_fluid_momentum_to_round_off() {
    let case = example_case(
        "dam_break_2d.toml",
        &[
            "particles.spacing = 0.04",
            "scheme.walls = \"no_slip\"",
            "diagnostics.loads = true",
        ],
    );
    let mut sim = Simulation::<2>::new(case).unwrap();
    while sim.time() < 0.8 {
        sim.step().unwrap();
    }
    let loads = sim.loads();
    let rates = sim.rates();
    let p = sim.particles();
    let g = Vector::<2>::new(0.0, -G);
    let (mut walls_on_fluid, mut scale) = (Vector::<2>::zeros(), 0.0);
    for i in (0..p.len()).filter(|&i| p.kind[i] == Kind::Fluid) {
        walls_on_fluid += (rates.du[i] - g) * p.mass[i];
        scale += p.mass[i] * rates.du[i].norm();
    }
    let total: Vector<2> = loads.iter().map(|l| l.force()).sum();
    let viscous: f64 = loads.iter().map(|l| l.viscous.norm()).sum();
    println!(
        "Σ loads {:?}, walls on fluid {:?}, viscous part {viscous:.3e}, scale {scale:.3e}",
        total.as_slice(),
        walls_on_fluid.as_slice()
    );
    assert!(viscous > 0.0, "the no-slip viscous part is measured");
    assert!(
        (total + walls_on_fluid).norm() < 1e-11 * scale,
        "imbalance {:e}",
        (total + walls_on_fluid).norm()
    );
}

/// The series carries each body's columns, named after it.
#[test]
fn the_series_names_each_body() {
    let sim = Simulation::<2>::new(tank_of_five_walls()).unwrap();
    let header = sim.series_header();
    for column in [
        "floor_pressure_fx",
        "floor_viscous_fy",
        "left_moment_z",
        "right_pressure_fy",
    ] {
        assert!(header.iter().any(|h| h == column), "{column} in {header:?}");
    }
}

/// With reference scales the series carries each body's force coefficients,
/// C = F / (½ ρ U² L) per unit width: the water's weight ρ0 g H L over ½ ρ0 U² L at
/// U = sqrt(2 g H) is 1, so in the hydrostatic start the vertical coefficients of the
/// floor and the two corner blocks, which together carry the water, sum to -1 (measured
/// -0.9942), the floor alone about -0.975, and each side wall's horizontal one is
/// ±H/(2L) = ±0.25, the thrust ρ0 g H²/2 (measured ∓0.2394 at the start, where the
/// wall pressure near the free surface is extrapolated over a truncated kernel; the
/// settled tank above carries the thrust within 1%).
#[test]
fn the_force_coefficients_scale_the_loads() {
    let mut case = tank_of_five_walls();
    case.diagnostics.reference = Some(sph_core::case::ReferenceConfig {
        velocity: (2.0 * G * 1.0_f64).sqrt(),
        length: 2.0,
        density: None,
    });
    let mut sim = Simulation::<2>::new(case).unwrap();
    let header = sim.series_header();
    let row = sim.series_values();
    let column = |name: &str| row[header.iter().position(|c| c == name).unwrap()];
    let carried = column("floor_cy") + column("left_corner_cy") + column("right_corner_cy");
    println!(
        "floor C_y {}, with the corners {carried}",
        column("floor_cy")
    );
    assert!(
        (carried + 1.0).abs() < 0.01,
        "floor and corners C_y = {carried}"
    );
    assert!((column("floor_cy") + 1.0).abs() < 0.05, "floor C_y");
    for (wall, sign) in [("left", -1.0), ("right", 1.0)] {
        let cx = column(&format!("{wall}_cx"));
        assert!((cx / (sign * 0.25) - 1.0).abs() < 0.06, "{wall} C_x = {cx}");
    }
}

/// Rectangular face sensors in 3D, at the hydrostatic start of a tank 0.3 m deep: on
/// the +x wall, a rectangle 0.12 m along y and 0.06 m high centred 0.2 m deep, and the
/// same rectangle turned upright (0.12 m along z, 0.06 m along y) centred 0.1 m deep.
/// The pressure is linear in depth, so each face reads ρ0 g times its centre's depth,
/// as its centre point does.
#[test]
fn rectangular_sensors_average_the_hydrostatic_pressure_over_their_face() {
    let text = "
        dimension = 3
        [particles]
        spacing = 0.02
        [fluid]
        density = 1000.0
        gravity = [0.0, 0.0, -9.81]
        [[fluid_block]]
        lo = [0.0, 0.0, 0.0]
        hi = [0.3, 0.2, 0.3]
        [[tank]]
        lo = [0.0, 0.0, 0.0]
        hi = [0.3, 0.2, 0.4]
        [time]
        end = 0.1
        [[diagnostics.sensors]]
        name = \"flat\"
        centre = [0.3, 0.1, 0.1]
        normal = [-1.0, 0.0, 0.0]
        size = 0.12
        width = 0.06
        along = [0.0, 1.0, 0.0]
        [[diagnostics.sensors]]
        name = \"upright\"
        centre = [0.3, 0.1, 0.2]
        normal = [-1.0, 0.0, 0.0]
        size = 0.12
        width = 0.06
        along = [0.0, 0.0, 1.0]
    ";
    let mut sim = Simulation::<3>::new(Case::from_toml_str(text).unwrap()).unwrap();
    let header = sim.series_header();
    let row = sim.series_values();
    let column = |name: &str| row[header.iter().position(|c| c == name).unwrap()];
    for (name, depth) in [("flat", 0.2), ("upright", 0.1)] {
        let (face, point) = (
            column(&format!("{name}_pressure")),
            column(&format!("{name}_point")),
        );
        let hydrostatic = 1000.0 * G * depth;
        println!("{name}: face {face:.1} Pa, centre {point:.1} Pa, ρ0 g d = {hydrostatic:.1} Pa");
        // Measured: flat 1.0000 ρ0 g d, upright 1.0005 (its top is 0.04 m, 2Δx, below
        // the surface, where the probes' support starts to be cut)
        assert!(
            (face / hydrostatic - 1.0).abs() < 0.003,
            "{name}: face {face}"
        );
        assert!(
            (face / point - 1.0).abs() < 0.002,
            "{name}: face {face} centre {point}"
        );
    }
}
