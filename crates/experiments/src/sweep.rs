//! A sweep: every grouping method for every trial of every grid cell, in parallel, with a
//! journal that makes it resumable. [`run_sweep`] runs and returns data only; the analysis
//! ([`crate::analysis`]) judges it and [`crate::output`] writes the files.
//!
//! A sweep without `--vary` is a grid of one cell, the scenario itself. Trial `k` of every
//! method and every cell starts from the same team (seed `trial_seed(base_seed, k)`: common
//! random numbers). Each finished trial is appended to the journal ([`crate::journal`]) as soon
//! as it ends; a resume reruns only trials with no successful record. All jobs of all cells
//! go through one thread pool; results are sorted by cell, method order and trial, so they do
//! not depend on thread count, completion order or interruptions.

use std::collections::HashSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use usar_sim::mission::{TrialResult, trial_seed};
use usar_sim::scenario::{Scenario, path_text, trial_steps};

use crate::atomic::remove_stale_temps;
use crate::executor::{CellPlan, Job, Runner, execute};
pub use crate::executor::{JournaledHook, SweepHooks, TrialKey, TrialObserverFactory};
use crate::fingerprint::scenario_hash;
use crate::grid::Grid;
use crate::lock::OutputLock;
pub use crate::method_factory::{MethodFactory, canonical_method, trust_model};
use crate::shard::{ShardRun, shard_dir};
use crate::stale_outputs::remove_previous_outputs;

use crate::journal::{
    CellHeader, GridHeader, JOURNAL_FORMAT, Journal, JournalContents, Outcome, RejectedRecord,
    SweepHeader, TrialRecord, header_diff, holds_no_line, other_sweeps, read_header, something_at,
};

/// Everything a sweep needs. [`SweepConfig::new`] gives the defaults of `usar sweep`; set
/// the fields that differ:
///
/// ```no_run
/// use experiments::sweep::{SweepConfig, run_sweep};
///
/// let scenario = usar_sim::scenario::load("scenarios/paper.ron")?;
/// let cfg = SweepConfig {
///     methods: vec!["rne".into(), "dis".into()],
///     trials: 2,
///     ..SweepConfig::new(scenario, "scenarios/paper.ron")
/// };
/// let outcome = run_sweep(&cfg)?;
/// assert_eq!(outcome.cells[0].results.len(), 4);
/// # Ok::<(), anyhow::Error>(())
/// ```
#[derive(Debug, Clone)]
pub struct SweepConfig {
    /// The scenario (with a grid: the base scenario the cells vary).
    pub scenario: Scenario,
    /// Path the scenario was loaded from (for the reports).
    pub scenario_path: PathBuf,
    /// The grid of `--vary`; `None` sweeps `scenario` alone, into `out_dir` itself.
    pub grid: Option<Grid>,
    /// Method names as accepted by `method_factory` (built-ins: `rne`, `dis`, `eng`,
    /// `hp_dis`).
    pub methods: Vec<String>,
    /// Builds each trial's grouping method from its name (default: the built-ins).
    pub method_factory: MethodFactory,
    /// Trials per method and cell (>= 1).
    pub trials: u32,
    /// Base seed (the same for every cell).
    pub base_seed: u64,
    /// Simulated length of each trial, seconds (> 0); `None`: each cell's
    /// `mission.duration_s`.
    pub duration_s: Option<f64>,
    /// Worker threads (>= 1); a sweep uses at most [`max_threads`] and never more than it
    /// has jobs to run ([`effective_threads`]).
    pub threads: usize,
    /// Output folder; the journal is at its top.
    pub out_dir: PathBuf,
    /// Continue the journal in `out_dir` (refused if it has other parameters).
    pub resume: bool,
    /// Discard an existing journal in `out_dir` and the earlier sweep's output files
    /// ([`crate::stale_outputs::remove_previous_outputs`]) and start afresh.
    pub overwrite: bool,
    /// Show a progress bar (only drawn on a terminal).
    pub progress: bool,
    /// Extension points: a step observer per trial, a call per journaled record (default
    /// none).
    pub hooks: SweepHooks,
    /// Run one shard of the sweep only (`--shard I/N`, default `None`): its jobs
    /// ([`crate::shard::Shard::jobs`]), into the journal of its folder under `out_dir`
    /// ([`shard_dir`]), with the plan beside it.
    pub shard: Option<ShardRun>,
}

