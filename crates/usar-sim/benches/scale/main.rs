//! Scaling bench (issues 10 and 38): for teams of 12, 100, 1,000, 3,000 and 10,000 robots, the
//! cost of a world step with all logic (`Simulation::step`: rounds, decisions, navigation,
//! resolver, Rapier, accounting) against a fair bare-Rapier baseline that steps the same
//! motion: the same bodies, colliders, integration parameters and static obstacles, driven
//! step by step by the velocities the logic commanded (recorded one block of 50 steps at a
//! time and replayed; `measure.rs` says how, and checks that the replayed bodies stand where
//! the world's do, bit for bit). Per team it prints the steps each measurement covered (and
//! whether it was cut), steps per CPU second of the logic and of the replay, their ratio,
//! simulated seconds per CPU second and per wall second, the same with the robots' software
//! run every step for a scenario with a control period (`sim.control_period_s`; the swarm
//! scenarios decide every 0.1 s), and the process's peak resident memory during the team.
//!
//! Teams (`teams.rs`): 12 robots is `scenarios/paper.ron`; a team of `n` is
//! `scenarios/swarm-<n>.ron` when that file exists (or a `--scenario` file with `n` robots),
//! else `swarm-1000.ron` with its kinds' counts and quotas scaled to `n`, and beyond 1,000
//! robots its plan stretched by `sqrt(n / 1000)` so each robot has the base's room; every team
//! steps Rapier every step (`sim.physics: EveryStep`, whatever its file says, so the replay is
//! the same motion; the gated steppings are measured by `experiments`' `trials_per_cpu`
//! bench). Rates are
//! per CPU second of the stepping thread (`clock_gettime`'s thread CPU clock), so other load
//! on a shared machine does not count; logic and replay alternate block by block.
//!
//! Run in release: `cargo bench -p usar-sim --bench scale` (every team, 1,500 steps = 30
//! simulated seconds each, measured in full), or `cargo bench -p usar-sim --bench scale --
//! --quick` (teams of 12 and 100, 20 steps: a smoke test). Options: `--base FILE` (the
//! scenario to scale, default `scenarios/swarm-1000.ron`), `--scenario FILE` (repeatable: the
//! team of that file's robot count, as it is), `--method NAME` (default `dis`: the grouping
//! is not what is measured here), `--steps N` (steps per measurement from the trial's start,
//! default 1,500), `--budget-s S` (stop a measurement at the first block end after S
//! wall-clock seconds; the output then says `CUT` and after how many steps; no budget by
//! default), `--teams 12,100,...`, `--no-every-step` (skip the software-every-step
//! measurement), `--threads N` (default 2; 1 skips it: the scenario's trial run twice side by
//! side in alternating blocks, on one thread and on a pool of N, timed by the wall clock, with
//! the speed-up and a check that both runs' robots stand in the same places; `threads.rs`;
//! always the full `--steps`, `--budget-s` does not cut it),
//! `--svg FILE` (relative to the workspace root; also draw the curves, log-log, with the 10x
//! and 25x real-time lines; `docs/img/scaling.svg` is made this way).
//!
//! `--robot-step` measures instead the cost per robot-step (`robot_step.rs`: nanoseconds per
//! robot per step of the three `sim.physics` modes on 1 and `--threads` threads, beside bare
//! Rapier; teams 1,000, 10,000 and 100,000 by default, `--warmup-steps N` untimed steps
//! first, default 250; `--skip MODE@N` leaves a mode out at team `N`; `--svg` draws its
//! figure, `docs/img/robot-step.svg`).
//!
//! A team that cannot be built (a scaled start grid that no longer fits, a file that does not
//! parse), an unknown `--method` or a failing step stops the bench with a one-line error,
//! exit status 1; a bad option exits with status 2. A replay whose bodies or a two-thread run
//! whose robots did not stand where the world's did ends it with exit status 1 too, after its
//! table and figure.

#[path = "../common/mod.rs"]
mod common;
mod figure;
mod measure;
mod options;
mod robot_step;
mod robot_step_figure;
mod teams;
mod threads;

use measure::{Measured, measure, peak_rss_mib, reset_peak_rss};
use options::Options;
use threads::{Threaded, measure_threads};

/// One team's measurements: at the scenario's control period (if it has one) and with the
/// software every step (the scenario itself when it has no control period).
struct Row {
    robots: usize,
    control: Option<Measured>,
    every_step: Option<Measured>,
    threaded: Option<Threaded>,
    peak_rss_mib: f64,
}

