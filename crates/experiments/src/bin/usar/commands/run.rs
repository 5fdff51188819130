//! `usar run`: one mission trial; prints its metrics and optionally writes its `TrialResult`
//! as JSON.

use std::io::Write;

use std::path::PathBuf;

use std::time::Instant;

use anyhow::{Context, Result};

use clap::Args;

use usar_sim::mission::{Simulation, TrialResult};

use usar_sim::scenario::{self, path_text};

use usar_sweep::atomic::write_atomic;

use usar_sweep::metrics::{Metric, Quantity, Scope};

use usar_report::table::{column_width, num};

use usar_sweep::trial_json::TrialJson;

use crate::shared::scenario_warnings::warn_about;
use crate::shared::table_limits::{ROBOTS_TABLE_MAX, TASKS_TABLE_MAX};
use crate::shared::trial_build::{TRIAL_THREADS_HELP, build_trial, trial_pool, warn_if_rounded};

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

    /// Also write the full TrialResult as JSON to this file, with each task's figures under its
    /// name (`by_task.hard.rescued`) and their totals (`total.rescued`): atomically (a temporary file
    /// renamed over it); a symlink is followed and stays a symlink; a FIFO or character device
    /// (/dev/stdout) is written directly; a folder, block device or socket is refused.
    #[arg(long, value_name = "FILE.json")]
    pub json: Option<PathBuf>,

    /// Also write the trial's per-round yields as CSV to this file: one row per round and
    /// task (rescuees, why the group left its search area, trips, empty trips, members that
    /// left to rest, when the group was back and how long it waited; columns in
    /// docs/calibration.md, "Per-round yields"), and print a summary per task. Written as
    /// --json is.
    #[arg(long, value_name = "FILE.csv")]
    pub rounds_csv: Option<PathBuf>,

    /// Print the per-robot table and every group's robot ids even for a team of more than 50
    /// robots, which otherwise gets group sizes and a summary per kind.
    #[arg(long)]
    pub robots: bool,

    /// Print a line per task and a column per task in the rounds table even for more than 12
    /// tasks, which otherwise get the totals, the first and last three tasks and each round's
    /// rescuees summed over its tasks.
    #[arg(long)]
    pub tasks: bool,

    #[arg(long, value_name = "N", help = TRIAL_THREADS_HELP)]
    pub threads: Option<usize>,
}

/// Runs `usar run`.
///
/// # Errors
/// A bad scenario or option, a failing trial, or an I/O error.
pub fn run(args: &RunArgs, out: &mut dyn Write) -> Result<()> {
    let pool = trial_pool(args.threads)?;
    let scenario = scenario::load(&args.scenario)?;
    let mut builder = Simulation::builder(&scenario)
        .method_named(&args.method)
        .trial(args.trial.unwrap_or(0));
    if let Some(seed) = args.seed {
        builder = builder.seed(seed);
    }
    if let Some(d) = args.duration {
        builder = builder.duration_s(d);
    }
    let mut sim = build_trial(builder)?;
    warn_about(&path_text(&args.scenario), &scenario);
    warn_if_rounded(args.duration, &sim);
    let t0 = Instant::now();
    let result = pool
        .install(|| sim.run_to_end())
        .context("the trial failed")?;
    let wall = t0.elapsed().as_secs_f64();
    // A seed given as is belongs to no trial index.
    let per_robot = args.robots || result.robots.len() <= ROBOTS_TABLE_MAX;
    let per_task = args.tasks || result.tasks.len() <= TASKS_TABLE_MAX;
    let lines = Lines {
        per_robot,
        per_task,
    };
    print_result(&result, args.seed.is_none(), lines, out)?;
    writeln!(
        out,
        "\n{} s simulated in {:.2} s wall-clock ({} sim-s per wall-s)",
        result.duration_s,
        wall,
        usar_report::console::speed(result.duration_s / wall.max(1e-9))
    )?;
    if let Some(path) = &args.json {
        let json = serde_json::to_string_pretty(&TrialJson::of(&result))
            .context("serialising the result")?;
        write_atomic(path, json.as_bytes()).context("--json")?;
        writeln!(out, "wrote {}", path.display())?;
    }
    if let Some(path) = &args.rounds_csv {
        crate::shared::rounds_csv::write_rounds_csv(
            path,
            &[(0, std::slice::from_ref(&result))],
            out,
        )?;
    }
    Ok(())
}

