//! `usar multiverse`: the paper's method comparison in every combination of its open choices
//! (`usar_study::multiverse`), each calibrated to the targets first.

use std::io::Write;

use std::sync::Arc;

use std::sync::atomic::{AtomicUsize, Ordering};

use anyhow::{Context, Result};

use clap::Args;

use usar_study::multiverse::{
    MultiverseError, MultiverseHooks, MultiverseProgress, run_multiverse, summary_text,
};

use usar_sweep::shard::Shard;

use rne_core::{TrustModel, Weights};
use usar_sweep::sweep::{MethodFactory, SweepHooks, canonical_method};

use crate::shared::multiverse_spec::{MultiverseSpecArgs, default_dir, failed_universes, setup_of};
use crate::shared::out_flag::out_setting;
use crate::shared::sweep_spec::threads_of;
use crate::shared::test_hooks::{STOP_EXIT_CODE, test_hooks};

const EXAMPLES: &str = "\
Examples:
  # The paper: 64 universes drawn from the factorial of the axes, each calibrated (HP damage
  # rate and search budget) to the paper's targets, then RNE, DIS, ENG, HP_DIS x 10 trials
  usar multiverse scenarios/paper.ron --axes scenarios/paper-axes.ron \\
      --targets scenarios/paper-targets.ron \\
      --free 'mission.hp_pct_per_step_in_radiation=0.001..0.02:log' \\
      --free 'mission.search_time_budget_s=6..30' --sample 64 --out results/multiverse-paper

  # A quick look: every universe, two methods, short trials and a small calibration budget
  usar multiverse scenarios/paper.ron --axes my-axes.ron --targets my-targets.ron \\
      --free 'mission.search_time_budget_s=6..30' --methods rne,dis --trials 3 --duration 120 \\
      --calibration-trials 2 --max-evals 8 --out /tmp/mv

  # On several machines: shard I of 4 each, then the merge (or: usar slurm ... --axes ...)
  usar multiverse scenarios/paper.ron --axes my-axes.ron --targets my-targets.ron \\
      --free 'mission.search_time_budget_s=6..30' --shard 0/4 --out results/mv
  usar merge results/mv