impl SweepConfig {
    /// The defaults of `usar sweep` for `scenario`: no grid, the four built-in methods, 10
    /// trials, the scenario's `sim.seed` as base seed, each cell's `mission.duration_s`, all
    /// cores, output folder `results/<scenario name>/`, no resume or overwrite, a progress
    /// bar, no hooks.
    pub fn new(scenario: Scenario, scenario_path: impl Into<PathBuf>) -> Self {
        Self {
            scenario_path: scenario_path.into(),
            grid: None,
            methods: rne_core::grouping::METHOD_NAMES
                .iter()
                .map(|m| m.to_string())
                .collect(),
            method_factory: MethodFactory::builtin(),
            trials: 10,
            base_seed: scenario.sim.seed,
            duration_s: None,
            threads: std::thread::available_parallelism().map_or(1, usize::from),
            out_dir: default_out_dir(&scenario),
            resume: false,
            overwrite: false,
            progress: true,
            hooks: SweepHooks::default(),
            shard: None,
            scenario,
        }
    }

    /// The scenario of each cell, in cell order: the grid's, or `scenario` alone.
    pub fn cell_scenarios(&self) -> Vec<&Scenario> {
        match &self.grid {
            Some(g) => g.cells.iter().map(|c| &c.scenario).collect(),
            None => vec![&self.scenario],
        }
    }

    /// The trial length of a cell with `scenario`: `duration_s` or its `mission.duration_s`.
    pub fn duration_of(&self, scenario: &Scenario) -> f64 {
        self.duration_s.unwrap_or(scenario.mission.duration_s.get())
    }

    /// The simulated length of each trial of a cell with `scenario`, seconds: its
    /// [`SweepConfig::duration_of`] run as whole steps ([`simulated_length_s`]).
    pub fn simulated_length_of(&self, scenario: &Scenario) -> f64 {
        simulated_length_s(self.duration_of(scenario), scenario.sim.dt_s.get())
    }

    /// The folder of the journal (and the lock): `out_dir`, or the shard's folder under it.
    pub fn journal_dir(&self) -> PathBuf {
        match &self.shard {
            Some(s) => shard_dir(&self.out_dir, s.shard),
            None => self.out_dir.clone(),
        }
    }
}

/// A trial that failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// Grid cell index.
    pub cell: usize,
    /// Method, upper case.
    pub method: String,
    /// Trial index.
    pub trial: u32,
    /// The trial's seed.
    pub seed: u64,
    /// The error or panic message.
    pub message: String,
}

/// What a sweep produced in one grid cell.
#[derive(Debug, Clone, Default)]
pub struct CellOutcome {
    /// Successful trials, sorted by method order then trial.
    pub results: Vec<TrialResult>,
    /// Failed trials, in the same order.
    pub failures: Vec<Failure>,
    /// Trials of this cell run by this invocation.
    pub ran: usize,
    /// Successful trials of this cell taken from the journal of an earlier run.
    pub reused: usize,
    /// Sum of the wall-clock times of this invocation's trials of this cell, seconds.
    pub trial_wall_sum_s: f64,
}

/// How the sweep came by its journal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JournalUse {
    /// A new journal (none was there, or `--overwrite` removed it).
    Created,
    /// `--resume` continued the journal.
    Resumed,
    /// A journal with the same parameters was there and was continued as with `--resume`
    /// (running the same command twice).
    Reused,
    /// The records come from the journals of the sweep's shards (`usar merge`,
    /// [`crate::shard::merge_shards`]).
    Merged,
}

/// What a sweep produced: data only (see [`crate::analysis`] and [`crate::output`]).
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    /// The journal header (the sweep's parameters and grid).
    pub header: SweepHeader,
    /// Per grid cell, in cell order.
    pub cells: Vec<CellOutcome>,
    /// How the journal was come by.
    pub journal: JournalUse,
    /// Trials run by this invocation.
    pub ran: usize,
    /// Successful trials taken from the journal of an earlier run.
    pub reused: usize,
    /// Wall-clock time of this invocation's trials, seconds.
    pub wall_s: f64,
    /// Sum of the wall-clock times of this invocation's trials, seconds (CPU-ish time).
    pub trial_wall_sum_s: f64,
    /// Threads used ([`effective_threads`]).
    pub threads: usize,
    /// The lock on the output folder ([`crate::lock`]), held while this outcome (or a clone of
    /// it) lives, so that the files written from it are written under the same lock.
    pub lock: Arc<OutputLock>,
}

impl SweepOutcome {
    /// Simulated seconds run by this invocation.
    pub fn simulated_s(&self) -> f64 {
        self.cells
            .iter()
            .zip(&self.header.grid.cells)
            .map(|(c, h)| c.ran as f64 * h.duration_s)
            .sum()
    }

