//! `usar slurm`: writes the sbatch scripts that run a sweep (or, with `--axes`, a
//! multiverse) on a Slurm cluster as a job array of shards plus a chained merge job, prints
//! how to submit them, and with `--submit` submits them.

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::Args;
use usar_sim::scenario::path_text;

use usar_sim::scenario;
use usar_study::multiverse::MultiversePlan;
use usar_study::multiverse::setup::{
    DEFAULT_CALIBRATION_TRIALS, DEFAULT_MAX_EVALS, DEFAULT_SAMPLE_SEED,
};
use usar_sweep::data::owner::check_claimable;
use usar_sweep::shard::shell_join;
use usar_sweep::slurm::{ShardedWork, SlurmJob, SlurmOptions, submit, write_scripts};
use usar_sweep::sweep::default_out_dir;

use crate::shared::multiverse_spec::{
    MultiverseSearchArgs, MultiverseSpecArgs, default_dir, setup_of,
};
use crate::shared::out_flag::out_setting;
use crate::shared::sweep_spec::{ReportArgs, SweepSpecArgs, warn_if_rounded};

const EXAMPLES: &str = "\
Examples:
  # 3,000 trials (5 x 5 cells x 4 methods x 30 trials) as 100 array tasks of 4 CPUs each,
  # then a merge job; writes results/big/slurm/{sweep.sbatch,merge.sbatch,submit.sh}
  usar slurm scenarios/paper.ron --trials 30 \\
      --vary mission.hp_pct_per_step_in_radiation=0.001,0.002,0.003,0.005,0.01 \\
      --vary 'kinds[0].max_speed_m_per_s=1.0,1.25,1.5,1.75,2.0' \\
      --out results/big --shards 100 --cpus-per-task 4 --time 02:00:00 --mem 4G \\
      --partition batch --account my-lab

  # The same, submitted at once (sbatch must be on the PATH)
  usar slurm scenarios/paper.ron --trials 30 --out results/big --shards 100 --submit

  # A multiverse (usar multiverse) instead of a sweep: --axes (with --targets and --free)
  # makes it one; 64 universes on 16 tasks of 4 CPUs
  usar slurm scenarios/paper.ron --axes scenarios/paper-axes.ron \\
      --targets scenarios/paper-targets.ron \\
      --free 'mission.hp_pct_per_step_in_radiation=0.001..0.02:log' \\
      --free 'mission.search_time_budget_s=6..30' --sample 64 \\
      --out results/multiverse-paper --shards 16 --cpus-per-task 4 --time 12:00:00

Task I of the array runs `usar sweep SCENARIO <options> --shard I/N --threads
$SLURM_CPUS_PER_TASK` (with --axes: `usar multiverse ...`, its script multiverse.sbatch); the
merge job runs `usar merge OUT` once every task has succeeded
(--dependency=afterok). Logs go to OUT/slurm/logs/. The scripts are plain and commented: edit
them as your cluster needs (modules, QOS), then run OUT/slurm/submit.sh. A failed task: submit
it again with `sbatch --array=I OUT/slurm/sweep.sbatch` (it continues its journal), then
`sbatch OUT/slurm/merge.sbatch`. Without Slurm, run the same shards with GNU parallel or by
hand: see docs/cluster.md.";

/// Arguments of `usar slurm`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct SlurmArgs {
    /// What to sweep: the options of `usar sweep`.
    #[command(flatten)]
    pub spec: SweepSpecArgs,

    /// Array tasks: the sweep is split into this many shards, one per task.
    #[arg(long, value_name = "N")]
    pub shards: usize,

    /// Slurm partition (sbatch --partition); default the cluster's.
    #[arg(long, value_name = "P")]
    pub partition: Option<String>,

    /// Time limit per task (sbatch --time: MM, MM:SS, HH:MM:SS, D-HH, D-HH:MM, D-HH:MM:SS or
    /// UNLIMITED); default the cluster's.
    #[arg(long, value_name = "T")]
    pub time: Option<String>,

    /// CPUs per task; each shard runs that many trials at once.
    #[arg(long, value_name = "C", default_value_t = 1)]
    pub cpus_per_task: usize,

    /// Memory per task (sbatch --mem: 4G, 500M); default the cluster's.
    #[arg(long, value_name = "M")]
    pub mem: Option<String>,

    /// Account to charge (sbatch --account); default yours.
    #[arg(long, value_name = "A")]
    pub account: Option<String>,

    /// Submit the array and the merge with sbatch (which must be on the PATH).
    #[arg(long)]
    pub submit: bool,

    /// A multiverse instead of a sweep (`usar multiverse`'s options).
    #[command(flatten)]
    pub multiverse: SlurmMultiverseArgs,
}

