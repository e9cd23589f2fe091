//! End-to-end behaviour of the `sph-cli` binary: checks, errors, output safety and
//! the stability guard.

use crate::common::{cli, cli_within, example, scratch, small_case};
use std::path::Path;
use std::time::Duration;

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

#[test]
fn bad_input_gives_one_clear_line_and_no_panic() {
    let dir = scratch("bad");
    for (edit, expected) in [
        (
            "spacing = 0.05 ",
            "particles.spacing = -0.05: expected a positive number",
        ),
        ("alpha = 0.02", "scheme.alphaa"),
        ("hi = [1.2, 0.6]", "fluid_block[0].hi"),
    ] {
        let case = small_case(&dir, "");
        let text = std::fs::read_to_string(&case).unwrap();
        let broken = match expected {
            e if e.starts_with("particles") => text.replace(edit, "spacing = -0.05 "),
            e if e.starts_with("scheme") => text.replace(edit, "alphaa = 0.02"),
            _ => text.replace(edit, "hi = [1.2, -0.6]"),
        };
        std::fs::write(&case, broken).unwrap();
        let out = cli(&["check", &case]);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert!(err.lines().next().unwrap().contains(expected), "{err}");
        assert!(!err.contains("panicked"), "{err}");
    }
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

/// `preview` writes the initial particles (snapshot, index) and a PNG into a run
/// folder of its own, and refuses a folder deltasph did not make.
#[test]
fn preview_writes_the_initial_particles_and_a_picture() {
    let dir = scratch("preview");
    let case = small_case(&dir, "");
    let out_dir = dir.join("look");
    let out = cli(&["preview", &case, "--out", out_dir.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let png = std::fs::read(out_dir.join("preview.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    let snapshot = hdf5::File::open(out_dir.join("particles_000000.h5")).unwrap();
    let x = snapshot.dataset("position").unwrap().shape();
    // 24 × 12 fluid particles at Δx = 0.05 and the tank's wall layers, in 3D points
    assert_eq!(x[1], 3);
    assert!(x[0] > 288, "{x:?}");
    assert!(out_dir.join("particles.xmf").exists());
    let foreign = dir.join("mine");
    std::fs::create_dir_all(&foreign).unwrap();
    std::fs::write(foreign.join("notes.txt"), "keep").unwrap();
    let out = cli(&[
        "preview",
        &case,
        "--out",
        foreign.to_str().unwrap(),
        "--force",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert_eq!(
        std::fs::read_to_string(foreign.join("notes.txt")).unwrap(),
        "keep"
    );
}

#[test]
fn fluid_overlapping_a_wall_is_refused() {
    let dir = scratch("overlap");
    let case = small_case(&dir, "\n[[wall]]\nlo = [0.5, 0.0]\nhi = [0.7, 0.3]\n");
    let out = cli(&["check", &case]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        err.starts_with("error: fluid_block = a fluid particle at"),
        "{err}"
    );
}

#[test]
fn run_writes_snapshots_and_series_and_never_overwrites() {
    let dir = scratch("run");
    let case = small_case(&dir, "");
    let out_dir = dir.join("out");
    let out = cli(&["run", &case, "--out", out_dir.to_str().unwrap(), "--quiet"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("particle-steps/s"), "{summary}");
    for f in [
        "particles.xmf",
        "particles_000000.h5",
        "timeseries.csv",
        "case.toml",
    ] {
        assert!(out_dir.join(f).is_file(), "{f} missing");
    }
    let xmf = std::fs::read_to_string(out_dir.join("particles.xmf")).unwrap();
    let snapshots = std::fs::read_dir(&out_dir)
        .unwrap()
        .filter(|e| {
            e.as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .starts_with("particles_")
        })
        .count();
    assert_eq!(
        xmf.matches("<Time ").count(),
        snapshots,
        "every snapshot is indexed"
    );
    assert!(snapshots >= 3);
    // A second run into the same folder is refused and leaves it untouched.
    let before = std::fs::read(out_dir.join("timeseries.csv")).unwrap();
    let again = cli(&["run", &case, "--out", out_dir.to_str().unwrap(), "--quiet"]);
    assert_eq!(again.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&again.stderr).contains("--force"));
    assert_eq!(
        std::fs::read(out_dir.join("timeseries.csv")).unwrap(),
        before
    );
    let forced = cli(&[
        "run",
        &case,
        "--out",
        out_dir.to_str().unwrap(),
        "--quiet",
        "--force",
    ]);
    assert!(forced.status.success());
}

/// Runs a hopeless variant of the small dam break (`edit` applied to its text) and
/// checks that the guard stops it, within a minute, with the expected reason, a final
/// snapshot and exit code 3.
fn assert_stopped_by_the_guard(name: &str, edit: impl Fn(String) -> String, reason: &str) {
    let dir = scratch(name);
    let case = small_case(&dir, "");
    let text = std::fs::read_to_string(&case).unwrap();
    std::fs::write(&case, edit(text.replace("end = 0.05", "end = 2.0"))).unwrap();
    let out_dir = dir.join("out");
    let out = cli_within(
        &["run", &case, "--out", out_dir.to_str().unwrap(), "--quiet"],
        Duration::from_secs(60),
    );
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(3), "{name}: {err}");
    assert!(err.starts_with("error: unstable at t = "), "{name}: {err}");
    assert!(
        err.contains(reason) && err.contains("at particle"),
        "{name}: {err}"
    );
    let stdout = String::from_utf8_lossy(&out.stdout);
    let last = stdout
        .lines()
        .find_map(|l| l.strip_prefix("last snapshot"))
        .unwrap_or_else(|| panic!("{name}: no last snapshot in {stdout}"));
    let file = last.trim().split(' ').next().unwrap();
    assert!(Path::new(file).is_file(), "{name}: {file}");
    assert!(
        !out_dir.join("restart.h5").exists(),
        "{name}: no restart from a blown-up state"
    );
}

#[test]
fn hopeless_cases_stop_with_the_guard_message_and_a_final_snapshot() {
    // c0 far too small: the column collapses into a compressible heap.
    assert_stopped_by_the_guard(
        "slow_sound",
        |t| {
            t.replace(
                "gravity = [0.0, -9.81]",
                "gravity = [0.0, -9.81]\nsound_speed = 0.5",
            )
        },
        "density variation",
    );
    // Δt forced far beyond the symplectic scheme's acoustic limit.
    assert_stopped_by_the_guard(
        "courant_3",
        |t| {
            t.replace("integrator = \"rk4\"", "integrator = \"symplectic\"")
                .replace("cfl = 1.5", "cfl = 3.0")
        },
        "density variation",
    );
    // A block thrown at 2.5 times the sound speed.
    assert_stopped_by_the_guard(
        "supersonic",
        |t| {
            t.replace("hi = [1.2, 0.6]", "hi = [1.2, 0.6]\nvelocity = [50.0, 0.0]")
                .replace(
                    "gravity = [0.0, -9.81]",
                    "gravity = [0.0, -9.81]\nsound_speed = 20.0",
                )
        },
        "beyond the limit 2.0000e1 m/s",
    );
}

#[test]
fn overlapping_fluid_blocks_are_refused() {
    let dir = scratch("doubled");
    let case = small_case(
        &dir,
        "\n[[fluid_block]]\nlo = [0.0, 0.0]\nhi = [0.3, 0.3]\n",
    );
    let out = cli(&["check", &case]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.starts_with("error: fluid_block = a fluid particle at [0.025, 0.025]: expected fluid blocks that do not overlap"),
        "{err}"
    );
}

/// Peak resident memory (VmHWM, kB) of a child process, polled until it exits.
fn run_with_peak_memory(args: &[&str]) -> (std::process::Output, u64) {
    let mut child = std::process::Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("sph-cli starts");
    let status = format!("/proc/{}/status", child.id());
    let mut peak = 0;
    let start = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        let hwm = std::fs::read_to_string(&status)
            .unwrap_or_default()
            .lines()
            .find_map(|l| l.strip_prefix("VmHWM:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok());
        peak = peak.max(hwm.unwrap_or(0));
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "sph-cli {args:?} too slow"
        );
        std::thread::sleep(Duration::from_millis(10));
    }
    (child.wait_with_output().unwrap(), peak)
}

/// The Martin & Moyce column in its tank open to +x, run to t = 3 s: the surge leaves
/// the tank at about 0.35 s and falls off the floor's edge. Before particles were
/// removed at the domain's bounds, a falling particle reached the sound speed at
/// t = 2.25 s and the Mach guard ended the run as unstable. Now the run ends with
/// status 0, every particle that left is counted, and memory stays flat (20 MB
/// measured at a/Δx = 20; the bound is 64 MB).
#[test]
fn fluid_that_leaves_an_open_tank_is_removed_and_counted() {
    let dir = scratch("outflow");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(example("dam_break_martin_moyce_2d.toml"))
        .unwrap()
        .replace("spacing = 0.0025 ", "spacing = 0.01 ")
        .replace("end = 0.25", "end = 3.0")
        .replace("output_interval = 0.025", "output_interval = 0.25");
    let case = dir.join("case.toml");
    std::fs::write(&case, text).unwrap();
    let out_dir = dir.join("out");
    let (out, peak_kb) = run_with_peak_memory(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
        "--quiet",
    ]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}{stdout}",
        String::from_utf8_lossy(&out.stderr)
    );
    let removed: u64 = stdout
        .lines()
        .find_map(|l| l.strip_prefix("removed"))
        .and_then(|l| l.split_whitespace().next())
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no removed count in {stdout}"));
    println!("removed {removed} of 200 fluid particles; peak memory {peak_kb} kB");
    assert!(removed > 100, "{stdout}");
    // the case has no [domain]: the first removal is told once, on stderr, with where
    let stderr = String::from_utf8_lossy(&out.stderr);
    let notices: Vec<&str> = stderr
        .lines()
        .filter(|l| l.starts_with("notice:"))
        .collect();
    assert_eq!(notices.len(), 1, "{stderr}");
    assert!(notices[0].contains("left the default domain"), "{stderr}");
    // and the summary gives their mass: ρ0 Δx² each, within the hydrostatic start's
    // density spread (ρ0 g H/c0² < 1%)
    let mass: f64 = stdout
        .lines()
        .find_map(|l| l.strip_prefix("removed"))
        .and_then(|l| {
            l.split(['(', ' '])
                .find_map(|w| w.parse::<f64>().ok().filter(|_| w.contains('e')))
        })
        .unwrap_or_else(|| panic!("no removed mass in {stdout}"));
    let each = 1000.0 * 0.01 * 0.01;
    assert!(
        (mass / (removed as f64 * each) - 1.0).abs() < 0.01,
        "removed mass {mass} kg for {removed} particles of {each} kg"
    );
    assert!(peak_kb < 64 * 1024, "peak memory {peak_kb} kB");
    // the time series counts them as they go, and the snapshots shrink with them
    let series = std::fs::read_to_string(out_dir.join("timeseries.csv")).unwrap();
    let header: Vec<&str> = series.lines().next().unwrap().split(',').collect();
    let col = header.iter().position(|h| *h == "removed").unwrap();
    let counts: Vec<f64> = series
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(col).unwrap().parse().unwrap())
        .collect();
    assert!(counts.windows(2).all(|w| w[1] >= w[0]) && counts[0] == 0.0);
    assert_eq!(*counts.last().unwrap(), removed as f64);
    let xmf = std::fs::read_to_string(out_dir.join("particles.xmf")).unwrap();
    let first = 200
        + xmf
            .split("NumberOfElements=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap()
            .parse::<u64>()
            .unwrap()
        - 200;
    let last: u64 = xmf
        .rsplit("NumberOfElements=\"")
        .next()
        .unwrap()
        .split('"')
        .next()
        .unwrap()
        .parse()
        .unwrap();
    assert_eq!(
        first - last,
        removed,
        "the index follows the particle count"
    );
}

/// A case too large for the machine is refused before anything is allocated, in one
/// line naming the spacing, the estimate and the memory; `check` prints the estimate,
/// and DELTASPH_MEMORY_GIB sets the limit on purpose (here below the small case's need).
#[test]
fn a_case_that_does_not_fit_in_memory_is_refused_at_once() {
    let dir = scratch("memory");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(example("dam_break_2d.toml"))
        .unwrap()
        .replace("spacing = 0.012", "spacing = 3e-5");
    let case = dir.join("huge.toml");
    std::fs::write(&case, text).unwrap();
    let start = std::time::Instant::now();
    let out = cli(&["check", case.to_str().unwrap()]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        start.elapsed() < Duration::from_secs(5),
        "took {:?}",
        start.elapsed()
    );
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    for part in [
        "particles.spacing = 0.00003",
        "8.0e8 particles",
        "TiB",
        "DELTASPH_MEMORY_GIB",
    ] {
        assert!(stderr.contains(part), "{part} not in {stderr}");
    }
    let small = example("dam_break_2d.toml");
    let out = cli(&["check", &small]);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("memory: about") && stdout.contains("steps: c0 ="),
        "{stdout}"
    );
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(["check", &small])
        .env("DELTASPH_MEMORY_GIB", "0.001")
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        !out.status.success() && stderr.contains("DELTASPH_MEMORY_GIB is 1.0 MiB"),
        "{stderr}"
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

/// The schema shipped for editors is the one the case types give today.
#[test]
fn the_shipped_case_schema_is_current() {
    let out = cli(&["schema"]);
    assert!(out.status.success());
    let shipped = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/case.schema.json");
    let shipped = std::fs::read_to_string(shipped).unwrap();
    assert!(
        String::from_utf8_lossy(&out.stdout) == shipped,
        "docs/case.schema.json is stale: regenerate it with \
         `cargo run --release -p sph-cli -- schema > docs/case.schema.json`"
    );
}

/// Started by mpirun, a build without MPI would run the whole case once per process
/// into one folder; it refuses instead.
#[cfg(not(feature = "mpi"))]
#[test]
fn a_build_without_mpi_refuses_to_run_under_a_launcher() {
    let dir = scratch("no-mpi");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(["run", &example("dam_break_2d.toml"), "--out"])
        .arg(&dir)
        .env("OMPI_COMM_WORLD_SIZE", "2")
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(
        stderr.starts_with("error: started by an MPI launcher"),
        "{stderr}"
    );
    assert!(!dir.exists(), "no folder is made");
}
