//! `usar sweep`: every grouping method for every trial of a scenario, in parallel; writes
//! `trials.csv`, `summary.csv`, the Fig. 3 figures and `report.md`.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Context, Result, bail};
use clap::Args;
use rne_core::grouping::METHOD_NAMES;
use usar_sim::scenario;

use crate::report::{CLAIMS, check_claim, mean_sd};
use crate::stats::Summary;
use crate::summary::{metric, rows_of, values};
use crate::sweep::{
    MethodFactory, SweepConfig, TestHooks, canonical_method, default_out_dir, run_sweep,
    trust_model,
};

const EXAMPLES: &str = "\
Examples:
  # The paper's comparison: RNE, DIS, ENG, HP_DIS x 10 trials x 600 s, all cores
  usar sweep scenarios/paper.ron

  # A quick look: two methods, 2 trials of 60 s, into a chosen folder
  usar sweep scenarios/paper.ron --methods rne,dis --trials 2 --duration 60 --out /tmp/quick

  # Continue a sweep that was interrupted (runs only the missing or failed trials)
  usar sweep scenarios/paper.ron --resume

Output folder (default results/<scenario name>/): journal.jsonl (every finished trial, appended
as it ends), trials.csv, summary.csv, report.md, fig3a_rescuees.svg,
fig3b_energy_per_rescuee.svg, fig3c_hp_per_rescuee.svg. trials.csv and summary.csv depend only
on the scenario, methods, trials, seed and duration (not on --threads or interruptions).
Trial k of every method starts from the same team, seed trial_seed(SEED, k); reproduce one row
with `usar run SCENARIO --method M --seed <seed column>`. The exit status is non-zero when a
trial failed; the others still run and are written.";

/// Arguments of `usar sweep`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct SweepArgs {
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

    /// Output folder; default `results/<scenario name>/`.
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,

    /// Worker threads; default all cores.
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,

    /// Continue the sweep journaled in the output folder: run only trials it lacks (or that
    /// failed). Refused if the journal was written with other parameters.
    #[arg(long)]
    pub resume: bool,

    /// Discard a journal already in the output folder and start afresh.
    #[arg(long, conflicts_with = "resume")]
    pub overwrite: bool,

    /// No progress bar (it is only drawn on a terminal anyway).
    #[arg(long, short)]
    pub quiet: bool,

    /// Test hook: make trial K of METHOD panic half-way (repeatable).
    #[arg(long, value_name = "METHOD:K", hide = true)]
    pub fail_trial: Vec<String>,

    /// Test hook: exit abruptly (status 75, no output files) after N trials are journaled.
    #[arg(long, value_name = "N", hide = true)]
    pub stop_after: Option<usize>,
}

fn parse_fail(spec: &str, model: &rne_core::TrustModel) -> Result<(String, u32)> {
    let (m, k) = spec
        .rsplit_once(':')
        .with_context(|| format!("--fail-trial {spec:?}: expected METHOD:K"))?;
    let k = k
        .trim()
        .parse::<u32>()
        .with_context(|| format!("--fail-trial {spec:?}: K is not a trial index"))?;
    Ok((canonical_method(m, &MethodFactory::builtin(), model)?, k))
}

/// Runs `usar sweep`.
///
/// # Errors
/// A bad scenario or option, a journal that cannot be resumed, an I/O error, or failed trials
/// (after every other trial has run and the files are written).
pub fn run(args: &SweepArgs, out: &mut dyn Write) -> Result<()> {
    let scenario = scenario::load(&args.scenario)?;
    let model = trust_model(&scenario)?;
    let fail = args
        .fail_trial
        .iter()
        .map(|s| parse_fail(s, &model))
        .collect::<Result<Vec<_>>>()?;
    let threads = match args.threads {
        Some(0) => bail!("--threads must be at least 1"),
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    };
    let cfg = SweepConfig {
        scenario_path: args.scenario.clone(),
        methods: args.methods.iter().map(|m| m.trim().to_string()).collect(),
        method_factory: MethodFactory::builtin(),
        trials: args.trials,
        base_seed: args.seed.unwrap_or(scenario.sim.seed),
        duration_s: args.duration.unwrap_or(scenario.mission.duration_s),
        threads,
        out_dir: args
            .out
            .clone()
            .unwrap_or_else(|| default_out_dir(&scenario)),
        resume: args.resume,
        overwrite: args.overwrite,
        progress: !args.quiet,
        hooks: TestHooks {
            fail,
            stop_after: args.stop_after,
        },
        scenario,
    };
    let o = run_sweep(&cfg)?;

    // Terminal summary.
    let h = &o.header;
    writeln!(
        out,
        "sweep {}: {} x {} trials x {} s, base seed {}",
        h.scenario,
        h.methods.join(","),
        h.trials,
        h.duration_s,
        h.base_seed
    )?;
    if o.ran > 0 {
        let rate = o.simulated_s() / o.wall_s.max(1e-9);
        writeln!(
            out,
            "ran {} trials in {:.2} s on {} thread(s): {:.0} sim-s per wall-s ({:.0} per thread){}",
            o.ran,
            o.wall_s,
            o.threads,
            rate,
            rate / o.threads as f64,
            if o.reused > 0 {
                format!("; {} from the journal", o.reused)
            } else {
                String::new()
            }
        )?;
    } else {
        writeln!(out, "all {} trials came from the journal", o.reused)?;
    }
    let cols = [
        "rescued_total",
        "rescued_hard",
        "rescued_easy",
        "energy_per_hard_rescuee_pct",
        "hp_per_hard_rescuee_pct",
    ];
    write!(out, "\n{:<8}", "method")?;
    for c in ["total", "hard", "easy", "eng/hard", "hp/hard"] {
        write!(out, " {c:>16}")?;
    }
    writeln!(out)?;
    for m in &h.methods {
        let rows = rows_of(&o.results, m);
        write!(out, "{m:<8}")?;
        for c in cols {
            let cell = mean_sd(&Summary::of(&values(&rows, metric(c))));
            write!(out, " {cell:>16}")?;
        }
        writeln!(out)?;
    }
    writeln!(out, "\nclaims (one-sided Welch, p < 0.05):")?;
    for c in CLAIMS {
        let chk = check_claim(c, &o.results, &h.methods);
        // A NaN p (a comparison that could not be tested) makes the worst p NaN ("n/a"),
        // rather than being skipped by max.
        let worst_p = chk
            .comparisons
            .iter()
            .map(|x| x.welch.p)
            .reduce(|a, b| {
                if a.is_nan() || b.is_nan() {
                    f64::NAN
                } else {
                    a.max(b)
                }
            })
            .unwrap_or(f64::NAN);
        writeln!(
            out,
            "  ({}) {}: {} (max p = {})",
            c.id,
            c.text,
            chk.verdict.words(),
            crate::report::pval(worst_p)
        )?;
    }
    writeln!(out, "\nwrote:")?;
    for f in &o.files {
        writeln!(out, "  {}", f.display())?;
    }
    if !o.failures.is_empty() {
        let list = o
            .failures
            .iter()
            .map(|f| format!("{} trial {} ({})", f.method, f.trial, f.message))
            .collect::<Vec<_>>()
            .join("; ");
        bail!(
            "{} of {} trials failed: {list}. The other trials are in the files above; run again \
             with --resume to retry the failed ones",
            o.failures.len(),
            h.methods.len() * h.trials as usize
        );
    }
    Ok(())
}