/// The options of `usar multiverse` that `usar slurm` takes besides the sweep's (`--axes`
/// makes the job a multiverse; `--methods`, `--trials`, `--seed`, `--duration` and `--out`
/// are shared).
#[derive(Debug, Clone, Args)]
pub struct SlurmMultiverseArgs {
    /// Run a multiverse over this axes file (usar multiverse --axes) instead of a sweep.
    #[arg(
        long,
        value_name = "AXES.ron",
        conflicts_with_all = ["vary", "grid_metrics"],
        requires_all = ["targets", "free"]
    )]
    pub axes: Option<PathBuf>,

    /// With --axes: the targets file each universe is calibrated to. Without: the targets
    /// the sweep's reports compare with (as `usar sweep --targets`).
    #[arg(long, value_name = "TARGETS.ron")]
    pub targets: Option<PathBuf>,

    /// The claims file: with --axes, the claims each universe checks (as `usar multiverse
    /// --claims`); without, the claims the sweep's reports check (as `usar sweep --claims`).
    #[arg(long, value_name = "CLAIMS.ron")]
    pub claims: Option<PathBuf>,

    /// With --axes: also give the shares among the universes whose calibration loss is at
    /// most LOSS (as `usar multiverse --near-loss`).
    #[arg(
        long,
        value_name = "LOSS",
        requires = "axes",
        allow_hyphen_values = true
    )]
    pub near_loss: Option<f64>,

    /// With --axes: a target reported but left out of the loss and admissibility
    /// (repeatable; as `usar multiverse --report-only`).
    #[arg(long = "report-only", value_name = "NAME", requires = "axes")]
    pub report_only: Vec<String>,

    /// With --axes: a field each universe's calibration fits (repeatable).
    #[arg(
        long,
        value_name = "FIELD=LO..HI[:log][,factor]",
        requires = "axes",
        allow_hyphen_values = true
    )]
    pub free: Vec<String>,

    /// With --axes: trials per method of each calibration evaluation.
    #[arg(long, value_name = "N", requires = "axes", default_value_t = DEFAULT_CALIBRATION_TRIALS)]
    pub calibration_trials: u32,

    /// With --axes: base seed of the calibrations; default --seed.
    #[arg(long, value_name = "SEED", requires = "axes")]
    pub calibration_seed: Option<u64>,

    /// With --axes: most evaluations of each calibration.
    #[arg(long, value_name = "N", requires = "axes", default_value_t = DEFAULT_MAX_EVALS)]
    pub max_evals: usize,

    /// With --axes: run N universes drawn from the full factorial.
    #[arg(long, value_name = "N", requires = "axes")]
    pub sample: Option<usize>,

    /// With --axes: seed of --sample's draw.
    #[arg(long, value_name = "S", requires = "sample", default_value_t = DEFAULT_SAMPLE_SEED)]
    pub sample_seed: u64,

    /// With --axes: the calibrations' design, search and check (as `usar multiverse`).
    #[command(flatten)]
    pub search: MultiverseSearchArgs,
}

/// `path` made absolute against the current folder (not resolved: links stay).
fn absolute(path: &Path) -> Result<PathBuf> {
    std::path::absolute(path)
        .with_context(|| format!("{}: cannot make it absolute", path_text(path)))
}

/// Runs `usar slurm`: checks the sweep (or multiverse), writes the scripts, prints (or runs)
/// the submission.
///
/// # Errors
/// A sweep or multiverse that would not run (bad scenario, `--vary`, axes, methods), bad
/// Slurm options, an I/O error, or with `--submit` an `sbatch` that is missing or refuses a
/// script.
pub fn run(args: &SlurmArgs, out: &mut dyn Write) -> Result<()> {
    if args.multiverse.axes.is_some() {
        return run_multiverse(args, out);
    }
    let mut plan = args.spec.plan()?;
    plan.targets.clone_from(&args.multiverse.targets);
    plan.claims.clone_from(&args.multiverse.claims);
    let out_dir = match &args.spec.out {
        Some(o) => o.clone(),
        None => default_out_dir(&scenario::load(&args.spec.scenario)?),
    };
    let out_dir = absolute(&out_dir)?;
    // The sweep must be one `usar sweep` accepts: build it (and its header) now.
    let cfg = usar_sweep::shard::plan_config::plan_config(&plan, &out_dir)?;
    let header = usar_sweep::sweep::header_of(&cfg)?;
    usar_sweep::sweep::check_config(&cfg, &header)?;
    ReportArgs {
        targets: plan.targets.clone(),
        claims: plan.claims.clone(),
    }
    .resolve(&cfg.scenario, &cfg.scenario_path, &cfg.methods)?;
    if let Some(d) = args.spec.duration {
        warn_if_rounded(d, &cfg.scenario, cfg.grid.as_ref());
    }
    let total = usar_sweep::sweep::trial_count(&cfg);
    if args.shards > total {
        // A shard without a trial would be one more job to wait for, with nothing to do.
        bail!(
            "--shards {}: the sweep has {total} trial(s), so at most {total} shards have work; \
             split it into at most {total}",
            args.shards
        );
    }
    write_and_submit(args, &plan, (&out_dir, args.spec.out.is_some()), out)
}

