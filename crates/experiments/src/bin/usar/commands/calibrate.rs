//! `usar calibrate`: fits `--free` scenario fields so that the statistics of a sweep of the
//! scenario fall inside the bands of a targets file (`usar_study::calibrate`).

use std::io::Write;

use std::path::PathBuf;

use std::sync::Arc;

use std::time::Duration;

use anyhow::{Context, Result};

use clap::Args;

use rne_core::grouping::METHOD_NAMES;

use usar_sim::scenario::{self, path_text};

use usar_study::calibrate::setup::{
    DEFAULT_CHECK_TRIALS, DEFAULT_DIGITS, DEFAULT_MAX_EVALS, DEFAULT_TRIALS, default_check_seed,
};

use usar_study::calibrate::{
    CalibrationError, CalibrationSetup, Progress, TrialPlan, calibrate, parse_free, summary_text,
};

use usar_report::calibration::targets_or_paper;

use usar_sweep::shard::shell_join;

use usar_sweep::sweep::default_out_dir_of;

use crate::shared::flag_tasks::{check_file_tasks, scenario_tasks};
use crate::shared::optimizer_arg::OptimizerArg;
use crate::shared::out_flag::out_setting;
use crate::shared::sweep_spec::threads_of;
use crate::shared::test_hooks::STOP_EXIT_CODE;
use usar_report::source_date::source_date;

const EXAMPLES: &str = "\
Examples:
  # The paper's calibration: the HP damage rate (log scale) and the search budget
  usar calibrate scenarios/paper.ron --targets scenarios/paper-targets.ron \\
      --free mission.hp_pct_per_step_in_radiation=0.002..0.02:log \\
      --free 'mission.search_time_budget_s=8..30' --out results/calibrate-paper

  # A quick try: two methods, 4 trials of 120 s per evaluation, at most 15 evaluations
  usar calibrate scenarios/paper.ron --free mission.pickup_s=0.5..2 --methods rne,dis \\
      --trials 4 --duration 120 --max-evals 15 --check-trials 0 --out /tmp/cal

  # At most half an hour; run the same command again to continue where it stopped
  usar calibrate scenarios/paper.ron --free 'kinds[*].max_speed_m_per_s=1.5..3.5' --max-time 30m

Each evaluation runs every method x --trials trials of the scenario with the free values set
(trial k of every method and evaluation from seed trial_seed(SEED, k)), pools the statistics of
TARGETS.ron over the methods, and scores them: loss = sum over targets of (distance outside the
band / half the band's width)^2, 0 when every statistic is in its band, inf when a trial fails
or the values break a scenario rule. Nelder-Mead searches the fields on [0, 1] per range (log
ranges in log space) from the scenario's own values (the range's middle when outside), and
stops at loss 0, --max-evals or --max-time. Free values are rounded to --digits significant
digits before they run. FIELD is any path --vary takes that holds a real number (an
Option<f64> such as mission.search_time_budget_s included).

Output folder (default results/calibrate-<scenario name>/): trace.jsonl (every evaluation,
appended as it ends, checksummed), then calibrated.ron (the scenario with the best values; its
header comment has the command, the date and every statistic), trace.csv, calibration.md,
convergence.svg (the loss) and statistics.svg (each target's statistic per evaluation, its
band shaded), written together at the end. Running the same command again replays the
search from trace.jsonl and runs only new points (a larger --max-evals continues a search); a
trace of another calibration is refused (--overwrite starts afresh). The date is the system
clock's (UTC), or SOURCE_DATE_EPOCH when set. Same inputs, same trace.csv and calibrated
scenario on any --threads and after any interruption.

