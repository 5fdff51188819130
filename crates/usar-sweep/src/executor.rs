//! Running a sweep's jobs: one thread pool for every job of every cell, a journal line per
//! finished trial, failures and panics isolated to their trial, a progress bar over the whole
//! sweep's simulated time with an ETA, and the [`SweepHooks`] extension points.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Mutex, PoisonError};
use std::time::Instant;

use rayon::prelude::*;
use rne_core::TrustModel;
use usar_sim::mission::{MissionError, Simulation, TrialResult};
use usar_sim::scenario::Scenario;

use crate::data::hooks::{SweepHooks, TrialKey};
use crate::data::limits::{max_threads, sweep_threads};
use crate::error::SweepError;
use crate::idle_threads::IdleThreads;
use crate::journal::{Journal, JournalError, Outcome, TrialRecord};
use crate::method_factory::{MethodFactory, TrialContext};
use crate::progress::progress_bar;

/// How to run a sweep's jobs.
pub struct Runner<'a> {
    /// Builds each trial's method.
    pub factory: &'a MethodFactory,
    /// Extension points.
    pub hooks: &'a SweepHooks,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
    /// Worker threads (>= 1).
    pub threads: usize,
    /// Whether the pool's threads may also run a trial's per-robot phases
    /// ([`crate::sweep::sweep_threads`]); `false`: each trial on one thread.
    pub inside_trials: bool,
}

/// Steps between two progress-bar updates from a running trial.
const PROGRESS_EVERY_STEPS: u64 = 50;

/// A job ready to run.
pub struct Job {
    /// Grid cell index.
    pub cell: usize,
    /// The method's name as given to the factory.
    pub method_arg: String,
    /// The method's display name (`GroupingMethod::display_name`, as written).
    pub method: String,
    /// Trial index.
    pub trial: u32,
    /// The trial's seed (`trial_seed(base_seed, trial)`).
    pub seed: u64,
}

/// What one cell needs to run trials.
pub struct CellPlan<'a> {
    /// ` in cell <folder>` for a grid cell, empty otherwise (for messages).
    pub label: String,
    /// The cell's scenario.
    pub scenario: &'a Scenario,
    /// Its trust model (its `needs_weights` may be varied).
    pub model: TrustModel,
    /// Trial length, seconds.
    pub duration_s: f64,
    /// Simulated microseconds per step (progress-bar units).
    pub step_us: u64,
    /// Steps per trial.
    pub steps_per_trial: u64,
}

