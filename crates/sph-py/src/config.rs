//! A Python dict with the keys of the TOML case file becomes a TOML table, so that
//! it goes through exactly the parser and validator of the command line (same
//! checks, same messages). Lists, tuples and numpy arrays become TOML arrays.

use crate::errors::config_error;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// Converts a config dict; `path` names the table for error messages ("" at the top).
pub fn table(dict: &Bound<'_, PyDict>, path: &str) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (key, value) in dict.iter() {
        let Ok(key) = key.cast::<PyString>() else {
            return Err(config_error(
                dict.py(),
                format!(
                    "{} = {}: expected string keys",
                    display_path(path),
                    key.repr()?
                ),
            ));
        };
        let key = key.to_cow()?.into_owned();
        let inner = join(path, &key);
        table.insert(key, to_toml(&value, &inner)?);
    }
    Ok(table)
}

fn to_toml(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    use toml::Value;
    if let Ok(b) = obj.cast::<PyBool>() {
        return Ok(Value::Boolean(b.is_true()));
    }
    if obj.is_instance_of::<PyInt>() {
        return Ok(Value::Integer(obj.extract()?));
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(Value::Float(obj.extract()?));
    }
    if let Ok(s) = obj.cast::<PyString>() {
        return Ok(Value::String(s.to_cow()?.into_owned()));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        return Ok(Value::Table(table(d, path)?));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let items: PyResult<Vec<Value>> = obj
            .try_iter()?
            .enumerate()
            .map(|(k, item)| to_toml(&item?, &format!("{path}[{k}]")))
            .collect();
        return Ok(Value::Array(items?));
    }
    // numpy arrays and scalars (float64, int64, bool_): their Python equivalents.
    if obj.hasattr("tolist")? {
        let plain = obj.call_method0("tolist")?;
        if !plain.is(obj) {
            return to_toml(&plain, path);
        }
    }
    Err(config_error(
        obj.py(),
        format!(
            "{path} = {}: expected a number, string, bool, list or dict",
            obj.repr()?
        ),
    ))
}

fn join(path: &str, key: &str) -> String {
    if path.is_empty() {
        key.to_string()
    } else {
        format!("{path}.{key}")
    }
}

fn display_path(path: &str) -> &str {
    if path.is_empty() {
        "config"
    } else {
        path
    }
}
