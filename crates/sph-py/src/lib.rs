//! The Python module `deltasph` (its native part, `deltasph._core`): a thin front
//! over `sph-core`. Cases go through the same parser and validator as the command
//! line; state comes back as numpy arrays in particle-id order.

mod arrays;
mod config;
mod errors;
mod simulation;

use pyo3::prelude::*;

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<simulation::PySimulation>()?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
