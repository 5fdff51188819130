//! The scaling bench's one-against-several-threads measurement: the same trial run twice side
//! by side, once on one thread and once on a rayon pool of `threads` threads (the team's
//! per-robot phases in parallel from `PARALLEL_MIN_ROBOTS` robots on, `docs/scaling.md`, "One
//! trial on all cores"), in alternating blocks of [`BLOCK_STEPS`](crate::measure::BLOCK_STEPS)
//! steps timed by the wall clock (each run first every other block), so both see the same load
//! of a shared machine. After each block (untimed) the two worlds' robots are compared: they
//! stand in the same place, bit for bit, as a trial gives the same numbers on any number of
//! threads.

use std::time::Instant;

use usar_sim::mission::Simulation;
use usar_sim::scenario::Scenario;

use crate::common::trial_steps::{same_positions, steps_of};
use crate::measure::{self, BLOCK_STEPS};

/// What one one-against-several-threads measurement covered and cost.
pub struct Threaded {
    /// Threads of the pool of the second run (>= 2).
    pub threads: usize,
    /// Steps run by both before the measured window, untimed (0: from the trial's first step).
    pub warmup: u64,
    /// Steps measured, the same for both runs (after the warm-up).
    pub steps: u64,
    /// Wall-clock seconds of the steps on this thread alone.
    pub one_wall_s: f64,
    /// Wall-clock seconds of the steps on the pool of [`Threaded::threads`].
    pub many_wall_s: f64,
    /// CPU seconds of the whole process (every thread) during the steps on one thread.
    pub one_cpu_s: f64,
    /// CPU seconds of the whole process (every thread) during the steps on the pool.
    pub many_cpu_s: f64,
    /// The first block end (a step count) at which the two runs' robots stood apart, if any.
    pub diverged_at: Option<u64>,
    /// Physics step, seconds.
    pub dt_s: f64,
}

impl Threaded {
    /// Simulated seconds per wall second on one thread.
    pub fn one_rate(&self) -> f64 {
        self.steps as f64 * self.dt_s / self.one_wall_s
    }

    /// Simulated seconds per wall second on the pool.
    pub fn many_rate(&self) -> f64 {
        self.steps as f64 * self.dt_s / self.many_wall_s
    }

    /// World steps per wall second on one thread and on the pool (the figure's curves).
    pub fn steps_per_wall_s(&self) -> (f64, f64) {
        let steps = self.steps as f64;
        (steps / self.one_wall_s, steps / self.many_wall_s)
    }

    /// Wall-clock speed-up of the pool over one thread.
    pub fn speed_up(&self) -> f64 {
        self.one_wall_s / self.many_wall_s
    }
}

/// Trial 0 of `s` under `method` ([`measure::trial`]) that runs its per-robot phases on the
/// calling rayon pool when `parallel`.
fn trial(s: &Scenario, method: &str, parallel: bool) -> Result<Simulation, String> {
    let mut sim = measure::trial(s, method)?;
    sim.set_parallel(parallel);
    Ok(sim)
}

/// Measures `steps` steps of trial 0 of `s` under `method`, after `warmup` untimed ones, on
/// one thread and on a pool of `threads` threads, in alternating blocks (see the module
/// docs), by the wall clock and the process's CPU clock. Both runs live on
/// the pool; the first forbids its per-robot phases to use it (`Simulation::set_parallel`), so
/// it steps on one thread. Errors (one line): the pool cannot start, the simulation does not
/// build or a step fails.
pub fn measure_threads(
    s: &Scenario,
    method: &str,
    warmup: u64,
    steps: u64,
    threads: usize,
) -> Result<Threaded, String> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| format!("a pool of {threads} threads: {e}"))?;
    pool.install(|| {
        let mut one = trial(s, method, false)?;
        let mut many = trial(s, method, true)?;
        let mut m = Threaded {
            threads,
            warmup,
            steps: 0,
            one_wall_s: 0.0,
            many_wall_s: 0.0,
            one_cpu_s: 0.0,
            many_cpu_s: 0.0,
            diverged_at: None,
            dt_s: s.sim().dt_s.get(),
        };
        let mut done = 0;
        while done < warmup {
            let len = BLOCK_STEPS.min(warmup - done);
            for sim in [&mut one, &mut many] {
                steps_of(sim, len)?;
            }
            done += len;
            if m.diverged_at.is_none() && !same_positions(&one, &many) {
                m.diverged_at = Some(done);
            }
        }
        let mut block = 0u64;
        while m.steps < steps {
            let len = BLOCK_STEPS.min(steps - m.steps);
            // Each run goes first every other block, so neither always finds the caches the
            // other left.
            let even = block.is_multiple_of(2);
            for is_one in [even, !even] {
                let (sim, wall_s, cpu) = if is_one {
                    (&mut one, &mut m.one_wall_s, &mut m.one_cpu_s)
                } else {
                    (&mut many, &mut m.many_wall_s, &mut m.many_cpu_s)
                };
                let (t0, c0) = (Instant::now(), measure::process_cpu_s());
                steps_of(sim, len)?;
                *cpu += measure::process_cpu_s() - c0;
                *wall_s += t0.elapsed().as_secs_f64();
            }
            block += 1;
            m.steps += len;
            done += len;
            if m.diverged_at.is_none() && !same_positions(&one, &many) {
                m.diverged_at = Some(done);
            }
        }
        Ok(m)
    })
}
