//! Building one trial for a command (`usar run`, `usar render`, `usar replay`): the builder's
//! errors named by their flag, and the warning for a `--duration` that is not a whole number
//! of steps; the `--threads` of every command and the thread pool a trial runs in.

use anyhow::{Context, Result, bail};
use usar_sim::mission::{MissionError, Simulation, TrialBuilder, trial_steps};
use usar_sim::scenario::number_text;
use usar_sweep::sweep::{MAX_THREADS_PER_CORE, max_threads};

/// The worker threads of `--threads`: all cores when not given; more than
/// [`max_threads`] are capped there with a warning.
///
/// # Errors
/// `--threads 0`.
pub fn threads_of(requested: Option<usize>) -> Result<usize> {
    Ok(match requested {
        Some(0) => bail!("--threads must be at least 1"),
        Some(n) if n > max_threads() => {
            crate::shared::stderr_lines::warn(format!(
                "warning: --threads {n} is more than {MAX_THREADS_PER_CORE} x the {} available \
                 cores: using {}",
                max_threads() / MAX_THREADS_PER_CORE,
                max_threads()
            ));
            max_threads()
        }
        Some(n) => n,
        None => std::thread::available_parallelism().map_or(1, usize::from),
    })
}

/// The help of `--threads` on the commands that simulate one trial.
pub const TRIAL_THREADS_HELP: &str = "Threads of the trial (>= 1); default all cores. A team of \
at least 512 robots runs its per-robot stages on them (path following, the contact gate of \
physics: NearBodies, the resolver's pair search and neighbour lists, steering, the read-back \
of the bodies with their radiation); a smaller team, Rapier, planning and the mission's \
decisions run on one. The results are the same, bit for bit, on any number of threads.";

/// The rayon pool one trial runs in, of `--threads` threads ([`threads_of`]: all cores when
/// not given, capped with a warning at 4 x the cores). Run the trial inside
/// [`rayon::ThreadPool::install`]: a team of at least
/// [`PARALLEL_MIN_ROBOTS`](usar_sim::world::PARALLEL_MIN_ROBOTS) robots spreads its per-robot
/// phases over the pool's threads, with the same results as on one.
///
/// # Errors
/// `--threads 0`, or the pool's threads could not be started.
pub fn trial_pool(threads: Option<usize>) -> Result<rayon::ThreadPool> {
    let n = threads_of(threads)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .build()
        .context("starting the trial's thread pool")
}

/// Builds the trial, with the flag a builder error is about as its context: `--method` for an
/// unknown or failing grouping method, `--duration` for a bad trial length.
///
/// # Errors
/// The builder's [`MissionError`], with that context.
pub fn build_trial(builder: TrialBuilder<'_>) -> Result<Simulation> {
    builder.build().map_err(|e| {
        let flag = match e {
            MissionError::Method(_) | MissionError::Grouping { .. } => "--method",
            MissionError::Duration(_) => "--duration",
            MissionError::World(_) => "the trial",
        };
        anyhow::Error::new(e).context(flag)
    })
}

/// Warns on stderr when the trial does not run the `requested` length exactly: a length that
/// is not a whole number of steps is rounded up to one (shorter than one step: one step).
pub fn warn_if_rounded(requested: Option<f64>, sim: &Simulation) {
    if let Some(d) = requested
        && let Some(w) = rounding_warning(d, sim.scenario().sim().dt_s.get())
    {
        crate::shared::stderr_lines::warn(w);
    }
}

/// The warning for a `--duration` of `requested_s` seconds at step `dt_s` when the trial runs
/// another length (its steps times `dt_s`, see `usar_sim::mission::trial_steps`), naming the
/// length actually run; `None` when it runs `requested_s` (within 1e-9 relative) or when the
/// length is refused anyway (the caller reports that error).
pub fn rounding_warning(requested_s: f64, dt_s: f64) -> Option<String> {
    let steps = trial_steps(requested_s, dt_s).ok()?;
    let actual_s = usar_sweep::sweep::simulated_length_s(requested_s, dt_s);
    if actual_s == requested_s {
        return None;
    }
    let why = if requested_s < dt_s {
        "is shorter than one step"
    } else {
        "is not a whole number of steps"
    };
    Some(format!(
        "warning: --duration {} s {why} of {} s (sim.dt_s): the trial runs {} s ({steps} \
         step{})",
        number_text(requested_s),
        number_text(dt_s),
        number_text(actual_s),
        if steps == 1 { "" } else { "s" }
    ))
}