/// `usar slurm --axes ...`: checks the multiverse as `usar multiverse` would, then writes
/// (and submits) its scripts.
fn run_multiverse(args: &SlurmArgs, out: &mut dyn Write) -> Result<()> {
    let (s, m) = (&args.spec, &args.multiverse);
    let spec = MultiverseSpecArgs {
        scenario: s.scenario.clone(),
        axes: m.axes.clone().unwrap_or_default(),
        targets: m.targets.clone().unwrap_or_default(),
        report_only: m.report_only.clone(),
        claims: m.claims.clone(),
        near_loss: m.near_loss,
        free: m.free.clone(),
        methods: s.methods.clone(),
        trials: s.trials,
        seed: s.seed,
        duration: s.duration,
        calibration_trials: m.calibration_trials,
        calibration_seed: m.calibration_seed,
        max_evals: m.max_evals,
        sample: m.sample,
        sample_seed: m.sample_seed,
        search: m.search.clone(),
        out: s.out.clone(),
    };
    let setup = setup_of(&spec, 1, None)?;
    let out_dir = match &s.out {
        Some(o) => o.clone(),
        None => default_dir(&setup)?,
    };
    let out_dir = absolute(&out_dir)?;
    let checked = setup.check()?;
    usar_study::multiverse::universe::check_shards(
        &format!("--shards {}", args.shards),
        args.shards,
        checked.universes.len(),
    )?;
    let plan = MultiversePlan::of(&setup, &checked, &out_dir)?;
    write_and_submit(args, &plan, (&out_dir, s.out.is_some()), out)
}

/// Writes the scripts of `work` into `out_dir/slurm/` (`out_dir` as `(path, given with
/// --out)`), then prints how to submit them or, with `--submit`, submits them.
fn write_and_submit(
    args: &SlurmArgs,
    work: &dyn ShardedWork,
    (out_dir, out_given): (&Path, bool),
    out: &mut dyn Write,
) -> Result<()> {
    let workdir = std::env::current_dir().context("reading the current folder")?;
    let usar = std::env::current_exe().context("finding the usar executable")?;
    let options = SlurmOptions {
        shards: args.shards,
        partition: args.partition.clone(),
        time: args.time.clone(),
        cpus_per_task: args.cpus_per_task,
        mem: args.mem.clone(),
        account: args.account.clone(),
    };
    // The shards will claim the folder on the cluster: a folder they would refuse is refused
    // now, before any script is written.
    check_claimable(out_dir, work.run_kind()).context(out_setting(out_given))?;
    let job = SlurmJob {
        plan: work,
        out_dir,
        workdir: &workdir,
        usar: &usar,
        options: &options,
    };
    let files = write_scripts(&job)?;
    writeln!(
        out,
        "wrote {} (an array of {} tasks, one shard each), {} and {}",
        files.array.display(),
        args.shards,
        files.merge.display(),
        files.submit.display()
    )?;
    if !args.submit {
        writeln!(out, "submit both (the merge waits for the whole array):")?;
        writeln!(
            out,
            "  {}",
            shell_join(&[files.submit.display().to_string()])
        )?;
        return Ok(());
    }
    let s = submit(&files, Path::new("sbatch")).context("--submit")?;
    writeln!(
        out,
        "submitted the array as job {} and the merge as job {} (afterok:{}); logs in {}",
        s.array_job,
        s.merge_job,
        s.array_job,
        files.logs.display()
    )?;
    writeln!(out, "watch: squeue -j {},{}", s.array_job, s.merge_job)?;
    Ok(())
}
