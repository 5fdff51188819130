//! `usar.sweep`: the trials of `usar sweep` (the same `SweepConfig`, seeds, thread pool and
//! order), in memory or, with `out`, into a folder with the journal and every file
//! `usar sweep` writes (`write_outputs`). Returns the bytes of `trials_long.csv`, which the
//! Python side reads into a pandas DataFrame.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use pyo3::exceptions::{PyKeyboardInterrupt, PyValueError};
use pyo3::prelude::*;
use usar_sim::mission::TrialResult;

use usar_report::analysis::Analysis;
use usar_report::calibration::ReportOptions;
use usar_report::csv_tables::trials_long_csv;
use usar_report::output::write_outputs;
use usar_sweep::grid::build_grid;
use usar_sweep::metrics::{Metric, Quantity, Scope};
use usar_sweep::sweep::{Failure, SweepConfig, run_in_memory};

use crate::detached::run_detached;
use crate::errors::{TrialError, chain_value_error, sweep_value_error, value_error};
use crate::methods::{PyMethods, claims_of, factory, methods_of, tracker};
use crate::notices;
use crate::py_method::{FirstError, MethodArg};
use crate::scenario::Scenario;

/// What a sweep gave, per cell (one without a grid): its successful trials (trials.csv order)
/// and failures, or `None` when stopped.
type Ran = Option<Vec<(Vec<TrialResult>, Vec<Failure>)>>;

/// Runs a sweep; returns `trials_long.csv`'s bytes. `progress(done, total)` is called about
/// every 25 ms from the calling thread.
///
/// # Errors
/// `ValueError` for bad arguments (the library's checks, [`usar_sweep::sweep::ConfigError`],
/// named by their keyword arguments) or a journal that cannot be resumed (in the package's
/// words, [`crate::errors::keyword`]); the first Python
/// method's exception or `GroupingError`; `TrialError` listing failed trials (with `out`,
/// after the files are written); `KeyboardInterrupt` on Ctrl-C (with `out`, the finished
/// trials are in the journal: `resume=True` runs the rest). The libraries' warnings (a
/// claims or targets file the scenario names that is missing, a record that does not verify,
/// a figure not drawn) are `usar.UsarWarning`s, given before the result or the error.
#[pyfunction]
#[pyo3(signature = (scenario, methods, trials = 10, threads = None, out = None, resume = false,
    duration_s = None, seed = None, progress = None, overwrite = false, targets = None,
    claims = None, vary = Vec::new()))]
#[allow(clippy::too_many_arguments)]
pub fn run_sweep(
    py: Python<'_>,
    scenario: &Scenario,
    methods: Vec<MethodArg>,
    trials: u32,
    threads: Option<usize>,
    out: Option<PathBuf>,
    resume: bool,
    duration_s: Option<f64>,
    seed: Option<u64>,
    progress: Option<Py<PyAny>>,
    overwrite: bool,
    targets: Option<PathBuf>,
    claims: Option<&Bound<'_, PyAny>>,
    vary: Vec<String>,
) -> PyResult<Vec<(Vec<String>, Vec<u8>)>> {
    if resume && overwrite {
        return Err(PyValueError::new_err(
            "resume=True and overwrite=True: give one (continue the journal, or start afresh)",
        ));
    }
    let (names, python) = methods_of(methods)?;
    let first_error = FirstError::default();
    let stop = Arc::new(AtomicBool::new(false));
    let done = Arc::new(AtomicUsize::new(0));
    let s = scenario.inner().clone();
    let mut cfg = SweepConfig {
        methods: names,
        method_factory: factory(
            &python,
            &first_error,
            s.kinds().iter().map(|k| k.name.clone()).collect(),
            None,
        ),
        trials,
        base_seed: seed.unwrap_or(s.sim().seed),
        duration_s,
        threads: threads
            .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, usize::from)),
        resume,
        overwrite,
        progress: false,
        ..SweepConfig::new(s, scenario.path())
    };
    if !vary.is_empty() {
        let grid = build_grid(cfg.scenario.spec(), &vary).map_err(|e| sweep_value_error(&e))?;
        cfg.grid = Some(grid);
    }
    add_hooks(&mut cfg, &python, &stop, &done);
    // A file the scenario names and that is missing is a warning of `resolve`.
    let report = report_options(&mut cfg, out.as_ref(), targets.as_deref(), claims);
    let report = notices::flushed(py, report)?;
    let cells = cfg.grid.as_ref().map_or(1, |g| g.cells.len());
    let total = cells * cfg.methods.len() * trials as usize;
    let cfg_ref = &cfg;
    let stopped = stop.clone();
    let work = move || sweep_trials(cfg_ref, report, &stopped);
    let tick = |py: Python<'_>| -> PyResult<()> {
        match &progress {
            Some(p) => p.call1(py, (done.load(Ordering::SeqCst), total)).map(drop),
            None => Ok(()),
        }
    };
    let ran = notices::flushed(py, run_detached(py, &stop, work, tick))?;
    let ran = ran.map_err(|e| sweep_value_error(e.as_ref()))?;
    let per_cell = successful_trials(ran, &first_error, &stop, total)?;
    per_cell
        .iter()
        .enumerate()
        .map(|(i, results)| {
            let (values, tasks) = match &cfg.grid {
                Some(g) => (g.cells[i].values(), g.cells[i].scenario.task_names()),
                None => (Vec::new(), cfg.scenario.task_names()),
            };
            let csv = trials_long_csv(results, &tasks).map_err(|e| chain_value_error(&e))?;
            Ok((values, csv))
        })
        .collect()
}

