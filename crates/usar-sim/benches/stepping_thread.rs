//! Where a trial steps from (issue 73; `docs/scaling.md`, "One trial on all cores"): the wall
//! clock of a large team's trial, whose per-robot phases spread over a rayon pool, stepped
//!
//! 1. **one trial**: on a thread of a pool of `--threads` threads (as `usar run` steps it),
//!    against the same trial stepped from this bench's own thread, outside every pool (as a
//!    script, the test harness or the Python package steps it), its phases on the global pool
//!    of as many threads (`Simulation::step` hands each whole step over to it);
//! 2. **two trials side by side**, each stepped from a thread of its own (as `cargo test` runs
//!    two tests at once): both spreading their per-robot phases over the global pool, against
//!    both stepping their robots in turn (`Simulation::set_parallel(false)`, as a sweep runs
//!    its trials).
//!
//! Each comparison runs its two arms in alternating blocks of [`BLOCK_STEPS`] steps (each arm
//! first every other block), so both see the same load of a shared machine, and checks after
//! every block, untimed, that the arms' robots stand in the same places, bit for bit (a trial
//! gives the same numbers wherever it steps). Printed: each arm's simulated seconds per wall
//! second and the ratio of the two.
//!
//! Run in release: `cargo bench -p usar-sim --bench stepping_thread` (`scenarios/swarm-10000.ron`,
//! DIS, trial 0, 1,500 steps = 30 simulated seconds, 2 threads). Options: `--scenario FILE`
//! (relative to the workspace root), `--method NAME` (default `dis`), `--steps N` (default
//! 1,500), `--threads N` (default 2, at least 2). A bad option exits with status 2 and a
//! one-line error; a scenario that does not load, a failing step or arms whose robots stood
//! apart exit with status 1.

use std::process::ExitCode;
use std::time::Instant;

use usar_sim::mission::Simulation;
use usar_sim::scenario::{self, Scenario};

mod common;
use common::trial_steps::{same_positions, steps_of};

/// Steps per block of the alternation.
const BLOCK_STEPS: u64 = 50;

/// Command-line options (after `--`).
struct Options {
    scenario: String,
    method: String,
    steps: u64,
    threads: usize,
}

/// Parses the options after `--`. Errors: one line naming the flag.
fn options(args: impl Iterator<Item = String>) -> Result<Options, String> {
    let mut o = Options {
        scenario: "scenarios/swarm-10000.ron".to_owned(),
        method: "dis".to_owned(),
        steps: 1500,
        threads: 2,
    };
    let mut args = args.filter(|a| a != "--bench");
    while let Some(flag) = args.next() {
        let mut value = || args.next().ok_or(format!("{flag}: expected a value"));
        match flag.as_str() {
            "--scenario" => o.scenario = value()?,
            "--method" => o.method = value()?,
            "--steps" => o.steps = count(&flag, &value()?, 1)?,
            "--threads" => o.threads = count(&flag, &value()?, 2)? as usize,
            _ => {
                return Err(format!(
                    "unknown option {flag:?} (--scenario, --method, --steps, --threads)"
                ));
            }
        }
    }
    Ok(o)
}

/// `text` as a whole number of at least `min` for `flag`. Errors: one line.
fn count(flag: &str, text: &str, min: u64) -> Result<u64, String> {
    match text.parse::<u64>() {
        Ok(n) if n >= min => Ok(n),
        _ => Err(format!(
            "{flag}: expected a whole number >= {min}, found {text:?}"
        )),
    }
}

/// Trial 0 of `s` under `method`, long enough for `steps` steps, its per-robot phases
/// parallel when `parallel`.
fn trial(s: &Scenario, method: &str, steps: u64, parallel: bool) -> Result<Simulation, String> {
    let duration_s = (steps + 1) as f64 * s.sim().dt_s.get();
    let mut sim = Simulation::builder(s)
        .method_named(method)
        .duration_s(duration_s)
        .build()
        .map_err(|e| format!("{method}: {e}"))?;
    sim.set_parallel(parallel);
    Ok(sim)
}

/// Wall-clock seconds of two arms run in alternating blocks, and the first block end (a step
/// count) at which they stood apart.
struct Compared {
    first_s: f64,
    second_s: f64,
    apart_at: Option<u64>,
}

