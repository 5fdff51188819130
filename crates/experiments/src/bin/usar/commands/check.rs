//! `usar check`: validates a scenario file (optionally with fields overridden by `--set`) and
//! prints what it holds, its scenario hash, or the resulting spec as RON; or the loader's
//! error.

use std::io::Write;

use std::path::PathBuf;

use anyhow::{Result, anyhow};

use clap::Args;

use usar_sim::scenario::{self, Debris, Locomotion, Scenario, number_text, path_text};
use usar_sim::world::ControlClock;

use usar_sweep::fingerprint::scenario_hash;

use usar_sweep::spec_ron::spec_to_ron;

use usar_sweep::vary::{Override, apply_overrides, brief, validate_overridden};

use crate::shared::scenario_warnings::warn_about;

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
}

/// Teams of at most this many robots get the per-robot table in `usar check`'s summary; larger
/// ones a summary per kind (counts, start extent, distance ranges), unless `--robots`.
pub const ROBOTS_TABLE_MAX: usize = 50;

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
        summarise(&s, args.robots || s.robots().len() <= ROBOTS_TABLE_MAX, out)?;
        writeln!(out, "scenario hash {hash}")?;
        let sets: Vec<String> = overrides.iter().map(|o| format!(" --set {o}")).collect();
        writeln!(out, "\n{}{}: valid", args.scenario.display(), sets.concat())?;
    }
    Ok(())
}

/// Decimals of the positions and distances the summary prints: 1 in an arena whose shorter
/// side is 10 m or more, one more per factor of ten below that (3 for a 0.5 m arena, 4 for
/// 8 cm), so that points a tenth of the arena's scale apart never print alike.
fn decimals(s: &Scenario) -> usize {
    decimals_for_side(s.arena().width().min(s.arena().height()))
}

/// [`decimals`] of an arena whose shorter side is `side_m` metres (> 0).
fn decimals_for_side(side_m: f64) -> usize {
    if side_m >= 10.0 {
        1
    } else {
        1 + (10.0 / side_m).log10().ceil().clamp(0.0, 15.0) as usize
    }
}

/// `v` metres with the summary's [`decimals`].
fn metres(v: f64, decimals: usize) -> String {
    format!("{v:.decimals$}")
}

/// `rest station (x, y) r R m`, or for several `rest stations: (x, y) r R m, ...`.
fn rest_stations(s: &Scenario) -> String {
    let d = decimals(s);
    let one = |c: &usar_sim::scenario::Circle| {
        format!(
            "({}, {}) r {} m",
            metres(c.center.x, d),
            metres(c.center.y, d),
            c.radius_m
        )
    };
    match s.rest_stations() {
        [c] => format!("rest station {}", one(c)),
        list => {
            let all: Vec<String> = list.iter().map(one).collect();
            format!("rest stations: {}", all.join(", "))
        }
    }
}

/// Prints a summary of a valid scenario: arena and timing, the kinds with their quota per
/// task, the tasks (hardest first marked by their difficulty), with `per_robot` every
/// robot's start and its distance to each task's goal (else the starts summarised per kind),
/// debris, radiation and the rest station.
///
/// # Errors
/// An I/O error writing to `out`.
pub fn summarise(s: &Scenario, per_robot: bool, out: &mut dyn Write) -> Result<()> {
    writeln!(out, "scenario {}: {}", s.name(), s.description())?;
    let (dt_s, duration_s) = (s.sim().dt_s.get(), s.mission().duration_s.get());
    // What a trial runs: whole steps (usar run, sweep and replay report this length).
    let run_s = usar_sweep::sweep::simulated_length_s(duration_s, dt_s);
    let rounded = if run_s == duration_s {
        String::new()
    } else {
        format!(
            "; mission.duration_s {} s rounded up to whole steps",
            number_text(duration_s)
        )
    };
    let control = match s.sim().control_period_s {
        Some(p) => {
            let k = ControlClock::of(s.sim()).period_steps();
            let steps = if k == 1 {
                "1 step".to_string()
            } else {
                format!("{k} steps")
            };
            format!("; robots decide every {} s ({steps})", number_text(p.get()))
        }
        None => String::new(),
    };
    let physics = match s.sim().physics {
        usar_sim::scenario::PhysicsStepping::EveryStep => "",
        usar_sim::scenario::PhysicsStepping::NearContacts => "; Rapier steps near contacts only",
        usar_sim::scenario::PhysicsStepping::NearBodies => {
            "; Rapier steps only the robots near contacts"
        }
    };
    writeln!(
        out,
        "arena {} m x {} m (walls {} m); step {} s, trial {} s ({} steps{rounded}), seed \
         {}{control}{physics}",
        s.arena().width_m,
        s.arena().height_m,
        s.arena().wall_thickness_m,
        s.sim().dt_s,
        number_text(run_s),
        s.steps_per_trial(),
        s.sim().seed
    )?;
    kinds_table(s, out)?;
    tasks_table(s, out)?;
    if per_robot {
        robots_table(s, out)?;
    } else {
        starts_by_kind(s, out)?;
    }
    adversaries(s, out)
}

