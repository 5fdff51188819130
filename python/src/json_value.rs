//! A scenario's values as Python data and back: the JSON form of a spec (`usar_sweep::vary`'s,
//! the form field paths walk) through Python's `json` module, and the values a field path
//! names (`Scenario.get`).

use pyo3::prelude::*;
use serde_json::Value;

use usar_sweep::vary::{FieldPath, Step};

/// `value` as Python data (dicts, lists, str, int, float, bool, None), through `json.loads`.
///
/// # Errors
/// Not expected: a JSON value always has a Python form.
pub fn to_python<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// Python data as JSON, through `json.dumps` (`allow_nan=False`: a NaN or infinity is an
/// error, as in a scenario file; numpy scalars and arrays as their Python values).
///
/// # Errors
/// `TypeError` for a value with no JSON form (an object), `ValueError` for a NaN.
pub fn from_python(data: &Bound<'_, PyAny>) -> PyResult<Value> {
    let py = data.py();
    let kwargs = pyo3::types::PyDict::new(py);
    kwargs.set_item("allow_nan", false)?;
    // numpy scalars and arrays (a DataFrame's int64) as their Python values.
    let plain = py.eval(
        c"lambda o: o.tolist() if hasattr(o, 'tolist') else (_ for _ in ()).throw(TypeError(f'{type(o).__name__} has no JSON form'))",
        None,
        None,
    )?;
    kwargs.set_item("default", plain)?;
    let text: String = py
        .import("json")?
        .call_method("dumps", (data,), Some(&kwargs))?
        .extract()?;
    serde_json::from_str(&text).map_err(|e| pyo3::exceptions::PyValueError::new_err(e.to_string()))
}

/// The value(s) `path` names in `root` (a spec's JSON form): one value, or with a `[*]` step
/// the list of every element's.
///
/// # Errors
/// The path's own message: a field the struct does not have (with the fields it has), an
/// index out of range, `[*]` over an empty list.
pub fn values_at(root: &Value, path: &FieldPath) -> Result<Value, String> {
    let mut copy = root.clone();
    let mut found = Vec::new();
    path.set(&mut copy, &mut |v| {
        found.push(v.clone());
        Ok(v.clone())
    })?;
    if path.steps().iter().any(|s| matches!(s, Step::All)) {
        Ok(Value::Array(found))
    } else {
        Ok(found.pop().unwrap_or(Value::Null))
    }
}
