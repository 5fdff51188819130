//! `usar merge DIR`: combines the journals of a sharded sweep's shards (`usar sweep ...
//! --shard I/N --out DIR`) into the files one sweep on one machine writes; for a multiverse's
//! folder (`usar multiverse ... --shard I/N --out DIR`), its universes' records into its top
//! files.

use std::io::Write;
use std::path::PathBuf;

use anyhow::{Result, bail};
use clap::Args;
use usar_sim::scenario::path_text;

use usar_report::analysis::Analysis;
use usar_report::console::print_sweep;
use usar_report::output::write_outputs;
use usar_study::multiverse::{is_multiverse_dir, merge_multiverse, summary_text};
use usar_sweep::shard::merge_shards;

use crate::shared::multiverse_spec::failed_universes;
use crate::shared::sweep_spec::{ReportArgs, grid_metrics};

const EXAMPLES: &str = "\
Examples:
  # Four shards of a sweep, on four machines (or one after another), then the merge
  usar sweep scenarios/paper.ron --trials 20 --shard 0/4 --out results/big
  usar sweep scenarios/paper.ron --trials 20 --shard 1/4 --out results/big
  usar sweep scenarios/paper.ron --trials 20 --shard 2/4 --out results/big
  usar sweep scenarios/paper.ron --trials 20 --shard 3/4 --out results/big
  usar merge results/big

  # The shards of a multiverse (usar multiverse ... --shard I/N --out results/mv)
  usar merge results/mv

Reads DIR/shards/<I>-of-<N>/journal.jsonl of every shard and writes into DIR what `usar sweep`
writes there (trials.csv, summary.csv, the figures and report.md; with --vary the cell folders,
grid.csv and grid.md); the CSV files are byte-identical to those of the same sweep run on one
machine. A shard with no journal, or with trials it has not run, stops the merge: the message
names it and gives the `usar sweep ... --shard I/N` command that runs it (again). Failed trials
are reported the same way after the files are written (non-zero exit status). See
docs/cluster.md. The reports compare with the targets and check the claims the shards were
given (--targets FILE, --claims FILE, recorded in their plan.json); --targets and --claims
here override.

A multiverse's folder (one with multiverse.json at its top or in its shard folders) is merged
from its universes' records: once every universe of the plan has its universes/<id>/
universe.json, DIR gets multiverse.csv, multiverse.md and the specification curves, the same
bytes as `usar multiverse` without --shard writes; otherwise the missing universes are listed
with the commands that run them. See docs/multiverse.md.";

/// Arguments of `usar merge`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct MergeArgs {
    /// The sweep's (or multiverse's) output folder (the --out of its shards).
    #[arg(value_name = "DIR")]
    pub dir: PathBuf,

    /// What the reports say beyond the results (a sweep's folder only); default what the
    /// shards were given.
    #[command(flatten)]
    pub report: ReportArgs,
}

/// Runs `usar merge`: merge, analyse, write, summarise.
///
/// # Errors
/// Missing or unfinished shards (named, with the commands to run them), journals of
/// different sweeps, an I/O error, or failed trials (after the files are written).
pub fn run(args: &MergeArgs, out: &mut dyn Write) -> Result<()> {
    if is_multiverse_dir(&args.dir) {
        if args.report.targets.is_some() || args.report.claims.is_some() {
            bail!(
                "--targets and --claims are for a sweep's folder; a multiverse's reports \
                 check the targets and claims its plan records"
            );
        }
        let here = std::env::current_dir().ok();
        let o = merge_multiverse(&args.dir, here.as_deref())?;
        out.write_all(summary_text(&o, &args.dir).as_bytes())?;
        return failed_universes(
            &o,
            "run the shards that hold them again (or the command without --shard, which runs \
             only what is missing or failed), then merge again",
        );
    }
    let m = merge_shards(&args.dir)?;
    for (path, r) in &m.rejected {
        crate::shared::stderr_lines::warn(format!(
            "warning: {}:{}: record does not verify (edited?); left out (trial {} #{} of cell {})",
            path_text(path),
            r.line,
            r.method,
            r.trial,
            r.cell
        ));
    }
    let tasks = m.config.scenario.task_names();
    let metrics = grid_metrics(&m.plan.grid_metrics, &tasks)?;
    let here = std::env::current_dir().ok();
    let report = ReportArgs {
        targets: (args.report.targets.clone()).or_else(|| m.plan.targets_path(here.as_deref())),
        claims: (args.report.claims.clone()).or_else(|| m.plan.claims_path(here.as_deref())),
    }
    .resolve(
        &m.config.scenario,
        &m.config.scenario_path,
        &m.config.methods,
    )?;
    let analysis = Analysis::with_report(&m.outcome, report);
    let files = write_outputs(&m.config, &m.outcome, &analysis, &metrics)?;
    writeln!(
        out,
        "merged {} shards of {}: {} trials",
        m.count,
        args.dir.display(),
        m.outcome.reused + m.outcome.failures().count()
    )?;
    print_sweep(out, &m.config, &m.outcome, &analysis, &metrics, &files)?;
    if m.failed_shards.is_empty() {
        return Ok(());
    }
    let commands: Vec<String> = m
        .failed_shards
        .iter()
        .map(|s| format!("  {}", m.plan.shard_command(*s, &args.dir, here.as_deref())))
        .collect();
    bail!(
        "{} trials failed (listed in report.md); the files above leave them out. Run their \
         shards again (a shard's command retries its failed trials), then merge again:\n{}",
        m.outcome.failures().count(),
        commands.join("\n")
    )
}
