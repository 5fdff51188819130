//! A sweep: every grouping method for every trial of a scenario, in parallel, with a journal
//! that makes it resumable, then `trials.csv`, `summary.csv`, the figures and `report.md`.
//!
//! Trial `k` of every method starts from the same team (seed `trial_seed(base_seed, k)`:
//! common random numbers). Each finished trial is appended to the journal
//! ([`crate::journal`]) as soon as it ends; `--resume` reruns only trials with no successful
//! record. The output files are built from the journal's records alone, sorted by method
//! order then trial, so they do not depend on thread count, completion order or
//! interruptions.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

use anyhow::{Context, Result, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};
use rayon::prelude::*;
use rne_core::grouping::{GroupingMethod, method_from_name};
use rne_core::{TrustModel, Weights};
use usar_sim::mission::{Simulation, TrialResult, trial_seed};
use usar_sim::scenario::Scenario;

use crate::atomic::write_atomic;
use crate::figures::{FIGURES, figure_svg};
use crate::journal::{JOURNAL_FORMAT, Journal, Outcome, SweepHeader, TrialRecord, fnv1a64_hex};
use crate::report::{ReportInput, report_md};
use crate::summary::{summary_csv, trials_csv};

/// Exit status of a sweep stopped on purpose by [`TestHooks::stop_after`].
pub const STOP_EXIT_CODE: i32 = 75;

/// Steps between two progress-bar updates from a running trial.
const PROGRESS_EVERY_STEPS: u64 = 50;

/// Hooks for tests: make trials fail and simulate a kill.
#[derive(Debug, Clone, Default)]
pub struct TestHooks {
    /// Trials that panic on purpose: (method, upper case; trial index).
    pub fail: Vec<(String, u32)>,
    /// Exit the process abruptly (status [`STOP_EXIT_CODE`], no output files) once this many
    /// trials have been journaled by this run; trials still running are lost, as in a kill.
    pub stop_after: Option<usize>,
}

/// Builds a grouping method from its name, once per trial (methods need not be `Clone` and
/// are never shared between threads). [`MethodFactory::builtin`] knows `rne`, `dis`, `eng` and
/// `hp_dis`; wrap it to add methods of your own without touching the sweep:
///
/// ```
/// use experiments::sweep::MethodFactory;
/// use rne_core::grouping::{Eng, GroupingMethod};
///
/// // `my_eng` is ENG under another name; anything else falls back to the built-ins.
/// let factory = MethodFactory::new(|name, model| match name {
///     "my_eng" => Ok(Box::new(Eng) as Box<dyn GroupingMethod>),
///     other => MethodFactory::builtin().build(other, model),
/// });
/// let model = rne_core::TrustModel::with_weights(rne_core::Weights::uniform(7)?);
/// assert_eq!(factory.build("my_eng", &model)?.name(), "eng");
/// assert_eq!(factory.build("dis", &model)?.name(), "dis");
/// # Ok::<(), rne_core::RneError>(())
/// ```
#[derive(Clone)]
pub struct MethodFactory(Arc<MethodBuilder>);

/// The function behind a [`MethodFactory`].
type MethodBuilder =
    dyn Fn(&str, &TrustModel) -> rne_core::Result<Box<dyn GroupingMethod>> + Send + Sync;

impl MethodFactory {
    /// A factory from a function `(name, RNE trust model of the scenario) -> method`.
    pub fn new(
        f: impl Fn(&str, &TrustModel) -> rne_core::Result<Box<dyn GroupingMethod>>
        + Send
        + Sync
        + 'static,
    ) -> Self {
        Self(Arc::new(f))
    }

    /// The built-in methods, by [`method_from_name`].
    pub fn builtin() -> Self {
        Self::new(method_from_name)
    }

    /// Builds the method called `name`.
    ///
    /// # Errors
    /// Whatever the factory reports for an unknown name (the built-ins list the valid names).
    pub fn build(
        &self,
        name: &str,
        model: &TrustModel,
    ) -> rne_core::Result<Box<dyn GroupingMethod>> {
        (self.0)(name, model)
    }
}

impl Default for MethodFactory {
    fn default() -> Self {
        Self::builtin()
    }
}

impl std::fmt::Debug for MethodFactory {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str("MethodFactory")
    }
}

