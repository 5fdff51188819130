//! A Python value as the RON text of a `--set`/`--vary` value: `True` -> `true`, `None` ->
//! `None`, an int or float as written in RON (floats in their shortest round-trip form), a
//! tuple -> `(a, b)`, a list -> `[a, b]`, a numpy scalar or array as its Python value
//! (`tolist()`); a `str` is taken as RON text itself (`"Some(3)"`,
//! `"Grid(spacing_m: 2.0)"`). A `str` set on a field that holds text is quoted before it
//! gets here (`Scenario.set`, `src/scenario.rs`).

use pyo3::prelude::*;
use pyo3::types::{PyBool, PyFloat, PyInt, PyList, PyString, PyTuple};

/// Nesting depth of tuples and lists a value may have.
const MAX_DEPTH: usize = 16;

/// The RON text of `value` (see the module doc).
///
/// # Errors
/// The message for a float that is not finite, a value nested deeper than 16 levels or a
/// type with no RON form (a dict, an object).
pub fn ron_text(value: &Bound<'_, PyAny>) -> Result<String, String> {
    ron_at(value, 0)
}

fn ron_at(value: &Bound<'_, PyAny>, depth: usize) -> Result<String, String> {
    let py_err = |e: PyErr| e.to_string();
    if depth > MAX_DEPTH {
        return Err(format!("a value nested deeper than {MAX_DEPTH} levels"));
    }
    if value.is_none() {
        return Ok("None".into());
    }
    if let Ok(b) = value.cast::<PyBool>() {
        return Ok(if b.is_true() { "true" } else { "false" }.into());
    }
    if value.is_instance_of::<PyInt>() {
        return Ok(value.str().map_err(py_err)?.to_string());
    }
    if value.is_instance_of::<PyFloat>() {
        let x: f64 = value.extract().map_err(py_err)?;
        if !x.is_finite() {
            return Err(format!("expected a finite number, found {x}"));
        }
        // `{:?}` is the shortest text that reads back as the same f64, with a decimal point.
        return Ok(format!("{x:?}"));
    }
    if let Ok(s) = value.cast::<PyString>() {
        return s.extract::<String>().map_err(py_err);
    }
    if is_numpy(value) && value.hasattr("tolist").map_err(py_err)? {
        // A numpy scalar (np.float32(1.5), np.int64(3), np.bool_) or array: its Python value
        // (a float, int, bool or nested list).
        let plain = value.call_method0("tolist").map_err(py_err)?;
        return ron_at(&plain, depth + 1);
    }
    let items = |seq: Vec<Bound<'_, PyAny>>| -> Result<String, String> {
        let parts = seq
            .iter()
            .map(|v| ron_at(v, depth + 1))
            .collect::<Result<Vec<_>, String>>()?;
        Ok(parts.join(", "))
    };
    if let Ok(t) = value.cast::<PyTuple>() {
        return Ok(format!("({})", items(t.iter().collect())?));
    }
    if let Ok(l) = value.cast::<PyList>() {
        return Ok(format!("[{}]", items(l.iter().collect())?));
    }
    let type_name = value.get_type().name().map_err(py_err)?;
    Err(format!(
        "no RON form for a value of type {type_name} (use a number, bool, None, str of RON, tuple or \
         list)"
    ))
}

/// Whether `value`'s type comes from numpy (its module is `numpy`), without importing numpy.
fn is_numpy(value: &Bound<'_, PyAny>) -> bool {
    value
        .get_type()
        .module()
        .is_ok_and(|m| m.extract::<String>().is_ok_and(|m| m == "numpy"))
}
