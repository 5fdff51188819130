//! `usar run`: one mission trial; prints its metrics and optionally writes its `TrialResult`
//! as JSON.

use std::io::Write;
use std::path::PathBuf;
use std::time::Instant;

use anyhow::{Context, Result, bail};
use clap::Args;
use rne_core::grouping::method_from_name;
use usar_sim::mission::{Simulation, TrialResult};
use usar_sim::scenario::{self, TaskLevel};

use crate::atomic::write_atomic;
use crate::sweep::trust_model;
use crate::table::num;

const EXAMPLES: &str = "\
Examples:
  # Trial 0 of the paper's mission with RNE grouping (the same team as trial 0 of a sweep)
  usar run scenarios/paper.ron --method rne

  # A given starting-team seed (e.g. the seed column of a sweep's trials.csv), 120 s only
  usar run scenarios/paper.ron --method dis --seed 1 --duration 120

  # Trial 3 with HP_DIS, the full result as JSON
  usar run scenarios/paper.ron --method hp_dis --trial 3 --json trial3.json

Methods: rne, dis, eng, hp_dis. --trial K uses seed trial_seed(scenario sim.seed, K), as trial
K of `usar sweep` without --seed; --seed S uses S itself as the starting team's seed.";

/// Arguments of `usar run`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct RunArgs {
    /// The scenario file (RON), e.g. scenarios/paper.ron.
    #[arg(value_name = "SCENARIO")]
    pub scenario: PathBuf,

    /// Grouping method: rne, dis, eng or hp_dis.
    #[arg(long, value_name = "NAME", default_value = "rne")]
    pub method: String,

    /// Index of the trial (0-based; selects the starting team's energy and HP).
    #[arg(long, value_name = "N", conflicts_with = "seed")]
    pub trial: Option<u32>,

    /// Seed of the starting team, used as is (a sweep's trials.csv `seed` column).
    #[arg(long, value_name = "SEED")]
    pub seed: Option<u64>,

    /// Length of the trial, seconds (> 0); default the scenario's mission.duration_s.
    #[arg(long, value_name = "SECONDS", allow_hyphen_values = true)]
    pub duration: Option<f64>,

    /// Also write the full TrialResult as JSON to this file: atomically (a temporary file
    /// renamed over it); a symlink is followed and stays a symlink; a FIFO or character device
    /// (/dev/stdout) is written directly; a folder, block device or socket is refused.
    #[arg(long, value_name = "FILE.json")]
    pub json: Option<PathBuf>,
}

/// Runs `usar run`.
///
/// # Errors
/// A bad scenario or option, a failing trial, or an I/O error.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<()> {
    let scenario = scenario::load(&args.scenario)?;
    let model = trust_model(&scenario)?;
    let method = method_from_name(&args.method, &model).context("--method")?;
    let mut sim = match (args.seed, args.trial) {
        (Some(seed), _) => Simulation::new(&scenario, method, seed),
        (None, trial) => Simulation::for_trial(&scenario, method, trial.unwrap_or(0)),
    };
    if let Some(d) = args.duration {
        if !(d.is_finite() && d > 0.0) {
            bail!("--duration: expected a number of seconds > 0, found {d}");
        }
        sim = sim.with_duration_s(d);
    }
    let t0 = Instant::now();
    let result = sim.run_to_end().context("the trial failed")?;
    let wall = t0.elapsed().as_secs_f64();
    print_result(&result, out)?;
    writeln!(
        out,
        "\n{} s simulated in {:.2} s wall-clock ({:.0} sim-s per wall-s)",
        result.duration_s,
        wall,
        result.duration_s / wall.max(1e-9)
    )?;
    if let Some(path) = &args.json {
        let json = serde_json::to_string_pretty(&result).context("serialising the result")?;
        write_atomic(path, json.as_bytes())?;
        writeln!(out, "wrote {}", path.display())?;
    }
    Ok(())
}

