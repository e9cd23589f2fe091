//! What Python reads off a running simulation beyond its state arrays: energies, the
//! bodies' loads, pressure probes, the free surface, wave elevations and prescribed
//! motions, as dicts and arrays.

use crate::arrays;
use crate::simulation::rows;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sph_core::motion::rigid::Pose;
use sph_core::{Simulation, Vector};

/// `kinetic`, `potential`, `internal`, `total`, `bodies` (the free bodies'), and
/// `dissipated`, `moving_work` and `forcing_work` (None without the energy budget).
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
    dict.set_item("forcing_work", budget.map(|b| b.work_of_forcing()))?;
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
    let points = reachable(s, points)?;
    let values: Vec<f64> = points
        .iter()
        .map(|x| s.probe_pressure(x).unwrap_or(f64::NAN))
        .collect();
    Ok(PyArray1::from_vec(py, values))
}

/// Shepard velocities at `points`, (M, D) (NaN rows where no fluid is in reach); a
/// point no fluid can ever reach raises ValueError.
pub(crate) fn probe_velocity<'py, const D: usize>(
    py: Python<'py>,
    s: &Simulation<D>,
    points: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let points = reachable(s, points)?;
    let values: Vec<Vector<D>> = (s.probe_velocities(&points).into_iter())
        .map(|u| u.unwrap_or(Vector::repeat(f64::NAN)))
        .collect();
    let rows: Vec<u32> = (0..values.len() as u32).collect();
    Ok(arrays::vectors(py, &rows, values.len(), &values))
}

/// The points of `points`, refused where no fluid can ever reach them (outside the
/// domain, or buried in a wall).
fn reachable<const D: usize>(
    s: &Simulation<D>,
    points: &Bound<'_, PyAny>,
) -> PyResult<Vec<Vector<D>>> {
    let points = arrays::points(points)?;
    for (k, x) in points.iter().enumerate() {
        if let Some(expected) = s.probe_refusal(x) {
            return Err(PyValueError::new_err(format!(
                "points[{k}] = {:?}: expected {expected}",
                x.as_slice()
            )));
        }
    }
    Ok(points)
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

/// The free surface's elevation above `diagnostics.still_level` at `positions`: x
/// values (2D) or (x, y) rows (3D).
pub(crate) fn wave_elevation<'py, const D: usize>(
    py: Python<'py>,
    s: &Simulation<D>,
    positions: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let rows: Vec<Vec<f64>> = match positions.extract::<Vec<Vec<f64>>>() {
        Ok(rows) => rows,
        Err(_) => (positions.extract::<Vec<f64>>()?.into_iter())
            .map(|x| vec![x])
            .collect(),
    };
    let values = (s.wave_elevations(&rows)).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(PyArray1::from_vec(py, values))
}

/// `{name: {"position": (M, D), "rotation": (M, 1|3), "velocity": (M, D),
/// "angular_velocity": (M, 1|3)}}` of every body with a prescribed motion at `times`.
pub(crate) fn prescribed_motion<'py, const D: usize>(
    py: Python<'py>,
    s: &Simulation<D>,
    times: Vec<f64>,
) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    let Some(motions) = s.motions() else {
        return Ok(dict);
    };
    let turned: &[usize] = if D == 2 { &[2] } else { &[0, 1, 2] };
    let samples: Vec<Vec<Option<_>>> = times.iter().map(|&t| motions.scheduled_poses(t)).collect();
    for (k, name) in s.moving_body_names().into_iter().enumerate() {
        if samples.first().is_some_and(|row| row[k].is_none()) {
            continue;
        }
        let poses: Vec<_> = samples.iter().filter_map(|row| row[k]).collect();
        let rows = |f: &dyn Fn(&Pose<D>) -> Vec<f64>| {
            let n = poses.first().map_or(0, |p| f(p).len());
            let flat: Vec<f64> = poses.iter().flat_map(f).collect();
            PyArray1::from_vec(py, flat).reshape([poses.len(), n])
        };
        let entry = PyDict::new(py);
        entry.set_item("position", rows(&|p| p.pivot.as_slice().to_vec())?)?;
        entry.set_item(
            "rotation",
            rows(&|p| turned.iter().map(|&a| p.phi[a]).collect())?,
        )?;
        entry.set_item("velocity", rows(&|p| p.velocity.as_slice().to_vec())?)?;
        let omega = |p: &Pose<D>| turned.iter().map(|&a| p.omega[a]).collect();
        entry.set_item("angular_velocity", rows(&omega)?)?;
        dict.set_item(name, entry)?;
    }
    Ok(dict)
}
