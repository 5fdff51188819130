//! `usar sweep`: every grouping method for every trial of a scenario, in parallel, optionally
//! once per cell of a grid of scenario field values (`--vary`); writes `trials.csv`,
//! `summary.csv`, the Fig. 3 figures and `report.md` (per cell, plus `grid.csv` and
//! `grid.md` for a grid).

use std::io::Write;

use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};

use clap::Args;

use usar_sim::scenario::{self, Scenario, path_text};

use usar_report::analysis::Analysis;

use crate::shared::out_flag::out_setting;
use crate::shared::scenario_warnings::{scenario_warnings, warn_about as warn_about_scenario};
use crate::shared::sweep_spec::{
    ReportArgs, SweepSpecArgs, grid_metrics, threads_of, warn_if_rounded,
};
use crate::shared::test_hooks::test_hooks;

use usar_report::console::print_sweep;

use usar_sweep::grid::{Grid, build_grid};

use usar_report::output::write_outputs;

use usar_report::replay::{DEFAULT_HZ, SweepReplays, parse_replay_list};

use usar_sweep::error::SweepError;
use usar_sweep::method_factory::MethodError;
use usar_sweep::shard::{Shard, ShardRun, shell_join};

use usar_sweep::sweep::{
    MethodFactory, SweepConfig, SweepOutcome, canonical_method, default_out_dir, run_sweep,
    trust_model,
};

const EXAMPLES: &str = "\
Examples:
  # The paper's comparison: RNE, DIS, ENG, HP_DIS x 10 trials x 600 s, all cores, with the
  # paper's calibration targets and claims checked in report.md
  usar sweep scenarios/paper.ron --targets scenarios/paper-targets.ron \\
      --claims scenarios/paper-claims.ron

  # A quick look: two methods, 2 trials of 60 s, into a chosen folder
  usar sweep scenarios/paper.ron --methods rne,dis --trials 2 --duration 60 --out /tmp/quick

  # Continue a sweep that was interrupted (runs only the missing or failed trials)
  usar sweep scenarios/paper.ron --resume

  # A parameter sweep: the comparison once per value of a scenario field
  usar sweep scenarios/paper.ron --vary mission.hp_pct_per_step_in_radiation=0.0003,0.003 \\
      --methods rne,dis --trials 5 --out results/hp-rate

  # Two fields (2 x 3 cells, heat maps), a wildcard over a list, chosen metrics
  usar sweep scenarios/paper.ron --vary 'radiation_zones[*].dose_rate_factor=1,2' \\
      --vary 'kinds[0].max_speed_m_per_s=1.0,1.5,2.0' --grid-metrics rescued_total,rounds

  # Also write replays of two trials (replay-rne-0.html, replay-dis-3.html) beside the outputs
  usar sweep scenarios/paper.ron --replay rne:0,dis:3

  # Reproduce one cell as a file (each cell folder also holds its scenario.ron)
  usar check scenarios/paper.ron --set mission.hp_pct_per_step_in_radiation=0.003 --print

