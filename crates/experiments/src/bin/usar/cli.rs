//! The top-level `usar` command line: [`Cli`] and the [`Command`] enum.
//!
//! To add a subcommand: write `src/bin/usar/commands/<name>.rs` with an `Args` struct and a `run`
//! function, declare it in `commands/mod.rs`, add one variant to [`Command`] and one arm
//! to [`run`]. Existing subcommands need no change.

use std::io::Write;

use anyhow::Result;
use clap::{Parser, Subcommand};

use crate::commands;

const EXAMPLES: &str = "\
Examples:
  # Pairwise RNE trust of the paper's Example 1 (natural log, nats)
  usar trust --weights 6,4,2 --needs 86,120,30 --needs 20,30,10 --needs 80,115,25

  # Add agent-group and group-group trust (Examples 2 and 3)
  usar trust --weights 6,4,2 --needs 86,120,30 --group \"82,114,24;79,117,23\" --group \"40,56,12;56,48,15\"

  # Draw the paper's arena as SVG; add --trace to draw the paths of one trial
  usar render scenarios/paper.ron --out arena.svg
  usar render scenarios/paper.ron --out trace.svg --trace --duration 200

  # Watch trial 0 with RNE grouping in a browser: one self-contained HTML file
  usar replay scenarios/paper.ron --method rne --trial 0 --out replay.html

  # Validate a scenario; run one trial; run the paper's whole comparison (with its
  # calibration targets and claims checked in report.md)
  usar check scenarios/paper.ron
  usar run scenarios/paper.ron --method rne --trial 0
  usar sweep scenarios/paper.ron --targets scenarios/paper-targets.ron \\
      --claims scenarios/paper-claims.ron --out results/paper

  # A parameter sweep: the comparison once per value of a scenario field (see docs/sweeps.md)
  usar sweep scenarios/paper.ron --vary mission.hp_pct_per_step_in_radiation=0.0003,0.003

  # On a Slurm cluster: a job array of 8 shards and a merge job (see docs/cluster.md)
  usar slurm scenarios/paper.ron --trials 30 --out results/big --shards 8 --submit

  # Fit scenario fields to the authors' statistics (see docs/calibration.md)
  usar calibrate scenarios/paper.ron --targets scenarios/paper-targets.ron \\
      --free mission.hp_pct_per_step_in_radiation=0.002..0.02:log --out results/calibrate-paper

  # The comparison in every combination of the paper's open choices, each calibrated first
  # (see docs/multiverse.md)
  usar multiverse scenarios/paper.ron --axes scenarios/paper-axes.ron \\
      --targets scenarios/paper-targets.ron \\
      --free 'mission.hp_pct_per_step_in_radiation=0.001..0.02:log' \\
      --free 'mission.search_time_budget_s=6..30' --sample 64 --out results/multiverse-paper";

/// `usar`: RNE trust between robots and groups, and USAR multi-robot experiments.
#[derive(Debug, Parser)]
#[command(name = "usar", version, about, after_help = EXAMPLES)]
pub struct Cli {
    /// The subcommand to run.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands of `usar`.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// RNE trust values between robots and groups (paper Defs. 1-3, Examples 1-3).
    Trust(commands::trust::TrustArgs),
    /// Top-down SVG picture of a scenario, optionally with the robots' paths in one trial.
    Render(commands::render::RenderArgs),
    /// Record one trial and write a self-contained HTML page that plays it in a browser.
    Replay(commands::replay::ReplayArgs),
    /// Validate a scenario file and print what it holds (or the loader's error).
    Check(commands::check::CheckArgs),
    /// One mission trial: rescuees, costs, rounds and per-robot figures.
    Run(commands::run::RunArgs),
    /// Every grouping method x every trial in parallel: CSV tables, statistics, figures, report.
    Sweep(commands::sweep::SweepArgs),
    /// Combine the journals of a sweep's shards (`sweep --shard I/N`) into its files.
    Merge(commands::merge::MergeArgs),
    /// Run a sweep on a Slurm cluster: a job array of shards and a chained merge job.
    Slurm(commands::slurm::SlurmArgs),
    /// Fit scenario fields (`--free`) so that a sweep's statistics fall in target bands.
    Calibrate(commands::calibrate::CalibrateArgs),
    /// The comparison in every combination of the paper's open choices, each calibrated.
    Multiverse(commands::multiverse::MultiverseArgs),
}

/// Runs the parsed command, writing its report to `out`.
///
/// # Errors
/// Whatever the subcommand reports (bad input, I/O).
pub fn run(cli: Cli, out: &mut dyn Write) -> Result<()> {
    match cli.command {
        Command::Trust(args) => commands::trust::run(&args, out),
        Command::Render(args) => commands::render::run(&args, out),
        Command::Replay(args) => commands::replay::run(&args, out),
        Command::Check(args) => commands::check::run(&args, out),
        Command::Run(args) => commands::run::run(&args, out),
        Command::Sweep(args) => commands::sweep::run(&args, out),
        Command::Merge(args) => commands::merge::run(&args, out),
        Command::Slurm(args) => commands::slurm::run(&args, out),
        Command::Calibrate(args) => commands::calibrate::run(&args, out),
        Command::Multiverse(args) => commands::multiverse::run(&args, out),
    }
}