/// Per kind: the count, the extent of the start positions and the range of distances from a
/// start to each task's goal (straight line), metres: the team's layout in a few lines.
fn starts_by_kind(s: &Scenario, out: &mut dyn Write) -> Result<()> {
    let d = decimals(s);
    write!(
        out,
        "\nstarts by kind ({} robots; the per-robot table: --robots)\n{:<10} {:>6} {:>20} {:>20}",
        s.robots().len(),
        "kind",
        "count",
        "x range (m)",
        "y range (m)"
    )?;
    for t in s.tasks() {
        write!(out, " {:>18}", format!("->{} m", t.name))?;
    }
    writeln!(out)?;
    let range = |v: &mut dyn Iterator<Item = f64>| {
        let (lo, hi) = v.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
            (a.min(x), b.max(x))
        });
        format!("{}..{}", metres(lo, d), metres(hi, d))
    };
    for (k, kind) in s.kinds().iter().enumerate() {
        let starts: Vec<scenario::PointM> = s
            .robots()
            .iter()
            .filter(|r| r.kind == k)
            .map(|r| r.start_in_world)
            .collect();
        if starts.is_empty() {
            continue;
        }
        write!(
            out,
            "{:<10} {:>6} {:>20} {:>20}",
            kind.name,
            starts.len(),
            range(&mut starts.iter().map(|p| p.x)),
            range(&mut starts.iter().map(|p| p.y))
        )?;
        for t in s.tasks() {
            let dist = range(&mut starts.iter().map(|&p| nalgebra_dist(p, t.goal)));
            write!(out, " {dist:>18}")?;
        }
        writeln!(out)?;
    }
    Ok(())
}