    /// Every failed trial, by cell, method order and trial.
    pub fn failures(&self) -> impl Iterator<Item = &Failure> {
        self.cells.iter().flat_map(|c| &c.failures)
    }

    /// Trials the sweep has in all: cells x methods x trials.
    pub fn expected_trials(&self) -> usize {
        self.header.grid.cells.len() * self.header.methods.len() * self.header.trials as usize
    }
}

/// Most worker threads per available core: a sweep never runs more than
/// `MAX_THREADS_PER_CORE` x [`std::thread::available_parallelism`] threads ([`max_threads`]).
pub const MAX_THREADS_PER_CORE: usize = 4;

/// The most worker threads a sweep uses on this machine: [`MAX_THREADS_PER_CORE`] x the
/// available parallelism (1 when that is unknown).
pub fn max_threads() -> usize {
    MAX_THREADS_PER_CORE * std::thread::available_parallelism().map_or(1, usize::from)
}

/// The worker threads a sweep with `jobs` jobs to run uses when `requested` threads are asked
/// for: at least 1, at most `max` (see [`max_threads`]) and at most `jobs`.
pub fn effective_threads(requested: usize, max: usize, jobs: usize) -> usize {
    requested.min(max).min(jobs).max(1)
}

/// Most trials one sweep may hold: grid cells x methods x trials, all shards together
/// (1,000,000). A sweep keeps a few hundred bytes per trial in memory (its job list, records
/// and tables), so the limit keeps a mistyped `--trials` a one-line error instead of an
/// allocation failure; a larger study is several sweeps (for example one per `--seed`).
pub const MAX_SWEEP_TRIALS: usize = 1_000_000;

/// Refuses a sweep of more than [`MAX_SWEEP_TRIALS`] trials (grid cells x methods x trials),
/// or split into more shards (`--shard I/N`) than it has trials, with a one-line error;
/// cheap, so a caller can check before any other work.
///
/// # Errors
/// The count and the limit, when the count is above it; see [`check_shard_count`].
pub fn check_trial_count(cfg: &SweepConfig) -> Result<()> {
    let cells = cfg.grid.as_ref().map_or(1, |g| g.cells.len());
    let total = trial_count(cfg);
    if let Some(s) = &cfg.shard {
        check_shard_count(
            &format!("--shard {}/{}", s.shard.index, s.shard.count),
            s.shard.count,
            total,
        )?;
    }
    check_sweep_size(cells, cfg.methods.len(), cfg.trials)
}

/// Refuses the sweep of `--vary` arguments `vary` x `methods` methods x `trials` trials above
/// [`MAX_SWEEP_TRIALS`] before its grid is built: the cells are counted from the value lists
/// ([`crate::grid::Grid::cell_count`]), none is made. `usar sweep` and `usar slurm` call it
/// before [`crate::grid::Grid::build`].
///
/// # Errors
/// A malformed `--vary` argument, or the counts and the limit when the sweep is above it.
pub fn check_grid_size(vary: &[String], methods: usize, trials: u32) -> Result<()> {
    check_sweep_size(crate::grid::Grid::cell_count(vary)?, methods, trials)
}

/// Refuses `cells` grid cells x `methods` methods x `trials` trials (saturating) above
/// [`MAX_SWEEP_TRIALS`]: the check of [`check_trial_count`] and [`check_grid_size`].
///
/// # Errors
/// The three counts, their product and the limit, when the product is above it.
pub fn check_sweep_size(cells: usize, methods: usize, trials: u32) -> Result<()> {
    let total = cells
        .saturating_mul(methods)
        .saturating_mul(trials as usize);
    if total > MAX_SWEEP_TRIALS {
        bail!(
            "the sweep's {cells} cell(s) x {methods} method(s) x {trials} trials make {total} \
             trials, more than the limit of {MAX_SWEEP_TRIALS} per sweep"
        );
    }
    Ok(())
}

/// The sweep's trials in all shards together: grid cells x methods x trials (saturating).
pub fn trial_count(cfg: &SweepConfig) -> usize {
    let cells = cfg.grid.as_ref().map_or(1, |g| g.cells.len());
    cells
        .saturating_mul(cfg.methods.len())
        .saturating_mul(cfg.trials as usize)
}

/// Refuses a split into more shards than the sweep has trials (`total`): a shard without a
/// trial would be one more job to run, and to wait for, with nothing to do. `option` names
/// the flag in the message (`--shard 3/50`, `--shards 50`).
///
/// # Errors
/// `shards > total`, naming the most shards the sweep can use.
pub fn check_shard_count(option: &str, shards: usize, total: usize) -> Result<()> {
    if shards > total {
        bail!(
            "{option}: the sweep has {total} trial(s), so at most {total} shards have work; \
             split it into at most {total}"
        );
    }
    Ok(())
}

