//! The checks that refuse a sweep before it runs: too many trials or shards, and parameters
//! no sweep can run with.

use anyhow::{Result, bail};
use usar_sim::scenario::trial_steps;

use crate::data::config::SweepConfig;
use crate::data::limits::{check_shard_count, check_sweep_size};
use crate::grid::build::cell_count;
use crate::journal::SweepHeader;

/// Refuses a sweep of more than [`MAX_SWEEP_TRIALS`](crate::sweep::MAX_SWEEP_TRIALS) trials (grid cells x methods x trials),
/// or split into more shards (`--shard I/N`) than it has trials, with a one-line error;
/// cheap, so a caller can check before any other work.
///
/// # Errors
/// The count and the limit, when the count is above it; see [`check_shard_count`].
pub fn check_trial_count(cfg: &SweepConfig) -> Result<()> {
    let cells = cfg.grid.as_ref().map_or(1, |g| g.cells.len());
    let total = trial_count(cfg);
    if let Some(s) = &cfg.shard {
        check_shard_count(
            &format!("--shard {}/{}", s.shard.index, s.shard.count),
            s.shard.count,
            total,
        )?;
    }
    check_sweep_size(cells, cfg.methods.len(), cfg.trials)
}

/// Refuses the sweep of `--vary` arguments `vary` x `methods` methods x `trials` trials above
/// [`MAX_SWEEP_TRIALS`](crate::sweep::MAX_SWEEP_TRIALS) before its grid is built: the cells are counted from the value lists
/// ([`crate::grid::cell_count`]), none is made. `usar sweep` and `usar slurm` call it
/// before [`crate::grid::build_grid`].
///
/// # Errors
/// A malformed `--vary` argument, or the counts and the limit when the sweep is above it.
pub fn check_grid_size(vary: &[String], methods: usize, trials: u32) -> Result<()> {
    check_sweep_size(cell_count(vary)?, methods, trials)
}

/// The sweep's trials in all shards together: grid cells x methods x trials (saturating).
pub fn trial_count(cfg: &SweepConfig) -> usize {
    let cells = cfg.grid.as_ref().map_or(1, |g| g.cells.len());
    cells
        .saturating_mul(cfg.methods.len())
        .saturating_mul(cfg.trials as usize)
}

/// Refuses parameters no sweep can run with: `--trials 0`, no method or one twice, a cell
/// whose tasks differ from the scenario's, or a trial length (`--duration`) that is not a
/// positive number of seconds. `header` is [`header_of`](crate::sweep::header_of) `cfg`. [`run_sweep`](crate::sweep::run_sweep) checks this
/// first; `usar slurm` checks it before it writes the scripts.
///
/// # Errors
/// The first parameter that is refused, in one line naming its option.
pub fn check_config(cfg: &SweepConfig, header: &SweepHeader) -> Result<()> {
    if cfg.trials == 0 {
        bail!("--trials must be at least 1");
    }
    if cfg.methods.is_empty() {
        bail!("--methods needs at least one method");
    }
    let tasks = cfg.scenario.task_names();
    for s in cfg.cell_scenarios() {
        if s.task_names() != tasks {
            bail!(
                "--vary: every cell must have the scenario's tasks ({}); a cell has {}",
                tasks.join(", "),
                s.task_names().join(", ")
            );
        }
        if let Err(e) = trial_steps(cfg.duration_of(s), s.sim().dt_s.get()) {
            bail!("--duration: {e}");
        }
    }
    let mut seen = header.methods.clone();
    seen.sort();
    seen.dedup();
    if seen.len() != header.methods.len() {
        bail!(
            "--methods lists a method twice: {}",
            header.methods.join(",")
        );
    }
    Ok(())
}
