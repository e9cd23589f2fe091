//! Particle state as numpy arrays in particle-id order. The solver reorders its
//! arrays by cell whenever it rebuilds the neighbour lists; row `i` of every array
//! handed to Python is always the particle with id `i`, so arrays from different
//! steps line up. There is a row for every id ever given: a particle that left the
//! domain keeps its row, filled with NaN (kind 255). Arrays going out are fresh
//! copies; arrays coming in are checked for type, dtype, shape and finiteness (of the
//! rows of particles still in the run) before anything is touched.

use numpy::ndarray::{Array1, Array2, ArrayView1, ArrayView2};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use sph_core::Vector;

/// `(rows, D)` float64 copy of per-particle vectors, row = id, NaN for removed ids.
pub fn vectors<'py, const D: usize>(
    py: Python<'py>,
    ids: &[u32],
    rows: usize,
    v: &[Vector<D>],
) -> Bound<'py, PyArray2<f64>> {
    let mut out = Array2::<f64>::from_elem((rows, D), f64::NAN);
    for (k, &id) in ids.iter().enumerate() {
        for d in 0..D {
            out[(id as usize, d)] = v[k][d];
        }
    }
    out.into_pyarray(py)
}

/// `(rows,)` copy of a per-particle scalar, row = id, `fill` for removed ids.
pub fn scalars<'py, T: numpy::Element + Copy, S: Copy>(
    py: Python<'py>,
    ids: &[u32],
    rows: usize,
    v: &[S],
    (fill, map): (T, impl Fn(S) -> T),
) -> Bound<'py, PyArray1<T>> {
    let mut out = Array1::<T>::from_elem(rows, fill);
    for (k, &id) in ids.iter().enumerate() {
        out[id as usize] = map(v[k]);
    }
    out.into_pyarray(py)
}

/// Checks that `obj` is a float64 ndarray of exactly `shape`: `TypeError` for a
/// non-array or another dtype, `ValueError` for another shape.
pub fn checked<'py>(obj: &Bound<'py, PyAny>, name: &str, shape: &[usize]) -> PyResult<()> {
    let py = obj.py();
    let expected = format!("{shape:?}").replace('[', "(").replace(']', ")");
    let Ok(array) = obj.cast::<PyUntypedArray>() else {
        return Err(PyTypeError::new_err(format!(
            "{name}: got {}, expected a numpy.ndarray of float64 with shape {expected}",
            obj.get_type().name()?
        )));
    };
    if !array.dtype().is_equiv_to(&numpy::dtype::<f64>(py)) {
        return Err(PyTypeError::new_err(format!(
            "{name}: dtype {}, expected float64 (convert with arr.astype(numpy.float64))",
            array.dtype()
        )));
    }
    if array.shape() != shape {
        let got = format!("{:?}", array.shape())
            .replace('[', "(")
            .replace(']', ")");
        return Err(PyValueError::new_err(format!(
            "{name}: shape {got}, expected {expected}"
        )));
    }
    Ok(())
}

/// Reads a checked `(N, D)` float64 array into per-particle vectors in the solver's
/// current order, refusing non-finite entries.
pub fn read_vectors<const D: usize>(
    obj: &Bound<'_, PyAny>,
    name: &str,
    ids: &[u32],
    rows: usize,
) -> PyResult<Vec<Vector<D>>> {
    checked(obj, name, &[rows, D])?;
    let array = obj.cast::<PyArray2<f64>>()?.readonly();
    let view: ArrayView2<f64> = array.as_array();
    let bad = ids
        .iter()
        .find(|&&id| (0..D).any(|d| !view[(id as usize, d)].is_finite()));
    if let Some(row) = bad {
        return Err(PyValueError::new_err(format!(
            "{name}: row {row} holds a non-finite value"
        )));
    }
    Ok(ids
        .iter()
        .map(|&id| Vector::<D>::from_fn(|d, _| view[(id as usize, d)]))
        .collect())
}

/// Reads a checked `(N,)` float64 array into the solver's current order.
pub fn read_scalars(
    obj: &Bound<'_, PyAny>,
    name: &str,
    ids: &[u32],
    rows: usize,
) -> PyResult<Vec<f64>> {
    checked(obj, name, &[rows])?;
    let array = obj.cast::<PyArray1<f64>>()?.readonly();
    let view: ArrayView1<f64> = array.as_array();
    if let Some(row) = ids.iter().find(|&&id| !view[id as usize].is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{name}: row {row} holds a non-finite value"
        )));
    }
    Ok(ids.iter().map(|&id| view[id as usize]).collect())
}

/// Points to probe: array-like `(M, D)`, or one point `(D,)`; as vectors.
pub fn points<const D: usize>(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Vector<D>>> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let array = np
        .call_method1("asarray", (obj, "float64"))
        .map_err(|e| PyValueError::new_err(format!("points: not an array of numbers ({e})")))?;
    let array = if array.getattr("ndim")?.extract::<usize>()? == 1 {
        array.call_method1("reshape", (1, -1))?
    } else {
        array
    };
    let Ok(array) = array.cast::<PyArray2<f64>>() else {
        return Err(PyValueError::new_err(format!(
            "points: shape {}, expected (M, {D}) or ({D},)",
            array.getattr("shape")?
        )));
    };
    let view = array.readonly();
    let view = view.as_array();
    if view.ncols() != D {
        return Err(PyValueError::new_err(format!(
            "points: shape ({}, {}), expected (M, {D}) or ({D},)",
            view.nrows(),
            view.ncols()
        )));
    }
    Ok(view
        .rows()
        .into_iter()
        .map(|row| Vector::<D>::from_fn(|d, _| row[d]))
        .collect())
}
