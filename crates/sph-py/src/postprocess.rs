//! Answers read from a finished run folder, for Python: the measure tool's series
//! ([`sph_core::postprocess::measure`]) as numpy arrays, and the free-surface meshes
//! ([`sph_core::postprocess::surface`]) written beside the run.

use crate::errors::to_py;
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sph_core::postprocess::measure::{measure as measure_run, Quantity, Request};
use sph_core::postprocess::surface::{write_surfaces, Request as SurfaceRequest};
use sph_core::postprocess::RunFolder;
use std::path::PathBuf;

/// A measurement as Python gets it: times, steps and the series by name.
type Measured<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<u64>>,
    Bound<'py, PyDict>,
);

/// Measures ``fields`` at ``points``, the elevation on the vertical lines at
/// ``elevations`` and the flow through the ``sections`` (their corners) in every
/// snapshot of the run folder ``run``: ``(times, steps, series)``, each series an array
/// (snapshots, points) or (snapshots, points, D) for the velocity; NaN where no fluid is
/// in reach. With ``out = (path, overwrite)``, also writes the CSV of ``sph-cli measure``
/// there (an earlier one replaced only with ``overwrite``).
#[pyfunction]
#[pyo3(signature = (run, points, fields, elevations, sections, out=None))]
pub fn measure<'py>(
    py: Python<'py>,
    run: PathBuf,
    points: Vec<Vec<f64>>,
    fields: Vec<String>,
    elevations: Vec<Vec<f64>>,
    sections: Vec<Vec<Vec<f64>>>,
    out: Option<(PathBuf, bool)>,
) -> PyResult<Measured<'py>> {
    let quantities = (fields.iter().map(|f| Quantity::parse(f)))
        .collect::<sph_core::Result<Vec<_>>>()
        .map_err(|e| to_py(py, e))?;
    let request = Request {
        points,
        quantities,
        elevations,
        sections,
    };
    let measured = py.detach(|| {
        let m = measure_run(&RunFolder::open(&run)?, &request)?;
        if let Some((path, overwrite)) = &out {
            m.write_csv(path, *overwrite)?;
        }
        Ok(m)
    });
    let m = measured.map_err(|e| to_py(py, e))?;
    let series = PyDict::new(py);
    let snapshots = m.times.len();
    for s in m.series {
        let array = PyArray1::from_vec(py, s.values);
        let array = match s.components {
            1 => array.reshape([snapshots, s.count])?.into_any(),
            c => array.reshape([snapshots, s.count, c])?.into_any(),
        };
        series.set_item(s.name, array)?;
    }
    Ok((
        PyArray1::from_vec(py, m.times),
        PyArray1::from_vec(py, m.steps),
        series,
    ))
}

/// Writes the free surface of every snapshot of the run folder ``run`` as meshes, as
/// ``sph-cli surface`` does: ``(collection, files)``, the paths of the ParaView
/// collection and of the mesh files in time order.
#[pyfunction]
#[pyo3(signature = (run, spacing=None, level=0.5, out=None, overwrite=false))]
pub fn surface(
    py: Python<'_>,
    run: PathBuf,
    spacing: Option<f64>,
    level: f64,
    out: Option<PathBuf>,
    overwrite: bool,
) -> PyResult<(PathBuf, Vec<PathBuf>)> {
    let request = SurfaceRequest {
        spacing,
        level,
        out,
        overwrite,
    };
    let written = py.detach(|| write_surfaces(&RunFolder::open(&run)?, &request));
    let written = written.map_err(|e| to_py(py, e))?;
    Ok((written.collection, written.files))
}
