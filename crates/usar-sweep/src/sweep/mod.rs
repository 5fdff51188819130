//! A sweep: every grouping method for every trial of every grid cell, in parallel, with a
//! journal that makes it resumable. [`run_sweep`] runs and returns data only; the analysis
//! (`usar_report::analysis`) judges it and `usar_report::output` writes the files.
//!
//! A sweep without `--vary` is a grid of one cell, the scenario itself. Trial `k` of every
//! method and every cell starts from the same team (seed `trial_seed(base_seed, k)`: common
//! random numbers). Each finished trial is appended to the journal ([`crate::journal`]) as soon
//! as it ends; a resume reruns only trials with no successful record. All jobs of all cells
//! go through one thread pool; results are sorted by cell, method order and trial, so they do
//! not depend on thread count, completion order or interruptions.
//!
//! [`run_in_memory`] runs the same trials with nothing on disk (no output folder, journal or
//! lock) and returns their results ([`SweepResults`]), bit-identical to `run_sweep`'s.
//!
//! The sweep's plan and outcome types, limits and output names are data ([`crate::data`]);
//! they are re-exported here at their old paths. [`checks`] refuses a sweep before it runs,
//! [`header`] makes its journal header, `open_journal` opens the journal, `plans` makes the
//! cells' plans and the jobs, [`run`] runs the jobs (`in_memory` without a journal) and
//! `records` sorts the records into per-cell outcomes.

pub mod checks;
pub mod header;
mod in_memory;
mod open_journal;
mod plans;
mod records;
pub mod run;

pub use crate::data::config::SweepConfig;
pub use crate::data::config_error::{ConfigError, ConfigField};
pub use crate::data::hooks::{JournaledHook, SweepHooks, TrialKey, TrialObserverFactory};
pub use crate::data::jobs::{JobId, job_list};
pub use crate::data::limits::{
    MAX_SWEEP_TRIALS, MAX_THREADS_PER_CORE, check_sweep_size, effective_threads, max_threads,
    sweep_threads,
};
pub use crate::data::out_dir::{MAX_FOLDER_NAME_BYTES, default_out_dir, default_out_dir_of};
pub use crate::data::outcome::{CellOutcome, Failure, JournalUse, SweepOutcome};
pub use crate::data::setting_error::SettingError;
pub use crate::data::trial_length::simulated_length_s;
pub use crate::error::SweepError;
pub use crate::method_factory::{
    ChaCha8Rng, METHOD_RNG_STREAM, MethodFactory, TrialContext, canonical_method, rand, trust_model,
};
pub use checks::{check_config, check_grid_size, check_trial_count, trial_count};
pub use header::header_of;
pub use in_memory::{SweepResults, run_in_memory};
pub(crate) use records::cells_from_records;
pub use run::run_sweep;
