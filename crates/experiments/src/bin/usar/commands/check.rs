//! `usar check`: validates a scenario file (optionally with fields overridden by `--set`) and
//! prints what it holds, its scenario hash, or the resulting spec as RON; or the loader's
//! error.

use std::io::Write;

use std::path::PathBuf;

use anyhow::{Result, anyhow};

use clap::Args;

use usar_report::scenario_summary::ScenarioSummary;
use usar_sim::scenario::{self, number_text, path_text};

use usar_sweep::fingerprint::scenario_hash;

use usar_sweep::spec_ron::spec_to_ron;

use usar_sweep::vary::{Override, apply_overrides, brief, validate_overridden};

use crate::shared::scenario_warnings::warn_about;
use crate::shared::table_limits::{ROBOTS_TABLE_MAX, TASKS_TABLE_MAX};

use crate::shared::check_many_tasks;
use crate::shared::check_numbers::{decimals, metres, metres_range, short};

const EXAMPLES: &str = "\
Examples:
  # Validate the paper's scenario and print a summary (with its scenario hash)
  usar check scenarios/paper.ron

  # In a script: the exit status is non-zero for an invalid file
  usar check my.ron > /dev/null && echo valid

  # Override fields (paths and values as for `usar sweep --vary`) and write the result as a
  # scenario file: reproduces a grid cell's scenario.ron
  usar check scenarios/paper.ron --set mission.hp_pct_per_step_in_radiation=0.003 \\
      --set 'kinds[0].starts.first_m=(30.0, 3.0)' --print > hot.ron

  # A scenario of many tasks in full: every task's line and quota and distance columns
  usar check scenarios/swarm-100000.ron --tasks

  # Only the scenario hash (as in sweep journals, reports and grid.md)
  usar check results/grid/c01_hp_pct_per_step_in_radiation=0.003/scenario.ron --hash

An invalid file prints the loader's error as `file:line:col: field.path: message` on stderr;

a bad --set as `--set FIELD=VALUE: field.path: message`.";

/// Arguments of `usar check`.
#[derive(Debug, Clone, Args)]
#[command(after_help = EXAMPLES)]
pub struct CheckArgs {
    /// The scenario file (RON) to validate.
    #[arg(value_name = "SCENARIO")]
    pub scenario: PathBuf,

    /// Set a field before validating (repeatable, applied in order): a path such as
    /// `mission.duration_s`, `kinds[0].count` or `radiation_zones[*].radius_m`, and one RON
    /// value (commas included).
    #[arg(long, value_name = "FIELD=VALUE", allow_hyphen_values = true)]
    pub set: Vec<String>,

    /// Print the (overridden) scenario spec as RON, every field written out, instead of the
    /// summary.
    #[arg(long, conflicts_with = "hash")]
    pub print: bool,

    /// Print only the scenario hash.
    #[arg(long)]
    pub hash: bool,

    /// Print the per-robot table (start and distance to each task's goal) even for a team of
    /// more than 50 robots, which otherwise get a summary per kind.
    #[arg(long)]
    pub robots: bool,

    /// Print everything per task (a line per task, a quota column and a distance column per
    /// task, every radiation zone's dose factor and every rest station) even for more than 12
    /// tasks, which otherwise get a summary: quota and distance ranges, the first and last
    /// three tasks.
    #[arg(long)]
    pub tasks: bool,
}

/// Runs `usar check`. A valid scenario with tasks no group can rescue from or goals some
/// robots cannot reach also gets one warning line each on stderr ([`warn_about`]); the exit
/// status stays 0.
///
/// # Errors
/// Without `--set`, the loader's error (its message names the file, line, column and field),
/// unchanged; with it, a bad `--set` (`--set FIELD=VALUE: field.path: message`) or a rule the
/// overridden file breaks ([`validate_overridden`]).
pub fn run(args: &CheckArgs, out: &mut dyn Write) -> Result<()> {
    let origin = path_text(&args.scenario);
    let overrides = args
        .set
        .iter()
        .map(|a| Override::parse(a).map_err(|e| anyhow!("--set {}: {e}", brief(a))))
        .collect::<Result<Vec<_>>>()?;
    let needs_spec = args.print || !overrides.is_empty();
    let (spec, s) = if needs_spec {
        let text = scenario::read_source(&args.scenario)?;
        let spec = apply_overrides(&scenario::parse_spec(&text, &origin)?, &overrides)
            .map_err(|(i, e)| anyhow!("--set {}: {e}", overrides[i].brief()))?;
        let s = validate_overridden(&spec, &text, &origin, "--set", &overrides)
            .map_err(|e| anyhow!(e))?;
        (Some(spec), s)
    } else {
        (None, scenario::load(&args.scenario)?)
    };
    warn_about(&origin, &s);
    let hash = scenario_hash(&s)?;
    if args.hash {
        writeln!(out, "{hash}")?;
    } else if let (true, Some(spec)) = (args.print, &spec) {
        let mut comments = vec![format!("{origin}, scenario hash {hash}")];
        if !overrides.is_empty() {
            let sets: Vec<String> = overrides.iter().map(ToString::to_string).collect();
            comments[0] = format!("{origin} with {}, scenario hash {hash}", sets.join(", "));
        }
        write!(out, "{}", spec_to_ron(spec, &comments)?)?;
    } else {
        let summary = ScenarioSummary::of(&s)?;
        summarise(
            &summary,
            args.robots || s.robots().len() <= ROBOTS_TABLE_MAX,
            args.tasks || s.tasks().len() <= TASKS_TABLE_MAX,
            out,
        )?;
        writeln!(out, "scenario hash {}", summary.hash)?;
        let sets: Vec<String> = overrides.iter().map(|o| format!(" --set {o}")).collect();
        writeln!(out, "\n{}{}: valid", args.scenario.display(), sets.concat())?;
    }
    Ok(())
}

