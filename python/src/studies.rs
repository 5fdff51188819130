//! `usar.calibrate` and `usar.multiverse`: `usar calibrate`'s and `usar multiverse`'s runs
//! (the same `CalibrationSetup` and `MultiverseSetup`, files and resumption) for built-in and
//! Python grouping methods, and claims as a file or as Python objects. Each returns the
//! summary `usar` prints and a JSON text of what the Python side needs beside the files.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::time::Duration;

use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use serde_json::json;

use usar_report::calibration::targets_or_paper;
use usar_report::claims::Claims;
use usar_report::source_date::source_date;
use usar_study::calibrate::{
    CalibrationError, CalibrationOutcome, CalibrationSetup, Optimizer, Progress, TargetCheck,
    Targets, TrialPlan, calibrate, parse_free,
};
use usar_study::multiverse::{
    Axes, MultiverseError, MultiverseOutcome, MultiverseProgress, MultiverseSetup, Sample,
    run_multiverse,
};

use crate::detached::run_detached;
use crate::errors::sweep_value_error;
use crate::methods::{PyMethods, claims_of, factory, methods_of, tracker};
use crate::notices;
use crate::py_method::{FirstError, MethodArg};
use crate::scenario::Scenario;

/// What a calibration and a multiverse share: their methods (names, the Python ones, their
/// first error), the stop flag and the count of finished steps for `progress`.
struct Run {
    names: Vec<String>,
    python: PyMethods,
    first_error: FirstError,
    stop: Arc<AtomicBool>,
    done: Arc<AtomicUsize>,
}

impl Run {
    fn new(methods: Vec<MethodArg>) -> PyResult<Self> {
        if methods.is_empty() {
            return Err(PyValueError::new_err("methods: give at least one method"));
        }
        let (names, python) = methods_of(methods)?;
        Ok(Self {
            names,
            python,
            first_error: FirstError::default(),
            stop: Arc::new(AtomicBool::new(false)),
            done: Arc::new(AtomicUsize::new(0)),
        })
    }

    /// The method factory over `scenario`'s kinds.
    fn factory(&self, scenario: &Scenario) -> usar_sweep::sweep::MethodFactory {
        let kinds = scenario.inner().kinds().iter().map(|k| k.name.clone());
        factory(
            &self.python,
            &self.first_error,
            kinds.collect(),
            Some(self.stop.clone()),
        )
    }

    /// The step observer of the Python methods' trials (none without one).
    fn observer(&self) -> Option<usar_sweep::sweep::TrialObserverFactory> {
        (!self.python.is_empty()).then(|| tracker(&self.python))
    }

    /// Runs `work` detached, calling `progress(done, total)`; then the first Python error,
    /// `KeyboardInterrupt` when stopped, or `work`'s error in the package's words.
    fn finish<T: Send, E: StudyError>(
        &self,
        py: Python<'_>,
        work: impl FnOnce() -> Result<T, E> + Send,
        progress: Option<Py<PyAny>>,
        total: usize,
    ) -> PyResult<T> {
        let tick = |py: Python<'_>| -> PyResult<()> {
            match &progress {
                Some(p) => p
                    .call1(py, (self.done.load(Ordering::SeqCst), total))
                    .map(drop),
                None => Ok(()),
            }
        };
        // The libraries' warnings (a trace line or universe record that does not verify, a
        // figure not drawn) as `usar.UsarWarning`s, before the result or the error.
        let outcome = notices::flushed(py, run_detached(py, &self.stop, work, tick))?;
        // A Python method's failure stopped the run (nothing of the evaluation or universe it
        // was in is kept): its own exception.
        if let Some(e) = self.first_error.lock().ok().and_then(|mut e| e.take()) {
            return Err(e);
        }
        match outcome {
            Err(e) if e.is_stopped() || self.stop.load(Ordering::SeqCst) => {
                Err(PyKeyboardInterrupt::new_err(
                    "stopped; the finished work is kept: the same call continues it",
                ))
            }
            Err(e) => Err(py_error(e)),
            Ok(v) => Ok(v),
        }
    }
}

/// A one-line `ValueError` of a library error, in the package's words.
fn py_error(e: impl std::error::Error + 'static) -> PyErr {
    sweep_value_error(&e)
}

/// A study's error: [`CalibrationError`] or [`MultiverseError`], which say whether the study
/// was stopped by its flag.
trait StudyError: std::error::Error + Send + 'static {
    /// Whether the study stopped because its stop flag was set.
    fn is_stopped(&self) -> bool;
}

impl StudyError for CalibrationError {
    fn is_stopped(&self) -> bool {
        CalibrationError::is_stopped(self)
    }
}

impl StudyError for MultiverseError {
    fn is_stopped(&self) -> bool {
        MultiverseError::is_stopped(self)
    }
}

