//! The Python module `deltasph` (its native part, `deltasph._core`): a thin front
//! over `sph-core`. Cases go through the same parser and validator as the command
//! line; state comes back as numpy arrays in particle-id order.

mod arrays;
mod config;
mod edits;
mod errors;
mod folder;
mod measures;
mod postprocess;
mod simulation;
mod stepping;
mod waves;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    sph_core::allocator::return_large_buffers();
    m.add_class::<simulation::PySimulation>()?;
    m.add_function(wrap_pyfunction!(folder::read_snapshot, m)?)?;
    m.add_function(wrap_pyfunction!(postprocess::measure, m)?)?;
    m.add_function(wrap_pyfunction!(postprocess::surface, m)?)?;
    m.add_function(wrap_pyfunction!(cli, m)?)?;
    m.add_function(wrap_pyfunction!(case_schema, m)?)?;
    m.add_function(wrap_pyfunction!(waves::regular_wave, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

/// What the Python command adds to the command line's help.
const PLOT_HELP: &str = "Also: deltasph plot <run folder> writes PNGs of its snapshots and \
                         time series (needs matplotlib).";

/// Runs the command line (``deltasph run|check|preview|measure|surface|schema ...``): ``args`` are the
/// words after the program name. Returns the exit code, as ``sph-cli`` does.
#[pyfunction]
fn cli(py: Python<'_>, args: Vec<std::ffi::OsString>) -> u8 {
    let argv = std::iter::once("deltasph".into()).chain(args).collect();
    py.detach(|| sph_cli::main_with("deltasph", argv, Some(PLOT_HELP)))
}

/// The JSON Schema of the case file (what ``sph-cli schema`` prints), as text.
#[pyfunction]
fn case_schema() -> String {
    sph_core::case::json_schema::case_schema()
}
