//! `sph-cli`: runs, checks and previews deltasph TOML cases.

use std::process::ExitCode;

fn main() -> ExitCode {
    ExitCode::from(sph_cli::main_with(
        "sph-cli",
        std::env::args_os().collect(),
        None,
    ))
}
