//! End-to-end behaviour of the `sph-cli` binary: errors, output safety, runs and
//! the stability guard.

use crate::common::{cli, cli_within, example, scratch, small_case};
use std::path::Path;
use std::time::Duration;

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
    // 1200 px wide (the IHDR chunk's width, big-endian at bytes 16-19)
    assert_eq!(u32::from_be_bytes(png[16..20].try_into().unwrap()), 1200);
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
    // notices of transients the guard let through may come first
    let error = err
        .lines()
        .find(|l| l.starts_with("error: "))
        .unwrap_or_default();
    assert!(
        error.starts_with("error: unstable at t = "),
        "{name}: {err}"
    );
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
/// into one folder; it refuses instead. (`scripts/test.sh` builds sph-cli with MPI; the
/// Python suite checks the same refusal with the wheel's `deltasph` command.)
#[cfg(not(feature = "mpi"))]
#[test]
fn a_build_without_mpi_refuses_to_run_under_a_launcher() {
    let dir = scratch("no-mpi");
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(["run", &example("dam_break_2d.toml"), "--out"])
        .arg(dir.as_os_str())
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

/// A free body's run with the energy budget: the time series carries the moving walls'
/// power and work and the free bodies' power and energy, with which the CSV alone
/// closes the budget (`total + free_bodies_energy + removed - work` stays at its start
/// within 1% of what the box gave the water), and the summary prints them.
#[test]
fn a_floating_box_s_budget_closes_from_its_time_series() {
    let dir = scratch("floating_budget");
    std::fs::create_dir_all(&dir).unwrap();
    let text = std::fs::read_to_string(example("floating_box_2d.toml"))
        .unwrap()
        .replace("spacing = 0.01 ", "spacing = 0.02 ")
        .replace(
            "lo = [0.4, 0.25], hi = [0.6, 0.35]",
            "lo = [0.4, 0.27], hi = [0.6, 0.37]",
        )
        .replace("end = 4.0", "end = 0.3")
        + "\n[diagnostics]\nenergy_budget = true\ninterval = 0.01\n";
    let case = dir.join("case.toml");
    std::fs::write(&case, text).unwrap();
    let out_dir = dir.join("out");
    let out = cli(&[
        "run",
        case.to_str().unwrap(),
        "--out",
        out_dir.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let summary = String::from_utf8_lossy(&out.stdout);
    assert!(summary.contains("moving walls' work"), "{summary}");
    assert!(summary.contains("free bodies' energy E_b"), "{summary}");
    let series = std::fs::read_to_string(out_dir.join("timeseries.csv")).unwrap();
    let mut lines = series.lines().filter(|l| !l.starts_with('#'));
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let column = |name: &str| {
        (header.iter().position(|h| *h == name)).unwrap_or_else(|| panic!("{name}: {header:?}"))
    };
    let names = ["total", "free_bodies_energy", "removed_energy"];
    let (sum, work) = (names.map(column), column("work_of_dissipation_and_walls"));
    let moving = column("moving_wall_work");
    let _ = (column("moving_wall_power"), column("free_body_power"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    let closure = |r: &Vec<f64>| sum.iter().map(|&k| r[k]).sum::<f64>() - r[work];
    let (first, last) = (&rows[0], &rows[rows.len() - 1]);
    let given = last[moving];
    let (bodies, start) = (column("free_bodies_energy"), closure(first));
    assert!(first[bodies] - last[bodies] > 0.5, "the box fell");
    assert!(given > 0.5, "its walls did work on the water: {given}");
    let worst = rows
        .iter()
        .map(|r| (closure(r) - start).abs())
        .fold(0.0, f64::max);
    assert!(worst < 0.01 * given, "{worst} against {given}");
}

/// A 3D case's preview: the picture as two projections, wider than tall.
#[test]
fn preview_draws_a_3d_case() {
    let dir = scratch("preview3d");
    let case = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../examples/dam_break_3d.toml"
    );
    let out_dir = dir.join("look");
    let out = cli(&["preview", case, "--out", out_dir.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let png = std::fs::read(out_dir.join("preview.png")).unwrap();
    let (w, h) = (
        u32::from_be_bytes(png[16..20].try_into().unwrap()),
        u32::from_be_bytes(png[20..24].try_into().unwrap()),
    );
    assert!(w == 1200 && h > 100 && h < w, "{w} × {h}");
}
