//! `usar.run`: one trial, run as `usar run` runs it (the same builder, seed and length), its
//! result returned as the JSON of `usar run --json` (`TrialJson`), which the Python side reads
//! into a `TrialResult`. [`trial_builder`] and [`drive`] are shared with `usar.render` and
//! `usar.replay` (`crate::pictures`).

use std::cell::Cell;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use rne_core::grouping::GroupingMethod;
use usar_sim::mission::{MissionError, Simulation, StepObserver, TrialBuilder};
use usar_sim::scenario::Scenario as ScenarioData;

use usar_sweep::trial_json::TrialJson;

use crate::detached::run_detached;
use crate::errors::{TrialError, value_error};
use crate::py_method::{FirstError, MethodArg, PositionTracker, PyMethod, clear_positions};
use crate::scenario::Scenario;

/// The builder of one trial of `s` with `method` (a Python one reports its first error into
/// `first_error`), trial `trial` or, given, the seed `seed` as is, and `duration_s` (`None`:
/// the scenario's); and whether the method is a Python one (its trial then needs
/// [`PositionTracker`]).
///
/// # Errors
/// `ValueError` for a trial index with a seed, or a Python method named as a built-in
/// ([`crate::methods::python_name`]).
pub fn trial_builder<'a>(
    s: &'a ScenarioData,
    method: MethodArg,
    trial: u32,
    seed: Option<u64>,
    duration_s: Option<f64>,
    first_error: &FirstError,
) -> PyResult<(TrialBuilder<'a>, bool)> {
    if seed.is_some() && trial != 0 {
        return Err(PyValueError::new_err(
            "give trial or seed, not both (a seed is used as is and names no trial)",
        ));
    }
    let python = matches!(method, MethodArg::Python(_));
    let mut builder = Simulation::builder(s).trial(trial);
    builder = match method {
        MethodArg::Name(name) => builder.method_named(&name),
        MethodArg::Python((name, adapter)) => {
            crate::methods::python_name("method", &name)?;
            let m = PyMethod {
                name,
                adapter: Arc::new(adapter),
                trial,
                seed: seed.unwrap_or_else(|| usar_sim::mission::trial_seed(s.sim().seed, trial)),
                round: Cell::new(0),
                first_error: first_error.clone(),
                kind_names: Arc::new(s.kinds().iter().map(|k| k.name.clone()).collect()),
                stop_on_error: None,
            };
            builder.method(Box::new(m) as Box<dyn GroupingMethod>)
        }
    };
    if let Some(seed) = seed {
        builder = builder.seed(seed);
    }
    if let Some(d) = duration_s {
        builder = builder.duration_s(d);
    }
    Ok((builder, python))
}

/// Runs `sim` to its end, `observer` seeing its start and every step (and, for a Python
/// method, the position tracker too); `None` when `stop` was set first.
///
/// # Errors
/// The trial's error.
pub fn drive(
    sim: &mut Simulation,
    python: bool,
    observer: &mut dyn StepObserver,
    stop: &AtomicBool,
) -> Result<Option<()>, MissionError> {
    let mut tracker = PositionTracker;
    observer.on_start(sim);
    if python {
        tracker.on_start(sim);
    } else {
        clear_positions();
    }
    while !sim.is_finished() {
        if stop.load(Ordering::SeqCst) {
            return Ok(None);
        }
        sim.step()?;
        observer.on_step(sim);
        if python {
            tracker.on_step(sim);
        }
    }
    Ok(Some(()))
}

/// The exception of a trial's `outcome` (run by [`drive`] from [`run_detached`]): the Python
/// method's first error, `KeyboardInterrupt` when stopped, `ValueError` for a bad method or
/// length, `TrialError` for another failure.
pub fn trial_outcome<T>(
    outcome: Result<Option<T>, MissionError>,
    first_error: &FirstError,
) -> PyResult<T> {
    if let Some(e) = first_error.lock().ok().and_then(|mut e| e.take()) {
        return Err(e);
    }
    match outcome {
        Ok(Some(value)) => Ok(value),
        Ok(None) => Err(pyo3::exceptions::PyKeyboardInterrupt::new_err("")),
        Err(e @ MissionError::Method(_)) => Err(value_error(e)),
        // The length is the keyword argument `duration_s`.
        Err(MissionError::Duration(reason)) => Err(value_error(format!("duration_s: {reason}"))),
        Err(e) => Err(TrialError::new_err(crate::errors::one_line(&e.to_string()))),
    }
}

/// Runs one trial; returns `usar run --json`'s JSON text.
///
/// # Errors
/// `ValueError` for an unknown method or a bad length; the Python method's own exception or a
/// `GroupingError` for its bad answer; `TrialError` for another failure; `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (scenario, method, trial = 0, duration_s = None, seed = None))]
pub fn run_trial(
    py: Python<'_>,
    scenario: &Scenario,
    method: MethodArg,
    trial: u32,
    duration_s: Option<f64>,
    seed: Option<u64>,
) -> PyResult<String> {
    run_observed(
        py,
        scenario,
        method,
        trial,
        duration_s,
        seed,
        &mut |_: &Simulation| {},
    )
}

/// [`run_trial`] with `observer` called on the trial's start and after every step (from the
/// trial's thread: `Send`). Returns `usar run --json`'s JSON text.
///
/// # Errors
/// As [`run_trial`].
pub(crate) fn run_observed(
    py: Python<'_>,
    scenario: &Scenario,
    method: MethodArg,
    trial: u32,
    duration_s: Option<f64>,
    seed: Option<u64>,
    observer: &mut (dyn StepObserver + Send),
) -> PyResult<String> {
    let first_error = FirstError::default();
    let (builder, python) = trial_builder(
        scenario.inner(),
        method,
        trial,
        seed,
        duration_s,
        &first_error,
    )?;
    let stop = Arc::new(AtomicBool::new(false));
    let work = || -> Result<Option<String>, MissionError> {
        let mut sim = builder.build()?;
        let Some(()) = drive(&mut sim, python, observer, &stop)? else {
            return Ok(None);
        };
        let json = serde_json::to_string(&TrialJson::of(&sim.result()));
        Ok(Some(json.unwrap_or_default()))
    };
    let outcome = run_detached(py, &stop, work, |_| Ok(()))?;
    trial_outcome(outcome, &first_error)
}