/// `rest station (x, y) r R m`, or for several `rest stations: (x, y) r R m, ...`.
fn rest_stations(s: &ScenarioSummary) -> String {
    let d = decimals(s);
    let one =
        |((x, y), r): &((f64, f64), f64)| format!("({}, {}) r {r} m", metres(*x, d), metres(*y, d));
    match s.rest_stations.as_slice() {
        [c] => format!("rest station {}", one(c)),
        list => {
            let all: Vec<String> = list.iter().map(one).collect();
            format!("rest stations: {}", all.join(", "))
        }
    }
}

/// Prints the summary of a valid scenario ([`ScenarioSummary`]): arena and timing, the kinds
/// with their quota per task, the tasks (hardest first marked by their difficulty), with
/// `per_robot` every robot's start and its distance to each task's goal (else the starts
/// summarised per kind), debris, radiation and the rest station. Without `per_task` the
/// description wraps and the tasks, quotas, distances, zones and stations are summarised
/// ([`check_many_tasks`]).
///
/// # Errors
/// An I/O error writing to `out`.
pub fn summarise(
    s: &ScenarioSummary,
    per_robot: bool,
    per_task: bool,
    out: &mut dyn Write,
) -> Result<()> {
    let title = format!("scenario {}: {}", s.name, s.description);
    if per_task {
        writeln!(out, "{title}")?;
    } else {
        writeln!(out, "{}", check_many_tasks::wrapped(&title))?;
    }
    // What a trial runs: whole steps (usar run, sweep and replay report this length).
    let rounded = if s.simulated_s == s.duration_s {
        String::new()
    } else {
        format!(
            "; mission.duration_s {} s rounded up to whole steps",
            number_text(s.duration_s)
        )
    };
    let control = match s.control_period_s {
        Some(p) => {
            let k = s.control_period_steps;
            let steps = if k == 1 {
                "1 step".to_string()
            } else {
                format!("{k} steps")
            };
            format!("; robots decide every {} s ({steps})", number_text(p))
        }
        None => String::new(),
    };
    let physics = match s.physics.as_str() {
        "NearContacts" => "; Rapier steps near contacts only",
        "NearBodies" => "; Rapier steps only the robots near contacts",
        _ => "",
    };
    writeln!(
        out,
        "arena {} m x {} m (walls {} m); step {} s, trial {} s ({} steps{rounded}), seed \
         {}{control}{physics}",
        s.arena.width_m,
        s.arena.height_m,
        s.arena.wall_thickness_m,
        s.dt_s,
        number_text(s.simulated_s),
        s.steps,
        s.seed
    )?;
    if per_task {
        kinds_table(s, out)?;
        tasks_table(s, out)?;
    } else {
        check_many_tasks::kinds_table(s, out)?;
        check_many_tasks::tasks_summary(s, out)?;
    }
    if per_robot {
        robots_table(s, out)?;
    } else if per_task {
        starts_by_kind(s, out)?;
    } else {
        check_many_tasks::starts_by_kind(s, out)?;
    }
    adversaries(s, per_task, out)
}

/// Per kind: the count, the extent of the start positions and the range of distances from a
/// start to each task's goal (straight line), metres: the team's layout in a few lines.
fn starts_by_kind(s: &ScenarioSummary, out: &mut dyn Write) -> Result<()> {
    let d = decimals(s);
    write!(
        out,
        "\nstarts by kind ({} robots; the per-robot table: --robots)\n{:<10} {:>6} {:>20} {:>20}",
        s.robots.len(),
        "kind",
        "count",
        "x range (m)",
        "y range (m)"
    )?;
    for t in &s.tasks {
        write!(out, " {:>18}", format!("->{} m", t.name))?;
    }
    writeln!(out)?;
    for k in &s.starts_by_kind {
        write!(
            out,
            "{:<10} {:>6} {:>20} {:>20}",
            k.kind,
            k.count,
            metres_range(k.x_range_m, d),
            metres_range(k.y_range_m, d)
        )?;
        for &to in &k.to_goal_m {
            write!(out, " {:>18}", metres_range(to, d))?;
        }
        writeln!(out)?;
    }
    Ok(())
}

