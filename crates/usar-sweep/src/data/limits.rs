//! The limits of a sweep: its most trials in all and its most worker threads, and the checks
//! that refuse a sweep above them (or split into more shards than it has trials) in one line.

use crate::data::config_error::ConfigError;

/// Most worker threads per available core: a sweep never runs more than
/// `MAX_THREADS_PER_CORE` x [`std::thread::available_parallelism`] threads ([`max_threads`]).
pub const MAX_THREADS_PER_CORE: usize = 4;

/// The most worker threads a sweep uses on this machine: [`MAX_THREADS_PER_CORE`] x the
/// available parallelism (1 when that is unknown).
pub fn max_threads() -> usize {
    MAX_THREADS_PER_CORE * std::thread::available_parallelism().map_or(1, usize::from)
}

/// The worker threads a sweep with `jobs` jobs to run uses when `requested` threads are asked
/// for: at least 1, at most `max` (see [`max_threads`]) and at most `jobs`.
pub fn effective_threads(requested: usize, max: usize, jobs: usize) -> usize {
    requested.min(max).min(jobs).max(1)
}

#[cfg(test)]
mod sweep_threads_tests {
    use super::*;

    #[test]
    fn threads_go_inside_trials_only_when_trials_are_fewer_than_threads() {
        let big = usar_sim::world::PARALLEL_MIN_ROBOTS;
        assert_eq!(sweep_threads(2, 8, 40, big), (2, false));
        assert_eq!(sweep_threads(2, 8, 2, big), (2, false));
        assert_eq!(sweep_threads(4, 8, 1, big), (4, true));
        assert_eq!(sweep_threads(16, 8, 3, big), (8, true));
        assert_eq!(sweep_threads(0, 8, 3, big), (1, false));
        // A small team: one thread per trial, never more threads than trials.
        assert_eq!(sweep_threads(4, 8, 1, big - 1), (1, false));
        assert_eq!(sweep_threads(16, 8, 3, 12), (3, false));
    }
}

/// The threads of a sweep of `jobs` trials whose largest team has `largest_team` robots, when
/// `requested` are asked for (capped at `max`), and whether threads go inside trials. The
/// rule: with at least as many trials as threads, trials run in parallel, one thread each
/// (`false`). With fewer trials, a team of at least [`usar_sim::world::PARALLEL_MIN_ROBOTS`]
/// robots gets every requested thread: every trial runs at once and the threads left over
/// join the trials' per-robot phases (`true`); a smaller team gets one thread per trial
/// ([`effective_threads`], `false`). The results are bit-identical either way: this is only
/// a choice of speed.
pub fn sweep_threads(
    requested: usize,
    max: usize,
    jobs: usize,
    largest_team: usize,
) -> (usize, bool) {
    let pool = requested.min(max).max(1);
    if jobs < pool && largest_team >= usar_sim::world::PARALLEL_MIN_ROBOTS {
        (pool, true)
    } else {
        (effective_threads(requested, max, jobs), false)
    }
}

/// Most trials one sweep may hold: grid cells x methods x trials, all shards together
/// (1,000,000). A sweep keeps a few hundred bytes per trial in memory (its job list, records
/// and tables), so the limit keeps a mistyped `--trials` a one-line error instead of an
/// allocation failure; a larger study is several sweeps (for example one per `--seed`).
pub const MAX_SWEEP_TRIALS: usize = 1_000_000;

/// Refuses `cells` grid cells x `methods` methods x `trials` trials (saturating) above
/// [`MAX_SWEEP_TRIALS`]: the check of [`check_trial_count`](crate::sweep::check_trial_count) and [`check_grid_size`](crate::sweep::check_grid_size).
///
/// # Errors
/// [`ConfigError::TooManyTrials`] (the three counts and their product) when the product is
/// above the limit.
pub fn check_sweep_size(cells: usize, methods: usize, trials: u32) -> Result<(), ConfigError> {
    let total = cells
        .saturating_mul(methods)
        .saturating_mul(trials as usize);
    if total > MAX_SWEEP_TRIALS {
        return Err(ConfigError::TooManyTrials {
            cells,
            methods,
            trials,
            total,
            limit: MAX_SWEEP_TRIALS,
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn threads_are_capped_at_the_maximum_and_the_job_count() {
        assert_eq!(effective_threads(100_000, 8, 1_000), 8);
        assert_eq!(effective_threads(100_000, 8, 3), 3);
        assert_eq!(effective_threads(2, 8, 1_000), 2);
        assert_eq!(effective_threads(2, 8, 0), 1);
        assert_eq!(effective_threads(0, 8, 5), 1);
        assert!(max_threads() >= MAX_THREADS_PER_CORE);
    }
}
