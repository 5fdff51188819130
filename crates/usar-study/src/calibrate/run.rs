//! [`calibrate`]: check the setup, lock the output folder, open (or continue) the trace,
//! search, check the best values on unseen trials, write the outputs.

use std::collections::HashMap;
use std::path::Path;
use std::time::Instant;

use usar_sim::scenario::path_text;

use super::cma_es::{INFINITE_LOSS, INITIAL_SIGMA, cma_es, population};
use super::error::CalibrationError;
use super::evaluate::{Evaluation, Evaluator};
use super::optimizer::{
    INITIAL_STEP, OUTSIDE_PENALTY, Optimizer, STALL_LIMIT, StopReason, nelder_mead,
};
use super::outcome::{CalibrationOutcome, CheckOutcome, best_index, target_checks};
use super::outputs::{clear, write_outputs};
use super::progress::{Display, Progress};
use super::searcher::{Searcher, key};
use super::setup::{CalibrationSetup, Checked};
use super::trace::{TRACE_FORMAT, Trace, TraceHeader, header_diff, read_trace};
use usar_sweep::atomic::{remove_named, remove_stale_temps};
use usar_sweep::data::hooks::Stopped;
use usar_sweep::data::owner::{RunKind, claim};
use usar_sweep::fingerprint::scenario_hash;
use usar_sweep::journal::{holds_no_line, something_at};
use usar_sweep::lock::OutputLock;

/// What the functions of this module return.
type Result<T> = std::result::Result<T, CalibrationError>;

/// Fits the free fields of `setup.base` so that the statistics of its trials fall inside the
/// bands of `setup.targets`, writing into `dir`: `trace.jsonl` (every evaluation, as it
/// ends), then `calibrated.ron`, `trace.csv`, `calibration.md`, `convergence.svg` and
/// `statistics.svg`.
///
/// Same inputs, same sequence of evaluated points and same files on any thread count (but
/// the date, unless `setup.date` sets it, and the timings in `calibration.md`). Running it again on a folder holding the trace
/// of the same calibration replays the search with the recorded evaluations and runs only new
/// points (so a killed calibration continues, and a larger `max_evals` extends one); a trace
/// of another calibration is refused unless `setup.overwrite`. The folder is locked while it
/// runs (`usar_sweep::lock`).
///
/// ```no_run
/// use std::path::Path;
/// use usar_study::calibrate::{CalibrationSetup, FreeField, Progress, Targets, calibrate};
/// use usar_study::calibrate::TrialPlan;
///
/// let text = std::fs::read_to_string("scenarios/paper.ron")?;
/// let base = usar_sim::scenario::parse_spec(&text, "scenarios/paper.ron")?;
/// let targets = Targets::load(Path::new("scenarios/paper-targets.ron"))?;
/// let free = vec![FreeField::parse("mission.pickup_s=0.8..1.6")?];
/// let seed = base.sim.seed;
/// let setup = CalibrationSetup {
///     trial_plan: TrialPlan {
///         methods: vec!["rne".into(), "dis".into()],
///         ..TrialPlan::builtin(4, seed)
///     },
///     max_evals: 12,
///     check_trials: 0,
///     ..CalibrationSetup::new(base, "scenarios/paper.ron", targets, free)
/// };
/// let outcome = calibrate(&setup, Path::new("results/calibrate-pickup"), Progress::off())?;
/// println!("pickup_s = {} (loss {})", outcome.best_values()[0], outcome.loss);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
///
/// # Errors
/// A setup that does not fit its scenario ([`CalibrationSetup::check`]), an output folder
/// that is not a folder or belongs to another kind of run ([`usar_sweep::data::owner`]), a folder
/// locked by another run, a trace that cannot be continued (another calibration's, edited, damaged), an
/// I/O error, or no evaluated point giving a valid scenario. Failing or panicking trials and
/// free values that break a rule are not errors: their evaluation's loss is +inf.
pub fn calibrate(
    setup: &CalibrationSetup,
    dir: &Path,
    progress: Progress,
) -> Result<CalibrationOutcome> {
    let t0 = Instant::now();
    let checked = setup.check()?;
    let header = header_of(setup, &checked)?;
    claim(dir, RunKind::Calibration)?;
    let _lock = OutputLock::acquire(dir)?;
    remove_stale_temps(dir)?;
    let (trace, recorded) = open_trace(dir, &header, setup.overwrite)?;
    let evaluator = Evaluator::new(setup, &checked)?;
    let starts: Vec<f64> = match &setup.start {
        Some(start) => start.clone(),
        None => setup
            .free
            .iter()
            .zip(&checked.base_values)
            .map(|(f, base)| {
                if setup.start_mid {
                    f.midpoint()
                } else {
                    f.start(*base)
                }
            })
            .collect(),
    };
    let search = search(setup, &evaluator, trace, recorded, &starts, &progress, t0)?;
    if search.stop == StopReason::Interrupted || setup.hooks.stopped() {
        return Err(Stopped.into());
    }
    let evaluations = search.sequence;
    let best = best_index(&evaluations).ok_or(CalibrationError::NoEvaluation)?;
    let (best_spec, best_scenario) = evaluator
        .scenario_at(&evaluations[best].values)
        .map_err(|problem| CalibrationError::NoValidPoint { problem })?;
    let check = (setup.check_trials > 0).then(|| unseen(setup, &evaluator, &best_scenario));
    if setup.hooks.stopped() {
        return Err(Stopped.into());
    }
    let mut outcome = CalibrationOutcome {
        header,
        origin: setup.origin.clone(),
        targets_origin: setup.targets.origin().to_owned(),
        command: setup.command.clone(),
        date: setup.date.clone().unwrap_or_else(|| {
            humantime::format_rfc3339_seconds(std::time::SystemTime::now()).to_string()
        }),
        loss: evaluations[best].search_loss(),
        admissible: evaluations[best].search_loss() == 0.0,
        statistics: target_checks(setup.targets.targets(), &evaluations[best].statistics),
        best,
        evaluations,
        best_spec,
        best_scenario,
        stop: search.stop,
        ran: search.ran,
        reused: search.reused,
        max_evals: setup.max_evals,
        starts,
        threads: checked.threads,
        wall_s: 0.0,
        check,
        files: vec![Trace::path_in(dir)],
    };
    outcome.wall_s = t0.elapsed().as_secs_f64();
    outcome.files.extend(write_outputs(&outcome, dir)?);
    Ok(outcome)
}