/// Everything a sweep needs.
#[derive(Debug, Clone)]
pub struct SweepConfig {
    /// The scenario.
    pub scenario: Scenario,
    /// Path the scenario was loaded from (for the report).
    pub scenario_path: PathBuf,
    /// Method names as accepted by `method_factory` (built-ins: `rne`, `dis`, `eng`,
    /// `hp_dis`).
    pub methods: Vec<String>,
    /// Builds each trial's grouping method from its name (default: the built-ins).
    pub method_factory: MethodFactory,
    /// Trials per method.
    pub trials: u32,
    /// Base seed.
    pub base_seed: u64,
    /// Simulated length of each trial, seconds.
    pub duration_s: f64,
    /// Worker threads (>= 1).
    pub threads: usize,
    /// Output folder.
    pub out_dir: PathBuf,
    /// Continue the journal in `out_dir`.
    pub resume: bool,
    /// Discard an existing journal in `out_dir` and start afresh.
    pub overwrite: bool,
    /// Show a progress bar (only drawn on a terminal).
    pub progress: bool,
    /// Test hooks.
    pub hooks: TestHooks,
}

/// A trial that failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// Method, upper case.
    pub method: String,
    /// Trial index.
    pub trial: u32,
    /// The trial's seed.
    pub seed: u64,
    /// The error or panic message.
    pub message: String,
}

/// What a sweep produced.
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    /// The journal header (the sweep's parameters).
    pub header: SweepHeader,
    /// Successful trials, sorted by method order then trial.
    pub results: Vec<TrialResult>,
    /// Failed trials, in the same order.
    pub failures: Vec<Failure>,
    /// Trials run by this invocation.
    pub ran: usize,
    /// Trials taken from the journal of an earlier run.
    pub reused: usize,
    /// Wall-clock time of this invocation's trials, seconds.
    pub wall_s: f64,
    /// Sum of the wall-clock times of this invocation's trials, seconds (CPU-ish time).
    pub trial_wall_sum_s: f64,
    /// Threads used.
    pub threads: usize,
    /// Files written, in order.
    pub files: Vec<PathBuf>,
}

impl SweepOutcome {
    /// Simulated seconds run by this invocation.
    pub fn simulated_s(&self) -> f64 {
        self.ran as f64 * self.header.duration_s
    }
}

/// Canonical (upper-case) name of a method, as `TrialResult::method` spells it.
///
/// # Errors
/// An unknown method name.
pub fn canonical_method(name: &str, factory: &MethodFactory, model: &TrustModel) -> Result<String> {
    let m = factory
        .build(name, model)
        .with_context(|| format!("method {name:?}"))?;
    Ok(m.name().to_ascii_uppercase())
}

/// The RNE trust model of `scenario` (its `needs_weights`).
///
/// # Errors
/// Weights rne-core rejects.
pub fn trust_model(scenario: &Scenario) -> Result<TrustModel> {
    let weights =
        Weights::new(scenario.needs_weights.to_vec()).context("scenario needs_weights")?;
    Ok(TrustModel::with_weights(weights))
}

/// The sweep's header: its parameters as recorded in the journal.
///
/// # Errors
/// An unknown method, or a scenario that cannot be serialised.
pub fn header_of(cfg: &SweepConfig) -> Result<SweepHeader> {
    let json = serde_json::to_vec(&cfg.scenario).context("serialising the scenario")?;
    let model = trust_model(&cfg.scenario)?;
    Ok(SweepHeader {
        format: JOURNAL_FORMAT,
        version: env!("CARGO_PKG_VERSION").to_string(),
        scenario: cfg.scenario.name.clone(),
        scenario_hash: fnv1a64_hex(&json),
        methods: cfg
            .methods
            .iter()
            .map(|m| canonical_method(m, &cfg.method_factory, &model))
            .collect::<Result<_>>()?,
        trials: cfg.trials,
        base_seed: cfg.base_seed,
        duration_s: cfg.duration_s,
    })
}

/// One job: a method and a trial index.
#[derive(Debug, Clone)]
struct Job {
    method_arg: String,
    method: String,
    trial: u32,
    seed: u64,
}

/// Runs one trial, turning errors and panics into `Err(message)`. `tick(n)` is called every
/// [`PROGRESS_EVERY_STEPS`] steps with the number of steps just taken.
fn run_trial(
    scenario: &Scenario,
    factory: &MethodFactory,
    model: &TrustModel,
    job: &Job,
    duration_s: f64,
    fail: bool,
    tick: &(dyn Fn(u64) + Sync),
) -> Result<TrialResult, String> {
    let body = || -> Result<TrialResult, String> {
        let method = factory
            .build(&job.method_arg, model)
            .map_err(|e| e.to_string())?;
        let mut sim = Simulation::new(scenario, method, job.seed).with_duration_s(duration_s);
        let mut last = 0u64;
        while !sim.is_finished() {
            sim.step()
                .map_err(|e| format!("at t = {:.2} s: {e}", sim.time_s()))?;
            let (done, total) = sim.progress();
            if fail && done * 2 >= total {
                panic!(
                    "failing on purpose (--fail-trial {}:{})",
                    job.method, job.trial
                );
            }
            if done - last >= PROGRESS_EVERY_STEPS {
                tick(done - last);
                last = done;
            }
        }
        tick(sim.progress().0 - last);
        let mut result = sim.result();
        result.trial = job.trial;
        Ok(result)
    };
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(r) => r,
        Err(payload) => {
            let msg = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic payload".to_string());
            Err(format!("panicked: {msg}"))
        }
    }
}