/// Prints a trial's metrics: rescuees, costs, rounds and the per-robot table.
///
/// # Errors
/// An I/O error writing to `out`.
pub fn print_result(r: &TrialResult, out: &mut dyn Write) -> Result<()> {
    let row = r.row();
    let opt = |x: Option<f64>| x.map_or_else(|| "n/a".to_string(), num);
    writeln!(
        out,
        "{} trial {} with {} (seed {}), {} s",
        r.scenario, r.trial, r.method, r.seed, r.duration_s
    )?;
    writeln!(
        out,
        "\n{:<7} {:>9} {:>13} {:>13} {:>15} {:>15}",
        "task", "rescuees", "energy (%)", "HP (%)", "energy/rescuee", "HP/rescuee"
    )?;
    let lines = [
        (
            "hard",
            row.rescued_hard,
            row.energy_hard_pct,
            row.hp_hard_pct,
            row.energy_per_hard_rescuee_pct,
            row.hp_per_hard_rescuee_pct,
        ),
        (
            "easy",
            row.rescued_easy,
            row.energy_easy_pct,
            row.hp_easy_pct,
            row.energy_per_easy_rescuee_pct,
            row.hp_per_easy_rescuee_pct,
        ),
        (
            "total",
            row.rescued_total,
            row.energy_total_pct,
            row.hp_total_pct,
            row.energy_per_rescuee_pct,
            row.hp_per_rescuee_pct,
        ),
    ];
    for (name, n, e, h, epr, hpr) in lines {
        writeln!(
            out,
            "{name:<7} {n:>9} {:>13} {:>13} {:>15} {:>15}",
            num(e),
            num(h),
            opt(epr),
            opt(hpr)
        )?;
    }
    writeln!(
        out,
        "\nrounds: {} ({})",
        r.rounds.len(),
        r.mean_round_s().map_or_else(
            || "none completed".to_string(),
            |m| format!("mean completed round {} s", num(m))
        )
    )?;
    writeln!(
        out,
        "{:>5} {:>9} {:>9} {:>9} {:>10} {:>5} {:>5}  groups (easy | hard)",
        "round", "start s", "end s", "length s", "completed", "easy", "hard"
    )?;
    for (i, rd) in r.rounds.iter().enumerate() {
        let ids = |v: &[usize]| v.iter().map(usize::to_string).collect::<Vec<_>>().join(",");
        writeln!(
            out,
            "{:>5} {:>9.2} {:>9.2} {:>9.2} {:>10} {:>5} {:>5}  {} | {}",
            i,
            rd.start_s,
            rd.end_s,
            rd.end_s - rd.start_s,
            if rd.completed { "yes" } else { "no" },
            rd.rescued.get(TaskLevel::Easy),
            rd.rescued.get(TaskLevel::Hard),
            ids(&rd.groups.easy),
            ids(&rd.groups.hard)
        )?;
    }
    writeln!(
        out,
        "\n{:>3} {:<10} {:>8} {:>8} {:>8} {:>8} {:>7} {:>6} {:>8} {:>7} {:>6} {:>6} {:>6}",
        "id",
        "kind",
        "dist m",
        "energy%",
        "spent%",
        "HP%",
        "lost%",
        "rech.",
        "rad. s",
        "held s",
        "deadl.",
        "picked",
        "deliv."
    )?;
    for m in &r.robots {
        writeln!(
            out,
            "{:>3} {:<10} {:>8.1} {:>8.2} {:>8.2} {:>8.2} {:>7.3} {:>6} {:>8.1} {:>7.1} {:>6} {:>6} {:>6}",
            m.id,
            m.kind,
            m.distance_m,
            m.final_energy_pct,
            m.energy_spent_pct,
            m.final_hp_pct,
            m.hp_lost_pct,
            m.recharges,
            m.time_in_radiation_s,
            m.time_held_s,
            m.deadlocks_resolved,
            m.picked_up,
            m.delivered
        )?;
    }
    Ok(())
}