/// A target check as JSON.
fn check_json(c: &TargetCheck) -> serde_json::Value {
    json!({
        "target": c.target.name,
        "value": c.value.is_finite().then_some(c.value),
        "goal": c.target.value,
        "band": c.target.band.to_string(),
        "holds": c.holds,
        "report_only": c.target.report_only,
    })
}

/// What the Python side reads of a calibration beside its files.
fn calibration_json(o: &CalibrationOutcome) -> serde_json::Value {
    let best: Vec<serde_json::Value> = o
        .header
        .free
        .iter()
        .zip(o.best_values())
        .map(|(f, x)| json!([f.label(), x]))
        .collect();
    json!({
        "summary": usar_study::calibrate::summary_text(o),
        "loss": o.loss.is_finite().then_some(o.loss),
        "admissible": o.admissible,
        "stop": o.stop.to_string(),
        "best": best,
        "best_index": o.best,
        "evaluations": o.evaluations.len(),
        "ran": o.ran,
        "reused": o.reused,
        "statistics": o.statistics.iter().map(check_json).collect::<Vec<_>>(),
        "unseen": o.check.as_ref().map(|c| c.statistics.iter().map(check_json).collect::<Vec<_>>()),
        "files": o.files.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
    })
}

/// Runs `usar calibrate` (see `usar.calibrate` for the arguments); returns the JSON text of
/// [`calibration_json`].
///
/// # Errors
/// `ValueError` for bad arguments, files or a folder that cannot be used (in the package's
/// words); the first Python method's exception; `KeyboardInterrupt` on Ctrl-C (the trace keeps
/// the finished evaluations: the same call continues).
#[pyfunction]
#[pyo3(signature = (scenario, free, out, targets, methods, trials, seed, duration_s, digits,
    max_evals, max_time_s, threads, check_seed, check_trials, optimizer, start_mid, overwrite,
    report_only, require, command, progress))]
#[allow(clippy::too_many_arguments)]
pub fn run_calibration(
    py: Python<'_>,
    scenario: &Scenario,
    free: Vec<String>,
    out: PathBuf,
    targets: Option<PathBuf>,
    methods: Vec<MethodArg>,
    trials: u32,
    seed: Option<u64>,
    duration_s: Option<f64>,
    digits: u32,
    max_evals: usize,
    max_time_s: Option<f64>,
    threads: Option<usize>,
    check_seed: Option<u64>,
    check_trials: u32,
    optimizer: &str,
    start_mid: bool,
    overwrite: bool,
    report_only: Vec<String>,
    require: Vec<String>,
    command: String,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let run = Run::new(methods)?;
    let mut t = targets_or_paper(targets.as_deref()).map_err(py_error)?;
    t.set_required(&require).map_err(py_error)?;
    t.set_report_only(&report_only).map_err(py_error)?;
    let free = parse_free(&free).map_err(py_error)?;
    let optimizer = match optimizer {
        "nelder-mead" => Optimizer::NelderMead,
        "cma-es" => Optimizer::CmaEs,
        other => {
            return Err(PyValueError::new_err(format!(
                "optimizer: expected \"nelder-mead\" or \"cma-es\", not {other:?}"
            )));
        }
    };
    let max_time = match max_time_s {
        Some(s) if !(s.is_finite() && s > 0.0) => {
            return Err(PyValueError::new_err(format!(
                "max_time_s must be a finite number of seconds > 0, not {s}"
            )));
        }
        // Beyond what a Duration holds (about 5.8e11 years): as long as it can be.
        s => s.map(|s| Duration::try_from_secs_f64(s).unwrap_or(Duration::MAX)),
    };
    let base_seed = seed.unwrap_or(scenario.spec().sim.seed);
    let counter = run.done.clone();
    let setup = CalibrationSetup {
        trial_plan: TrialPlan {
            methods: run.names.clone(),
            method_factory: run.factory(scenario),
            trials,
            base_seed,
            duration_s,
        },
        digits,
        max_evals,
        max_time,
        threads: threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from)),
        check_seed: check_seed
            .unwrap_or(usar_study::calibrate::setup::default_check_seed(base_seed)),
        check_trials,
        overwrite,
        optimizer,
        start_mid,
        command,
        date: source_date().map_err(py_error)?,
        hooks: usar_sweep::data::hooks::CalibrationHooks {
            trial_observer: run.observer(),
            stop: Some(run.stop.clone()),
        },
        ..CalibrationSetup::new(scenario.spec().clone(), scenario.origin_text(), t, free)
    };
    let hook = Progress {
        on_evaluated: Some(Arc::new(move |_, _| {
            counter.fetch_add(1, Ordering::SeqCst);
        })),
        ..Progress::off()
    };
    let work = || calibrate(&setup, &out, hook).map(|o| calibration_json(&o).to_string());
    run.finish(py, work, progress, max_evals)
}