A universe takes one alternative of each axis of AXES.ron (the full factorial, first axis
slowest, or --sample N of it drawn without replacement with --sample-seed):
  Axes(axes: [
      (name: \"hp effect\",
       paper: \"\\\"the lower its HP, the smaller its velocity, sensing, and observing range\\\" (VI.B)\",
       alternatives: [
           (name: \"linear\", set: [\"mission.hp_effect=Linear\"]),
           (name: \"threshold\", set: [\"mission.hp_effect=Threshold(below_pct: 50.0, factor: 0.6)\"]),
           (name: \"none\", set: [\"mission.hp_effect=NoEffect\"]),
       ]),
  ])
An alternative is a list of FIELD=VALUE overrides (as --set takes them); every alternative is
checked against the scenario before anything runs, and no axis may set a --free field.

In each universe the --free fields are calibrated to TARGETS.ron as `usar calibrate` does
(--calibration-trials per method and evaluation, at most --max-evals evaluations); the universe
is admissible when every target's statistic lies in its band (loss 0). Then every method runs
--trials trials on the calibrated scenario (trial k from seed trial_seed(SEED, k) in every
universe), and each claim of --claims FILE (default: the file the scenario's `report` section
names; paper.ron names the paper's five) gets its verdict (as in a sweep's report) and its
effect: the subject minus its strongest rival, > 0 in the claim's
direction, with a 95 % Welch confidence interval.

Output folder (default results/multiverse-<scenario name>/): universes/<id>/ per universe
(scenario.ron, calibration/, comparison/, universe.json), then multiverse.csv (long form: a row
per universe, per universe x method x metric, per universe x claim), multiverse.md and
spec_curve_<claim>.svg (a specification curve per claim). Running the same command again
continues: finished universes are not run again, a universe stopped half-way continues its
calibration and comparison, failed ones are retried. A folder holding a multiverse of other
parameters is refused (--overwrite starts afresh). Same inputs, same multiverse.csv,
multiverse.md and figures on any --threads, resumed, or sharded and merged. See
docs/multiverse.md.";

/// Arguments of `usar multiverse`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct MultiverseArgs {
    /// What to run.
    #[command(flatten)]
    pub spec: MultiverseSpecArgs,

    /// Worker threads (>= 1) of each calibration and comparison; default all cores. Never
    /// changes a result.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,

    /// Discard a multiverse already in the output folder (its universes and files) and start
    /// afresh (other files stay).
    #[arg(long, conflicts_with = "shard")]
    pub overwrite: bool,

    /// No progress bar and no line per universe.
    #[arg(long, short)]
    pub quiet: bool,

    /// Run only shard I of N (I from 0): a fixed, balanced share of the universes. No top
    /// files are written; once every shard is done, `usar merge OUT` writes them.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,

    /// Test hook: exit abruptly (status 75, no output files) after N calibration evaluations
    /// and comparison trials in all.
    #[arg(long, value_name = "N", hide = true)]
    pub stop_after: Option<usize>,

    /// Test hook: make comparison trial K of METHOD panic half-way in every universe
    /// (repeatable).
    #[arg(long, value_name = "METHOD:K", hide = true)]
    pub fail_trial: Vec<String>,
}

/// `--fail-trial METHOD:K`: the built-in method's display name (`RNE`) and the trial.
fn parse_fail(spec: &str) -> Result<(String, u32)> {
    let (m, k) = spec
        .rsplit_once(':')
        .and_then(|(m, k)| Some((m, k.trim().parse().ok()?)))
        .with_context(|| format!("--fail-trial {spec:?}: expected METHOD:K"))?;
    // A built-in's display name does not depend on the trust model's weights or the seed.
    let model = TrustModel::with_weights(Weights::uniform(1)?);
    let name = canonical_method(m, &MethodFactory::builtin(), &model, 0)
        .with_context(|| format!("--fail-trial {spec:?}"))?;
    Ok((name, k))
}

/// `--stop-after N`: hooks that exit the process abruptly once N calibration evaluations and
/// comparison trials (counted together) are recorded.
fn stop_hooks(limit: usize) -> MultiverseHooks {
    let count = Arc::new(AtomicUsize::new(0));
    let stop = move || {
        let n = count.fetch_add(1, Ordering::SeqCst) + 1;
        if n >= limit {
            crate::shared::stderr_lines::warn(format!("--stop-after {n}: stopping abruptly"));
            std::process::exit(STOP_EXIT_CODE);
        }
    };
    let again = stop.clone();
    MultiverseHooks {
        calibration: Some(Arc::new(move |_, _| stop())),
        sweep: SweepHooks {
            trial_observer: None,
            on_journaled: Some(Arc::new(move |_, _| again())),
            stop: None,
        },
        ..MultiverseHooks::default()
    }
}

/// Runs `usar multiverse`: run (or continue) the universes, write the top files, print the
/// summary.
///
/// # Errors
/// A bad scenario, axes file, targets file, `--free` or option; an output folder holding
/// another multiverse or locked by another run; an I/O error; or failed universes (after the
/// others have run and the files are written).
pub fn run(args: &MultiverseArgs, out: &mut dyn Write) -> Result<()> {
    let shard: Option<Shard> = args.shard.as_deref().map(str::parse).transpose()?;
    let mut setup = setup_of(&args.spec, threads_of(args.threads)?, shard)?;
    setup.overwrite = args.overwrite;
    if let Some(limit) = args.stop_after {
        setup.hooks = stop_hooks(limit);
    }
    if !args.fail_trial.is_empty() {
        let fail = args
            .fail_trial
            .iter()
            .map(|s| parse_fail(s))
            .collect::<Result<Vec<_>>>()?;
        setup.hooks.sweep.trial_observer = test_hooks(fail, None).trial_observer;
    }
    let dir = match &args.spec.out {
        Some(d) => d.clone(),
        None => default_dir(&setup)?,
    };
    let progress = if args.quiet {
        MultiverseProgress::off()
    } else {
        MultiverseProgress::terminal()
    };
    let o = run_multiverse(&setup, &dir, progress).map_err(|e| match e {
        MultiverseError::Owner(_) | MultiverseError::Lock(_) => {
            anyhow::Error::new(e).context(out_setting(args.spec.out.is_some()))
        }
        e => e.into(),
    })?;
    out.write_all(summary_text(&o, &dir).as_bytes())?;
    failed_universes(&o, "run the same command again to retry them")
}