/// The sweep's header: its parameters and grid as recorded in the journal.
///
/// # Errors
/// An unknown method, a scenario that cannot be serialised, or more than
/// [`MAX_SWEEP_TRIALS`] trials in all.
pub fn header_of(cfg: &SweepConfig) -> Result<SweepHeader> {
    check_trial_count(cfg)?;
    let model = trust_model(&cfg.scenario)?;
    let values: Vec<Vec<String>> = match &cfg.grid {
        Some(g) => g.cells.iter().map(|c| c.values()).collect(),
        None => vec![Vec::new()],
    };
    let cells = cfg
        .cell_scenarios()
        .into_iter()
        .zip(values)
        .map(|(s, values)| {
            Ok(CellHeader {
                values,
                scenario_hash: scenario_hash(s)?,
                duration_s: cfg.duration_of(s),
                tasks: s.task_names(),
                hardest_first: s.hardest_first(),
            })
        })
        .collect::<Result<_>>()?;
    Ok(SweepHeader {
        format: JOURNAL_FORMAT,
        version: env!("CARGO_PKG_VERSION").to_string(),
        build: crate::report::software_build().to_owned(),
        scenario: cfg.scenario.name.clone(),
        methods: cfg
            .methods
            .iter()
            .map(|m| canonical_method(m, &cfg.method_factory, &model))
            .collect::<Result<_>>()?,
        trials: cfg.trials,
        base_seed: cfg.base_seed,
        grid: GridHeader {
            fields: cfg.grid.as_ref().map(Grid::fields).unwrap_or_default(),
            cells,
        },
    })
}

/// One job of the sweep: indices of its cell and method, and its trial.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct JobId {
    /// Grid cell index.
    pub cell: usize,
    /// Index of the method in the sweep's method order.
    pub method: usize,
    /// Trial index.
    pub trial: u32,
}

/// Every job of a sweep of `cells` x `methods` x `trials`, in the canonical order jobs are
/// started in: trial-major, then cell, then method, so a partial sweep has every cell and
/// method on its first trials. [`crate::shard::Shard::jobs`] splits this list into shards.
pub fn job_list(cells: usize, methods: usize, trials: u32) -> Vec<JobId> {
    let mut jobs = Vec::with_capacity(cells * methods * trials as usize);
    for trial in 0..trials {
        for cell in 0..cells {
            for method in 0..methods {
                jobs.push(JobId {
                    cell,
                    method,
                    trial,
                });
            }
        }
    }
    jobs
}

/// Where the record of each job goes: one slot per (cell, method, trial).
struct Slots {
    methods: Vec<String>,
    cells: usize,
    trials: u32,
}

impl Slots {
    fn len(&self) -> usize {
        self.cells * self.methods.len() * self.trials as usize
    }

    fn of(&self, cell: usize, method: &str, trial: u32) -> Option<usize> {
        let m = self.methods.iter().position(|x| x == method)?;
        (cell < self.cells && trial < self.trials)
            .then(|| (cell * self.methods.len() + m) * self.trials as usize + trial as usize)
    }

    fn of_record(&self, r: &TrialRecord) -> Option<usize> {
        self.of(r.cell, &r.method, r.trial)
    }
}

/// Warns about each journal line of `dir` that does not verify, with what becomes of its
/// trial: it runs again, it is another shard's (`in_shard` holds this shard's jobs), or it is
/// no trial of this sweep. A line that a later record of its trial (one that verifies)
/// supersedes changes nothing and is not reported.
fn warn_rejected(
    dir: &Path,
    rejected: &[RejectedRecord],
    slots: &Slots,
    records: &[Option<TrialRecord>],
    in_shard: Option<&HashSet<JobId>>,
) {
    for r in rejected {
        let method = slots.methods.iter().position(|m| *m == r.method);
        let owned_elsewhere = |method| {
            let id = JobId {
                cell: r.cell,
                method,
                trial: r.trial,
            };
            in_shard.is_some_and(|own| !own.contains(&id))
        };
        let fate = match (slots.of(r.cell, &r.method, r.trial), method) {
            (Some(i), _) if is_ok(records[i].as_ref()) => continue,
            (Some(_), Some(m)) if owned_elsewhere(m) => {
                "is another shard's (the shard that owns it runs it)"
            }
            (Some(_), _) => "will run again",
            (None, _) => "is not used (no such trial in this sweep)",
        };
        crate::console::warn(format!(
            "warning: {}:{}: record does not verify (edited?); trial {} #{} of cell {} {fate}",
            path_text(&Journal::path_in(dir)),
            r.line,
            r.method,
            r.trial,
            r.cell,
        ));
    }
}