/// Which of `usar run`'s tables get a line or column per robot and per task.
#[derive(Debug, Clone, Copy)]
pub struct Lines {
    /// The per-robot table and every group's robot ids (else group sizes and a summary per
    /// kind).
    pub per_robot: bool,
    /// A line per task and a column per task in the rounds table (else the totals, the first
    /// and last [`TASKS_SHOWN`] tasks and each round's rescuees summed over its tasks).
    pub per_task: bool,
}

/// Tasks shown at each end of the task table of a trial with many tasks.
pub const TASKS_SHOWN: usize = 3;

/// Prints a trial's metrics: rescuees and costs per task and in total, the rounds and the
/// per-robot table, as `lines` says ([`Lines`]). The header names the trial's index when
/// `indexed` (`trial 3`), else only its seed (`usar run --seed`).
///
/// # Errors
/// An I/O error writing to `out`.
pub fn print_result(
    r: &TrialResult,
    indexed: bool,
    lines: Lines,
    out: &mut dyn Write,
) -> Result<()> {
    let Lines {
        per_robot,
        per_task,
    } = lines;
    let trial = if indexed {
        format!("trial {}", r.trial)
    } else {
        "a trial".to_string()
    };
    writeln!(
        out,
        "{} {trial} with {} (seed {}), {} s",
        r.scenario, r.method, r.seed, r.duration_s
    )?;
    print_tasks(r, per_task, out)?;
    print_rounds(r, per_robot, per_task, out)?;
    if per_robot {
        print_robots(r, out)
    } else {
        print_kinds(r, out)
    }
}

fn print_tasks(r: &TrialResult, per_task: bool, out: &mut dyn Write) -> Result<()> {
    let width = column_width(r.tasks.iter().map(String::len).max().unwrap_or(0).max(7));
    writeln!(
        out,
        "\n{:<width$} {:>9} {:>13} {:>13} {:>15} {:>15}",
        "task", "rescuees", "energy (%)", "HP (%)", "energy/rescuee", "HP/rescuee"
    )?;
    let cell = |q: Quantity, scope: Scope| {
        Metric::new(q, scope)
            .value(r)
            .map_or_else(|| "n/a".to_string(), num)
    };
    let n = r.tasks.len();
    let shown = |t: &usize| per_task || *t < TASKS_SHOWN || *t + TASKS_SHOWN >= n;
    let scopes = (0..n)
        .filter(shown)
        .map(|t| (r.tasks[t].as_str(), Scope::Task(t)))
        .chain(std::iter::once(("total", Scope::Total)));
    for (name, scope) in scopes {
        if !per_task && scope == Scope::Task(n - TASKS_SHOWN) {
            writeln!(
                out,
                "... {} more tasks (every task: --tasks)",
                n - 2 * TASKS_SHOWN
            )?;
        }
        let rescued = Metric::new(Quantity::Rescued, scope)
            .value(r)
            .unwrap_or(0.0);
        writeln!(
            out,
            "{name:<width$} {rescued:>9} {:>13} {:>13} {:>15} {:>15}",
            cell(Quantity::Energy, scope),
            cell(Quantity::Hp, scope),
            cell(Quantity::EnergyPerRescuee, scope),
            cell(Quantity::HpPerRescuee, scope)
        )?;
    }
    Ok(())
}

