//! What a multiverse runs, as `usar multiverse` and `usar slurm multiverse` take it
//! ([`MultiverseSpecArgs`]), its setup and default folder, and the error that lists failed
//! universes (`usar multiverse`, `usar merge`).

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use rne_core::grouping::METHOD_NAMES;
use usar_sim::scenario::{self, ScenarioSpec, path_text};

use usar_report::claims::Claims;
use usar_study::calibrate::{Targets, TrialPlan, parse_free};
use usar_study::multiverse::setup::{
    DEFAULT_CALIBRATION_TRIALS, DEFAULT_DESIGN, DEFAULT_MAX_EVALS, DEFAULT_SAMPLE_SEED,
    DEFAULT_TRIALS,
};
use usar_study::multiverse::{Axes, MultiverseSetup, Sample};
use usar_sweep::shard::Shard;
use usar_sweep::sweep::default_out_dir_of;

use usar_report::source_date::source_date;

use super::flag_tasks::{check_file_tasks, scenario_tasks};
use super::optimizer_arg::OptimizerArg;
use super::scenario_field::scenario_field;

/// The arguments of `usar multiverse` that decide what it runs.
#[derive(Debug, Clone, Args)]
pub struct MultiverseSpecArgs {
    /// The base scenario file (RON), e.g. scenarios/paper.ron.
    #[arg(value_name = "SCENARIO")]
    pub scenario: PathBuf,

    /// The axes file (RON, see below): the open choices and their alternatives.
    #[arg(long, value_name = "AXES.ron")]
    pub axes: PathBuf,

    /// The targets file each universe is calibrated to (RON, as `usar calibrate --targets`).
    #[arg(long, value_name = "TARGETS.ron")]
    pub targets: PathBuf,

    /// The claims each admissible universe's comparison checks (RON; the paper's:
    /// scenarios/paper-claims.ron; see docs/sweeps.md, "Claims"). Default: the file the
    /// scenario's `report: (claims: ...)` names, else none (the multiverse then says only
    /// which universes are admissible).
    #[arg(long, value_name = "CLAIMS.ron")]
    pub claims: Option<PathBuf>,

    /// Also give the shares among the near-admissible universes: those whose calibration
    /// reached a loss of at most LOSS (> 0), a sensitivity variant of admissibility (loss 0)
    /// in multiverse.md. Changes no universe. Default: none.
    #[arg(long, value_name = "LOSS", allow_hyphen_values = true)]
    pub near_loss: Option<f64>,

    /// The name of a target to compute and report but leave out of the loss (and so out of
    /// what makes a universe admissible): a target known to conflict with the others, or one
    /// only watched; repeatable. A file can mark one with `report_only: true`.
    #[arg(long = "report-only", value_name = "NAME")]
    pub report_only: Vec<String>,

    /// A field each universe's calibration fits and its range: FIELD=LO..HI, or
    /// FIELD=LO..HI:log (LO > 0); repeatable, each field once, none set by an axis.
    #[arg(
        long,
        value_name = "FIELD=LO..HI[:log][,factor]",
        required = true,
        allow_hyphen_values = true
    )]
    pub free: Vec<String>,

    /// Grouping methods, comma-separated: rne, dis, eng, hp_dis.
    #[arg(long, value_name = "NAME,..", value_delimiter = ',', default_values_t = METHOD_NAMES.map(String::from))]
    pub methods: Vec<String>,

    /// Comparison trials per method in each universe.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_TRIALS)]
    pub trials: u32,

    /// Base seed of the comparison's trials; default the scenario's sim.seed.
    #[arg(long, value_name = "SEED")]
    pub seed: Option<u64>,

    /// Length of every trial, seconds (> 0); default each universe's mission.duration_s.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub duration: Option<f64>,

    /// Trials per method of each calibration evaluation.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_CALIBRATION_TRIALS)]
    pub calibration_trials: u32,

    /// Base seed of the calibrations' trials; default --seed.
    #[arg(long, value_name = "SEED")]
    pub calibration_seed: Option<u64>,

    /// Most evaluations of each universe's calibration.
    #[arg(long, value_name = "N", default_value_t = DEFAULT_MAX_EVALS)]
    pub max_evals: usize,

    /// Run N universes drawn without replacement from the full factorial (default: all).
    #[arg(long, value_name = "N")]
    pub sample: Option<usize>,

    /// Seed of --sample's draw.
    #[arg(long, value_name = "S", default_value_t = DEFAULT_SAMPLE_SEED, requires = "sample")]
    pub sample_seed: u64,

    /// How each universe's calibration searches and is confirmed.
    #[command(flatten)]
    pub search: MultiverseSearchArgs,

    /// Output folder; default `results/multiverse-<scenario name>/`. Locked while it runs.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// How each universe's calibration searches and is confirmed (`usar multiverse` and `usar
/// slurm --axes`).
#[derive(Debug, Clone, Args)]
pub struct MultiverseSearchArgs {
    /// Evaluate N design points spread over the universes and the free ranges first, fit an
    /// emulator of every target's statistic to them, and start each universe's calibration
    /// where it predicts the least loss (docs/multiverse.md, "A design shared by the
    /// universes"). Default 0: no design, each search starts at the scenario's values.
    #[arg(long, value_name = "N", requires = "axes", default_value_t = DEFAULT_DESIGN)]
    pub design: usize,