fn is_ok(r: Option<&TrialRecord>) -> bool {
    matches!(
        r,
        Some(TrialRecord {
            outcome: Outcome::Ok(_),
            ..
        })
    )
}

/// Refuses parameters no sweep can run with: `--trials 0`, no method or one twice, a cell
/// whose tasks differ from the scenario's, or a trial length (`--duration`) that is not a
/// positive number of seconds. `header` is [`header_of`] `cfg`. [`run_sweep`] checks this
/// first; `usar slurm` checks it before it writes the scripts.
///
/// # Errors
/// The first parameter that is refused, in one line naming its option.
pub fn check_config(cfg: &SweepConfig, header: &SweepHeader) -> Result<()> {
    if cfg.trials == 0 {
        bail!("--trials must be at least 1");
    }
    if cfg.methods.is_empty() {
        bail!("--methods needs at least one method");
    }
    let tasks = cfg.scenario.task_names();
    for s in cfg.cell_scenarios() {
        if s.task_names() != tasks {
            bail!(
                "--vary: every cell must have the scenario's tasks ({}); a cell has {}",
                tasks.join(", "),
                s.task_names().join(", ")
            );
        }
        if let Err(e) = trial_steps(cfg.duration_of(s), s.sim.dt_s.get()) {
            bail!("--duration: {e}");
        }
    }
    let mut seen = header.methods.clone();
    seen.sort();
    seen.dedup();
    if seen.len() != header.methods.len() {
        bail!(
            "--methods lists a method twice: {}",
            header.methods.join(",")
        );
    }
    Ok(())
}

/// A journal opened for a sweep, with what it already held.
struct OpenJournal {
    journal: Journal,
    /// Records that verify, in file order.
    records: Vec<TrialRecord>,
    /// Record lines that do not verify.
    rejected: Vec<RejectedRecord>,
    how: JournalUse,
}

impl OpenJournal {
    fn new(journal: Journal) -> Self {
        Self {
            journal,
            records: Vec::new(),
            rejected: Vec::new(),
            how: JournalUse::Created,
        }
    }

    fn continued((journal, contents): (Journal, JournalContents), how: JournalUse) -> Self {
        Self {
            journal,
            records: contents.records,
            rejected: contents.rejected,
            how,
        }
    }
}

/// Creates, resumes or reuses the journal in `dir`, with the records it holds.
fn open_journal(cfg: &SweepConfig, dir: &Path, header: &SweepHeader) -> Result<OpenJournal> {
    let path = Journal::path_in(dir);
    if holds_no_line(&path) {
        // An empty file, or a header cut short, holds no trial: nothing to resume or lose.
        std::fs::remove_file(&path).with_context(|| format!("removing {}", path_text(&path)))?;
    }
    if cfg.overwrite && !cfg.resume {
        // The earlier sweep's tables, figures and grid cells go with its journal.
        remove_previous_outputs(dir, &path)?;
        if something_at(&path) {
            std::fs::remove_file(&path)
                .with_context(|| format!("removing {}", path_text(&path)))?;
        }
        return Ok(OpenJournal::new(Journal::create(dir, header)?));
    }
    if !something_at(&path) {
        if cfg.shard.is_none() {
            refuse_other_sweeps_shards(dir, header)?;
        }
        return Ok(OpenJournal::new(Journal::create(dir, header)?));
    }
    if cfg.resume {
        let resumed = Journal::open_resume(dir, header)?;
        return Ok(OpenJournal::continued(resumed, JournalUse::Resumed));
    }
    let why = match read_header(&path) {
        Ok(found) if &found == header => {
            let resumed = Journal::open_resume(dir, header)?;
            return Ok(OpenJournal::continued(resumed, JournalUse::Reused));
        }
        Ok(found) if found.build != header.build => bail!(
            "{} already exists ({}): its trials cannot be continued by this build; pass \
             --overwrite to start afresh (or choose another --out, or run the build that \
             wrote it)",
            path_text(&path),
            header_diff(&found, header)
        ),
        Ok(found) => format!(
            "it was written with other parameters: {}",
            header_diff(&found, header)
        ),
        // It cannot be continued: its own message says how to start afresh.
        Err(e) => return Err(e),
    };
    bail!(
        "{} already exists ({why}): pass --resume to continue that sweep, or --overwrite to \
         start afresh (or choose another --out)",
        path_text(&path)
    )
}

