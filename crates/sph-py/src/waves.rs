//! Regular-wave theory for checking a flume: the numbers the wave maker is built from.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use sph_core::waves::theory::{
    bound_second_harmonic, madsen_second_order_stroke, wavenumber, Paddle,
};

/// Linear and second-order theory of regular waves of ``height`` [m] and ``period``
/// [s] in water ``depth`` [m] deep (docs/theory.md §14): ``{"wavenumber",
/// "wavelength", "kd", "bound_second_harmonic"`` (Stokes's A₂ [m])``,
/// "piston_stroke"`` (S [m] by Biesel's transfer)``, "flap_stroke"`` (S at the
/// still level of a flap hinged ``hinge_height`` above the bed)``,
/// "madsen_second_order"`` (the amplitude [m] of a piston's 2ω motion)``}``.
#[pyfunction]
#[pyo3(signature = (height, period, depth, gravity=9.81, hinge_height=0.0))]
pub fn regular_wave<'py>(
    py: Python<'py>,
    height: f64,
    period: f64,
    depth: f64,
    gravity: f64,
    hinge_height: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let positive = [height, period, depth, gravity]
        .iter()
        .all(|v| v.is_finite() && *v > 0.0);
    if !positive || !hinge_height.is_finite() || hinge_height >= depth {
        return Err(PyValueError::new_err(format!(
            "height = {height}, period = {period}, depth = {depth}, gravity = {gravity}, \
             hinge_height = {hinge_height}: expected positive numbers and a hinge below \
             the still level"
        )));
    }
    let k = wavenumber(2.0 * std::f64::consts::PI / period, depth, gravity);
    let flap = Paddle::Flap {
        hinge: hinge_height,
    };
    let d = PyDict::new(py);
    d.set_item("wavenumber", k)?;
    d.set_item("wavelength", 2.0 * std::f64::consts::PI / k)?;
    d.set_item("kd", k * depth)?;
    d.set_item(
        "bound_second_harmonic",
        bound_second_harmonic(height, k, depth),
    )?;
    d.set_item(
        "piston_stroke",
        height / Paddle::Piston.height_over_stroke(k, depth),
    )?;
    d.set_item("flap_stroke", height / flap.height_over_stroke(k, depth))?;
    d.set_item(
        "madsen_second_order",
        madsen_second_order_stroke(height, k, depth),
    )?;
    Ok(d)
}
