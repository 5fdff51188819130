//! What a sweep runs, as `usar sweep` and `usar slurm` take it ([`SweepSpecArgs`]), what its
//! reports show (`--targets`, `--claims`: [`ReportArgs`], for `usar sweep`, `usar merge` and
//! `usar slurm`), and the option checks `usar sweep`, `usar merge`, `usar calibrate` and
//! `usar multiverse` share: `--grid-metrics`, `--threads` and a `--duration` rounded to whole
//! steps.

use std::path::{Path, PathBuf};

use anyhow::{Context, Result};
use clap::Args;
use rne_core::grouping::METHOD_NAMES;
use usar_sim::scenario::{self, Scenario};

use usar_report::calibration::{ReportOptions, ReportOptionsError};
use usar_sweep::grid::Grid;
use usar_sweep::metrics::{Metric, Quantity, Scope};
use usar_sweep::shard::SweepPlan;

use super::scenario_field::scenario_field;
use crate::shared::trial_build::rounding_warning;
pub use crate::shared::trial_build::threads_of;

/// The arguments of `usar sweep` that decide what the sweep runs (shared with `usar slurm`).
#[derive(Debug, Clone, Args)]
pub struct SweepSpecArgs {
    /// The scenario file (RON), e.g. scenarios/paper.ron.
    #[arg(value_name = "SCENARIO")]
    pub scenario: PathBuf,

    /// Grouping methods, comma-separated: rne, dis, eng, hp_dis.
    #[arg(long, value_name = "NAME,..", value_delimiter = ',', default_values_t = METHOD_NAMES.map(String::from))]
    pub methods: Vec<String>,

    /// Trials per method.
    #[arg(long, value_name = "N", default_value_t = 10)]
    pub trials: u32,

    /// Base seed of the starting teams; default the scenario's sim.seed.
    #[arg(long, value_name = "SEED")]
    pub seed: Option<u64>,

    /// Length of each trial, seconds (> 0); default the scenario's mission.duration_s.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub duration: Option<f64>,

    /// Vary a scenario field: run the sweep once per value, in a grid over every --vary
    /// (repeatable; the first varies slowest). FIELD is a path such as
    /// `mission.duration_s`, `kinds[0].count` or `radiation_zones[*].radius_m`; values are RON.
    /// The scenario file must be valid on its own; each cell is validated with its values.
    #[arg(long, value_name = "FIELD=V1,V2,..", allow_hyphen_values = true)]
    pub vary: Vec<String>,

    /// Metrics of grid.md and its figures (names as in summary.csv); default
    /// rescued_total,rescued_hard,rescued_easy.
    #[arg(long, value_name = "NAME,..", value_delimiter = ',', requires = "vary")]
    pub grid_metrics: Vec<String>,

    /// Output folder; default `results/<scenario name>/`. Locked while the sweep runs (a
    /// second sweep into it is refused, naming the holder's pid). Output files that are
    /// symlinks are followed and stay symlinks; a FIFO or character device is written directly.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

impl SweepSpecArgs {
    /// The sweep's plan: the scenario file's text and these options (no report options:
    /// the commands that have them set [`SweepPlan::targets`] and [`SweepPlan::claims`]).
    ///
    /// # Errors
    /// The scenario file cannot be read.
    pub fn plan(&self) -> Result<SweepPlan> {
        let scenario_text = scenario::read_source(&self.scenario)?;
        Ok(SweepPlan {
            scenario_path: self.scenario.clone(),
            scenario_text,
            vary: self.vary.clone(),
            methods: self.methods.iter().map(|m| m.trim().to_string()).collect(),
            trials: self.trials,
            seed: self.seed,
            duration_s: self.duration,
            grid_metrics: self.grid_metrics.clone(),
            working_dir: std::env::current_dir().ok(),
            targets: None,
            claims: None,
        })
    }
}

/// `--targets FILE` and `--claims FILE`: what the reports say beyond the scenario's own
/// results.
#[derive(Debug, Clone, Default, Args)]
pub struct ReportArgs {
    /// Compare the statistics pooled over all trials of all methods with the targets in FILE
    /// (RON, as `usar calibrate --targets`; the paper's: scenarios/paper-targets.ron) in
    /// report.md, grid.md and the summary. Default: no comparison. Changing it re-renders a
    /// journaled sweep's reports without running its trials again.
    #[arg(long, value_name = "FILE")]
    pub targets: Option<PathBuf>,

    /// Check the claims in FILE (RON; the paper's: scenarios/paper-claims.ron; see
    /// docs/sweeps.md, "Claims") in report.md, grid.md and the summary. Default: the file the
    /// scenario's `report: (claims: ...)` names, else none. Changing it re-renders a
    /// journaled sweep's reports without running its trials again.
    #[arg(long, value_name = "FILE")]
    pub claims: Option<PathBuf>,
}

impl ReportArgs {
    /// The report options for `scenario` (loaded from `scenario_path`) swept with `methods`.
    ///
    /// # Errors
    /// A targets or claims file that cannot be read or parsed, that names a task the
    /// scenario lacks, or a claim naming a method neither built in nor among `methods`.
    pub fn resolve(
        &self,
        scenario: &Scenario,
        scenario_path: &Path,
        methods: &[String],
    ) -> Result<ReportOptions> {
        ReportOptions::resolve(
            self.targets.as_deref(),
            self.claims.as_deref(),
            scenario,
            scenario_path,
            methods,
        )
        .map_err(|e| {
            // The flag when given, else the scenario's field that named the file.
            let (flag, field) = match e {
                ReportOptionsError::Targets(_) => (self.targets.is_some(), "targets"),
                ReportOptionsError::Claims(_) => (self.claims.is_some(), "claims"),
            };
            let setting = if flag {
                format!("--{field}")
            } else {
                scenario_field(scenario_path, &format!("report.{field}"))
            };
            anyhow::Error::new(e).context(setting)
        })
    }
}

/// The metrics named by `--grid-metrics` for a scenario with tasks `tasks`, or the default
/// ones (rescuees in total and per task).
///
/// # Errors
/// An unknown name (the message lists the valid ones).
pub fn grid_metrics(names: &[String], tasks: &[String]) -> Result<Vec<Metric>> {
    if names.is_empty() {
        let mut out = vec![Metric::new(Quantity::Rescued, Scope::Total)];
        out.extend((0..tasks.len()).map(|t| Metric::new(Quantity::Rescued, Scope::Task(t))));
        return Ok(out);
    }
    names
        .iter()
        .map(|n| {
            Metric::parse(n.trim(), tasks).with_context(|| {
                let valid: Vec<String> = Metric::all(tasks.len())
                    .iter()
                    .map(|m| m.name(tasks))
                    .collect();
                format!(
                    "--grid-metrics: unknown metric {:?} (metrics: {})",
                    n.trim(),
                    valid.join(", ")
                )
            })
        })
        .collect()
}

/// Warns once per distinct step (`sim.dt_s` of the scenario or of a grid's cells) when the
/// `--duration` of `requested_s` seconds is not a whole number of steps of it.
pub fn warn_if_rounded(requested_s: f64, scenario: &Scenario, grid: Option<&Grid>) {
    let mut steps: Vec<f64> = match grid {
        Some(g) => g
            .cells
            .iter()
            .map(|c| c.scenario.sim().dt_s.get())
            .collect(),
        None => vec![scenario.sim().dt_s.get()],
    };
    steps.sort_by(f64::total_cmp);
    steps.dedup();
    for dt_s in steps {
        if let Some(w) = rounding_warning(requested_s, dt_s) {
            crate::shared::stderr_lines::warn(w);
        }
    }
}
