//! Helpers shared by the CLI tests: run the binary, find examples, make scratch folders.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

pub fn cli(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_sph-cli"))
        .args(args)
        .output()
        .expect("sph-cli runs")
}

pub fn example(name: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
        .display()
        .to_string()
}

pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("sph-cli-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A small, fast variant of the 2D dam break written to `dir/case.toml`.
pub fn small_case(dir: &Path, extra: &str) -> String {
    std::fs::create_dir_all(dir).unwrap();
    let text = std::fs::read_to_string(example("dam_break_2d.toml"))
        .unwrap()
        .replace("spacing = 0.012 ", "spacing = 0.05 ")
        .replace("end = 1.73", "end = 0.05")
        .replace("output_interval = 0.05", "output_interval = 0.02")
        + extra;
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    path.display().to_string()
}