/// The claims of a multiverse: `claims` (a file's path, or a list of dicts), else the file
/// the scenario's `report: (claims: ...)` names (relative to its folder; none when missing).
fn multiverse_claims(
    py: Python<'_>,
    claims: Option<&Bound<'_, PyAny>>,
    scenario: &Scenario,
    methods: &[String],
) -> PyResult<Option<Claims>> {
    let load = |p: &Path| Claims::load(p).map(Some).map_err(py_error);
    match claims {
        Some(c) => match c.extract::<PathBuf>() {
            Ok(p) => load(&p),
            Err(_) => claims_of(c, &scenario.inner().task_names(), methods).map(Some),
        },
        None => match &scenario.spec().report.claims {
            Some(file) => {
                let p = scenario.path().parent().unwrap_or(Path::new("")).join(file);
                if p.exists() {
                    return load(&p);
                }
                let message = format!(
                    "{}: report.claims: {} not found (relative to the scenario's folder); no \
                     claims are checked (claims= gives them)",
                    scenario.origin_text(),
                    p.display()
                );
                let category = py.get_type::<crate::errors::UsarWarning>();
                PyErr::warn(py, &category, &std::ffi::CString::new(message)?, 1)?;
                Ok(None)
            }
            None => Ok(None),
        },
    }
}

/// What the Python side reads of a multiverse beside its files.
fn multiverse_json(o: &MultiverseOutcome, dir: &Path) -> serde_json::Value {
    json!({
        "summary": usar_study::multiverse::summary_text(o, dir),
        "universes": o.records.len(),
        "admissible": o.admissible(),
        "failed": o.failed().map(|r| json!([r.id, r.message])).collect::<Vec<_>>(),
        "ran": o.ran,
        "reused": o.reused,
        "files": o.files.iter().map(|p| p.display().to_string()).collect::<Vec<_>>(),
    })
}

/// Runs `usar multiverse` (see `usar.multiverse` for the arguments); returns the JSON text of
/// [`multiverse_json`].
///
/// # Errors
/// As [`run_calibration`]; failed universes are not an error (the JSON lists them).
#[pyfunction]
#[pyo3(signature = (scenario, axes, targets, free, out, methods, claims, near_loss,
    report_only, trials, seed, duration_s, calibration_trials, calibration_seed, max_evals,
    sample, sample_seed, threads, overwrite, progress))]
#[allow(clippy::too_many_arguments)]
pub fn run_multiverse_py(
    py: Python<'_>,
    scenario: &Scenario,
    axes: PathBuf,
    targets: PathBuf,
    free: Vec<String>,
    out: PathBuf,
    methods: Vec<MethodArg>,
    claims: Option<&Bound<'_, PyAny>>,
    near_loss: Option<f64>,
    report_only: Vec<String>,
    trials: u32,
    seed: Option<u64>,
    duration_s: Option<f64>,
    calibration_trials: u32,
    calibration_seed: Option<u64>,
    max_evals: usize,
    sample: Option<usize>,
    sample_seed: u64,
    threads: Option<usize>,
    overwrite: bool,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    let run = Run::new(methods)?;
    let axes = Axes::load(&axes).map_err(py_error)?;
    let mut t = Targets::load(&targets).map_err(py_error)?;
    t.set_report_only(&report_only).map_err(py_error)?;
    let free = parse_free(&free).map_err(py_error)?;
    let claims = multiverse_claims(py, claims, scenario, &run.names)?;
    let seed = seed.unwrap_or(scenario.spec().sim.seed);
    let mut setup = MultiverseSetup {
        claims,
        near_loss,
        comparison: TrialPlan {
            methods: run.names.clone(),
            method_factory: run.factory(scenario),
            trials,
            base_seed: seed,
            duration_s,
        },
        calibration_trials,
        calibration_seed: calibration_seed.unwrap_or(seed),
        max_evals,
        sample: sample.map(|n| Sample {
            n,
            seed: sample_seed,
        }),
        threads: threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from)),
        overwrite,
        date: source_date().map_err(py_error)?,
        ..MultiverseSetup::new(
            scenario.spec().clone(),
            scenario.origin_text(),
            axes,
            t,
            free,
        )
    };
    let counter = run.done.clone();
    setup.hooks.universe_done = Some(Arc::new(move |_, _| {
        counter.fetch_add(1, Ordering::SeqCst);
    }));
    setup.hooks.stop = Some(run.stop.clone());
    setup.hooks.calibration_trials = run.observer();
    setup.hooks.sweep.trial_observer = run.observer();
    let total = setup.check().map_err(py_error)?.own(None).len();
    let work = || {
        run_multiverse(&setup, &out, MultiverseProgress::off())
            .map(|o| multiverse_json(&o, &out).to_string())
    };
    run.finish(py, work, progress, total)
}
