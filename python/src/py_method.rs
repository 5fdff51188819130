//! A grouping method written in Python: `PyMethod` implements rne-core's `GroupingMethod`
//! by calling a Python function once per grouping round, with the GIL taken for that call
//! only. The Python side (`usar/_grouping.py`) wraps the user's callable in an adapter that
//! builds the `GroupingRequest` object from the raw dict made here and returns plain lists of
//! ids; this side checks the answer (`Assignment::validate`) and keeps the first Python
//! exception or broken rule so that `usar.run` and `usar.sweep` raise it.
//!
//! Robot positions, the rescuees so far and the time are not part of rne-core's request: a
//! step observer ([`track_positions`]) copies them after every step into a thread-local that
//! the method reads (a trial runs on one thread: its method and its observer share it).

use std::cell::{Cell, RefCell};
use std::sync::{Arc, Mutex, PoisonError};

use pyo3::prelude::*;
use pyo3::types::PyDict;
use rne_core::RneError;
use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
use usar_sim::mission::Simulation;

use crate::errors::GroupingError;

/// What a Python method sees of the trial beyond rne-core's request, as of the last step.
#[derive(Default)]
struct Observed {
    /// The robots' positions (x, y metres), by id.
    positions: Vec<(f64, f64)>,
    /// Rescuees so far per task (the rounds' counts summed), by task id.
    rescued: Vec<u32>,
    /// Simulated time, seconds.
    time_s: f64,
}

thread_local! {
    /// What the trial running on this thread looked like after its last step.
    static OBSERVED: RefCell<Observed> = RefCell::new(Observed::default());
}

/// Copies `sim`'s robot positions, rescuees so far and time into this thread's table (call
/// after every step).
pub fn track_positions(sim: &Simulation) {
    OBSERVED.with(|o| {
        let mut o = o.borrow_mut();
        o.positions.clear();
        o.positions.extend(
            sim.world()
                .robots()
                .iter()
                .map(|r| (r.position.x, r.position.y)),
        );
        o.rescued.clear();
        o.rescued.resize(sim.scenario().tasks().len(), 0);
        for round in sim.rounds() {
            for (sum, n) in o.rescued.iter_mut().zip(&round.rescued) {
                *sum += n;
            }
        }
        o.time_s = sim.time_s();
    });
}

/// Empties this thread's table (before a trial without a Python method).
pub fn clear_positions() {
    OBSERVED.with(|o| *o.borrow_mut() = Observed::default());
}

/// The first error a Python method met, shared by every trial of a run or sweep.
pub type FirstError = Arc<Mutex<Option<PyErr>>>;

/// Keeps `e` if it is the first.
pub fn keep_first(slot: &FirstError, e: PyErr) {
    let mut s = slot.lock().unwrap_or_else(PoisonError::into_inner);
    if s.is_none() {
        *s = Some(e);
    }
}

/// A Python grouping method in one trial.
pub struct PyMethod {
    /// The method's name (results show it as written).
    pub name: String,
    /// The adapter: `adapter(raw: dict) -> list[list[int]]`, one list of ids per task.
    pub adapter: Arc<Py<PyAny>>,
    /// The trial's index and seed (given to the method with each request).
    pub trial: u32,
    /// The trial's seed.
    pub seed: u64,
    /// Rounds grouped so far in this trial.
    pub round: Cell<u32>,
    /// Where the first failure goes.
    pub first_error: FirstError,
    /// The scenario's kind names, by kind index (errors name a kind by both).
    pub kind_names: Arc<Vec<String>>,
    /// Set at the method's first failure, when given: a study stops at once (a sweep runs
    /// its other trials and lists the failed ones).
    pub stop_on_error: Option<Arc<std::sync::atomic::AtomicBool>>,
}

impl PyMethod {
    /// Sets [`PyMethod::stop_on_error`], if any.
    fn stop_run(&self) {
        if let Some(stop) = &self.stop_on_error {
            stop.store(true, std::sync::atomic::Ordering::SeqCst);
        }
    }