/// Refuses to start a sweep in `dir` when a journal of its shards (`dir/shards/`, see
/// [`crate::shard`]) was written by another sweep: `usar merge` writes that sweep's files into
/// `dir`, and the two would mix. `--overwrite` removes those files instead
/// ([`remove_previous_outputs`]).
fn refuse_other_sweeps_shards(dir: &Path, header: &SweepHeader) -> Result<()> {
    for (_, shard) in crate::shard::shard_folders(dir)? {
        let path = Journal::path_in(&shard);
        if let Some(why) = other_sweeps(&path, header) {
            bail!(
                "{} is a shard's journal of another sweep ({why}), whose merge writes its files \
                 into {}: pass --overwrite to start afresh there (the merged files go, the \
                 shards stay), or choose another --out",
                path_text(&path),
                path_text(dir)
            );
        }
    }
    Ok(())
}

/// Runs the sweep (every job without a successful record in the journal) and returns its
/// data. Failed trials do not stop it: they are journaled and listed in
/// [`CellOutcome::failures`] (the caller decides the exit status). No file but the journal
/// (and the lock file) is written.
///
/// Once the parameters are checked, it locks the output folder ([`OutputLock`]; the lock
/// stays in [`SweepOutcome::lock`]) and removes the temporary files killed runs left there and
/// in the cell folders ([`remove_stale_temps`]) before it opens the journal.
///
/// With [`SweepConfig::shard`] it runs only the shard's jobs, and the folder it locks, cleans
/// and journals into is the shard's ([`SweepConfig::journal_dir`]), where it also writes the
/// plan ([`crate::shard::SweepPlan`]) once the journal is open; the outcome holds the shard's
/// records only.
///
/// # Errors
/// Bad parameters, an output folder locked by another sweep, a journal that cannot be started
/// or resumed, or an I/O error writing the journal.
pub fn run_sweep(cfg: &SweepConfig) -> Result<SweepOutcome> {
    let header = header_of(cfg)?;
    check_config(cfg, &header)?;
    let plans = cfg
        .cell_scenarios()
        .into_iter()
        .zip(&header.grid.cells)
        .enumerate()
        .map(|(i, (scenario, h))| {
            let steps = trial_steps(h.duration_s, scenario.sim.dt_s.get())
                .map_err(|e| anyhow::anyhow!("--duration: {e}"))?;
            Ok(CellPlan {
                label: match &cfg.grid {
                    Some(g) => format!(" in cell {}", g.cells[i].dir),
                    None => String::new(),
                },
                scenario,
                model: trust_model(scenario)?,
                duration_s: h.duration_s,
                step_us: (scenario.sim.dt_s.get() * 1e6).round().max(1.0) as u64,
                steps_per_trial: steps,
            })
        })
        .collect::<Result<Vec<_>>>()?;
    let dir = cfg.journal_dir();
    let lock = OutputLock::acquire(&dir)?;
    remove_stale_temps(&dir)?;
    if let (Some(g), None) = (&cfg.grid, &cfg.shard) {
        for cell in &g.cells {
            remove_stale_temps(&cfg.out_dir.join(&cell.dir))?;
        }
    }
    let opened = open_journal(cfg, &dir, &header)?;
    if let Some(s) = &cfg.shard {
        s.plan.write(&dir)?;
    }
    let in_shard: Option<HashSet<JobId>> = cfg
        .shard
        .as_ref()
        .map(|s| s.shard.jobs(&header).into_iter().collect());

    let slots = Slots {
        methods: header.methods.clone(),
        cells: plans.len(),
        trials: cfg.trials,
    };
    // Last record per (cell, method, trial) wins.
    let mut records: Vec<Option<TrialRecord>> = vec![None; slots.len()];
    for r in opened.records {
        if let Some(i) = slots.of_record(&r) {
            records[i] = Some(r);
        }
    }
    warn_rejected(&dir, &opened.rejected, &slots, &records, in_shard.as_ref());
    let jobs: Vec<Job> = job_list(plans.len(), header.methods.len(), cfg.trials)
        .into_iter()
        .filter(|id| in_shard.as_ref().is_none_or(|own| own.contains(id)))
        .filter(|id| {
            let i = slots.of(id.cell, &header.methods[id.method], id.trial);
            !is_ok(i.and_then(|i| records[i].as_ref()))
        })
        .map(|id| Job {
            cell: id.cell,
            method_arg: cfg.methods[id.method].clone(),
            method: header.methods[id.method].clone(),
            trial: id.trial,
            seed: trial_seed(cfg.base_seed, id.trial),
        })
        .collect();

    let threads = effective_threads(cfg.threads, max_threads(), jobs.len());
    let start = Instant::now();
    let runner = Runner {
        factory: &cfg.method_factory,
        hooks: &cfg.hooks,
        progress: cfg.progress,
        threads,
    };
    let new_records = execute(&runner, &plans, &jobs, opened.journal)?;
    let wall_s = start.elapsed().as_secs_f64();
    let ran = new_records.len();
    let trial_wall_sum_s = new_records.iter().map(|r| r.wall_s).sum();
    let cells = collect(&slots, records, new_records);
    Ok(SweepOutcome {
        header,
        reused: cells.iter().map(|c| c.reused).sum(),
        cells,
        journal: opened.how,
        ran,
        wall_s,
        trial_wall_sum_s,
        threads,
        lock: Arc::new(lock),
    })
}