fn kinds_table(s: &Scenario, out: &mut dyn Write) -> Result<()> {
    write!(
        out,
        "\n{:<10} {:<9} {:<7} {:>5}",
        "kind", "role", "moves", "count"
    )?;
    for t in s.tasks() {
        write!(out, " {:>6}", t.name)?;
    }
    writeln!(
        out,
        " {:>7} {:>6} {:>7} {:>7} {:>5} {:>5}",
        "speed", "sense", "observe", "radius", "cap", "res"
    )?;
    for k in s.kinds() {
        let moves = match k.locomotion {
            Locomotion::Ground => "ground",
            Locomotion::Aerial => "aerial",
        };
        write!(
            out,
            "{:<10} {:<9} {:<7} {:>5}",
            k.name,
            format!("{:?}", k.role),
            moves,
            k.count
        )?;
        for q in &k.quota {
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

fn tasks_table(s: &Scenario, out: &mut dyn Write) -> Result<()> {
    writeln!(out)?;
    let order = s.hardest_first();
    for (t, task) in s.tasks().iter().enumerate() {
        let d: Vec<f64> = s
            .robots()
            .iter()
            .map(|r| nalgebra_dist(r.start_in_world, task.goal))
            .collect();
        let (lo, hi) = d
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
                (a.min(*x), b.max(*x))
            });
        let mean = d.iter().sum::<f64>() / d.len().max(1) as f64;
        let rank = order.iter().position(|&x| x == t).unwrap_or(0) + 1;
        let m = |v: f64| metres(v, decimals(s));
        let (area, goal, drop) = (&task.search_area, &task.goal, &task.drop_off);
        writeln!(
            out,
            "task {} (difficulty {}, #{rank} of {} from the hardest): {} rescuees in \
             [{}, {}]-[{}, {}] m, goal ({}, {}), drop-off ({}, {}) r {} m; \
             start->goal {}-{} m (mean {})",
            task.name,
            task.difficulty,
            s.tasks().len(),
            task.rescuees.len(),
            m(area.min.x),
            m(area.min.y),
            m(area.max.x),
            m(area.max.y),
            m(goal.x),
            m(goal.y),
            m(drop.center.x),
            m(drop.center.y),
            drop.radius_m,
            m(lo),
            m(hi),
            m(mean)
        )?;
    }
    Ok(())
}

fn robots_table(s: &Scenario, out: &mut dyn Write) -> Result<()> {
    write!(out, "\n{:>3} {:<10} {:>14}", "id", "kind", "start (m)")?;
    for t in s.tasks() {
        write!(out, " {:>12}", format!("->{} m", t.name))?;
    }
    writeln!(out)?;
    let d = decimals(s);
    for (id, r) in s.robots().iter().enumerate() {
        let (x, y) = (r.start_in_world.x, r.start_in_world.y);
        write!(
            out,
            "{:>3} {:<10} {:>14}",
            id,
            s.kind_of(id).name,
            format!("({}, {})", metres(x, d), metres(y, d))
        )?;
        for t in s.tasks() {
            let dist = metres(nalgebra_dist(r.start_in_world, t.goal), d);
            write!(out, " {dist:>12}")?;
        }
        writeln!(out)?;
    }
    Ok(())
}

fn adversaries(s: &Scenario, out: &mut dyn Write) -> Result<()> {
    let rects = s
        .debris()
        .iter()
        .filter(|d| matches!(d, Debris::Rect { .. }))
        .count();
    let doses = if s.radiation_zones().is_empty() {
        String::new()
    } else {
        let factors: Vec<String> = s
            .radiation_zones()
            .iter()
            .map(|z| z.dose_rate_factor.to_string())
            .collect();
        format!(" (dose factors {})", factors.join(", "))
    };
    writeln!(
        out,
        "\ndebris: {} ({} rectangles, {} discs); radiation zones: {}{}; {}",
        s.debris().len(),
        rects,
        s.debris().len() - rects,
        s.radiation_zones().len(),
        doses,
        rest_stations(s)
    )?;
    writeln!(
        out,
        "needs weights (hp, v, sen, eng, res, cap, obs): {:?}",
        s.needs_weights().to_array()
    )?;
    Ok(())
}

fn nalgebra_dist(a: scenario::PointM, b: scenario::PointM) -> f64 {
    (a - b).norm()
}

/// `x` rounded to 4 decimals, as short as Rust writes it (`2.5`, `1.6667`), for table columns.
fn short(x: f64) -> String {
    ((x * 1e4).round() / 1e4).to_string()
}

#[cfg(test)]
mod tests {
    use super::{decimals_for_side, metres};

    #[test]
    fn small_arenas_print_positions_with_more_decimals() {
        assert_eq!(decimals_for_side(80.0), 1);
        assert_eq!(decimals_for_side(10.0), 1);
        assert_eq!(decimals_for_side(9.9), 2);
        assert_eq!(decimals_for_side(1.0), 2);
        assert_eq!(decimals_for_side(0.5), 3);
        assert_eq!(decimals_for_side(0.08), 4);
        // Millimetre positions in an 8 cm arena print apart (they printed (0.0, 0.0)).
        let d = decimals_for_side(0.08);
        assert_eq!(metres(0.002, d), "0.0020");
        assert_ne!(metres(0.002, d), metres(0.003, d));
        assert_eq!(metres(32.5, decimals_for_side(80.0)), "32.5");
    }
}