/// Runs `steps` steps of two arms held in `arms` in alternating blocks: `run(arms, arm, len)`
/// steps arm 0 or 1 by `len` steps; `same(arms)` compares them after each block.
fn alternate<T>(
    steps: u64,
    arms: &mut T,
    mut run: impl FnMut(&mut T, usize, u64) -> Result<(), String>,
    same: impl Fn(&T) -> bool,
) -> Result<Compared, String> {
    let mut c = Compared {
        first_s: 0.0,
        second_s: 0.0,
        apart_at: None,
    };
    let mut done = 0;
    while done < steps {
        let len = BLOCK_STEPS.min(steps - done);
        let even = (done / BLOCK_STEPS).is_multiple_of(2);
        for arm in if even { [0, 1] } else { [1, 0] } {
            let t0 = Instant::now();
            run(arms, arm, len)?;
            let wall_s = t0.elapsed().as_secs_f64();
            *(if arm == 0 {
                &mut c.first_s
            } else {
                &mut c.second_s
            }) += wall_s;
        }
        done += len;
        if c.apart_at.is_none() && !same(arms) {
            c.apart_at = Some(done);
        }
    }
    Ok(c)
}

/// Measurement 1 (module docs): arm 0 on a pool of `o.threads`, arm 1 from this thread.
fn one_trial(s: &Scenario, o: &Options) -> Result<Compared, String> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(o.threads)
        .build()
        .map_err(|e| format!("a pool of {} threads: {e}", o.threads))?;
    let mut sims = [
        trial(s, &o.method, o.steps, true)?,
        trial(s, &o.method, o.steps, true)?,
    ];
    alternate(
        o.steps,
        &mut sims,
        |[in_pool, outside], arm, len| match arm {
            0 => pool.install(|| steps_of(in_pool, len)),
            _ => steps_of(outside, len),
        },
        |[a, b]| same_positions(a, b),
    )
}

/// Measurement 2 (module docs): arm 0 both trials parallel, arm 1 both in turn; each pair's
/// two trials step side by side, one thread of its own each.
fn two_trials(s: &Scenario, o: &Options) -> Result<Compared, String> {
    let pair = |parallel| -> Result<[Simulation; 2], String> {
        Ok([
            trial(s, &o.method, o.steps, parallel)?,
            trial(s, &o.method, o.steps, parallel)?,
        ])
    };
    let mut pairs = [pair(true)?, pair(false)?];
    alternate(
        o.steps,
        &mut pairs,
        |pairs, arm, len| {
            let [a, b] = &mut pairs[arm];
            std::thread::scope(|scope| {
                let other = scope.spawn(|| steps_of(b, len));
                let mine = steps_of(a, len);
                let other = other
                    .join()
                    .map_err(|_| "a stepping thread panicked".to_owned())?;
                mine.and(other)
            })
        },
        |[spread, in_turn]| {
            same_positions(&spread[0], &in_turn[0]) && same_positions(&spread[1], &in_turn[1])
        },
    )
}

/// Prints one comparison: each arm's simulated seconds per wall second (`trials` trials per
/// arm) and the second arm's wall clock over the first's.
fn report(title: &str, arms: [&str; 2], c: &Compared, o: &Options, dt_s: f64, trials: u32) {
    let sim_s = o.steps as f64 * dt_s * f64::from(trials);
    println!("{title}");
    for (arm, wall_s) in arms.iter().zip([c.first_s, c.second_s]) {
        println!(
            "  {arm}: {wall_s:.2} s wall, {:.2} simulated s per wall s",
            sim_s / wall_s
        );
    }
    println!(
        "  wall of the second over the first: {:.3}",
        c.second_s / c.first_s
    );
    match c.apart_at {
        None => println!("  the robots stood in the same places at every block end"),
        Some(step) => println!("  ROBOTS APART at step {step}"),
    }
}

fn main() -> ExitCode {
    let o = match options(std::env::args().skip(1)) {
        Ok(o) => o,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let root = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");
    let path = format!("{root}/{}", o.scenario);
    let run = || -> Result<bool, String> {
        let s = scenario::load(&path).map_err(|e| e.to_string())?;
        rayon::ThreadPoolBuilder::new()
            .num_threads(o.threads)
            .build_global()
            .map_err(|e| format!("the global pool of {} threads: {e}", o.threads))?;
        let dt_s = s.sim().dt_s.get();
        println!(
            "{}: {} robots, {}, trial 0, {} steps ({} simulated s), {} threads",
            o.scenario,
            s.robots().len(),
            o.method,
            o.steps,
            o.steps as f64 * dt_s,
            o.threads
        );
        let one = one_trial(&s, &o)?;
        report(
            "one trial",
            [
                "on a thread of the pool",
                "from a thread outside every pool",
            ],
            &one,
            &o,
            dt_s,
            1,
        );
        let two = two_trials(&s, &o)?;
        report(
            "two trials side by side, one thread of their own each",
            [
                "phases spread over the global pool",
                "robots stepped in turn",
            ],
            &two,
            &o,
            dt_s,
            2,
        );
        Ok(one.apart_at.is_none() && two.apart_at.is_none())
    };
    match run() {
        Ok(true) => ExitCode::SUCCESS,
        Ok(false) => ExitCode::FAILURE,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::FAILURE
        }
    }
}
