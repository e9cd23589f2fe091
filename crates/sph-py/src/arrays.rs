//! Particle state as numpy arrays in particle-id order. The solver reorders its
//! arrays by cell whenever it rebuilds the neighbour lists; row `i` of every array
//! handed to Python is always the particle with id `i`, so arrays from different
//! steps line up. Arrays going out are fresh copies; arrays coming in are checked
//! for type, dtype, shape and finiteness before anything is touched.

use numpy::ndarray::{Array1, Array2, ArrayView1, ArrayView2};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArrayDescrMethods, PyArrayMethods, PyUntypedArray,
    PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use sph_core::Vector;

/// `(N, D)` float64 copy of per-particle vectors, row = id.
pub fn vectors<'py, const D: usize>(
    py: Python<'py>,
    ids: &[u32],
    v: &[Vector<D>],
) -> Bound<'py, PyArray2<f64>> {
    let mut out = Array2::<f64>::zeros((v.len(), D));
    for (k, &id) in ids.iter().enumerate() {
        for d in 0..D {
            out[(id as usize, d)] = v[k][d];
        }
    }
    out.into_pyarray(py)
}

/// `(N,)` copy of a per-particle scalar, row = id.
pub fn scalars<'py, T: numpy::Element + Copy + Default, S: Copy>(
    py: Python<'py>,
    ids: &[u32],
    v: &[S],
    map: impl Fn(S) -> T,
) -> Bound<'py, PyArray1<T>> {
    let mut out = Array1::<T>::from_elem(v.len(), T::default());
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
) -> PyResult<Vec<Vector<D>>> {
    checked(obj, name, &[ids.len(), D])?;
    let array = obj.cast::<PyArray2<f64>>()?.readonly();
    let view: ArrayView2<f64> = array.as_array();
    if let Some((row, _)) = view.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{name}: row {} holds a non-finite value",
            row.0
        )));
    }
    Ok(ids
        .iter()
        .map(|&id| Vector::<D>::from_fn(|d, _| view[(id as usize, d)]))
        .collect())
}

/// Reads a checked `(N,)` float64 array into the solver's current order.
pub fn read_scalars(obj: &Bound<'_, PyAny>, name: &str, ids: &[u32]) -> PyResult<Vec<f64>> {
    checked(obj, name, &[ids.len()])?;
    let array = obj.cast::<PyArray1<f64>>()?.readonly();
    let view: ArrayView1<f64> = array.as_array();
    if let Some((row, _)) = view.indexed_iter().find(|(_, v)| !v.is_finite()) {
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