/// Sets the sweep's hooks: each journaled trial counts into `done` (for `progress`), `stop`
/// stops the sweep, and, when there are Python methods, their trials track positions.
fn add_hooks(
    cfg: &mut SweepConfig,
    python: &PyMethods,
    stop: &Arc<AtomicBool>,
    done: &Arc<AtomicUsize>,
) {
    let counter = done.clone();
    cfg.hooks.on_journaled = Some(Arc::new(move |_, _| {
        counter.fetch_add(1, Ordering::SeqCst);
    }));
    cfg.hooks.stop = Some(stop.clone());
    if !python.is_empty() {
        cfg.hooks.trial_observer = Some(tracker(python));
    }
}

/// With `out`, points the sweep's output folder at it and returns the report options: the
/// targets file `targets` and the claims `claims` (a claims file's path, or a list of claims
/// as dicts with a claims file's fields) or else those the scenario's `report` section names;
/// without, `None` (an in-memory sweep; `targets` or `claims` then are an error: only
/// report.md shows them).
///
/// # Errors
/// `ValueError` when the report options cannot be resolved or are given without `out`.
fn report_options(
    cfg: &mut SweepConfig,
    out: Option<&PathBuf>,
    targets: Option<&Path>,
    claims: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<ReportOptions>> {
    let Some(dir) = out else {
        if targets.is_some() || claims.is_some() {
            return Err(PyValueError::new_err(
                "targets and claims are checked in report.md: give out= too",
            ));
        }
        return Ok(None);
    };
    cfg.out_dir = dir.clone();
    let file = match claims {
        Some(c) if c.extract::<PathBuf>().is_ok() => Some(c.extract::<PathBuf>()?),
        _ => None,
    };
    let mut report = ReportOptions::resolve(
        targets,
        file.as_deref(),
        &cfg.scenario,
        &cfg.scenario_path,
        &cfg.methods,
    )
    .map_err(value_error)?;
    if let Some(list) = claims.filter(|_| file.is_none()) {
        report.claims = Some(claims_of(list, &cfg.scenario.task_names(), &cfg.methods)?);
    }
    Ok(Some(report))
}

/// The sweep's work, off the Python thread: without `report`, the trials in memory; with
/// it, `usar sweep`'s run into `cfg.out_dir` and, unless `stopped`, every file it writes
/// (metrics: rescued in total and per task). `None` when stopped or there is no cell.
fn sweep_trials(
    cfg: &SweepConfig,
    report: Option<ReportOptions>,
    stopped: &AtomicBool,
) -> Result<Ran, Box<dyn std::error::Error + Send + Sync>> {
    let Some(report) = report else {
        let r = run_in_memory(cfg)?;
        return Ok(Some(
            r.cells
                .into_iter()
                .map(|c| (c.results, c.failures))
                .collect(),
        ));
    };
    let o = usar_sweep::sweep::run_sweep(cfg)?;
    if stopped.load(Ordering::SeqCst) {
        return Ok(None);
    }
    let tasks = cfg.scenario.task_names();
    let mut metrics = vec![Metric::new(Quantity::Rescued, Scope::Total)];
    metrics.extend((0..tasks.len()).map(|t| Metric::new(Quantity::Rescued, Scope::Task(t))));
    let analysis = Analysis::with_report(&o, report);
    write_outputs(cfg, &o, &analysis, &metrics)?;
    Ok(Some(
        o.cells
            .into_iter()
            .map(|c| (c.results, c.failures))
            .collect(),
    ))
}

/// The successful trials of a finished sweep (`ran`) of `total` trials, per cell.
///
/// # Errors
/// In this order: the first Python method's exception; `KeyboardInterrupt` when `stop` is
/// set or the sweep gave nothing; `TrialError` listing the failed trials.
fn successful_trials(
    ran: Ran,
    first_error: &FirstError,
    stop: &AtomicBool,
    total: usize,
) -> PyResult<Vec<Vec<TrialResult>>> {
    if let Some(e) = first_error.lock().ok().and_then(|mut e| e.take()) {
        return Err(e);
    }
    if stop.load(Ordering::SeqCst) {
        return Err(PyKeyboardInterrupt::new_err("the sweep was stopped"));
    }
    let Some(cells) = ran.filter(|c| !c.is_empty()) else {
        return Err(PyKeyboardInterrupt::new_err("the sweep was stopped"));
    };
    let failures: Vec<&Failure> = cells.iter().flat_map(|(_, f)| f).collect();
    if !failures.is_empty() {
        let grid = cells.len() > 1;
        let list: Vec<String> = failures
            .iter()
            .map(|f| {
                let cell = if grid {
                    format!("cell {} ", f.cell)
                } else {
                    String::new()
                };
                format!("{cell}{} trial {} ({})", f.method, f.trial, f.message)
            })
            .collect();
        return Err(TrialError::new_err(format!(
            "{} of {total} trials failed: {}",
            failures.len(),
            list.join("; ")
        )));
    }
    Ok(cells.into_iter().map(|(results, _)| results).collect())
}