/// What the search did.
struct Searched {
    sequence: Vec<Evaluation>,
    stop: StopReason,
    ran: usize,
    reused: usize,
}

/// Runs the search from the free values `starts`, with the `recorded` evaluations of an
/// earlier run as a cache and every new one appended to `trace`.
fn search(
    setup: &CalibrationSetup,
    evaluator: &Evaluator<'_>,
    trace: Trace,
    recorded: Vec<Evaluation>,
    starts: &[f64],
    progress: &Progress,
    t0: Instant,
) -> Result<Searched> {
    let mut searcher = Searcher {
        evaluator,
        free: &setup.free,
        digits: setup.digits,
        cache: recorded
            .into_iter()
            .map(|e| (key(&e.values), e))
            .collect::<HashMap<_, _>>(),
        sequence: Vec::new(),
        positions: HashMap::new(),
        trace,
        max_evals: setup.max_evals,
        // A budget past what an `Instant` holds (`--max-time` of 5e11 years) is no limit.
        deadline: setup.max_time.and_then(|d| t0.checked_add(d)),
        stop: setup.hooks.stop.clone(),
        display: Display::new(progress, setup.max_evals),
        ran: 0,
        reused: 0,
        error: None,
    };
    let u0: Vec<f64> = setup
        .free
        .iter()
        .zip(starts)
        .map(|(f, &x)| f.to_unit(x))
        .collect();
    let stop = match setup.optimizer {
        Optimizer::NelderMead => nelder_mead(&u0, &mut searcher),
        Optimizer::CmaEs => cma_es(&u0, &mut searcher, setup.trial_plan.base_seed),
    };
    searcher.display.finish();
    if let Some(e) = searcher.error {
        return Err(CalibrationError::TraceStopped(e));
    }
    Ok(Searched {
        sequence: searcher.sequence,
        stop,
        ran: searcher.ran,
        reused: searcher.reused,
    })
}

