//! What Python reads off a running simulation beyond its state arrays: energies, the
//! bodies' loads, pressure probes and the free surface, as dicts and arrays.

use crate::arrays;
use crate::simulation::rows;
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sph_core::Simulation;

/// `kinetic`, `potential`, `internal`, `total`, `bodies` (the free bodies'), and
/// `dissipated` and `moving_work` (None without the energy budget).
pub(crate) fn energies<'py, const D: usize>(
    py: Python<'py>,
    s: &Simulation<D>,
) -> PyResult<Bound<'py, PyDict>> {
    let (e, budget) = (s.energies(), s.budget());
    let dict = PyDict::new(py);
    dict.set_item("kinetic", e.kinetic)?;
    dict.set_item("potential", e.potential)?;
    dict.set_item("internal", e.internal)?;
    dict.set_item("total", e.total())?;
    let bodies = s
        .motions()
        .map_or(0.0, sph_core::motion::Motions::free_energy);
    dict.set_item("bodies", bodies)?;
    dict.set_item("dissipated", budget.map(|b| 0.0 - b.work()))?;
    dict.set_item("moving_work", budget.map(|b| b.work_of_moving_walls()))?;
    Ok(dict)
}

/// `{name: {"pressure": (D,), "viscous": (D,), "moment": (3,)}}` for every body.
pub(crate) fn loads<'py, const D: usize>(
    py: Python<'py>,
    s: &mut Simulation<D>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let names: Vec<String> = s.bodies().iter().map(|b| b.name.clone()).collect();
    for (name, load) in names.into_iter().zip(s.loads()) {
        let entry = PyDict::new(py);
        entry.set_item(
            "pressure",
            PyArray1::from_slice(py, load.pressure.as_slice()),
        )?;
        entry.set_item("viscous", PyArray1::from_slice(py, load.viscous.as_slice()))?;
        entry.set_item("moment", PyArray1::from_slice(py, load.moment.as_slice()))?;
        dict.set_item(name, entry)?;
    }
    Ok(dict)
}

/// Shepard pressures at `points` (NaN where no fluid is in reach); a point no fluid
/// can ever reach (outside the domain, or buried in a wall) raises ValueError.
pub(crate) fn probe_pressure<'py, const D: usize>(
    py: Python<'py>,
    s: &Simulation<D>,
    points: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let points = arrays::points(points)?;
    for (k, x) in points.iter().enumerate() {
        if let Some(expected) = s.probe_refusal(x) {
            return Err(PyValueError::new_err(format!(
                "points[{k}] = {:?}: expected {expected}",
                x.as_slice()
            )));
        }
    }
    let values: Vec<f64> = points
        .iter()
        .map(|x| s.probe_pressure(x).unwrap_or(f64::NAN))
        .collect();
    Ok(PyArray1::from_vec(py, values))
}

/// `on_surface`, `normal` and `lambda` in id order.
pub(crate) fn free_surface<'py, const D: usize>(
    py: Python<'py>,
    s: &Simulation<D>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let f = s.free_surface();
    let (id, n) = (&s.particles().id, rows(s));
    dict.set_item(
        "on_surface",
        arrays::scalars(py, id, n, &f.on_surface, (false, |b| b)),
    )?;
    dict.set_item("normal", arrays::vectors(py, id, n, &f.normal))?;
    dict.set_item(
        "lambda",
        arrays::scalars(py, id, n, &f.lambda, (f64::NAN, |v| v)),
    )?;
    Ok(dict)
}

/// `{name: {"position", "rotation", "velocity", "angular_velocity"}}` for every moving
/// body now: the pivot's position (D,) and velocity (D,), the rotation (2D: (1,), the
/// angle; 3D: (3,), the rotation vector) and the angular velocity (2D (1,), 3D (3,)).
pub(crate) fn body_motions<'py, const D: usize>(
    py: Python<'py>,
    s: &Simulation<D>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let turned: &[usize] = if D == 2 { &[2] } else { &[0, 1, 2] };
    for (name, pose) in s.moving_body_names().into_iter().zip(s.body_poses()) {
        let entry = PyDict::new(py);
        let angular = |v: &[f64]| turned.iter().map(|&k| v[k]).collect::<Vec<_>>();
        entry.set_item("position", PyArray1::from_slice(py, pose.pivot.as_slice()))?;
        entry.set_item(
            "rotation",
            PyArray1::from_vec(py, angular(pose.phi.as_slice())),
        )?;
        entry.set_item(
            "velocity",
            PyArray1::from_slice(py, pose.velocity.as_slice()),
        )?;
        entry.set_item(
            "angular_velocity",
            PyArray1::from_vec(py, angular(pose.omega.as_slice())),
        )?;
        dict.set_item(name, entry)?;
    }
    Ok(dict)
}