/// The pool's threads and whether they go inside trials
/// ([`sweep_threads`](crate::sweep::sweep_threads)) for `jobs` trials of `plans` when
/// `requested` threads are asked for.
pub(crate) fn threads_for(requested: usize, plans: &[CellPlan<'_>], jobs: usize) -> (usize, bool) {
    let largest_team = plans.iter().map(|p| p.scenario.robots().len()).max();
    sweep_threads(requested, max_threads(), jobs, largest_team.unwrap_or(0))
}

/// Runs `jobs` on a pool of `runner.threads`, journaling each record as it ends (into
/// `journal`; `None`: in memory, nothing is written); returns the new records (in completion
/// order).
pub(crate) fn execute(
    runner: &Runner<'_>,
    plans: &[CellPlan<'_>],
    jobs: &[Job],
    journal: Option<Journal>,
) -> Result<Vec<TrialRecord>, SweepError> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(runner.threads.max(1))
        .build()
        .map_err(SweepError::ThreadPool)?;
    let total_us = jobs
        .iter()
        .map(|j| plans[j.cell].steps_per_trial * plans[j.cell].step_us)
        .sum();
    let over = if plans.len() > 1 {
        format!(" over {} cells", plans.len())
    } else {
        String::new()
    };
    let pb = progress_bar(
        runner.progress,
        &format!("0/{} trials{over}", jobs.len()),
        total_us,
    );
    let journal = Mutex::new(journal);
    let new_records: Mutex<Vec<TrialRecord>> = Mutex::new(Vec::new());
    let journal_error: Mutex<Option<JournalError>> = Mutex::new(None);
    let abort = AtomicBool::new(false);
    let done = AtomicUsize::new(0);
    // One trial per thread: the threads its tail leaves idle go to the large teams' trials
    // still running.
    let idle = (!runner.inside_trials).then(|| IdleThreads::new(jobs.len(), runner.threads));
    pool.install(|| {
        jobs.par_iter().for_each(|job| {
            if let Some(idle) = &idle {
                idle.take();
            }
            let stopped = runner.hooks.stop.as_ref();
            if abort.load(Ordering::SeqCst) || stopped.is_some_and(|s| s.load(Ordering::SeqCst)) {
                return;
            }
            let plan = &plans[job.cell];
            let _running = idle.as_ref().map(IdleThreads::running);
            let tick = |steps| pb.inc(steps * plan.step_us);
            // A team too small to spread its phases would only ask at every step.
            let lent = (idle.as_ref())
                .filter(|_| plan.scenario.robots().len() >= usar_sim::world::PARALLEL_MIN_ROBOTS);
            let record = run_job(runner, plan, job, &tick, lent);
            let mut j = journal.lock().unwrap_or_else(PoisonError::into_inner);
            if let Some(Err(e)) = j.as_mut().map(|j| j.append(&record)) {
                abort.store(true, Ordering::SeqCst);
                journal_error
                    .lock()
                    .unwrap_or_else(PoisonError::into_inner)
                    .get_or_insert(e);
                return;
            }
            let n = done.fetch_add(1, Ordering::SeqCst) + 1;
            if let Outcome::Failed(msg) = &record.outcome {
                pb.suspend(|| {
                    tracing::info!(
                        "trial {} #{} (seed {}){} failed: {msg}",
                        record.method,
                        record.trial,
                        record.seed,
                        plans[record.cell].label
                    );
                });
            }
            pb.set_message(format!("{n}/{} trials{over}", jobs.len()));
            if let Some(hook) = &runner.hooks.on_journaled {
                pb.suspend(|| hook(&record, n));
            }
            drop(j);
            new_records
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .push(record);
        });
    });
    pb.finish_and_clear();
    if let Some(e) = journal_error
        .into_inner()
        .unwrap_or_else(PoisonError::into_inner)
    {
        return Err(SweepError::JournalStopped(e));
    }
    Ok(new_records
        .into_inner()
        .unwrap_or_else(PoisonError::into_inner))
}

/// Runs one job into its journal record (`idle`: see [`run_trial_lent`]).
fn run_job(
    runner: &Runner<'_>,
    plan: &CellPlan<'_>,
    job: &Job,
    tick: &(dyn Fn(u64) + Sync),
    idle: Option<&IdleThreads>,
) -> TrialRecord {
    let t0 = Instant::now();
    let outcome = run_trial_lent(plan, runner, job, tick, idle);
    TrialRecord {
        cell: job.cell,
        method: job.method.clone(),
        trial: job.trial,
        seed: job.seed,
        wall_s: t0.elapsed().as_secs_f64(),
        outcome: match outcome {
            Ok(r) => Outcome::Ok(Box::new(r)),
            Err(msg) => Outcome::Failed(msg),
        },
    }
}

/// Runs one trial, turning errors and panics into `Err(message)`. `tick(n)` is called every
/// `PROGRESS_EVERY_STEPS` steps with the number of steps just taken. (A calibration runs its
/// trials through it too: `usar_study::calibrate::evaluate`.)
pub fn run_trial(
    plan: &CellPlan<'_>,
    runner: &Runner<'_>,
    job: &Job,
    tick: &(dyn Fn(u64) + Sync),
) -> Result<TrialResult, String> {
    run_trial_lent(plan, runner, job, tick, None)
}

/// [`run_trial`], the trial spreading its per-robot phases over the pool's threads once
/// `idle` lends them ([`IdleThreads::lend`]) when `runner.inside_trials` is false.
fn run_trial_lent(
    plan: &CellPlan<'_>,
    runner: &Runner<'_>,
    job: &Job,
    tick: &(dyn Fn(u64) + Sync),
    idle: Option<&IdleThreads>,
) -> Result<TrialResult, String> {
    let body = || -> Result<TrialResult, String> {
        let mut hook = runner.hooks.trial_observer.as_ref().and_then(|make| {
            make(&TrialKey {
                cell: job.cell,
                method: job.method.clone(),
                trial: job.trial,
                seed: job.seed,
            })
        });
        let method = runner
            .factory
            .build(
                &job.method_arg,
                &plan.model,
                &TrialContext::new(job.trial, job.seed),
            )
            .map_err(|e| e.to_string())?;
        let mut sim = Simulation::builder(plan.scenario)
            .method(method)
            .trial(job.trial)
            .seed(job.seed)
            .duration_s(plan.duration_s)
            .build()
            .map_err(|e| e.to_string())?;
        sim.set_parallel(runner.inside_trials);
        if let Some(h) = hook.as_mut() {
            h.on_start(&sim);
        }
        let mut last = 0u64;
        let mut observe = |sim: &Simulation| {
            if let Some(h) = hook.as_mut() {
                h.on_step(sim);
            }
            let (done, _) = sim.progress();
            if done - last >= PROGRESS_EVERY_STEPS {
                tick(done - last);
                last = done;
            }
        };
        let result = step_to_end(&mut sim, &mut observe, runner.inside_trials, idle)
            .map_err(|e| format!("at t = {:.2} s: {e}", sim.time_s()))?;
        tick(sim.progress().0 - last);
        Ok(result)
    };
    match catch_unwind(AssertUnwindSafe(body)) {
        Ok(r) => r,
        Err(payload) => {
            let msg = payload
                .downcast_ref::<&str>()
                .map(|s| (*s).to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic payload".to_string());
            Err(format!("panicked: {msg}"))
        }
    }
}

/// Steps `sim` to its end, calling `observe` after each step (as
/// [`Simulation::run_observed`] with a closure), and returns its result. A trial not spreading
/// its per-robot phases already (`inside` false) spreads them from the first step at which
/// `idle` lends it the pool's idle threads ([`IdleThreads::lend`]); the results are the same
/// bits either way.
fn step_to_end(
    sim: &mut Simulation,
    observe: &mut dyn FnMut(&Simulation),
    inside: bool,
    idle: Option<&IdleThreads>,
) -> Result<TrialResult, MissionError> {
    let mut lent = inside;
    while !sim.is_finished() {
        if !lent && idle.is_some_and(IdleThreads::lend) {
            lent = true;
            sim.set_parallel(true);
        }
        sim.step()?;
        observe(sim);
    }
    Ok(sim.result())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SWARM_1000: &str = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/swarm-1000.ron"
    );

    /// Steps 5 steps of swarm-1000's trial 0 (DIS) to its end with [`step_to_end`] on a pool
    /// of two threads, `idle` as given: whether the per-robot phases were spread at each
    /// step, and the result.
    fn five_steps(idle: &IdleThreads) -> (Vec<bool>, TrialResult) {
        let scenario = usar_sim::scenario::load(SWARM_1000).unwrap();
        let dt = scenario.sim().dt_s.get();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        pool.install(|| {
            let mut sim = Simulation::builder(&scenario)
                .method_named("dis")
                .duration_s(5.0 * dt)
                .build()
                .unwrap();
            sim.set_parallel(false);
            let mut spread = Vec::new();
            let mut observe = |s: &Simulation| spread.push(s.world().per_robot_parallel());
            let r = step_to_end(&mut sim, &mut observe, false, Some(idle)).unwrap();
            (spread, r)
        })
    }

    #[test]
    fn a_trial_takes_the_idle_threads_it_is_lent_and_gives_the_same_bits() {
        // The last trial of a batch running alone on two threads: lent.
        let alone = IdleThreads::new(1, 2);
        alone.take();
        let _running = alone.running();
        // Two trials running on two threads: not lent.
        let busy = IdleThreads::new(2, 2);
        busy.take();
        busy.take();
        let _both = (busy.running(), busy.running());
        let (lent, lent_result) = five_steps(&alone);
        let (kept, kept_result) = five_steps(&busy);
        assert_eq!(lent, [true; 5], "a lent trial spreads its phases");
        assert_eq!(kept, [false; 5], "a trial not lent keeps to its thread");
        assert_eq!(lent_result, kept_result, "the same results either way");
    }
}
