//! The cost per robot-step (`--robot-step`, issue 73): for each team (default the shipped
//! `scenarios/swarm-1000.ron`, `swarm-10000.ron` and `swarm-100000.ron`, as they are but for
//! `sim.physics`), for each of the three `sim.physics` modes (`EveryStep`, `NearContacts`,
//! `NearBodies`, set with `Scenario::edit`), trial 0 on one thread and on a rayon pool of
//! `--threads` threads side by side (`threads.rs`: alternating blocks, the per-robot stages on
//! the pool as `usar run --threads N` runs them, the robots compared at every block end), after
//! `--warmup-steps` untimed steps (default 250 = 5 simulated seconds: the first round's plans
//! are made), timed over a window of `--steps` steps, by the wall clock and by the process's
//! CPU clock (every thread); and bare Rapier: `measure.rs`'s replay of the `EveryStep` logic's
//! commands over the same window, one thread, by the thread's CPU clock. Every cost is
//! printed in nanoseconds per robot per step (the cost over steps x robots).
//!
//! The window is the same for every configuration of a team: `--steps` when given, else
//! 5 million robot-steps bounded to 100 to 1,000 steps (1,000 steps at 1,000 robots, 500 at
//! 10,000, 100 at 100,000). `--skip MODE@N` (repeatable) leaves a mode out at team `N`: the
//! table says so and the figure's curve has no point there.

use usar_sim::scenario::{PhysicsStepping, Scenario};

use crate::measure::{self, Measured, measure, peak_rss_mib, reset_peak_rss};
use crate::options::Options;
use crate::teams;
use crate::threads::{Threaded, measure_threads};

/// The three `sim.physics` modes, in the order measured.
pub const MODES: [PhysicsStepping; 3] = [
    PhysicsStepping::EveryStep,
    PhysicsStepping::NearContacts,
    PhysicsStepping::NearBodies,
];

/// Robot-steps per window when `--steps` is not given ([`window_steps`]).
const ROBOT_STEPS_PER_WINDOW: u64 = 5_000_000;

/// One team's costs.
pub struct TeamCost {
    /// Robots.
    pub robots: usize,
    /// Per physics mode (in [`MODES`] order): one thread against the pool (`None`: skipped
    /// with `--skip`).
    pub modes: Vec<(PhysicsStepping, Option<Threaded>)>,
    /// The `EveryStep` logic and its bare-Rapier replay over the same window, one thread.
    pub bare: Measured,
    /// Peak resident memory during the team, MiB.
    pub peak_rss_mib: f64,
}

/// Nanoseconds per robot per step of `cost_s` seconds over `steps` steps of `robots` robots.
pub fn ns(cost_s: f64, steps: u64, robots: usize) -> f64 {
    cost_s * 1e9 / (steps as f64 * robots.max(1) as f64)
}

/// The window of the team of `n` robots, steps: `given`, else [`ROBOT_STEPS_PER_WINDOW`] /
/// `n` bounded to 100..=1000.
pub fn window_steps(n: usize, given: Option<u64>) -> u64 {
    given.unwrap_or((ROBOT_STEPS_PER_WINDOW / n.max(1) as u64).clamp(100, 1000))
}

/// Prints one mode's line, indented under its team.
fn report_mode(mode: PhysicsStepping, t: &Threaded, n: usize) {
    let same = match t.diverged_at {
        None => "the robots stood in the same places at every block end".to_owned(),
        Some(step) => format!("THE RUNS DIVERGED: robots stand apart at step {step}"),
    };
    println!(
        "  {mode:?}: 1 thread {:.0} ns wall, {:.0} ns CPU; {} threads {:.0} ns wall, {:.0} ns CPU per robot-step; speed-up {:.2}; {same}",
        ns(t.one_wall_s, t.steps, n),
        ns(t.one_cpu_s, t.steps, n),
        t.threads,
        ns(t.many_wall_s, t.steps, n),
        ns(t.many_cpu_s, t.steps, n),
        t.speed_up(),
    );
}

/// Prints the bare-Rapier line, indented under its team.
fn report_bare(m: &Measured, n: usize) {
    let replay = match m.diverged_at {
        None => "the replayed bodies stood where the world's did at every block end".to_owned(),
        Some(step) => format!("REPLAY DIVERGED: bodies differ from the world's at step {step}"),
    };
    println!(
        "  bare Rapier replaying EveryStep's commands: {:.0} ns CPU per robot-step (the logic it replays {:.0} ns CPU, {:.2}x); {replay}",
        ns(m.bare_cpu_s, m.steps, n),
        ns(m.logic_cpu_s, m.steps, n),
        m.ratio(),
    );
}

/// The team scenario `s` with `sim.physics` set to `mode`. Errors (one line): it does not
/// validate.
fn with_physics(s: &Scenario, mode: PhysicsStepping) -> Result<Scenario, String> {
    s.edit(|spec| spec.sim.physics = mode)
        .map_err(|e| e.to_string())
}

