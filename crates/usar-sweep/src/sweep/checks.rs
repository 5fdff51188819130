//! The checks that refuse a sweep before it runs: too many trials or shards, and parameters
//! no sweep can run with.

use usar_sim::scenario::trial_steps;

use crate::data::config::SweepConfig;
use crate::data::config_error::ConfigError;
use crate::data::limits::check_sweep_size;
use crate::error::SweepError;
use crate::grid::build::cell_count;
use crate::journal::SweepHeader;

/// Refuses a sweep of more than [`MAX_SWEEP_TRIALS`](crate::sweep::MAX_SWEEP_TRIALS) trials (grid cells x methods x trials),
/// or split into more shards (`--shard I/N`) than it has trials, with a one-line error;
/// cheap, so a caller can check before any other work.
///
/// # Errors
/// [`ConfigError::TooManyShards`] or [`ConfigError::TooManyTrials`].
pub fn check_trial_count(cfg: &SweepConfig) -> Result<(), ConfigError> {
    let cells = cfg.grid.as_ref().map_or(1, |g| g.cells.len());
    let total = trial_count(cfg);
    if let Some(s) = &cfg.shard
        && s.shard.count > total
    {
        return Err(ConfigError::TooManyShards {
            index: s.shard.index,
            shards: s.shard.count,
            total,
        });
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
pub fn check_grid_size(vary: &[String], methods: usize, trials: u32) -> Result<(), SweepError> {
    Ok(check_sweep_size(cell_count(vary)?, methods, trials)?)
}

/// The sweep's trials in all shards together: grid cells x methods x trials (saturating).
pub fn trial_count(cfg: &SweepConfig) -> usize {
    let cells = cfg.grid.as_ref().map_or(1, |g| g.cells.len());
    cells
        .saturating_mul(cfg.methods.len())
        .saturating_mul(cfg.trials as usize)
}

/// Refuses parameters no sweep can run with: no trial, no worker thread, no method or one
/// twice, a cell whose tasks differ from the scenario's, or a trial length (`duration_s`)
/// that is not a positive number of seconds. `header` is
/// [`header_of`](crate::sweep::header_of) `cfg`. [`run_sweep`](crate::sweep::run_sweep) and
/// [`run_in_memory`](crate::sweep::run_in_memory) check this first; `usar slurm` checks it
/// before it writes the scripts.
///
/// # Errors
/// The first parameter that is refused, as the [`ConfigError`] naming its field.
pub fn check_config(cfg: &SweepConfig, header: &SweepHeader) -> Result<(), ConfigError> {
    if cfg.trials == 0 {
        return Err(ConfigError::NoTrials);
    }
    if cfg.threads == 0 {
        return Err(ConfigError::NoThreads);
    }
    if cfg.methods.is_empty() {
        return Err(ConfigError::NoMethods);
    }
    let tasks = cfg.scenario.task_names();
    for s in cfg.cell_scenarios() {
        if s.task_names() != tasks {
            return Err(ConfigError::CellTasks {
                scenario: tasks,
                cell: s.task_names(),
            });
        }
        if let Err(reason) = trial_steps(cfg.duration_of(s), s.sim().dt_s.get()) {
            return Err(ConfigError::TrialLength { reason });
        }
    }
    let mut seen = header.methods.clone();
    seen.sort();
    seen.dedup();
    if seen.len() != header.methods.len() {
        return Err(ConfigError::MethodTwice {
            methods: header.methods.clone(),
        });
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::data::config_error::ConfigField;
    use crate::sweep::header_of;

    const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");

    /// The refusal of paper.ron's sweep (RNE and DIS x 2 trials x 20 s) edited by `edit`.
    fn refusal(edit: impl FnOnce(&mut SweepConfig)) -> Option<ConfigError> {
        let scenario = usar_sim::scenario::load(PAPER).unwrap();
        let mut cfg = SweepConfig {
            methods: vec!["rne".into(), "dis".into()],
            trials: 2,
            duration_s: Some(20.0),
            threads: 2,
            ..SweepConfig::new(scenario, PAPER)
        };
        edit(&mut cfg);
        let header = match header_of(&cfg) {
            Ok(h) => h,
            Err(SweepError::Config(e)) => return Some(e),
            Err(e) => panic!("not a ConfigError: {e}"),
        };
        check_config(&cfg, &header).err()
    }

    #[test]
    fn each_refused_field_is_its_own_variant() {
        assert_eq!(refusal(|_| {}), None);
        assert_eq!(refusal(|c| c.trials = 0), Some(ConfigError::NoTrials));
        assert_eq!(refusal(|c| c.threads = 0), Some(ConfigError::NoThreads));
        assert_eq!(refusal(|c| c.methods.clear()), Some(ConfigError::NoMethods));
        assert_eq!(
            refusal(|c| c.methods.push("RNE".into())),
            Some(ConfigError::MethodTwice {
                methods: ["RNE", "DIS", "RNE"].map(String::from).to_vec()
            })
        );
        let Some(ConfigError::TrialLength { reason }) = refusal(|c| c.duration_s = Some(-1.0))
        else {
            panic!("a negative length is a TrialLength");
        };
        assert!(reason.contains("found -1"), "{reason}");
        assert_eq!(
            refusal(|c| c.trials = 600_000),
            Some(ConfigError::TooManyTrials {
                cells: 1,
                methods: 2,
                trials: 600_000,
                total: 1_200_000,
                limit: crate::data::limits::MAX_SWEEP_TRIALS,
            })
        );
        let e = refusal(|c| c.trials = 0).unwrap();
        assert_eq!(e.field(), Some(ConfigField::Trials));
        assert_eq!(e.to_string(), "trials must be at least 1");
    }
}