TARGETS.ron (default: the paper's eighteen targets, scenarios/paper-targets.ron, built in):
  Targets(targets: [
      (name: \"rounds per trial\", statistic: Mean(\"rounds\"), value: 6.2, band: PlusMinus(0.6)),
      (name: \"easy / hard\", statistic: RatioOfMeans(\"rescued_easy\", \"rescued_hard\"),
       value: 1.36, band: PlusMinus(0.2)),
      (name: \"SD\", statistic: PooledSd(\"rescued_total\"), value: 4.69, band: Between(3.0, 7.0)),
  ])
Statistics: Mean(m), RatioOfMeans(m1, m2), MeanOfRatios(m1, m2), PooledSd(m) (pooled
within-method SD); metrics are trials.csv column names (rescued_total, rescued_<task>,
energy_<task>_pct, hp_<task>_pct, rounds, ...).";

/// Arguments of `usar calibrate`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct CalibrateArgs {
    /// The scenario file (RON) whose fields are fitted, e.g. scenarios/paper.ron.
    #[arg(value_name = "SCENARIO")]
    pub scenario: PathBuf,

    /// The targets file (RON, see below); default the paper's eighteen targets
    /// (scenarios/paper-targets.ron, built in).
    #[arg(long, value_name = "TARGETS.ron")]
    pub targets: Option<PathBuf>,

    /// The name of a target to compute and report but leave out of the loss (and so out of
    /// what "every band holds" means): a target known to conflict with the others, or one
    /// only watched; repeatable. A file can mark one with `report_only: true`.
    #[arg(long = "report-only", value_name = "NAME")]
    pub report_only: Vec<String>,

    /// The name of a target the file marks `report_only: true` to fit after all (repeatable;
    /// applied before --report-only). The paper's "energy per trial" and "HP lost per trial"
    /// are report-only until the sheet's cost unit is read as percentage points of a full
    /// level: `--require "energy per trial" --require "HP lost per trial"` reads it so.
    #[arg(long = "require", value_name = "NAME")]
    pub require: Vec<String>,

    /// Start the search at the middle of each free range (geometric for a log range) instead
    /// of the scenario's own values: a fit that does not depend on the values the file holds.
    #[arg(long)]
    pub start_mid: bool,

    /// A field to fit and its range: FIELD=LO..HI, or FIELD=LO..HI:log for a log scale (LO >
    /// 0); with :factor (or :log,factor) the value is a factor of the base scenario's value(s)
    /// (`kinds[*].max_speed_m_per_s=0.5..2:factor` scales every kind's speed, keeping their
    /// ratios); repeatable, each field once.
    #[arg(
        long,
        value_name = "FIELD=LO..HI[:log][,factor]",
        required = true,
        allow_hyphen_values = true
    )]
    pub free: Vec<String>,

    /// Output folder; default `results/calibrate-<scenario name>/`. Locked while it runs.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Grouping methods, comma-separated: rne, dis, eng, hp_dis.
    #[arg(long, value_name = "NAME,..", value_delimiter = ',', default_values_t = METHOD_NAMES.map(String::from))]
    pub methods: Vec<String>,

    /// Trials per method in each evaluation.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_TRIALS)]
    pub trials: u32,

    /// Base seed of the trials; default the scenario's sim.seed.
    #[arg(long, value_name = "SEED")]
    pub seed: Option<u64>,

    /// Length of each trial, seconds (> 0); default the scenario's mission.duration_s.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub duration: Option<f64>,

    /// Significant digits the free values are rounded to (1 to 17).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_DIGITS)]
    pub digits: u32,

    /// Most evaluations of the search (those a rerun takes from trace.jsonl included).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_EVALS)]
    pub max_evals: usize,

    /// Wall-clock budget of this run (90s, 30m, 2h): no new evaluation starts after it.
    #[arg(long, value_name = "DURATION", value_parser = parse_time)]
    pub max_time: Option<Duration>,

    /// Worker threads (>= 1); default all cores. Never changes a result.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,

    /// Base seed of the check on unseen trials; default 7 (8 when --seed is 7).
    #[arg(long, value_name = "SEED")]
    pub check_seed: Option<u64>,

    /// Trials per method of the check of the best values on unseen trials (0 skips it).
    #[arg(long, value_name = "N", default_value_t = DEFAULT_CHECK_TRIALS)]
    pub check_trials: u32,

    /// The search: `nelder-mead` (a simplex from the start point; for one to three free
    /// values) or `cma-es` (CMA-ES seeded by --seed; for wider free sets and noisy losses).
    /// Part of the calibration's identity: a trace of the other search is not continued.
    #[arg(long, value_enum, value_name = "SEARCH", default_value_t = OptimizerArg::NelderMead)]
    pub optimizer: OptimizerArg,

    /// Discard a trace of another calibration in the output folder, and its files, and start
    /// afresh.
    #[arg(long)]
    pub overwrite: bool,

    /// No progress bar and no line per improvement.
    #[arg(long, short)]
    pub quiet: bool,

    /// Test hook: exit abruptly (status 75, no output files) after N new evaluations.
    #[arg(long, value_name = "N", hide = true)]
    pub stop_after: Option<usize>,
}

