//! Runs split over processes (`mpirun --oversubscribe`, built with the `mpi` feature)
//! against the serial run: `cargo test --release -p sph-cli --features mpi --test mpi`.
//!
//! The processes' pair sums run in another order than the serial run's, so states
//! agree to round-off: the tolerance 1e-10 (relative to the largest value of each
//! field) is three orders above the differences measured after 200 steps (1e-13 in
//! velocity and pressure, 1e-15 in position and density), and a halo one pass too
//! shallow misses it by four orders (1e-6).
#![cfg(feature = "mpi")]

#[path = "../end_to_end/common/mod.rs"]
mod common;

use common::{cli, example, scratch};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const TOLERANCE: f64 = 1e-10;

/// `sph-cli args` on `n` processes, each with one Rayon thread.
fn mpirun(n: usize, args: &[&str]) -> Output {
    Command::new("mpirun")
        .args([
            "--allow-run-as-root",
            "--oversubscribe",
            "-n",
            &n.to_string(),
        ])
        .arg(env!("CARGO_BIN_EXE_sph-cli"))
        .args(args)
        .env("RAYON_NUM_THREADS", "1")
        .output()
        .expect("mpirun runs (Open MPI's openmpi-bin)")
}

fn succeeded(out: &Output) -> String {
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    assert!(
        out.status.success(),
        "{text}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    text
}

/// `example` with `edits` (text replacements) and `extra` lines, written to `dir`.
fn case(dir: &Path, example_name: &str, edits: &[(&str, &str)], extra: &str) -> String {
    std::fs::create_dir_all(dir).unwrap();
    let mut text = std::fs::read_to_string(example(example_name)).unwrap();
    for (from, to) in edits {
        assert!(text.contains(from), "{example_name} has no {from:?}");
        text = text.replace(from, to);
    }
    let path = dir.join("case.toml");
    std::fs::write(&path, text + extra).unwrap();
    path.display().to_string()
}

/// Snapshot `k` of a run folder: each dataset's values, in the order of the ids.
struct State {
    id: Vec<u32>,
    fields: Vec<(&'static str, Vec<f64>)>,
}

fn dataset<T: hdf5::H5Type>(file: &hdf5::File, name: &str) -> Vec<T> {
    file.dataset(name).unwrap().read_raw().unwrap()
}

fn state(file: &Path, names: &[&'static str]) -> State {
    let h5 = hdf5::File::open(file).unwrap_or_else(|e| panic!("{file:?}: {e}"));
    let id: Vec<u32> = dataset(&h5, "id");
    let mut order: Vec<usize> = (0..id.len()).collect();
    order.sort_by_key(|&i| id[i]);
    let fields = (names.iter())
        .map(|&name| {
            let values: Vec<f64> = dataset(&h5, name);
            let width = values.len() / id.len();
            let sorted = (order.iter())
                .flat_map(|&i| values[i * width..(i + 1) * width].to_vec())
                .collect();
            (name, sorted)
        })
        .collect();
    State {
        id: order.iter().map(|&i| id[i]).collect(),
        fields,
    }
}

fn snapshot(dir: &Path, k: usize) -> PathBuf {
    dir.join(format!("particles_{k:06}.h5"))
}

/// Asserts the same particles and, field by field, values within [`TOLERANCE`] of
/// the largest (positions by minimum image in a box `period` wide, when it is not
/// zero); returns the largest relative difference.
fn assert_agree(serial: &State, split: &State, what: &str, period: f64) -> f64 {
    assert_eq!(serial.id, split.id, "{what}: particles differ");
    let mut worst: f64 = 0.0;
    for ((name, a), (_, b)) in serial.fields.iter().zip(&split.fields) {
        let scale = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let apart = |x: f64, y: f64| match (*name, period > 0.0) {
            ("position", true) => (x - y).abs().min(period - (x - y).abs()),
            _ => (x - y).abs(),
        };
        let diff = (a.iter().zip(b)).fold(0.0f64, |m, (x, y)| m.max(apart(*x, *y)));
        let relative = diff / scale;
        assert!(
            relative <= TOLERANCE,
            "{what}: {name} differs by {relative:.2e} of its largest value"
        );
        worst = worst.max(relative);
    }
    worst
}

/// The time series as numbers, row by row.
fn series(dir: &Path) -> Vec<Vec<f64>> {
    let text = std::fs::read_to_string(dir.join("timeseries.csv")).unwrap();
    (text.lines().skip(1))
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect()
}

/// Rows equal to the series' eleven digits (a last digit may round either way).
fn assert_same_series(a: &Path, b: &Path) {
    let (ra, rb) = (series(a), series(b));
    assert_eq!(ra.len(), rb.len(), "rows of {a:?} and {b:?}");
    for (x, y) in ra.iter().flatten().zip(rb.iter().flatten()) {
        let same = (x.is_nan() && y.is_nan()) || (x - y).abs() <= 2e-10 * x.abs().max(1e-300);
        assert!(same, "series of {a:?} and {b:?}: {x} against {y}");
    }
}

/// Masses of the restart file, in the order of the ids, bit for bit.
fn masses(dir: &Path) -> Vec<u64> {
    let h5 = hdf5::File::open(dir.join("restart.h5")).unwrap();
    let (id, mass): (Vec<u32>, Vec<f64>) = (dataset(&h5, "id"), dataset(&h5, "mass"));
    let mut pairs: Vec<(u32, u64)> = id
        .into_iter()
        .zip(mass.iter().map(|m| m.to_bits()))
        .collect();
    pairs.sort_unstable();
    pairs.into_iter().map(|(_, m)| m).collect()
}

/// Runs `case` serially and on each of `processes` and compares the end states, the
/// series (energies, probes, surge front) and the masses.
fn agrees_with_serial(name: &str, case_file: &str, dir: &Path, processes: &[usize]) {
    let serial = dir.join("serial");
    succeeded(&cli(&[
        "run",
        case_file,
        "--out",
        serial.to_str().unwrap(),
        "--quiet",
    ]));
    let fields = ["position", "velocity", "density", "pressure"];
    let end = state(&snapshot(&serial, 1), &fields);
    for &n in processes {
        let split = dir.join(format!("p{n}"));
        let report = succeeded(&mpirun(
            n,
            &[
                "run",
                case_file,
                "--out",
                split.to_str().unwrap(),
                "--quiet",
            ],
        ));
        assert!(
            n == 1 || report.contains(&format!("processes       {n} ")),
            "{report}"
        );
        let worst = assert_agree(
            &end,
            &state(&snapshot(&split, 1), &fields),
            &format!("{name} on {n}"),
            0.0,
        );
        println!("{name} on {n} processes: largest difference {worst:.2e} of the largest value");
        assert_same_series(&serial, &split);
        assert_eq!(masses(&serial), masses(&split), "{name} on {n}: masses");
    }
}

#[test]
fn the_2d_dam_break_on_1_to_4_processes_is_the_serial_run() {
    let dir = scratch("mpi-dam-2d");
    let edits = [
        ("end = 4.95", "end = 4.95\nmax_steps = 200"),
        ("output_interval = 0.05", "output_interval = 0.0"),
    ];
    let file = case(&dir, "dam_break_2d.toml", &edits, "");
    agrees_with_serial("2D dam break", &file, &dir, &[1, 2, 3, 4]);
}

/// With δ+ shifting the halo covers the free surface's passes too (three), and the
/// shifting velocities move with the particles. The flow amplifies round-off: a
/// serial run with gravity one ulp larger is 7e-6 away in position after 200 steps,
/// as the split run is (8e-6); so the states are compared after 60 steps, where the
/// split run is 6e-14 away. A halo of one pass leaves it 7.5e-3 away; one of two
/// passes agrees here too (8.5e-14).
#[test]
fn the_2d_dam_break_with_shifting_on_3_processes_is_the_serial_run() {
    let dir = scratch("mpi-dam-shifting");
    let edits = [
        ("end = 4.95", "end = 4.95\nmax_steps = 60"),
        ("output_interval = 0.05", "output_interval = 0.0"),
        ("[scheme]", "[scheme]\nshifting = \"delta_plus\""),
    ];
    let file = case(&dir, "dam_break_2d.toml", &edits, "");
    agrees_with_serial("2D dam break with δ+ shifting", &file, &dir, &[3]);
}

#[test]
fn the_3d_dam_break_on_2_to_4_processes_is_the_serial_run() {
    let dir = scratch("mpi-dam-3d");
    let edits = [
        ("spacing = 0.02", "spacing = 0.03"),
        ("end = 3.5", "end = 3.5\nmax_steps = 200"),
        ("output_interval = 0.05", "output_interval = 0.0"),
    ];
    let file = case(&dir, "dam_break_3d.toml", &edits, "");
    agrees_with_serial("3D dam break", &file, &dir, &[2, 3, 4]);
}

#[test]
fn periodic_taylor_green_on_4_processes_keeps_every_particle_once() {
    let dir = scratch("mpi-taylor-green");
    // a snapshot after every step: each holds every id once
    let edits = [
        ("end = 1.0", "end = 1.0\nmax_steps = 100"),
        ("output_interval = 0.1", "output_interval = 1e-6"),
    ];
    let file = case(&dir, "taylor_green_2d.toml", &edits, "");
    let (serial, split) = (dir.join("serial"), dir.join("p4"));
    succeeded(&cli(&[
        "run",
        &file,
        "--out",
        serial.to_str().unwrap(),
        "--quiet",
    ]));
    let report = succeeded(&mpirun(
        4,
        &["run", &file, "--out", split.to_str().unwrap(), "--quiet"],
    ));
    let handed: Vec<u64> = (report.lines())
        .filter_map(|l| l.split(" fluid, halo ").nth(1))
        .map(|rest| {
            rest.split(", ")
                .nth(1)
                .unwrap()
                .split(' ')
                .next()
                .unwrap()
                .parse()
                .unwrap()
        })
        .collect();
    assert_eq!(handed.len(), 4, "{report}");
    assert!(
        handed.iter().all(|&h| h > 100),
        "particles crossed between processes: {handed:?}"
    );
    let mut snapshots = 0;
    while snapshot(&split, snapshots).exists() {
        let s = state(&snapshot(&split, snapshots), &[]);
        let expected: Vec<u32> = (0..2500).collect();
        assert_eq!(s.id, expected, "snapshot {snapshots}: ids lost or repeated");
        snapshots += 1;
    }
    assert!(
        snapshots > 100,
        "a snapshot after every step, found {snapshots}"
    );
    // this flow amplifies round-off by about 300 every 20 steps: the serial run with
    // its amplitude one ulp larger is 1.6e-14 away at step 40 and 2.2e-8 at step 100,
    // as the split run is (1.6e-14 and 3.0e-8); so the states are compared at step 40
    let fields = ["position", "velocity", "density"];
    let (a, b) = (snapshot(&serial, 40), snapshot(&split, 40));
    assert_agree(
        &state(&a, &fields),
        &state(&b, &fields),
        "Taylor-Green on 4",
        1.0,
    );
}

#[test]
fn a_run_restarted_on_another_process_count_reaches_the_serial_state() {
    let dir = scratch("mpi-restart");
    let file = case(
        &dir,
        "dam_break_2d.toml",
        &[("output_interval = 0.05", "output_interval = 0.0")],
        "",
    );
    let (serial, split) = (dir.join("serial"), dir.join("split"));
    let s = serial.to_str().unwrap();
    succeeded(&cli(&[
        "run", &file, "--out", s, "--until", "0.07", "--quiet",
    ]));
    succeeded(&cli(&[
        "run",
        "--restart",
        &format!("{s}/restart.h5"),
        "--until",
        "0.14",
        "--quiet",
    ]));
    let p = split.to_str().unwrap();
    succeeded(&mpirun(
        2,
        &["run", &file, "--out", p, "--until", "0.07", "--quiet"],
    ));
    succeeded(&mpirun(
        3,
        &[
            "run",
            "--restart",
            &format!("{p}/restart.h5"),
            "--until",
            "0.14",
            "--quiet",
        ],
    ));
    let fields = ["position", "velocity", "density"];
    assert_agree(
        &state(&snapshot(&serial, 2), &fields),
        &state(&snapshot(&split, 2), &fields),
        "2 then 3 processes",
        0.0,
    );
}

#[test]
fn a_signal_to_one_process_stops_every_process_with_a_restart_file() {
    let dir = scratch("mpi-signal");
    let file = case(
        &dir,
        "dam_break_2d.toml",
        &[("output_interval = 0.05", "output_interval = 0.01")],
        "",
    );
    let out = dir.join("out");
    let child = Command::new("mpirun")
        .args(["--allow-run-as-root", "--oversubscribe", "-n", "3"])
        .arg(env!("CARGO_BIN_EXE_sph-cli"))
        .args(["run", &file, "--out", out.to_str().unwrap(), "--quiet"])
        .env("RAYON_NUM_THREADS", "1")
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let started = std::time::Instant::now();
    while !snapshot(&out, 2).exists() {
        assert!(
            started.elapsed().as_secs() < 60,
            "no second snapshot within a minute"
        );
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    // the last of the processes (not process 0, which writes) gets the signal
    let pids = Command::new("pgrep")
        .args(["-f", out.to_str().unwrap()])
        .output()
        .unwrap();
    let pids = String::from_utf8_lossy(&pids.stdout).into_owned();
    let last = pids
        .split_whitespace()
        .last()
        .expect("the processes' ids")
        .to_string();
    assert!(Command::new("kill")
        .args(["-TERM", &last])
        .status()
        .unwrap()
        .success());
    let ended = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&ended.stderr);
    assert_eq!(ended.status.code(), Some(128 + 15), "{stderr}");
    assert!(stderr.contains("interrupted by SIGTERM"), "{stderr}");
    assert!(out.join("restart.h5").exists());
    let continued = mpirun(
        2,
        &[
            "run",
            "--restart",
            out.join("restart.h5").to_str().unwrap(),
            "--until",
            "0.2",
            "--quiet",
        ],
    );
    succeeded(&continued);
}

#[test]
fn a_case_a_split_run_cannot_do_is_refused_in_one_line() {
    let out = mpirun(
        2,
        &[
            "run",
            &example("les_taylor_green.toml"),
            "--out",
            scratch("mpi-les").to_str().unwrap(),
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&out.stderr);
    let errors: Vec<&str> = stderr.lines().filter(|l| l.starts_with("error:")).collect();
    assert_eq!(errors.len(), 1, "one process reports: {stderr}");
    assert!(errors[0].contains("scheme.turbulence"), "{stderr}");
}
