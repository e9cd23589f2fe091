//! Solver errors as Python exceptions (classes defined in `deltasph/errors.py`):
//! bad values → `ConfigError` (a `ValueError`), unknown or missing keys →
//! `ConfigKeyError` (also a `KeyError`), blow-up → `InstabilityError`, output
//! problems → `OSError`. The message is the command line's, word for word.

use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;
use sph_core::SphError;

/// Instantiates `deltasph.errors.<class>(*args)` as a raisable error.
fn raise<'py>(py: Python<'py>, class: &str, args: impl pyo3::call::PyCallArgs<'py>) -> PyErr {
    let made = py
        .import("deltasph.errors")
        .and_then(|m| m.getattr(class))
        .and_then(|c| c.call1(args));
    match made {
        Ok(value) => PyErr::from_value(value),
        Err(e) => e,
    }
}

/// A `ConfigError` with the given message.
pub fn config_error(py: Python<'_>, message: String) -> PyErr {
    raise(py, "ConfigError", (message,))
}

/// The Python exception for a solver error.
pub fn to_py(py: Python<'_>, e: SphError) -> PyErr {
    let message = e.to_string();
    match e {
        SphError::Schema { message: ref m, .. }
            if m.starts_with("unknown field") || m.starts_with("missing field") =>
        {
            raise(py, "ConfigKeyError", (message,))
        }
        SphError::CaseFile { .. } | SphError::InvalidValue { .. } | SphError::Schema { .. } => {
            config_error(py, message)
        }
        SphError::Unstable {
            time,
            step,
            particle,
            position,
            reason,
        } => raise(
            py,
            "InstabilityError",
            (message, time, step, particle, position, reason),
        ),
        SphError::Output { .. } => PyOSError::new_err(message),
    }
}