/// Prints one measurement's coverage, rates and replay check, indented under its team.
fn report(label: &str, m: &Measured) {
    let replay = match m.diverged_at {
        None => "the replayed bodies stood where the world's did at every block end".to_owned(),
        Some(step) => format!("REPLAY DIVERGED: bodies differ from the world's at step {step}"),
    };
    println!("  {label}: {}", m.coverage());
    println!(
        "    logic {:.3} CPU-s ({:.3} wall-s), bare replay {:.3} CPU-s: {:.0} and {:.0} steps per CPU-s, logic/bare {:.2}, {:.1} sim-s per CPU-s, {:.1} sim-s per wall-s; {replay}",
        m.logic_cpu_s,
        m.logic_wall_s,
        m.bare_cpu_s,
        m.logic_rate(),
        m.bare_rate(),
        m.ratio(),
        m.logic_rate() * m.dt_s,
        m.steps as f64 * m.dt_s / m.logic_wall_s,
    );
}

/// Prints the one-against-several-threads measurement, indented under its team.
fn report_threads(t: &Threaded) {
    let same = match t.diverged_at {
        None => "the two runs' robots stood in the same places at every block end".to_owned(),
        Some(step) => format!("THE RUNS DIVERGED: robots stand apart at step {step}"),
    };
    println!(
        "  the scenario on 1 and on {} threads: {}, {:.3} and {:.3} wall-s, {:.1} and {:.1} sim-s per wall-s, speed-up {:.2}; {same}",
        t.threads,
        measure::window(t.warmup, t.steps, t.dt_s),
        t.one_wall_s,
        t.many_wall_s,
        t.one_rate(),
        t.many_rate(),
        t.speed_up(),
    );
}

/// Builds and measures the team of `n` (see the module docs). Errors: one line.
fn run_team(n: usize, o: &Options) -> Result<Row, String> {
    let rss_reset = reset_peak_rss();
    let team = teams::team(n, &o.base, &o.scenarios).map_err(|e| format!("team of {n}: {e}"))?;
    let s = &team.scenario;
    let period_s = s.sim().control_period_s.map(|p| p.get());
    println!("team of {n}: {}", team.source);
    let mut row = Row {
        robots: n,
        control: None,
        every_step: None,
        threaded: None,
        peak_rss_mib: 0.0,
    };
    let err = |e: String| format!("team of {n}: {e}");
    if let Some(p) = period_s {
        let m = measure(s, &o.method, 0, o.steps, o.budget_s).map_err(err)?;
        report(&format!("software every {p} s (the scenario)"), &m);
        row.control = Some(m);
        if !o.no_every_step {
            let each = s
                .edit(|spec| spec.sim.control_period_s = None)
                .map_err(|e| err(e.to_string()))?;
            let m = measure(&each, &o.method, 0, o.steps, o.budget_s).map_err(err)?;
            report("software every step", &m);
            row.every_step = Some(m);
        }
    } else {
        let m = measure(s, &o.method, 0, o.steps, o.budget_s).map_err(err)?;
        report("software every step (the scenario)", &m);
        row.every_step = Some(m);
    }
    if o.threads > 1 {
        let t = measure_threads(s, &o.method, 0, o.steps, o.threads).map_err(err)?;
        report_threads(&t);
        row.threaded = Some(t);
    }
    row.peak_rss_mib = peak_rss_mib();
    let since = if rss_reset {
        "this team"
    } else {
        "the process start"
    };
    println!(
        "  peak resident memory since {since}: {:.0} MiB",
        row.peak_rss_mib
    );
    Ok(row)
}

/// Four table cells of a measurement: steps (simulated seconds; `CUT` if cut), logic and bare
/// replay steps per CPU second, their ratio.
fn cells(m: Option<&Measured>) -> String {
    match m {
        None => "(none: the scenario decides every step) | | | ".to_owned(),
        Some(m) => format!(
            "{}{} ({:.0} s) | {:.0} | {:.0} | {:.2}",
            m.steps,
            if m.cut.is_some() { " CUT" } else { "" },
            m.steps as f64 * m.dt_s,
            m.logic_rate(),
            m.bare_rate(),
            m.ratio()
        ),
    }
}

