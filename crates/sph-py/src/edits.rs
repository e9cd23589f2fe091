//! State set from Python: velocities and densities, checked row by row (walls keep the
//! motion the case prescribes, densities stay positive).

use crate::arrays;
use crate::simulation::rows;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use sph_core::{Kind, Simulation};

pub(crate) fn set_velocities<const D: usize>(
    s: &mut Simulation<D>,
    velocities: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let u = arrays::read_vectors::<D>(velocities, "velocities", &s.particles().id, rows(s))?;
    let p = s.particles();
    let changed_wall = (0..u.len()).find(|&k| p.kind[k] == Kind::Wall && u[k] != p.u[k]);
    if let Some(k) = changed_wall {
        return Err(PyValueError::new_err(format!(
            "velocities: row {} = {:?} is a wall particle, expected its velocity {:?} \
             (walls move as the case prescribes: a lid at tank.lid_velocity, else at rest)",
            p.id[k],
            u[k].as_slice(),
            p.u[k].as_slice()
        )));
    }
    s.edit(|p| p.u = u);
    Ok(())
}

pub(crate) fn set_density<const D: usize>(
    s: &mut Simulation<D>,
    density: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let rho = arrays::read_scalars(density, "density", &s.particles().id, rows(s))?;
    if let Some(k) = rho.iter().position(|&r| r <= 0.0) {
        return Err(PyValueError::new_err(format!(
            "density: row {} = {}, expected a positive density",
            s.particles().id[k],
            rho[k]
        )));
    }
    s.edit(|p| p.rho = rho);
    Ok(())
}
