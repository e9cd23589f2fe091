//! End-to-end behaviour of the `sph-cli` binary, in one test binary (one link): checks
//! and errors, output safety, restarts and the stability guard.

mod check;
mod cli;
mod common;
mod measure;
mod output_safety;
mod restart;
mod surface;