/// Builds and measures the team of `n` (see the module docs). Errors (one line): the team
/// does not build or a step fails.
fn measure_team(n: usize, o: &Options) -> Result<TeamCost, String> {
    let rss_reset = reset_peak_rss();
    let err = |e: String| format!("team of {n}: {e}");
    let team = teams::team(n, &o.base, &o.scenarios).map_err(err)?;
    let (warmup, steps) = (o.warmup_steps, window_steps(n, o.steps_given));
    // `teams::team` sets `EveryStep`; each mode is set below in turn.
    let source = team.source.trim_end_matches(", physics every step");
    println!(
        "team of {n}: {source}, each physics mode in turn; {}",
        measure::window(warmup, steps, team.scenario.sim().dt_s.get())
    );
    let mut modes = Vec::new();
    for mode in MODES {
        if o.skip.contains(&(format!("{mode:?}"), n)) {
            println!("  {mode:?}: skipped (--skip {mode:?}@{n})");
            modes.push((mode, None));
            continue;
        }
        let s = with_physics(&team.scenario, mode).map_err(err)?;
        let t = measure_threads(&s, &o.method, warmup, steps, o.threads).map_err(err)?;
        report_mode(mode, &t, n);
        modes.push((mode, Some(t)));
    }
    let every = with_physics(&team.scenario, PhysicsStepping::EveryStep).map_err(err)?;
    let bare = measure(&every, &o.method, warmup, steps, None).map_err(err)?;
    report_bare(&bare, n);
    let peak_rss_mib = peak_rss_mib();
    let since = if rss_reset { "this team" } else { "the start" };
    println!("  peak resident memory since {since}: {peak_rss_mib:.0} MiB");
    Ok(TeamCost {
        robots: n,
        modes,
        bare,
        peak_rss_mib,
    })
}

/// Prints the summary table (markdown), nanoseconds per robot-step.
fn print_table(costs: &[TeamCost], threads: usize) {
    println!();
    println!(
        "| robots | physics | steps | 1 thread, wall | 1 thread, CPU | {threads} threads, wall | {threads} threads, CPU | speed-up (wall) | same places | peak RSS MiB |"
    );
    println!("|---:|---|---:|---:|---:|---:|---:|---:|---|---:|");
    for c in costs {
        let n = c.robots;
        for (mode, t) in &c.modes {
            let Some(t) = t else {
                println!("| {n} | {mode:?} | skipped (`--skip {mode:?}@{n}`) | | | | | | | |");
                continue;
            };
            println!(
                "| {n} | {mode:?} | {}-{} | {:.0} | {:.0} | {:.0} | {:.0} | {:.2} | {} | {:.0} |",
                t.warmup + 1,
                t.warmup + t.steps,
                ns(t.one_wall_s, t.steps, n),
                ns(t.one_cpu_s, t.steps, n),
                ns(t.many_wall_s, t.steps, n),
                ns(t.many_cpu_s, t.steps, n),
                t.speed_up(),
                if t.diverged_at.is_none() { "yes" } else { "NO" },
                c.peak_rss_mib,
            );
        }
        let b = &c.bare;
        println!(
            "| {n} | bare Rapier (EveryStep's replay) | {}-{} | | {:.0} | | | | {} | |",
            b.warmup + 1,
            b.warmup + b.steps,
            ns(b.bare_cpu_s, b.steps, n),
            if b.diverged_at.is_none() {
                "yes (replay exact)"
            } else {
                "NO (replay diverged)"
            },
        );
    }
}

/// Runs `--robot-step` (see the module docs): measures every team of `--teams`, printing its
/// lines and then the table, and returns the teams' costs (`main.rs` draws the figure and then
/// fails on [`diverged`]). Errors (one line): a team fails.
pub fn run(o: &Options) -> Result<Vec<TeamCost>, String> {
    println!(
        "cost per robot-step: method {}, trial 0, {} warm-up steps then a window per team, on 1 and {} threads side by side in alternating blocks of {} steps; nanoseconds per robot per step",
        o.method,
        o.warmup_steps,
        o.threads,
        measure::BLOCK_STEPS
    );
    let costs = o
        .teams
        .iter()
        .map(|&n| measure_team(n, o))
        .collect::<Result<Vec<_>, _>>()?;
    print_table(&costs, o.threads);
    Ok(costs)
}

/// One line per configuration whose two runs, or whose bare replay, did not stand in the same
/// places as the world (empty when every one did).
pub fn diverged(costs: &[TeamCost]) -> Vec<String> {
    costs
        .iter()
        .flat_map(|c| {
            let runs = c.modes.iter().filter_map(move |(mode, t)| {
                let step = t.as_ref()?.diverged_at?;
                Some(format!(
                    "{} robots {mode:?}: the runs at step {step}",
                    c.robots
                ))
            });
            let bare = c
                .bare
                .diverged_at
                .map(|step| format!("{} robots: the bare replay at step {step}", c.robots));
            runs.chain(bare)
        })
        .collect()
}