fn progress_bar(cfg: &SweepConfig, trials: usize, steps_per_trial: u64) -> ProgressBar {
    let draw = cfg.progress && std::io::IsTerminal::is_terminal(&std::io::stderr());
    if !draw {
        return ProgressBar::hidden();
    }
    let dt = cfg.scenario.sim.dt_s;
    let pb = ProgressBar::with_draw_target(
        Some(trials as u64 * steps_per_trial),
        ProgressDrawTarget::stderr(),
    );
    let style = ProgressStyle::with_template(
        "{elapsed_precise} [{bar:32.cyan/blue}] {msg}, {simrate}, ETA {eta}",
    )
    .unwrap_or_else(|_| ProgressStyle::default_bar())
    .with_key(
        "simrate",
        move |s: &ProgressState, w: &mut dyn std::fmt::Write| {
            let _ = write!(w, "{:.0} sim-s/s", s.per_sec() * dt);
        },
    )
    .progress_chars("=> ");
    pb.set_style(style);
    pb.set_message(format!("0/{trials} trials"));
    pb.enable_steady_tick(std::time::Duration::from_millis(250));
    pb
}

/// Runs the sweep and writes its files into `cfg.out_dir`. Failed trials do not stop it: they
/// are journaled and listed in [`SweepOutcome::failures`] (the caller decides the exit status).
///
/// # Errors
/// Bad parameters, a journal that cannot be started or resumed, or an I/O error writing the
/// journal or the output files.
pub fn run_sweep(cfg: &SweepConfig) -> Result<SweepOutcome> {
    if cfg.trials == 0 {
        bail!("--trials must be at least 1");
    }
    if cfg.methods.is_empty() {
        bail!("--methods needs at least one method");
    }
    if !(cfg.duration_s.is_finite() && cfg.duration_s > 0.0) {
        bail!(
            "--duration: expected a number of seconds > 0, found {}",
            cfg.duration_s
        );
    }
    let header = header_of(cfg)?;
    {
        let mut seen = header.methods.clone();
        seen.sort();
        seen.dedup();
        if seen.len() != header.methods.len() {
            bail!(
                "--methods lists a method twice: {}",
                header.methods.join(",")
            );
        }
    }
    for (m, k) in &cfg.hooks.fail {
        if !header.methods.contains(m) || *k >= cfg.trials {
            bail!("--fail-trial {m}:{k} names no trial of this sweep");
        }
    }
    let model = trust_model(&cfg.scenario)?;

    let journal_path = Journal::path_in(&cfg.out_dir);
    let (journal, previous) = if cfg.resume && journal_path.exists() {
        Journal::open_resume(&cfg.out_dir, &header)?
    } else {
        if journal_path.exists() {
            if cfg.overwrite {
                std::fs::remove_file(&journal_path)
                    .with_context(|| format!("removing {}", journal_path.display()))?;
            } else {
                bail!(
                    "{} already exists: pass --resume to continue that sweep, or --overwrite \
                     to start afresh (or choose another --out)",
                    journal_path.display()
                );
            }
        }
        (Journal::create(&cfg.out_dir, &header)?, Vec::new())
    };

    // Last record per (method, trial) wins.
    let slot = |method: &str, trial: u32| -> Option<usize> {
        let mi = header.methods.iter().position(|m| m == method)?;
        (trial < cfg.trials).then(|| mi * cfg.trials as usize + trial as usize)
    };
    let n_slots = header.methods.len() * cfg.trials as usize;
    let mut records: Vec<Option<TrialRecord>> = vec![None; n_slots];
    for r in previous {
        if let Some(i) = slot(&r.method, r.trial) {
            records[i] = Some(r);
        }
    }
    let reused = records
        .iter()
        .filter(|r| {
            matches!(
                r,
                Some(TrialRecord {
                    outcome: Outcome::Ok(_),
                    ..
                })
            )
        })
        .count();

    // Jobs trial-major, so a partial sweep has every method on the first trials.
    let mut jobs = Vec::new();
    for trial in 0..cfg.trials {
        for (arg, method) in cfg.methods.iter().zip(&header.methods) {
            let i = slot(method, trial).unwrap_or(usize::MAX);
            if matches!(
                records.get(i),
                Some(Some(TrialRecord {
                    outcome: Outcome::Ok(_),
                    ..
                }))
            ) {
                continue;
            }
            jobs.push(Job {
                method_arg: arg.clone(),
                method: method.clone(),
                trial,
                seed: trial_seed(cfg.base_seed, trial),
            });
        }
    }

    let threads = cfg.threads.max(1);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .context("starting the thread pool")?;
    let scenario = &cfg.scenario;
    let steps_per_trial = (cfg.duration_s / scenario.sim.dt_s).ceil().max(0.0) as u64;
    let pb = progress_bar(cfg, jobs.len(), steps_per_trial);
    let journal = Mutex::new(journal);
    let new_records: Mutex<Vec<TrialRecord>> = Mutex::new(Vec::new());
    let journal_error: Mutex<Option<anyhow::Error>> = Mutex::new(None);
    let abort = AtomicBool::new(false);
    let done = AtomicUsize::new(0);
    let n_jobs = jobs.len();
    let start = Instant::now();
    pool.install(|| {
        jobs.par_iter().for_each(|job| {
            if abort.load(Ordering::SeqCst) {
                return;
            }
            let fail = cfg
                .hooks
                .fail
                .iter()
                .any(|(m, k)| *m == job.method && *k == job.trial);
            let t0 = Instant::now();
            let outcome = run_trial(
                scenario,
                &cfg.method_factory,
                &model,
                job,
                cfg.duration_s,
                fail,
                &|n| {
                    pb.inc(n);
                },
            );
            let record = TrialRecord {
                method: job.method.clone(),
                trial: job.trial,
                seed: job.seed,
                wall_s: t0.elapsed().as_secs_f64(),
                outcome: match outcome {
                    Ok(r) => Outcome::Ok(Box::new(r)),
                    Err(msg) => Outcome::Failed(msg),
                },
            };
            let mut j = journal
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner);
            if let Err(e) = j.append(&record) {
                abort.store(true, Ordering::SeqCst);
                journal_error
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner)
                    .get_or_insert(e);
                return;
            }
            let n = done.fetch_add(1, Ordering::SeqCst) + 1;
            if let Outcome::Failed(msg) = &record.outcome {
                pb.suspend(|| {
                    eprintln!(
                        "trial {} #{} (seed {}) failed: {msg}",
                        record.method, record.trial, record.seed
                    );
                });
            }
            pb.set_message(format!("{n}/{n_jobs} trials"));
            if cfg.hooks.stop_after.is_some_and(|s| n >= s) {
                pb.suspend(|| eprintln!("--stop-after {n}: stopping abruptly"));
                std::process::exit(STOP_EXIT_CODE);
            }
            drop(j);
            new_records
                .lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .push(record);
        });
    });
    pb.finish_and_clear();
    let wall_s = start.elapsed().as_secs_f64();
    if let Some(e) = journal_error
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
    {
        return Err(e.context("the journal could not be written; the sweep stopped"));
    }
    let new_records = new_records
        .into_inner()
        .unwrap_or_else(std::sync::PoisonError::into_inner);
    let ran = new_records.len();
    let trial_wall_sum_s = new_records.iter().map(|r| r.wall_s).sum();
    for r in new_records {
        if let Some(i) = slot(&r.method, r.trial) {
            records[i] = Some(r);
        }
    }

    let mut results = Vec::new();
    let mut failures = Vec::new();
    for r in records.into_iter().flatten() {
        match r.outcome {
            Outcome::Ok(res) => results.push(*res),
            Outcome::Failed(message) => failures.push(Failure {
                method: r.method,
                trial: r.trial,
                seed: r.seed,
                message,
            }),
        }
    }

    let mut outcome = SweepOutcome {
        header,
        results,
        failures,
        ran,
        reused,
        wall_s,
        trial_wall_sum_s,
        threads,
        files: Vec::new(),
    };
    outcome.files = write_outputs(cfg, &outcome)?;
    Ok(outcome)
}

/// Writes `trials.csv`, `summary.csv`, the figures and `report.md` atomically into
/// `cfg.out_dir`; returns their paths.
fn write_outputs(cfg: &SweepConfig, o: &SweepOutcome) -> Result<Vec<PathBuf>> {
    let dir = &cfg.out_dir;
    let methods = &o.header.methods;
    let mut files = Vec::new();
    let mut put = |name: &str, bytes: &[u8]| -> Result<()> {
        let p = dir.join(name);
        write_atomic(&p, bytes)?;
        files.push(p);
        Ok(())
    };
    put("trials.csv", &trials_csv(&o.results)?)?;
    put("summary.csv", &summary_csv(&o.results, methods)?)?;
    for spec in &FIGURES {
        put(spec.file, figure_svg(spec, &o.results, methods)?.as_bytes())?;
    }
    let report = report_md(&ReportInput {
        scenario: &cfg.scenario,
        scenario_path: &cfg.scenario_path,
        outcome: o,
    });
    put("report.md", report.as_bytes())?;
    Ok(files)
}

/// Default output folder for a scenario: `results/<scenario name>/`.
pub fn default_out_dir(scenario: &Scenario) -> PathBuf {
    Path::new("results").join(&scenario.name)
}
