//! A scenario's values as Python data and back: the JSON form of a spec (`usar_sweep::vary`'s,
//! the form field paths walk) through Python's `json` module, and the values a field path
//! names (`Scenario.get`).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyFloat, PyList, PyString, PyTuple};
use serde_json::Value;

use usar_sweep::vary::{FieldPath, Step};

/// `value` as Python data (dicts, lists, str, int, float, bool, None), through `json.loads`.
///
/// # Errors
/// Not expected: a JSON value always has a Python form.
pub fn to_python<'py>(py: Python<'py>, value: &Value) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value).map_err(|e| PyValueError::new_err(e.to_string()))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// Python data as JSON, through `json.dumps` (`allow_nan=False`: a NaN or infinity is an
/// error, as in a scenario file; numpy scalars and arrays as their Python values). `root`
/// names `data` in that error, which points at the number: `claims[0].alpha: expected a
/// finite number, found NaN` (`root` empty: the path alone, `mission.duration_s: ...`).
///
/// # Errors
/// `TypeError` for a value with no JSON form (an object), `ValueError` for a NaN or infinity
/// (naming where it is) or a circular reference.
pub fn from_python(data: &Bound<'_, PyAny>, root: &str) -> PyResult<Value> {
    let py = data.py();
    let kwargs = PyDict::new(py);
    kwargs.set_item("allow_nan", false)?;
    // numpy scalars and arrays (a DataFrame's int64) as their Python values.
    let plain = py.eval(
        c"lambda o: o.tolist() if hasattr(o, 'tolist') else (_ for _ in ()).throw(TypeError(f'{type(o).__name__} has no JSON form'))",
        None,
        None,
    )?;
    kwargs.set_item("default", plain)?;
    let text: String = match py
        .import("json")?
        .call_method("dumps", (data,), Some(&kwargs))
    {
        Ok(text) => text.extract()?,
        Err(e) if e.is_instance_of::<PyValueError>(py) => {
            return Err(match non_finite(data, root.to_string(), 0)? {
                Some((path, x)) => {
                    PyValueError::new_err(format!("{path}: expected a finite number, found {x}"))
                }
                None => e,
            });
        }
        Err(e) => return Err(e),
    };
    serde_json::from_str(&text).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// Deepest nesting [`non_finite`] looks into (a circular list is no JSON either).
const MAX_DEPTH: usize = 128;

/// The path (`path`, then `.key` and `[i]` steps) and value of the first NaN or infinity in
/// `data`, looking into dicts, lists, tuples and numpy values as `json.dumps` does.
fn non_finite(
    data: &Bound<'_, PyAny>,
    path: String,
    depth: usize,
) -> PyResult<Option<(String, f64)>> {
    if depth > MAX_DEPTH || data.is_instance_of::<PyString>() {
        return Ok(None);
    }
    if data.is_instance_of::<PyFloat>() {
        let x: f64 = data.extract()?;
        return Ok((!x.is_finite()).then_some((path, x)));
    }
    let step = |p: &str, s: String| if p.is_empty() { s } else { format!("{p}.{s}") };
    if let Ok(d) = data.cast::<PyDict>() {
        for (k, v) in d.iter() {
            if let Some(found) = non_finite(&v, step(&path, k.str()?.to_string()), depth + 1)? {
                return Ok(Some(found));
            }
        }
        return Ok(None);
    }
    if data.is_instance_of::<PyList>() || data.is_instance_of::<PyTuple>() {
        for (i, v) in data.try_iter()?.enumerate() {
            if let Some(found) = non_finite(&v?, format!("{path}[{i}]"), depth + 1)? {
                return Ok(Some(found));
            }
        }
        return Ok(None);
    }
    if data.hasattr("tolist")? {
        return non_finite(&data.call_method0("tolist")?, path, depth + 1);
    }
    Ok(None)
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