Output folder (default results/<scenario name>/): journal.jsonl (every finished trial, appended
as it ends), trials.csv, summary.csv, report.md, fig3a_rescuees.svg,
fig3b_energy_per_rescuee.svg, fig3c_hp_per_rescuee.svg. With --vary: journal.jsonl, grid.csv
(every metric, one row per cell x method x metric), grid.md and grid_<metric>.svg at the top,
and one folder per cell (c00_<field>=<value>...) with the files above plus scenario.ron. Field
paths are written as the loader's errors write them (mission.duration_s, kinds[0].count,
tasks.hard.goal_m, radiation_zones[*].radius_m); values are RON (0.003, true, Aerial,
(1.0, 2.0), Some(3), Grid(spacing_m: 2.0)), split on top-level commas. Every cell is validated like
a scenario file before anything runs. The CSV files depend only on the scenario, grid,
methods, trials, seed and duration (not on --threads or interruptions). Running the same
command again continues its journal (like --resume) and rewrites the files. One sweep at a time
writes into a folder: it holds a lock on sweep.lock there (the file keeps the pid of the last
holder; a killed sweep's lock ends with it). Every journal line carries a checksum: an edited
record is reported by line and its trial runs again; an edited header is refused.
report.md, grid.md and the summary compare with calibration targets only with --targets FILE,
and check the claims of a claims file only with --claims FILE (or the scenario's `report`
section: paper.ron names the paper's); these change no trial, so running the same sweep again
with other ones only rewrites the reports.
Trial k of every method starts from the same team, seed trial_seed(SEED, k); reproduce one row
with `usar run SCENARIO --method M --seed <seed column>`. The exit status is non-zero when a
trial failed; the others still run and are written.";

/// Arguments of `usar sweep`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct SweepArgs {
    /// What to sweep.
    #[command(flatten)]
    pub spec: SweepSpecArgs,

    /// What the reports say beyond the results.
    #[command(flatten)]
    pub report: ReportArgs,

    /// Worker threads (>= 1); default all cores. Capped, with a warning, at 4 x the available
    /// cores. Trials run in parallel, one thread each; with fewer trials than threads, a team
    /// of at least 512 robots gets the threads left over inside its trials, a smaller one no
    /// more threads than trials; at the sweep's tail, a team of at least 512 gets the threads
    /// whose trials have ended. Same results on any thread count.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,

    /// Continue the sweep journaled in the output folder: run only trials it lacks (or that
    /// failed). Refused if the journal was written with other parameters. (A journal with the
    /// same parameters is continued even without --resume.)
    #[arg(long)]
    pub resume: bool,

    /// Discard a journal already in the output folder, and the tables, figures and grid cells
    /// of that sweep, and start afresh (other files stay).
    #[arg(long, conflicts_with = "resume")]
    pub overwrite: bool,

    /// No progress bar (it is only drawn on a terminal anyway).
    #[arg(long, short)]
    pub quiet: bool,

    /// Run only shard I of N of the sweep (I from 0): a fixed, balanced share of its trials,
    /// journaled in `OUT/shards/<I>-of-<N>/`. No tables are written; once every shard is done,
    /// `usar merge OUT` writes them (the same as one sweep would). For job arrays:
    /// `--shard $SLURM_ARRAY_TASK_ID/N` (see `usar slurm`).
    #[arg(long, value_name = "I/N")]
    pub shard: Option<String>,

    /// Also write replays of these trials (`METHOD:TRIAL`, comma-separated, repeatable) as
    /// `replay-<method>-<trial>.html` beside the outputs (in every cell of a grid): recorded
    /// while the sweep runs them; a trial already in the journal is run once more, alone, for
    /// its replay. See `usar replay --help` and docs/replay.md.
    #[arg(long, value_name = "METHOD:TRIAL,..", conflicts_with = "shard")]
    pub replay: Vec<String>,

    /// Samples per simulated second of the replays (--replay).
    #[arg(long, value_name = "HZ", default_value_t = DEFAULT_HZ, requires = "replay")]
    pub replay_hz: f64,

    /// Also write every trial's per-round yields as CSV to this file (one row per cell, method,
    /// trial, round and task; the columns of `usar run --rounds-csv`, with `cell` the grid
    /// cell) and print a summary per task over all trials. Written from the journal after the
    /// sweep, so adding it to a finished sweep runs no trial again.
    #[arg(long, value_name = "FILE.csv", conflicts_with = "shard")]
    pub rounds_csv: Option<PathBuf>,

    /// Test hook: make trial K of METHOD panic half-way (repeatable).
    #[arg(long, value_name = "METHOD:K", hide = true)]
    pub fail_trial: Vec<String>,

    /// Test hook: exit abruptly (status 75, no output files) after N trials are journaled.
    #[arg(long, value_name = "N", hide = true)]
    pub stop_after: Option<usize>,
}

/// `--fail-trial METHOD:K`: the built-in method's display name (`RNE`) and the trial.
fn parse_fail(spec: &str, model: &rne_core::TrustModel, seed: u64) -> Result<(String, u32)> {
    let (m, k) = spec
        .rsplit_once(':')
        .with_context(|| format!("--fail-trial {spec:?}: expected METHOD:K"))?;
    let k = k
        .trim()
        .parse::<u32>()
        .with_context(|| format!("--fail-trial {spec:?}: K is not a trial index"))?;
    Ok((
        canonical_method(m, &MethodFactory::builtin(), model, seed)?,
        k,
    ))
}

/// The grid of `--vary`, built from the scenario file's spec; `None` without `--vary`. A grid
/// that would make the sweep larger than its limit is refused before any cell is built.
fn grid_of(args: &SweepSpecArgs) -> Result<Option<Grid>> {
    if args.vary.is_empty() {
        return Ok(None);
    }
    usar_sweep::sweep::check_grid_size(&args.vary, args.methods.len(), args.trials)?;
    let origin = path_text(&args.scenario);
    let text = scenario::read_source(&args.scenario)?;
    let spec = scenario::parse_spec(&text, &origin)?;
    Ok(Some(build_grid(&spec, &args.vary)?))
}

/// `e` of [`run_sweep`] with the flag it is about named: `--methods` for a method it cannot
/// build; `--out` for an output folder it could not take (its lock or its owner file), or,
/// when the folder is the default one (`out_given` false), how to set another.
fn name_the_flag(e: SweepError, out_given: bool) -> anyhow::Error {
    let flag = match (&e, out_given) {
        (SweepError::Method(MethodError::NeedsWeights(_)), _) => return e.into(),
        (SweepError::Method(_), _) => "--methods",
        (SweepError::Lock(_) | SweepError::Owner(_), _) => out_setting(out_given),
        _ => return e.into(),
    };
    anyhow::Error::new(e).context(flag)
}

/// The sweep's configuration from the arguments.
fn config(all: &SweepArgs) -> Result<SweepConfig> {
    let args = &all.spec;
    let scenario = scenario::load(&args.scenario)?;
    let model = trust_model(&scenario)?;
    let base_seed = args.seed.unwrap_or(scenario.sim().seed);
    let fail = all
        .fail_trial
        .iter()
        .map(|s| parse_fail(s, &model, base_seed))
        .collect::<Result<Vec<_>>>()?;
    for (m, k) in &fail {
        let methods = args
            .methods
            .iter()
            .map(|x| canonical_method(x.trim(), &MethodFactory::builtin(), &model, base_seed))
            .collect::<Result<Vec<_>, _>>()?;
        if !methods.contains(m) || *k >= args.trials {
            bail!("--fail-trial {m}:{k} names no trial of this sweep");
        }
    }
    let threads = threads_of(all.threads)?;
    let grid = grid_of(args)?;
    if let Some(d) = args.duration {
        warn_if_rounded(d, &scenario, grid.as_ref());
    }
    Ok(SweepConfig {
        scenario_path: args.scenario.clone(),
        grid,
        methods: args.methods.iter().map(|m| m.trim().to_string()).collect(),
        method_factory: MethodFactory::builtin(),
        trials: args.trials,
        base_seed,
        duration_s: args.duration,
        threads,
        out_dir: args
            .out
            .clone()
            .unwrap_or_else(|| default_out_dir(&scenario)),
        resume: all.resume,
        overwrite: all.overwrite,
        progress: !all.quiet,
        hooks: test_hooks(fail, all.stop_after),
        shard: shard_run(all)?,
        scenario,
    })
}

/// [`warn_about_scenario`] the scenario, or the cells of a grid: each warning once, with
/// the cells it holds for (`(cells 0, 2)`, or `(every cell)`).
fn warn_about(origin: &str, scenario: &Scenario, grid: Option<&Grid>) {
    let Some(g) = grid else {
        return warn_about_scenario(origin, scenario);
    };
    let mut found: Vec<(String, Vec<usize>)> = Vec::new();
    for (i, c) in g.cells.iter().enumerate() {
        for text in scenario_warnings(&c.scenario) {
            match found.iter_mut().find(|(t, _)| *t == text) {
                Some((_, cells)) => cells.push(i),
                None => found.push((text, vec![i])),
            }
        }
    }
    for (text, cells) in found {
        let at = if cells.len() == g.cells.len() {
            "every cell".to_string()
        } else {
            let list: Vec<String> = cells.iter().map(usize::to_string).collect();
            format!("cells {}", list.join(", "))
        };
        crate::shared::stderr_lines::warn(format!("warning: {origin} ({at}): {text}"));
    }
}

/// Runs `usar sweep`: run, analyse, write, summarise.
///
/// # Errors
/// A bad scenario, `--vary` or option, a journal that cannot be resumed, an I/O error, or
/// failed trials (after every other trial has run and the files are written).
pub fn run(args: &SweepArgs, out: &mut dyn Write) -> Result<()> {
    let mut cfg = config(args)?;
    let tasks = cfg.scenario.task_names();
    let metrics = grid_metrics(&args.spec.grid_metrics, &tasks)?;
    let replays = replays_of(args, &cfg)?;
    // Options first (a bad one is the only line), then what the scenario warns about.
    usar_sweep::sweep::check_trial_count(&cfg)?;
    let report = args
        .report
        .resolve(&cfg.scenario, &cfg.scenario_path, &cfg.methods)?;
    warn_about(
        &path_text(&cfg.scenario_path),
        &cfg.scenario,
        cfg.grid.as_ref(),
    );
    if let Some(r) = &replays {
        cfg.hooks.trial_observer = Some(r.observer_factory(cfg.hooks.trial_observer.take()));
    }
    let o = run_sweep(&cfg).map_err(|e| name_the_flag(e, args.spec.out.is_some()))?;
    if let Some(s) = &cfg.shard {
        print_shard(out, &cfg, s.shard, &o)?;
        return failed_trials(&cfg, &o);
    }
    let analysis = Analysis::with_report(&o, report);
    let files = write_outputs(&cfg, &o, &analysis, &metrics)?;
    print_sweep(out, &cfg, &o, &analysis, &metrics, &files)?;
    if let Some(path) = &args.rounds_csv {
        let cells: Vec<_> = o
            .cells
            .iter()
            .enumerate()
            .map(|(i, c)| (i, c.results.as_slice()))
            .collect();
        crate::shared::rounds_csv::write_rounds_csv(path, &cells, out)?;
    }
    if let Some(r) = &replays {
        for w in r.finish(&cfg, &o)? {
            writeln!(
                out,
                "replay: {} ({:.2} MB{})",
                w.path.display(),
                w.bytes as f64 / 1e6,
                if w.rerun {
                    ", trial run again for it: it was in the journal"
                } else {
                    ""
                }
            )?;
        }
    }
    failed_trials(&cfg, &o)
}

/// The replays `--replay` asks for, checked against the sweep's methods and trials before
/// any trial runs; `None` without `--replay`.
fn replays_of(args: &SweepArgs, cfg: &SweepConfig) -> Result<Option<SweepReplays>> {
    if args.replay.is_empty() {
        return Ok(None);
    }
    let model = trust_model(&cfg.scenario)?;
    let canonical = |m: &str| canonical_method(m, &cfg.method_factory, &model, cfg.base_seed).ok();
    let methods: Vec<String> = cfg.methods.iter().filter_map(|m| canonical(m)).collect();
    let requests = parse_replay_list(&args.replay, &methods, cfg.trials, &canonical)?;
    usar_report::replay::ReplayRecorder::new(args.replay_hz).context("--replay-hz")?;
    Ok(Some(SweepReplays::new(cfg, requests, args.replay_hz)?))
}

/// The shard and plan of `--shard`, if given (the plan records the report options, which
/// `usar merge` renders with).
fn shard_run(args: &SweepArgs) -> Result<Option<ShardRun>> {
    let Some(text) = &args.shard else {
        return Ok(None);
    };
    let mut plan = args.spec.plan()?;
    plan.targets.clone_from(&args.report.targets);
    plan.claims.clone_from(&args.report.claims);
    Ok(Some(ShardRun {
        shard: text.parse()?,
        plan,
    }))
}

/// What a shard did, and what to do next.
fn print_shard(
    out: &mut dyn Write,
    cfg: &SweepConfig,
    shard: Shard,
    o: &SweepOutcome,
) -> Result<()> {
    let done: usize = o
        .cells
        .iter()
        .map(|c| c.results.len() + c.failures.len())
        .sum();
    writeln!(
        out,
        "shard {shard} of sweep {}: {done} of the sweep's {} trials ({} run now on {} \
         thread(s) in {:.2} s, {} from the shard's journal)",
        o.header.scenario,
        o.expected_trials(),
        o.ran,
        o.threads,
        o.wall_s,
        o.reused
    )?;
    writeln!(
        out,
        "journal: {}",
        usar_sweep::journal::Journal::path_in(&cfg.journal_dir()).display()
    )?;
    writeln!(
        out,
        "when every shard of {} is done: {}",
        shard.count,
        merge_command(&cfg.out_dir)
    )?;
    Ok(())
}

/// `usar merge OUT`, quoted for a POSIX shell where it needs it.
fn merge_command(out_dir: &Path) -> String {
    shell_join(&["usar".into(), "merge".into(), out_dir.display().to_string()])
}

/// The error listing failed trials, if any.
fn failed_trials(cfg: &SweepConfig, o: &SweepOutcome) -> Result<()> {
    let failures: Vec<String> = o
        .failures()
        .map(|f| {
            let cell = match &cfg.grid {
                Some(g) => format!(" in cell {}", g.cells[f.cell].dir),
                None => String::new(),
            };
            format!("{} trial {}{cell} ({})", f.method, f.trial, f.message)
        })
        .collect();
    if failures.is_empty() {
        return Ok(());
    }
    bail!(
        "{} of {} trials failed: {}. The other trials are in the files above; run again with \
         --resume to retry the failed ones",
        failures.len(),
        o.expected_trials(),
        failures.join("; ")
    )
}
