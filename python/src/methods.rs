//! The grouping methods and claims a run is given from Python: built-in names beside Python
//! methods (their factory and the position tracker their trials need), and claims as a list
//! of dicts. Shared by `usar.sweep`, `usar.grid`, `usar.calibrate` and `usar.multiverse`.

use std::cell::Cell;
use std::collections::HashMap;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rne_core::grouping::{GroupingMethod, builtin_name};

use usar_report::claims::{Claim, Claims};
use usar_sweep::sweep::{MethodFactory, TrialObserverFactory};

use crate::errors::value_error;
use crate::py_method::{FirstError, MethodArg, PositionTracker, PyMethod, clear_positions};

/// The Python methods of a sweep by name.
pub type PyMethods = HashMap<String, Arc<Py<PyAny>>>;

/// The sweep's methods: names for `SweepConfig::methods` and the Python ones by name.
pub fn methods_of(methods: Vec<MethodArg>) -> PyResult<(Vec<String>, PyMethods)> {
    let mut names = Vec::new();
    let mut python = PyMethods::new();
    for m in methods {
        match m {
            MethodArg::Name(n) => names.push(n),
            MethodArg::Python((n, adapter)) => {
                python_name("methods", &n)?;
                if python.insert(n.clone(), Arc::new(adapter)).is_some() {
                    return Err(PyValueError::new_err(format!(
                        "methods: two Python methods are named {n:?}"
                    )));
                }
                names.push(n);
            }
        }
    }
    Ok((names, python))
}

/// Refuses a Python method named as a built-in (by [`rne_core::grouping::method_key`]:
/// `rne`, `RNE`, `hp-dis`, ...), whose results would read as the built-in's; `argument`
/// names the keyword argument (`method`, `methods`). The package's own functions of the
/// built-ins (`usar.rne`, ...) are passed as names by the Python side and never come here.
///
/// # Errors
/// `ValueError`, one line: `methods: a Python method may not be named "rne", a built-in's
/// name: rename it, or give "rne" for the built-in`.
pub fn python_name(argument: &str, name: &str) -> PyResult<()> {
    match builtin_name(name) {
        Some(_) => Err(PyValueError::new_err(format!(
            "{argument}: a Python method may not be named {name:?}, a built-in's name: rename \
             it, or give {name:?} for the built-in"
        ))),
        None => Ok(()),
    }
}

/// The factory: Python methods by name (`kinds`: the scenario's kind names, for their
/// errors; `stop_on_error`: set at a Python method's first failure, see
/// [`PyMethod::stop_on_error`]), the built-ins otherwise.
pub fn factory(
    python: &PyMethods,
    first_error: &FirstError,
    kinds: Vec<String>,
    stop_on_error: Option<Arc<AtomicBool>>,
) -> MethodFactory {
    let (python, first_error) = (python.clone(), first_error.clone());
    let kind_names = Arc::new(kinds);
    MethodFactory::new(move |name, model, ctx| match python.get(name) {
        Some(adapter) => Ok(Box::new(PyMethod {
            name: name.to_string(),
            adapter: adapter.clone(),
            trial: ctx.trial,
            seed: ctx.seed,
            round: Cell::new(0),
            first_error: first_error.clone(),
            kind_names: kind_names.clone(),
            stop_on_error: stop_on_error.clone(),
        }) as Box<dyn GroupingMethod>),
        None => MethodFactory::builtin().build(name, model, ctx),
    })
}

/// A position tracker for the trials of Python methods (by display name).
pub fn tracker(python: &PyMethods) -> TrialObserverFactory {
    let names: Vec<String> = python.keys().cloned().collect();
    Arc::new(move |key| {
        if names.contains(&key.method) {
            Some(Box::new(PositionTracker) as Box<dyn usar_sim::mission::StepObserver>)
        } else {
            clear_positions();
            None
        }
    })
}

/// Claims given as Python objects: a list of dicts with a claims file's fields (`id`,
/// `sentence`, `subject`, `metric`, `direction` `"More"` or `"Less"`, and optionally
/// `rivals` `"Every"` or `{"Only": [...]}`, `test`, `alpha`, `correction`), checked as a
/// claims file is, against the scenario's `tasks` and the run's `methods`.
///
/// # Errors
/// `ValueError` naming the claim and field that is wrong.
pub fn claims_of(
    list: &Bound<'_, PyAny>,
    tasks: &[String],
    methods: &[String],
) -> PyResult<Claims> {
    let json = crate::json_value::from_python(list, "claims")?;
    let serde_json::Value::Array(items) = json else {
        return Err(PyValueError::new_err(
            "claims: expected a claims file's path or a list of claims (dicts)",
        ));
    };
    let claims = items
        .into_iter()
        .enumerate()
        .map(|(i, item)| {
            serde_json::from_value::<Claim>(item)
                .map_err(|e| PyValueError::new_err(format!("claims[{i}]: {e}")))
        })
        .collect::<PyResult<Vec<Claim>>>()?;
    let c = Claims::new(claims, "claims").map_err(value_error)?;
    c.check_tasks(tasks).map_err(value_error)?;
    c.check_methods(methods).map_err(value_error)?;
    Ok(c)
}
