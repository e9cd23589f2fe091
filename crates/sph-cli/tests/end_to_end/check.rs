//! What `sph-cli check` reports: every example valid, the split among processes, moving
//! and free bodies, regions and the closest fluid to a wall, the viscosity, long runs
//! and unreachable probes.

use crate::common::{cli, example, scratch, small_case};

#[test]
fn every_example_passes_check() {
    for name in [
        "dam_break_2d",
        "dam_break_martin_moyce_2d",
        "dam_break_3d",
        "floating_box_2d",
        "floating_buoy_3d",
        "hydrostatic_2d",
        "taylor_green_2d",
        "wave_flume_2d",
        "wave_flume_irregular_2d",
        "wedge_entry_2d",
    ] {
        let out = cli(&["check", &example(&format!("{name}.toml"))]);
        assert!(
            out.status.success(),
            "{name}: {}",
            String::from_utf8_lossy(&out.stderr)
        );
    }
}

/// `check --ranks P` splits the 2D dam break's 5000 fluid particles among P processes:
/// one line per process whose fluid counts add up to the case's, and the imbalance;
/// `--ranks 0` is refused.
#[test]
fn check_reports_the_split_among_processes() {
    let out = cli(&["check", &example("dam_break_2d.toml"), "--ranks", "3"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let fluid: Vec<usize> = text
        .lines()
        .filter(|l| l.trim_start().starts_with("rank "))
        .map(|l| {
            let (head, _) = l.split_once(" fluid").unwrap();
            head.rsplit(' ').next().unwrap().parse().unwrap()
        })
        .collect();
    assert_eq!(fluid.len(), 3, "{text}");
    assert_eq!(fluid.iter().sum::<usize>(), 5000, "{text}");
    assert!(text.contains("imbalance"), "{text}");
    let refused = cli(&["check", &example("dam_break_2d.toml"), "--ranks", "0"]);
    assert_eq!(refused.status.code(), Some(2));
}

/// `check` reports what each region built: the water wedge (a polygon) and its floor.
/// The shaken tank moves by A(1 - cos ωt) after its ramp, A ω² = g/2: at most 2A up, at
/// A ω = 0.78 m/s and (within the ramp's overshoot) g/2 = 4.9 m/s².
/// The line of `sph-cli check` on the example `name` that starts with `start`.
fn check_line(name: &str, start: &str) -> String {
    let out = cli(&["check", &example(name)]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (text.lines())
        .find(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("{text}"))
        .to_string()
}

#[test]
fn check_reports_how_far_and_fast_a_body_moves() {
    let line = check_line("validation/shaking_tank.toml", "motion of tank[0]: ");
    let numbers: Vec<f64> = (line.split_whitespace())
        .filter_map(|w| w.parse().ok())
        .collect();
    let (moved, speed, accel) = (numbers[0], numbers[2], numbers[3]);
    assert!((moved - 2.0 * 0.12424).abs() < 1e-3, "{line}");
    assert!(
        (speed - 0.12424 * std::f64::consts::TAU).abs() < 0.01,
        "{line}"
    );
    assert!(accel > 4.9 && accel < 5.5, "{line}");
}

/// The floating buoy of the STL example: a 24-sided prism of radius 0.1 m and height
/// 0.2 m at 400 kg/m³, its mass `400 V`, `V = (n/2) r² sin(2π/n) h`, and its draft `0.4 h`.
#[test]
fn check_reports_a_free_body_s_mass_and_draft() {
    let line = check_line("floating_buoy_3d.toml", "free body shape[0]: ");
    let number_after = |word: &str| -> f64 {
        let rest = line.split(word).nth(1).unwrap_or_else(|| panic!("{line}"));
        rest.split_whitespace()
            .next()
            .unwrap()
            .trim_end_matches(',')
            .parse()
            .unwrap()
    };
    let (n, r, h) = (24.0, 0.1, 0.2);
    let volume = 0.5 * n * r * r * (std::f64::consts::TAU / n).sin() * h;
    let mass = number_after("mass ");
    assert!((mass / (400.0 * volume) - 1.0).abs() < 1e-3, "{line}");
    let draft = number_after("draft of ");
    assert!((draft / (0.4 * h) - 1.0).abs() < 1e-3, "{line}");
}

/// A wave maker's line: regular waves' kd, wavelength, steepness and stroke from
/// linear theory (H = 0.04 m, T = 1.625 s in d = 0.5 m: kd = 1.0003, L = 3.1405 m,
/// stroke H/(H/S) = 0.04/0.98206 m by Biesel's piston transfer).
#[test]
fn check_reports_a_wave_maker_s_waves() {
    let out = cli(&["check", &example("wave_flume_2d.toml")]);
    let text = String::from_utf8_lossy(&out.stdout);
    let line = (text.lines())
        .find(|l| l.trim_start().starts_with("waves:"))
        .unwrap_or_else(|| panic!("{text}"));
    assert!(
        line.contains("waves: piston, H = 0.04 m, T = 1.6250 s, order 2: kd = 1.0003, L = 3.1405 m, H/L = 1.27%, stroke 4.0729e-2 m"),
        "{line}"
    );
}

/// An absorbing paddle's gauge stands a kernel support, half a spacing and a stroke
/// in front of it (0.2 + 0.025 + 0.0204 m); one so far off that the waves' phase
/// across it passes 1 rad (a coarse spacing, a wide kernel) is refused in one line.
#[test]
fn check_places_an_absorbing_paddle_s_gauge_and_refuses_one_too_far_off() {
    let case = example("validation/wave_paddle_absorption.toml");
    let out = cli(&["check", &case]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        text.contains("active absorption from a gauge 0.2454 m in front of the paddle at x = 0.2454 m (k x = 0.491 rad)"),
        "{text}"
    );
    let dir = scratch("absorbing_paddle");
    std::fs::create_dir_all(&dir).unwrap();
    let coarse = std::fs::read_to_string(&case)
        .unwrap()
        .replace("spacing = 0.05 ", "spacing = 0.1\nh_over_dx = 3.0 ")
        .replace("lo = [-0.2, 0.0] ", "lo = [-0.7, 0.0] ")
        .replace("lo = [-0.5, 0.0]", "lo = [-1.0, 0.0]");
    let path = dir.join("case.toml");
    std::fs::write(&path, coarse).unwrap();
    let out = cli(&["check", path.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.starts_with("error: wall[0].prescribed.waves.active_absorption = true: expected waves long beside the kernel: the gauge 0.6704 m in front of the paddle sits at k x = 1.341 rad"),
        "{err}"
    );
}

#[test]
fn check_reports_each_region_and_the_closest_fluid_to_a_wall() {
    let out = cli(&["check", &example("validation/water_wedge.toml")]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    // a 45° wedge 0.5 m high at Δx = 0.005: 100 rows of 2k lattice points, k = 1..100
    assert!(
        text.contains("10100 fluid and 1600 wall particles"),
        "{text}"
    );
    let line = |key: &str| {
        text.lines()
            .find(|l| l.trim_start().starts_with(key))
            .unwrap()
    };
    assert!(
        line("shape[0]").contains("10100 particles, from [-0.4975, 0.0025]"),
        "{text}"
    );
    assert!(
        line("wall[0] (floor)").contains(" 1600 particles"),
        "{text}"
    );
    assert!(
        line("closest fluid").contains("0.0050 m (1.00 Δx), shape[0] at [-0.0025, 0.0025]"),
        "{text}"
    );
}

/// `check` warns when the run would take more than a day: gravity of 10³⁰ m/s² makes
/// the sound speed 10¹⁶ m/s and the step 10⁻¹⁸ s.
#[test]
fn check_warns_of_a_run_longer_than_a_day() {
    let dir = scratch("long_run");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(example("dam_break_2d.toml"))
        .unwrap()
        .replace("gravity = [0.0, -9.81]", "gravity = [0.0, -1e30]");
    let case = dir.join("case.toml");
    std::fs::write(&case, text).unwrap();
    let out = cli(&["check", case.to_str().unwrap()]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("warning: this run would take more than a day"),
        "{stdout}"
    );
    let out = cli(&["check", &example("dam_break_2d.toml")]);
    assert!(!String::from_utf8_lossy(&out.stdout).contains("warning"));
}

/// `check` refuses what cannot be meant, in one line naming the key: a probe far
/// outside the tank, wall layers thinner than the kernel support.
#[test]
fn check_refuses_unreachable_probes_and_thin_walls() {
    let dir = scratch("check_refuses");
    for (edit, expected) in [
        (
            (
                "probes = [[3.2196, 0.12], [3.2196, 0.16]]",
                "probes = [[3.2196, 0.12], [3.2196, 0.16], [5.0, 5.0]]",
            ),
            "error: diagnostics.probes[2] = [5.0, 5.0]: expected a point inside the domain",
        ),
        (
            ("h_over_dx = 1.33", "h_over_dx = 2.0"),
            "error: tank[0].layers = 3: expected at least 4 layers",
        ),
    ] {
        let case = small_case(&dir, "");
        let text = std::fs::read_to_string(&case)
            .unwrap()
            .replace(edit.0, edit.1);
        std::fs::write(&case, text).unwrap();
        let out = cli(&["check", &case]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(err.starts_with(expected), "{err}");
    }
}

/// The impinging jet's inlet: at the domain's top, y = 0.325 m, its default width (the
/// support R = 2h = 0.02 m, four spacings, plus one) puts the inner face, where the jet
/// leaves the nozzle, at y = 0.3 m.
#[test]
fn check_reports_where_an_inlets_inner_face_lies() {
    let line = check_line("validation/impinging_jet.toml", "  open_boundary[0]");
    assert!(
        line.contains("inlet  at y hi = 0.325: 0.025 m wide, inner face at y = 0.3, 100 particles"),
        "{line}"
    );
}

/// `check` names the viscous term's kinematic viscosity: the jet's artificial one is
/// α h c0/8 = 0.02 · 0.01 m · 10 m/s / 8 (Δx = 0.005 m, h/Δx = 2), the oscillating
/// cylinder's physical one μ/ρ0 = 0.01 m²/s.
#[test]
fn check_reports_the_viscosity_the_flow_gets() {
    for (name, line) in [
        (
            "validation/impinging_jet.toml",
            "viscosity: artificial, α = 0.02: ν = α h c0/8 = 2.500e-4 m²/s",
        ),
        (
            "validation/oscillating_cylinder.toml",
            "viscosity: physical, ν = 1.000e-2 m²/s",
        ),
    ] {
        let out = cli(&["check", &example(name)]);
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(stdout.contains(line), "{name}: {stdout}");
    }
}