fn print_rounds(
    r: &TrialResult,
    per_robot: bool,
    per_task: bool,
    out: &mut dyn Write,
) -> Result<()> {
    writeln!(
        out,
        "\nrounds: {} ({})",
        r.rounds.len(),
        r.mean_round_s().map_or_else(
            || "none completed".to_string(),
            |m| format!("mean completed round {} s", num(m))
        )
    )?;
    if !per_task {
        return print_rounds_summed(r, out);
    }
    write!(
        out,
        "{:>5} {:>9} {:>9} {:>9} {:>10}",
        "round", "start s", "end s", "length s", "completed"
    )?;
    for t in &r.tasks {
        write!(out, " {t:>5}")?;
    }
    let what = if per_robot { "groups" } else { "group sizes" };
    writeln!(out, "  {what} ({})", r.tasks.join(" | "))?;
    // Rounds are numbered from 1, as on the replay page.
    for (i, rd) in r.rounds.iter().enumerate() {
        write!(
            out,
            "{:>5} {:>9.2} {:>9.2} {:>9.2} {:>10}",
            i + 1,
            rd.start_s,
            rd.end_s,
            rd.end_s - rd.start_s,
            if rd.completed { "yes" } else { "no" },
        )?;
        for n in &rd.rescued {
            write!(out, " {n:>5}")?;
        }
        let groups: Vec<String> = rd
            .groups
            .iter()
            .map(|g| {
                if per_robot {
                    g.iter().map(usize::to_string).collect::<Vec<_>>().join(",")
                } else {
                    g.len().to_string()
                }
            })
            .collect();
        writeln!(out, "  {}", groups.join(" | "))?;
    }
    Ok(())
}

/// The rounds of a trial with many tasks: per round its times, the rescuees summed over its
/// tasks and the range of its groups' sizes.
fn print_rounds_summed(r: &TrialResult, out: &mut dyn Write) -> Result<()> {
    writeln!(
        out,
        "{:>5} {:>9} {:>9} {:>9} {:>10} {:>9}  groups ({} tasks; per task: --tasks)",
        "round",
        "start s",
        "end s",
        "length s",
        "completed",
        "rescuees",
        r.tasks.len()
    )?;
    for (i, rd) in r.rounds.iter().enumerate() {
        let sizes = rd.groups.iter().map(Vec::len);
        let (lo, hi) = (sizes.clone().min().unwrap_or(0), sizes.max().unwrap_or(0));
        let range = if lo == hi {
            lo.to_string()
        } else {
            format!("{lo} to {hi}")
        };
        writeln!(
            out,
            "{:>5} {:>9.2} {:>9.2} {:>9.2} {:>10} {:>9}  {} groups of {range} robots",
            i + 1,
            rd.start_s,
            rd.end_s,
            rd.end_s - rd.start_s,
            if rd.completed { "yes" } else { "no" },
            rd.rescued.iter().map(|&n| u64::from(n)).sum::<u64>(),
            rd.groups.len(),
        )?;
    }
    Ok(())
}

/// One line per kind, in the order of the kinds' first robots: the robots' count, their mean
/// distance, final energy and final HP, and their total recharges, pick-ups and deliveries.
fn print_kinds(r: &TrialResult, out: &mut dyn Write) -> Result<()> {
    writeln!(
        out,
        "\n{:<10} {:>6} {:>11} {:>12} {:>9} {:>8} {:>8} {:>8}   (per-robot table: --robots)",
        "kind", "robots", "mean dist m", "mean energy%", "mean HP%", "rech.", "picked", "deliv."
    )?;
    let mut kinds: Vec<&str> = Vec::new();
    for m in &r.robots {
        if !kinds.contains(&m.kind.as_str()) {
            kinds.push(&m.kind);
        }
    }
    for kind in kinds {
        let of_kind = || r.robots.iter().filter(move |m| m.kind == kind);
        let n = of_kind().count();
        let mean = |f: fn(&usar_sim::mission::RobotMetrics) -> f64| {
            of_kind().map(f).sum::<f64>() / n as f64
        };
        let total = |f: fn(&usar_sim::mission::RobotMetrics) -> u64| of_kind().map(f).sum::<u64>();
        writeln!(
            out,
            "{kind:<10} {n:>6} {:>11.1} {:>12.2} {:>9.2} {:>8} {:>8} {:>8}",
            mean(|m| m.distance_m),
            mean(|m| m.final_energy_pct),
            mean(|m| m.final_hp_pct),
            total(|m| u64::from(m.recharges)),
            total(|m| u64::from(m.picked_up)),
            total(|m| u64::from(m.delivered)),
        )?;
    }
    Ok(())
}

fn print_robots(r: &TrialResult, out: &mut dyn Write) -> Result<()> {
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
