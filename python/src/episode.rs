//! `usar.gym`'s pictures without a replay: a [`PathLog`] records every robot's path while the
//! episode's trial runs ([`run_trial_logged`], `usar.run`'s trial with the log as a step
//! observer), and [`episode_svg`] draws `usar render`'s picture from it at any round, at the
//! cost of one picture whatever the round.
//!
//! The log samples as `usar render --trace` does (`usar_report::render::PathRecorder`: the
//! start, every [`TRACE_SAMPLE_S`] of simulated time, the trial's last step) and keeps the
//! positions after the last step too: while the trial waits for a round's groups, the picture
//! ends where the robots stand at that round's start, as a trial run to that time ends.

use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use pyo3::prelude::*;
use usar_report::render::{TRACE_SAMPLE_S, Trace, render_svg_string};
use usar_sim::mission::{Simulation, StepObserver};
use usar_sim::scenario::PointM;

use crate::errors::chain_value_error;
use crate::py_method::MethodArg;
use crate::run::run_observed;
use crate::scenario::Scenario;

/// The paths of one trial so far.
#[derive(Debug, Default)]
struct Paths {
    /// Steps between two samples (set at the first sample).
    every_steps: u64,
    /// Every robot's sampled path, by id (empty before the trial starts).
    traces: Vec<Trace>,
    /// Every robot's position after the last step seen, by id.
    latest: Vec<PointM>,
    /// Whether that step was sampled (its positions end `traces`).
    latest_sampled: bool,
}

impl Paths {
    fn sample(&mut self, sim: &Simulation) {
        let robots = sim.world().robots();
        if self.traces.is_empty() {
            let dt_s = sim.scenario().sim().dt_s.get();
            self.every_steps = ((TRACE_SAMPLE_S / dt_s).round() as u64).max(1);
            self.traces = vec![Vec::new(); robots.len()];
        }
        for (t, r) in self.traces.iter_mut().zip(robots) {
            t.push(r.position);
        }
        self.latest_sampled = true;
    }

    /// The paths to the last step seen (its positions added when they were not sampled).
    fn so_far(&self) -> Vec<Trace> {
        let mut traces = self.traces.clone();
        if !self.latest_sampled {
            for (t, p) in traces.iter_mut().zip(&self.latest) {
                t.push(*p);
            }
        }
        traces
    }
}

/// Every robot's path so far in one trial, filled by [`run_trial_logged`] from the trial's
/// thread and read by [`episode_svg`] from any thread (a lock per step; the picture is drawn
/// while the trial waits for a round's groups). `len(log)`: samples per robot so far (0
/// before the trial starts). Not picklable: `usar.gym` makes a new one per trial.
#[pyclass(frozen, module = "usar._usar")]
#[derive(Debug, Default)]
pub struct PathLog {
    paths: Arc<Mutex<Paths>>,
}

impl PathLog {
    fn lock(&self) -> MutexGuard<'_, Paths> {
        self.paths.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

#[pymethods]
impl PathLog {
    /// An empty log.
    #[new]
    fn new() -> Self {
        Self::default()
    }

    fn __len__(&self) -> usize {
        let p = self.lock();
        p.traces
            .first()
            .map_or(0, |t| t.len() + usize::from(!p.latest_sampled))
    }
}

/// The [`StepObserver`] that fills a [`PathLog`].
struct Logger(Arc<Mutex<Paths>>);

impl Logger {
    fn lock(&self) -> MutexGuard<'_, Paths> {
        self.0.lock().unwrap_or_else(PoisonError::into_inner)
    }
}

impl StepObserver for Logger {
    fn on_start(&mut self, sim: &Simulation) {
        let mut p = self.lock();
        *p = Paths::default();
        p.sample(sim);
    }

    fn on_step(&mut self, sim: &Simulation) {
        let mut p = self.lock();
        let (steps, _) = sim.progress();
        if p.traces.is_empty() || steps.is_multiple_of(p.every_steps) || sim.is_finished() {
            p.sample(sim);
        } else {
            p.latest.clear();
            p.latest
                .extend(sim.world().robots().iter().map(|r| r.position));
            p.latest_sampled = false;
        }
    }
}

/// Runs one trial as `usar.run` does (`run_trial`: the same arguments and errors), `log`
/// recording every robot's path as it runs (emptied first). Returns `usar run --json`'s JSON
/// text.
///
/// # Errors
/// As `run_trial`: `ValueError` for an unknown method or a bad length; the Python method's
/// own exception or a `GroupingError`; `TrialError`; `KeyboardInterrupt`.
#[pyfunction]
#[pyo3(signature = (scenario, method, log, trial = 0, duration_s = None, seed = None))]
pub fn run_trial_logged(
    py: Python<'_>,
    scenario: &Scenario,
    method: MethodArg,
    log: &PathLog,
    trial: u32,
    duration_s: Option<f64>,
    seed: Option<u64>,
) -> PyResult<String> {
    let mut logger = Logger(log.paths.clone());
    run_observed(py, scenario, method, trial, duration_s, seed, &mut logger)
}

/// `usar render`'s SVG picture of `scenario` as text: with `log`, every robot's path in it so
/// far (as `usar render --trace` draws a trial run to that time); without, the arena with the
/// robots at their starts. A log with nothing yet draws the arena too.
///
/// # Errors
/// `ValueError` if the picture cannot be drawn.
#[pyfunction]
#[pyo3(signature = (scenario, log = None))]
pub fn episode_svg(scenario: &Scenario, log: Option<&PathLog>) -> PyResult<String> {
    let traces = log.map(|l| l.lock().so_far()).filter(|t| !t.is_empty());
    render_svg_string(scenario.inner(), traces.as_deref()).map_err(|e| chain_value_error(&e))
}