    /// The raw request dict the adapter turns into a `usar.GroupingRequest`.
    fn raw<'py>(&self, py: Python<'py>, req: &GroupingRequest) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        let robots = req.robots();
        d.set_item("trial", self.trial)?;
        d.set_item("seed", self.seed)?;
        d.set_item("round", self.round.get())?;
        d.set_item("ids", robots.iter().map(|r| r.id).collect::<Vec<_>>())?;
        d.set_item("kinds", robots.iter().map(|r| r.kind).collect::<Vec<_>>())?;
        let needs: Vec<Vec<f64>> = robots.iter().map(|r| r.needs.as_slice().to_vec()).collect();
        d.set_item("needs", needs)?;
        d.set_item(
            "energy_pct",
            robots.iter().map(|r| r.energy_pct).collect::<Vec<_>>(),
        )?;
        d.set_item(
            "hp_pct",
            robots.iter().map(|r| r.hp_pct).collect::<Vec<_>>(),
        )?;
        let dist: Vec<Vec<f64>> = robots
            .iter()
            .map(|r| r.distance_to_goal_m.clone())
            .collect();
        d.set_item("distance_to_goal_m", dist)?;
        OBSERVED.with(|o| {
            let o = o.borrow();
            let positions: Vec<Option<(f64, f64)>> = robots
                .iter()
                .map(|r| o.positions.get(r.id).copied())
                .collect();
            d.set_item("positions", positions)?;
            d.set_item("rescued_so_far", o.rescued.clone())?;
            d.set_item("time_s", o.time_s)
        })?;
        d.set_item("quotas", req.quotas().to_vec())?;
        d.set_item("hardest_first", req.hardest_first().to_vec())?;
        Ok(d)
    }

    /// `e`'s message with each `kind K` followed by the kind's name: `kind 1 (supplier) got
    /// [1, 3] robots per task but the quotas are [2, 2]`.
    fn with_kind_names(&self, e: &impl std::fmt::Display) -> String {
        let mut text = e.to_string();
        for (k, name) in self.kind_names.iter().enumerate() {
            text = text.replace(&format!("kind {k} "), &format!("kind {k} ({name}) "));
        }
        text
    }

    /// Calls the adapter and reads its answer.
    fn call(&self, req: &GroupingRequest) -> PyResult<Vec<Vec<usize>>> {
        Python::attach(|py| {
            let raw = self.raw(py, req)?;
            let answer = self.adapter.bind(py).call1((raw,))?;
            answer.extract::<Vec<Vec<usize>>>().map_err(|_| {
                GroupingError::new_err(format!(
                    "method {}: the answer must be one list of robot ids per task",
                    self.name
                ))
            })
        })
    }
}

impl GroupingMethod for PyMethod {
    fn name(&self) -> &str {
        &self.name
    }

    fn assign(&self, request: &GroupingRequest) -> rne_core::Result<Assignment> {
        let answer = self.call(request);
        self.round.set(self.round.get() + 1);
        match answer {
            Ok(groups) => {
                let assignment = Assignment::new(groups);
                if let Err(e) = assignment.validate(request) {
                    let message = format!("method {}: {}", self.name, self.with_kind_names(&e));
                    keep_first(&self.first_error, GroupingError::new_err(message));
                    self.stop_run();
                    return Err(e);
                }
                Ok(assignment)
            }
            Err(e) => {
                let message = Python::attach(|py| {
                    let text = e.value(py).repr().map(|r| r.to_string());
                    text.unwrap_or_else(|_| "an exception".into())
                });
                keep_first(&self.first_error, e);
                self.stop_run();
                Err(RneError::InvalidAssignment(format!(
                    "method {} raised {message}",
                    self.name
                )))
            }
        }
    }
}

/// A step observer that keeps this thread's position table current for a Python method.
pub struct PositionTracker;

impl usar_sim::mission::StepObserver for PositionTracker {
    fn on_step(&mut self, sim: &Simulation) {
        track_positions(sim);
    }

    fn on_start(&mut self, sim: &Simulation) {
        track_positions(sim);
    }
}

/// A method given from Python: a built-in's name, or a Python method's name and adapter.
#[derive(FromPyObject)]
pub enum MethodArg {
    /// A method of rne-core by name (`rne`, `dis`, `eng`, `hp_dis`).
    Name(String),
    /// A Python method: `(name, adapter)`.
    Python((String, Py<PyAny>)),
}