/// The per-cell outcomes of the sweep with `header` from journal `records` (in journal
/// order: the last record per `(cell, method, trial)` wins; records of no job of the sweep are
/// left out). Every successful record counts as reused ([`CellOutcome::reused`]).
pub(crate) fn cells_from_records(
    header: &SweepHeader,
    records: Vec<TrialRecord>,
) -> Vec<CellOutcome> {
    let slots = Slots {
        methods: header.methods.clone(),
        cells: header.grid.cells.len(),
        trials: header.trials,
    };
    let mut by_slot: Vec<Option<TrialRecord>> = vec![None; slots.len()];
    for r in records {
        if let Some(i) = slots.of_record(&r) {
            by_slot[i] = Some(r);
        }
    }
    collect(&slots, by_slot, Vec::new())
}

/// Sorts the journal's and this run's records into per-cell outcomes.
fn collect(
    slots: &Slots,
    mut records: Vec<Option<TrialRecord>>,
    new_records: Vec<TrialRecord>,
) -> Vec<CellOutcome> {
    let mut cells = vec![CellOutcome::default(); slots.cells];
    for r in &records {
        if let Some(r) = r.as_ref().filter(|r| is_ok(Some(r))) {
            cells[r.cell].reused += 1;
        }
    }
    for r in new_records {
        let cell = &mut cells[r.cell];
        cell.ran += 1;
        cell.trial_wall_sum_s += r.wall_s;
        if let Some(i) = slots.of_record(&r) {
            records[i] = Some(r);
        }
    }
    for r in records.into_iter().flatten() {
        let cell = &mut cells[r.cell];
        match r.outcome {
            Outcome::Ok(res) => cell.results.push(*res),
            Outcome::Failed(message) => cell.failures.push(Failure {
                cell: r.cell,
                method: r.method,
                trial: r.trial,
                seed: r.seed,
                message,
            }),
        }
    }
    cells
}

/// The simulated length of a trial asked to last `duration_s` at step `dt_s`, seconds: its
/// whole steps (`usar_sim::scenario::trial_steps`) times `dt_s`, or `duration_s` itself when
/// that is a whole number of steps (within 1e-9 relative: `600` stays `600`, not
/// `600.0000000000001`) or a length the sweep refuses anyway. `--duration 0.01` at the default
/// 0.02 s step runs 0.02 s. The product is rounded to 12 significant digits, so that it prints
/// as the steps' length (`0.7`, not `0.7000000000000001`, for 35 steps of 0.02 s).
pub fn simulated_length_s(duration_s: f64, dt_s: f64) -> f64 {
    match trial_steps(duration_s, dt_s) {
        Ok(steps) => {
            let ran_s = steps as f64 * dt_s;
            if (ran_s - duration_s).abs() <= 1e-9 * duration_s.abs().max(1.0) {
                duration_s
            } else {
                format!("{ran_s:.11e}").parse().unwrap_or(ran_s)
            }
        }
        Err(_) => duration_s,
    }
}

/// Default output folder for a scenario: `results/<scenario name>/`, always one folder inside
/// `results/`: in the name, path separators (`/`, `\`), `:` and control characters become
/// `_`, surrounding white space is dropped, and a name left empty or made only of dots (`.`,
/// `..`) becomes `scenario`. So a scenario file cannot direct output elsewhere (`name:
/// "../../x"` writes to `results/.._.._x/`). A name longer than [`MAX_FOLDER_NAME_BYTES`]
/// is cut there (at a character boundary) and ends with `~` and the first 8 hex digits of
/// the FNV-1a hash of the whole name, so that the folder can be created (most file systems
/// allow 255 bytes) and two long names stay apart.
pub fn default_out_dir(scenario: &Scenario) -> PathBuf {
    Path::new("results").join(folder_name(&scenario.name))
}