/// `--max-time`: a duration as humantime reads it (`90s`, `30m`, `1h 30m`).
fn parse_time(text: &str) -> Result<Duration, String> {
    humantime::parse_duration(text).map_err(|e| format!("{e} (write it like 90s, 30m or 2h)"))
}

/// The calibration's setup from the arguments.
fn setup_of(args: &CalibrateArgs) -> Result<CalibrationSetup> {
    let origin = path_text(&args.scenario);
    let text = scenario::read_source(&args.scenario)?;
    let base = scenario::parse_spec(&text, &origin)?;
    // The built-in targets are not the user's flag: only a given file is blamed on it.
    let mut targets = match &args.targets {
        Some(path) => {
            let t = targets_or_paper(Some(path)).context("--targets")?;
            let tasks = scenario_tasks(&base, &origin);
            check_file_tasks("--targets", tasks.as_deref(), |n| {
                t.check_tasks_of_scenario(n, &origin)
            })?;
            t
        }
        None => targets_or_paper(None)?,
    };
    targets.set_required(&args.require)?;
    targets.set_report_only(&args.report_only)?;
    let free = parse_free(&args.free)?;
    let seed = args.seed.unwrap_or(base.sim.seed);
    let command = shell_join(
        &std::iter::once("usar".to_string())
            .chain(std::env::args().skip(1))
            .collect::<Vec<_>>(),
    );
    Ok(CalibrationSetup {
        trial_plan: TrialPlan {
            methods: args.methods.iter().map(|m| m.trim().to_string()).collect(),
            duration_s: args.duration,
            ..TrialPlan::builtin(args.trials, seed)
        },
        digits: args.digits,
        max_evals: args.max_evals,
        max_time: args.max_time,
        threads: threads_of(args.threads)?,
        check_seed: args.check_seed.unwrap_or(default_check_seed(seed)),
        check_trials: args.check_trials,
        overwrite: args.overwrite,
        start_mid: args.start_mid,
        optimizer: args.optimizer.into(),
        command,
        date: source_date()?,
        ..CalibrationSetup::new(base, origin, targets, free)
    })
}

/// The default output folder: `results/calibrate-<scenario name>/` (the name made safe as
/// for a sweep's folder).
fn default_dir(setup: &CalibrationSetup) -> Result<PathBuf> {
    let scenario = setup.base.validate(&setup.origin)?;
    Ok(default_out_dir_of("calibrate", &scenario))
}

/// Runs `usar calibrate`: calibrate, then print the summary.
///
/// # Errors
/// A bad scenario, targets file, `--free` or option, an output folder holding another
/// calibration or locked by another run, or an I/O error.
pub fn run(args: &CalibrateArgs, out: &mut dyn Write) -> Result<()> {
    let setup = setup_of(args)?;
    let dir = match &args.out {
        Some(d) => d.clone(),
        None => default_dir(&setup)?,
    };
    let mut progress = if args.quiet {
        Progress::off()
    } else {
        Progress::terminal()
    };
    if let Some(limit) = args.stop_after {
        progress.on_evaluated = Some(Arc::new(move |_, n| {
            if n >= limit {
                crate::shared::stderr_lines::warn(format!("--stop-after {n}: stopping abruptly"));
                std::process::exit(STOP_EXIT_CODE);
            }
        }));
    }
    let outcome = calibrate(&setup, &dir, progress).map_err(|e| match e {
        CalibrationError::Owner(_) | CalibrationError::Lock(_) => {
            anyhow::Error::new(e).context(out_setting(args.out.is_some()))
        }
        e => e.into(),
    })?;
    out.write_all(summary_text(&outcome).as_bytes())?;
    Ok(())
}
