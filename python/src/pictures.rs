//! `usar.render` and `usar.replay`: the picture of `usar render` and the page of `usar
//! replay`, written by the same library code (`usar_report::render`, `usar_report::replay`),
//! for a built-in or a Python grouping method.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use pyo3::prelude::*;
use usar_sim::mission::{MissionError, Simulation};

use usar_report::render::{PathRecorder, render_svg};
use usar_report::replay::{ReplayRecorder, SampleClock, default_hz, write_replay};

use crate::detached::run_detached;
use crate::errors::{chain_value_error, value_error};
use crate::py_method::{FirstError, MethodArg};
use crate::run::{drive, trial_builder, trial_outcome};
use crate::scenario::Scenario;

/// Writes `usar render`'s SVG picture of `scenario` to `out`: the arena with the robots at
/// their starts, or, given a `method`, with every robot's path in its trial `trial` (or the
/// trial of `seed`) over `duration_s` (default the scenario's). Returns the number of samples
/// per robot (0 without a trial).
///
/// # Errors
/// `ValueError` for a bad method, length or output path; the Python method's exception,
/// `GroupingError` or `TrialError` for a failing trial; `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (scenario, out, method = None, trial = 0, duration_s = None, seed = None))]
pub fn render(
    py: Python<'_>,
    scenario: &Scenario,
    out: PathBuf,
    method: Option<MethodArg>,
    trial: u32,
    duration_s: Option<f64>,
    seed: Option<u64>,
) -> PyResult<usize> {
    let s = scenario.inner();
    let Some(method) = method else {
        render_svg(s, None, &out).map_err(|e| chain_value_error(&e))?;
        return Ok(0);
    };
    let first_error = FirstError::default();
    let (builder, python) = trial_builder(s, method, trial, seed, duration_s, &first_error)?;
    let stop = Arc::new(AtomicBool::new(false));
    let work = || -> Result<Option<PathRecorder>, MissionError> {
        let mut sim = builder.build()?;
        let mut recorder = PathRecorder::new();
        Ok(drive(&mut sim, python, &mut recorder, &stop)?.map(|()| recorder))
    };
    let outcome = run_detached(py, &stop, work, |_| Ok(()))?;
    let traces = trial_outcome(outcome, &first_error)?.into_traces();
    render_svg(s, Some(&traces), &out).map_err(|e| chain_value_error(&e))?;
    Ok(traces.first().map_or(0, Vec::len))
}

/// Writes `usar replay`'s HTML page of one trial of `scenario` with `method` (trial `trial`,
/// or the trial of `seed`, over `duration_s`, sampled at `hz` samples per simulated second,
/// default as `usar replay`'s) to `out`. Returns the JSON of the trial's result (as
/// `usar.run`'s) and the page's size in bytes.
///
/// # Errors
/// `ValueError` for a bad method, length, `hz` or output path; the Python method's exception,
/// `GroupingError` or `TrialError` for a failing trial; `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (scenario, out, method, trial = 0, duration_s = None, seed = None, hz = None))]
#[allow(clippy::too_many_arguments)]
pub fn replay(
    py: Python<'_>,
    scenario: &Scenario,
    out: PathBuf,
    method: MethodArg,
    trial: u32,
    duration_s: Option<f64>,
    seed: Option<u64>,
    hz: Option<f64>,
) -> PyResult<(String, u64)> {
    let s = scenario.inner();
    let first_error = FirstError::default();
    let (builder, python) = trial_builder(s, method, trial, seed, duration_s, &first_error)?;
    let sim = builder.build().map_err(value_error)?;
    let dt_s = s.sim().dt_s.get();
    let hz = hz.unwrap_or_else(|| default_hz(s.robots().len(), sim.progress().1, dt_s));
    SampleClock::new(hz, dt_s, sim.progress().1).map_err(|e| value_error(format!("hz: {e}")))?;
    let recorder = ReplayRecorder::new(hz).map_err(|e| value_error(format!("hz: {e}")))?;
    let stop = Arc::new(AtomicBool::new(false));
    let watched = stop.clone();
    let work = move || -> Result<Option<(Simulation, ReplayRecorder)>, MissionError> {
        let (mut sim, mut recorder) = (sim, recorder);
        Ok(drive(&mut sim, python, &mut recorder, &watched)?.map(|()| (sim, recorder)))
    };
    let outcome = run_detached(py, &stop, work, |_| Ok(()))?;
    let (sim, mut recorder) = trial_outcome(outcome, &first_error)?;
    let rec = recorder
        .take()
        .ok_or_else(|| value_error("the trial recorded nothing"))?;
    let bytes = write_replay(s, &rec, &out).map_err(|e| chain_value_error(&e))?;
    let result = usar_sweep::trial_json::TrialJson::of(&sim.result());
    let json = serde_json::to_string(&result).map_err(value_error)?;
    Ok((json, bytes))
}
