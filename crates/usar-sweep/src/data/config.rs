//! The sweep's plan: everything a sweep needs ([`SweepConfig`]), with the defaults of
//! `usar sweep`.
//!
//! A sweep without `--vary` is a grid of one cell, the scenario itself; the grid, the methods,
//! the trials and seed, the trial length, the output folder and the shard all sit here, as
//! data: [`crate::sweep::run_sweep`] runs it.

use std::path::PathBuf;

use usar_sim::scenario::Scenario;

use crate::data::grid_cells::Grid;
use crate::data::hooks::SweepHooks;
use crate::data::out_dir::default_out_dir;
use crate::data::owner::RunKind;
use crate::data::shard_folders::{ShardRun, shard_dir};
use crate::data::trial_length::simulated_length_s;
use crate::method_factory::MethodFactory;

/// Everything a sweep needs. [`SweepConfig::new`] gives the defaults of `usar sweep`; set
/// the fields that differ:
///
/// ```no_run
/// use usar_sweep::sweep::{SweepConfig, run_sweep};
///
/// let scenario = usar_sim::scenario::load("scenarios/paper.ron")?;
/// let cfg = SweepConfig {
///     methods: vec!["rne".into(), "dis".into()],
///     trials: 2,
///     ..SweepConfig::new(scenario, "scenarios/paper.ron")
/// };
/// let outcome = run_sweep(&cfg)?;
/// assert_eq!(outcome.cells[0].results.len(), 4);
/// # Ok::<(), Box<dyn std::error::Error>>(())
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
    /// Worker threads (>= 1); a sweep uses at most [`max_threads`](crate::sweep::max_threads): trials in
    /// parallel, one thread each, and with fewer trials than threads, for a team of at least
    /// 512 robots, the threads left over inside the trials, else no more threads than trials
    /// ([`sweep_threads`](crate::sweep::sweep_threads)).
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
            base_seed: scenario.sim().seed,
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
        self.duration_s
            .unwrap_or(scenario.mission().duration_s.get())
    }

    /// The simulated length of each trial of a cell with `scenario`, seconds: its
    /// [`SweepConfig::duration_of`] run as whole steps ([`simulated_length_s`]).
    pub fn simulated_length_of(&self, scenario: &Scenario) -> f64 {
        simulated_length_s(self.duration_of(scenario), scenario.sim().dt_s.get())
    }

    /// The kind of run this sweep is, which owns its folders ([`crate::data::owner`]): a
    /// sharded sweep with a shard, a grid with `--vary` cells, a sweep otherwise.
    pub fn run_kind(&self) -> RunKind {
        match (&self.shard, &self.grid) {
            (Some(_), _) => RunKind::ShardedSweep,
            (None, Some(_)) => RunKind::Grid,
            (None, None) => RunKind::Sweep,
        }
    }

    /// The folder of the journal (and the lock): `out_dir`, or the shard's folder under it.
    pub fn journal_dir(&self) -> PathBuf {
        match &self.shard {
            Some(s) => shard_dir(&self.out_dir, s.shard),
            None => self.out_dir.clone(),
        }
    }
}
