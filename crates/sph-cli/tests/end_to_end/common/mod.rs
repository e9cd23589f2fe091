//! Helpers shared by the CLI tests: run the binary, find examples, make scratch folders.
// Each test crate compiles this module and uses a part of it.
#![allow(dead_code)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

pub fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(args)
        .output()
        .expect("sph-cli runs")
}

/// Runs the binary and fails the test if it has not finished within `limit`.
pub fn cli_within(args: &[&str], limit: Duration) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("sph-cli starts");
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > limit {
            child.kill().unwrap();
            panic!("sph-cli {args:?} still running after {limit:?}");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

pub fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
        .display()
        .to_string()
}

/// A scratch folder for one test, removed when the test passes (kept, with its path
/// printed, when it fails, for a look at what the run wrote).
pub struct Scratch(PathBuf);

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if std::thread::panicking() {
            eprintln!("scratch folder kept: {}", self.0.display());
        } else {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

pub fn scratch(name: &str) -> Scratch {
    let dir = std::env::temp_dir().join(format!("sph-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    Scratch(dir)
}

/// A small, fast variant of the 2D dam break written to `dir/case.toml`.
pub fn small_case(dir: &Path, extra: &str) -> String {
    std::fs::create_dir_all(dir).unwrap();
    let text = std::fs::read_to_string(example("dam_break_2d.toml"))
        .unwrap()
        .replace("spacing = 0.012 ", "spacing = 0.05 ")
        .replace("end = 4.95", "end = 0.05")
        .replace("output_interval = 0.05", "output_interval = 0.02")
        + extra;
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}

/// [`small_case`] run into `dir/out` (snapshots at t = 0, 0.02, 0.04 and the end); the
/// run folder's path.
pub fn small_run(dir: &Path) -> String {
    let case = small_case(dir, "");
    let run = dir.join("out").display().to_string();
    assert!(cli(&["run", &case, "--out", &run, "--quiet"])
        .status
        .success());
    run
}