fn kinds_table(s: &ScenarioSummary, out: &mut dyn Write) -> Result<()> {
    write!(
        out,
        "\n{:<10} {:<9} {:<7} {:>5}",
        "kind", "role", "moves", "count"
    )?;
    for t in &s.tasks {
        write!(out, " {:>6}", t.name)?;
    }
    writeln!(
        out,
        " {:>7} {:>6} {:>7} {:>7} {:>5} {:>5}",
        "speed", "sense", "observe", "radius", "cap", "res"
    )?;
    for k in &s.kinds {
        write!(
            out,
            "{:<10} {:<9} {:<7} {:>5}",
            k.name, k.role, k.locomotion, k.count
        )?;
        for (_, q) in &k.quota {
            write!(out, " {q:>6}")?;
        }
        writeln!(
            out,
            " {:>7} {:>6} {:>7} {:>7} {:>5} {:>5}",
            short(k.max_speed_m_per_s),
            short(k.sensing_range_m),
            short(k.observing_range_m),
            short(k.body_radius_m),
            k.carrying_capacity,
            k.rescuing_resources
        )?;
    }
    writeln!(
        out,
        "(task columns = quota per task; speed m/s; ranges and radius m)"
    )?;
    Ok(())
}

fn tasks_table(s: &ScenarioSummary, out: &mut dyn Write) -> Result<()> {
    writeln!(out)?;
    let m = |v: f64| metres(v, decimals(s));
    for task in &s.tasks {
        let ((ax0, ay0), (ax1, ay1)) = task.search_area_m;
        let (gx, gy) = task.goal_m;
        let ((dx, dy), dr) = task.drop_off;
        let (lo, hi, mean) = task.start_to_goal_m;
        writeln!(
            out,
            "task {} (difficulty {}, #{} of {} from the hardest): {} rescuees in \
             [{}, {}]-[{}, {}] m, goal ({}, {}), drop-off ({}, {}) r {} m; \
             start->goal {}-{} m (mean {})",
            task.name,
            task.difficulty,
            task.rank + 1,
            s.tasks.len(),
            task.rescuees,
            m(ax0),
            m(ay0),
            m(ax1),
            m(ay1),
            m(gx),
            m(gy),
            m(dx),
            m(dy),
            dr,
            m(lo),
            m(hi),
            m(mean)
        )?;
    }
    Ok(())
}

fn robots_table(s: &ScenarioSummary, out: &mut dyn Write) -> Result<()> {
    write!(out, "\n{:>3} {:<10} {:>14}", "id", "kind", "start (m)")?;
    for t in &s.tasks {
        write!(out, " {:>12}", format!("->{} m", t.name))?;
    }
    writeln!(out)?;
    let d = decimals(s);
    for r in &s.robots {
        let (x, y) = r.start_m;
        write!(
            out,
            "{:>3} {:<10} {:>14}",
            r.id,
            r.kind,
            format!("({}, {})", metres(x, d), metres(y, d))
        )?;
        for (_, dist) in &r.distance_to_goal_m {
            write!(out, " {:>12}", metres(*dist, d))?;
        }
        writeln!(out)?;
    }
    Ok(())
}

/// The debris, radiation and rest-station line and the needs weights; without `per_task`
/// long lists of dose factors and rest stations as ranges.
fn adversaries(s: &ScenarioSummary, per_task: bool, out: &mut dyn Write) -> Result<()> {
    let stations = match per_task {
        true => None,
        false => check_many_tasks::rest_stations(s),
    };
    let doses = if s.radiation_zones.is_empty() {
        String::new()
    } else if !per_task {
        let factors: Vec<f64> = s.radiation_zones.iter().map(|z| z.2).collect();
        format!(" ({})", check_many_tasks::dose_factors(&factors))
    } else {
        let factors: Vec<String> = s
            .radiation_zones
            .iter()
            .map(|(_, _, factor)| factor.to_string())
            .collect();
        format!(" (dose factors {})", factors.join(", "))
    };
    writeln!(
        out,
        "\ndebris: {} ({} rectangles, {} discs); radiation zones: {}{}; {}",
        s.debris_rects + s.debris_circles,
        s.debris_rects,
        s.debris_circles,
        s.radiation_zones.len(),
        doses,
        stations.unwrap_or_else(|| rest_stations(s))
    )?;
    writeln!(
        out,
        "needs weights (hp, v, sen, eng, res, cap, obs): {:?}",
        s.needs_weights
    )?;
    Ok(())
}