    /// Each calibration's search: `nelder-mead` or `cma-es` (as `usar calibrate
    /// --optimizer`).
    #[arg(
        long,
        value_enum,
        value_name = "SEARCH",
        requires = "axes",
        default_value_t = OptimizerArg::NelderMead
    )]
    pub optimizer: OptimizerArg,

    /// Trials per method of each calibration's check on unseen trials: a point in band
    /// counts only when these trials are in band too (as `usar calibrate --check-trials`).
    /// Default 0: no check.
    #[arg(long, value_name = "N", requires = "axes", default_value_t = 0)]
    pub check_trials: u32,

    /// Base seed of that check; default 7 (8 when the calibration seed is 7).
    #[arg(long, value_name = "SEED", requires = "check_trials")]
    pub check_seed: Option<u64>,
}

/// The setup of `spec` with `threads` worker threads, run as `shard`.
///
/// # Errors
/// A scenario, axes file, targets file or `--free` that cannot be read or parsed, or a
/// targets or claims file about a task the scenario lacks (blamed on its flag).
pub fn setup_of(
    spec: &MultiverseSpecArgs,
    threads: usize,
    shard: Option<Shard>,
) -> Result<MultiverseSetup> {
    let origin = path_text(&spec.scenario);
    let text = scenario::read_source(&spec.scenario)?;
    let base = scenario::parse_spec(&text, &origin)?;
    let axes = Axes::load(&spec.axes).context("--axes")?;
    let mut targets = Targets::load(&spec.targets).context("--targets")?;
    let tasks = scenario_tasks(&base, &origin);
    check_file_tasks("--targets", tasks.as_deref(), |n| {
        targets.check_tasks_of_scenario(n, &origin)
    })?;
    targets.set_report_only(&spec.report_only)?;
    let free = parse_free(&spec.free)?;
    let seed = spec.seed.unwrap_or(base.sim.seed);
    let methods: Vec<String> = spec.methods.iter().map(|m| m.trim().to_string()).collect();
    let claims = claims_of(spec, &base, tasks.as_deref(), &methods)?;
    Ok(MultiverseSetup {
        claims,
        near_loss: spec.near_loss,
        comparison: TrialPlan {
            methods,
            duration_s: spec.duration,
            ..TrialPlan::builtin(spec.trials, seed)
        },
        calibration_trials: spec.calibration_trials,
        calibration_seed: spec.calibration_seed.unwrap_or(seed),
        max_evals: spec.max_evals,
        design: spec.search.design,
        optimizer: spec.search.optimizer.into(),
        check_trials: spec.search.check_trials,
        check_seed: spec.search.check_seed,
        sample: spec.sample.map(|n| Sample {
            n,
            seed: spec.sample_seed,
        }),
        threads,
        shard,
        date: source_date()?,
        ..MultiverseSetup::new(base, origin, axes, targets, free)
    })
}

/// The claims of `--claims FILE`, or else of the file the scenario's `report: (claims: ...)`
/// names (relative to its folder; a missing one is a warning and no claims), checked against
/// `tasks`, the scenario's task names ([`scenario_tasks`]), and `methods` (`--methods`,
/// trimmed).
///
/// # Errors
/// A claims file that cannot be read or parsed, one about a task the scenario lacks, or one
/// naming a method that is neither built in nor one of `methods`.
fn claims_of(
    spec: &MultiverseSpecArgs,
    base: &ScenarioSpec,
    tasks: Option<&[String]>,
    methods: &[String],
) -> Result<Option<Claims>> {
    let path = match (&spec.claims, &base.report.claims) {
        (Some(p), _) => p.clone(),
        (None, None) => return Ok(None),
        (None, Some(file)) => {
            let p = spec.scenario.parent().unwrap_or(Path::new("")).join(file);
            if !p.exists() {
                crate::shared::stderr_lines::warn(format!(
                    "warning: {}: report.claims: {} not found (relative to the scenario's \
                     folder); no claims are checked (--claims FILE gives them)",
                    path_text(&spec.scenario),
                    path_text(&p)
                ));
                return Ok(None);
            }
            p
        }
    };
    let setting = if spec.claims.is_some() {
        "--claims".to_owned()
    } else {
        scenario_field(&spec.scenario, "report.claims")
    };
    let claims = Claims::load(&path).context(setting.clone())?;
    check_file_tasks(&setting, tasks, |n| {
        claims.check_tasks_of_scenario(n, &path_text(&spec.scenario))
    })?;
    // As `usar sweep` checks them: a method neither built in nor run, blamed on the setting.
    claims
        .check_methods(methods)
        .with_context(|| setting.clone())?;
    Ok(Some(claims))
}

/// The default output folder: `results/multiverse-<scenario name>/` (the name made safe as
/// for a sweep's folder).
pub fn default_dir(setup: &MultiverseSetup) -> Result<PathBuf> {
    let scenario = setup.base.validate(&setup.origin)?;
    Ok(default_out_dir_of("multiverse", &scenario))
}

/// The error listing failed universes, if any, ending with `retry` (how to retry them).
pub fn failed_universes(o: &usar_study::multiverse::MultiverseOutcome, retry: &str) -> Result<()> {
    let failed: Vec<String> = o
        .failed()
        .map(|r| format!("{} ({})", r.id, r.message.as_deref().unwrap_or("failed")))
        .collect();
    if failed.is_empty() {
        return Ok(());
    }
    bail!(
        "{} of {} universes failed: {}. The others are in the files; {retry}",
        failed.len(),
        o.records.len(),
        failed.join("; ")
    )
}