/// The scenario name as one folder name (see [`default_out_dir`]).
fn folder_name(name: &str) -> String {
    let clean: String = name
        .chars()
        .map(|c| {
            if matches!(c, '/' | '\\' | ':') || c.is_control() {
                '_'
            } else {
                c
            }
        })
        .collect();
    let clean = clean.trim();
    if clean.chars().all(|c| c == '.') {
        return "scenario".to_string();
    }
    if clean.len() <= MAX_FOLDER_NAME_BYTES {
        return clean.to_string();
    }
    let hash = crate::fingerprint::fnv1a64_hex(name.as_bytes());
    let keep = MAX_FOLDER_NAME_BYTES - 9;
    let cut = (0..=keep)
        .rev()
        .find(|&i| clean.is_char_boundary(i))
        .unwrap_or(0);
    format!("{}~{}", clean[..cut].trim_end(), &hash[..8])
}

/// The longest default output folder name, bytes (see [`default_out_dir`]); 100.
pub const MAX_FOLDER_NAME_BYTES: usize = 100;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simulated_length_is_the_whole_steps_that_run() {
        assert_eq!(simulated_length_s(600.0, 0.02), 600.0);
        assert_eq!(simulated_length_s(30.0, 0.02), 30.0);
        assert_eq!(simulated_length_s(0.01, 0.02), 0.02);
        assert!((simulated_length_s(0.03, 0.02) - 0.04).abs() < 1e-12);
        assert!((simulated_length_s(12.345, 0.02) - 12.36).abs() < 1e-12);
        // Printed as the steps' length, without float noise: 35 x 0.02 s.
        assert_eq!(simulated_length_s(0.69, 0.02).to_string(), "0.7");
        // A length the sweep refuses is shown as asked (the sweep fails on it).
        assert_eq!(simulated_length_s(-1.0, 0.02), -1.0);
    }

    #[test]
    fn default_out_dirs_stay_one_folder_inside_results() {
        for (name, folder) in [
            ("paper", "paper"),
            ("swarm-1000 v2", "swarm-1000 v2"),
            ("/etc", "_etc"),
            ("../../escaped", ".._.._escaped"),
            ("a/../b", "a_.._b"),
            ("..", "scenario"),
            (" . ", "scenario"),
            ("C:\\tmp", "C__tmp"),
            ("line\nbreak", "line_break"),
            (&"x".repeat(100), &"x".repeat(100)),
        ] {
            assert_eq!(folder_name(name), folder, "{name:?}");
            let dir = Path::new("results").join(folder_name(name));
            let parts: Vec<_> = dir.components().collect();
            assert_eq!(parts.len(), 2, "{name:?} gives {}", dir.display());
            assert!(
                matches!(parts[1], std::path::Component::Normal(_)),
                "{name:?}"
            );
        }
    }

    /// A name too long for a file name (300 x "x", 90 CJK characters of 3 bytes) is cut
    /// with a hash of the whole name: `usar sweep` without `--out` failed with "File name too
    /// long (os error 36)".
    #[test]
    fn long_names_are_cut_with_a_hash() {
        let dir = tempfile::tempdir().unwrap();
        let long = "x".repeat(300);
        let cjk = "漢".repeat(90);
        let mut seen = Vec::new();
        for name in [long.clone(), format!("{long}y"), cjk] {
            let folder = folder_name(&name);
            assert!(folder.len() <= MAX_FOLDER_NAME_BYTES, "{folder}");
            assert!(folder.len() > MAX_FOLDER_NAME_BYTES - 12, "{folder}");
            assert_eq!(folder.as_bytes()[folder.len() - 9], b'~', "{folder}");
            std::fs::create_dir(dir.path().join(&folder)).expect("a valid folder name");
            seen.push(folder);
        }
        assert_ne!(seen[0], seen[1]);
    }

    #[test]
    fn threads_are_capped_at_the_maximum_and_the_job_count() {
        assert_eq!(effective_threads(100_000, 8, 1_000), 8);
        assert_eq!(effective_threads(100_000, 8, 3), 3);
        assert_eq!(effective_threads(2, 8, 1_000), 2);
        assert_eq!(effective_threads(2, 8, 0), 1);
        assert_eq!(effective_threads(0, 8, 5), 1);
        assert!(max_threads() >= MAX_THREADS_PER_CORE);
    }
}