/// The statistics of `scenario` on the unseen trials of `setup.check_seed`.
fn unseen(
    setup: &CalibrationSetup,
    evaluator: &Evaluator<'_>,
    scenario: &usar_sim::scenario::Scenario,
) -> CheckOutcome {
    let set = evaluator.run(scenario, setup.check_seed, setup.check_trials);
    CheckOutcome {
        seed: setup.check_seed,
        trials: setup.check_trials,
        statistics: target_checks(setup.targets.targets(), &setup.targets.values(&set.results)),
        failures: set.failures,
    }
}

/// The search's description in the header: its kind and constants.
fn search_text(setup: &CalibrationSetup) -> String {
    match setup.optimizer {
        Optimizer::NelderMead => format!(
            "Nelder-Mead (argmin) on [0, 1]^d: initial step {INITIAL_STEP}, outside penalty \
             {OUTSIDE_PENALTY}, stall limit {STALL_LIMIT}"
        ),
        Optimizer::CmaEs => format!(
            "CMA-ES (fcmaes-core, active) on [0, 1]^d: population {}, initial step size \
             {INITIAL_SIGMA}, seed {}, +inf told as {INFINITE_LOSS:e}, stall limit {STALL_LIMIT}",
            population(setup.free.len()),
            setup.trial_plan.base_seed
        ),
    }
}

fn header_of(setup: &CalibrationSetup, checked: &Checked) -> Result<TraceHeader> {
    Ok(TraceHeader {
        format: TRACE_FORMAT,
        version: env!("CARGO_PKG_VERSION").to_string(),
        build: usar_sweep::data::software::software_build().to_owned(),
        scenario: checked.scenario.name().to_owned(),
        scenario_hash: scenario_hash(&checked.scenario).map_err(CalibrationError::Serialise)?,
        targets: setup.targets.targets().to_vec(),
        free: setup.free.clone(),
        methods: checked.methods.clone(),
        trials: setup.trial_plan.trials,
        base_seed: setup.trial_plan.base_seed,
        duration_s: setup.trial_plan.duration_s,
        digits: setup.digits,
        search: match (&setup.start, setup.start_mid) {
            (Some(start), _) => format!(
                "{}; start: {}",
                search_text(setup),
                start
                    .iter()
                    .map(|x| format!("{x:?}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            ),
            (None, true) => format!("{}; start: the ranges' middles", search_text(setup)),
            (None, false) => search_text(setup),
        },
    })
}

/// Opens the trace in `dir` for the calibration with `header`: a new one, or the same
/// calibration's (its verified evaluations returned). With `overwrite`, a trace there and
/// the outputs beside it are removed first.
fn open_trace(
    dir: &Path,
    header: &TraceHeader,
    overwrite: bool,
) -> Result<(Trace, Vec<Evaluation>)> {
    let path = Trace::path_in(dir);
    if overwrite {
        clear(dir)?;
    } else if holds_no_line(&path) {
        // An empty trace, or one killed while it wrote its header, holds nothing to lose.
        remove_named(dir, &[super::trace::TRACE_FILE])?;
    }
    if !something_at(&path) {
        return Ok((Trace::create(dir, header)?, Vec::new()));
    }
    if !path.is_file() {
        return Err(CalibrationError::TraceNotAFile {
            path: path_text(&path),
        });
    }
    let contents = read_trace(&path)?;
    if &contents.header != header {
        return Err(CalibrationError::OtherCalibration {
            path: path_text(&path),
            diff: header_diff(&contents.header, header),
        });
    }
    for line in &contents.rejected {
        tracing::warn!(
            "{}:{line}: evaluation does not verify (edited?); its point runs again if the \
             search comes to it",
            path_text(&path)
        );
    }
    let trace = Trace::resume(&path, &contents)?;
    Ok((trace, contents.evaluations))
}