/// Prints the summary table of every team (markdown); `threads` is the pool of the
/// one-against-several-threads measurement.
fn print_table(rows: &[Row], threads: usize) {
    println!();
    println!(
        "| robots | control period: steps (sim) | logic steps/CPU-s | bare replay steps/CPU-s | logic / bare | sim-s per CPU-s | software every step: steps (sim) | logic steps/CPU-s | bare replay steps/CPU-s | logic / bare | sim-s per wall-s, 1 thread | the same, {threads} threads | speed-up | peak RSS MiB |"
    );
    println!("|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for r in rows {
        let speed = r
            .control
            .as_ref()
            .or(r.every_step.as_ref())
            .map_or(String::new(), |m| format!("{:.1}", m.logic_rate() * m.dt_s));
        let every = match &r.every_step {
            None => " | | | ".to_owned(),
            Some(m) => cells(Some(m)),
        };
        let threaded = r.threaded.as_ref().map_or(" | | ".to_owned(), |t| {
            format!(
                "{:.1} | {:.1} | {:.2}",
                t.one_rate(),
                t.many_rate(),
                t.speed_up()
            )
        });
        println!(
            "| {} | {} | {speed} | {every} | {threaded} | {:.0} |",
            r.robots,
            cells(r.control.as_ref()),
            r.peak_rss_mib
        );
    }
}

fn main() {
    let o = options::options();
    if o.robot_step {
        let costs = robot_step::run(&o).unwrap_or_else(|e| {
            eprintln!("error: {e}");
            std::process::exit(1)
        });
        if let Some(path) = &o.svg {
            if let Err(e) = robot_step_figure::draw(&costs, o.threads, path) {
                eprintln!("error: cannot draw {path}: {e}");
                std::process::exit(1);
            }
            println!("figure: {}", teams::short(path));
        }
        fail_if_diverged(&robot_step::diverged(&costs));
        return;
    }
    println!(
        "scaling bench: method {}, {} steps per measurement{}, one thread, rates per CPU second of the thread; logic and bare-Rapier replay of its commands in alternating blocks of {} steps{}",
        o.method,
        o.steps,
        o.budget_s
            .map_or(", each measured in full".to_owned(), |b| format!(
                ", a measurement cut at the first block end after {b} s of wall time"
            )),
        measure::BLOCK_STEPS,
        if o.threads > 1 {
            format!(
                "; then the scenario on 1 and on {} threads side by side, by the wall clock",
                o.threads
            )
        } else {
            String::new()
        }
    );
    let mut rows = Vec::new();
    for &n in &o.teams {
        match run_team(n, &o) {
            Ok(row) => rows.push(row),
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(1);
            }
        }
    }
    print_table(&rows, o.threads);
    if let Some(path) = &o.svg {
        let points: Vec<figure::Point> = rows
            .iter()
            .map(|r| figure::Point {
                robots: r.robots,
                dt_s: r
                    .control
                    .as_ref()
                    .or(r.every_step.as_ref())
                    .map_or(0.02, |m| m.dt_s),
                control: r.control.as_ref().map(|m| (m.logic_rate(), m.bare_rate())),
                every_step: r
                    .every_step
                    .as_ref()
                    .map(|m| (m.logic_rate(), m.bare_rate())),
                threads: r.threaded.as_ref().map(Threaded::steps_per_wall_s),
            })
            .collect();
        if let Err(e) = figure::draw(&points, o.threads, path) {
            eprintln!("error: cannot draw {path}: {e}");
            std::process::exit(1);
        }
        println!("figure: {}", teams::short(path));
    }
    // A replay or a two-thread run that did not stand where the world did fails the bench,
    // after the table and the figure.
    fail_if_diverged(&diverged(&rows));
}

/// One line per team whose replays or two-thread run did not stand in the world's places
/// (empty when every one did).
fn diverged(rows: &[Row]) -> Vec<String> {
    rows.iter()
        .flat_map(|r| {
            let replays = [&r.control, &r.every_step]
                .into_iter()
                .filter_map(|m| m.as_ref()?.diverged_at)
                .map(move |step| format!("{} robots: a replay at step {step}", r.robots));
            let runs = r
                .threaded
                .as_ref()
                .and_then(|t| t.diverged_at)
                .map(|step| format!("{} robots: the two runs at step {step}", r.robots));
            replays.chain(runs)
        })
        .collect()
}

/// Ends the bench with exit status 1 and one line naming them when `diverged` is not empty.
fn fail_if_diverged(diverged: &[String]) {
    if !diverged.is_empty() {
        eprintln!("error: not the same places: {}", diverged.join("; "));
        std::process::exit(1);
    }
}
