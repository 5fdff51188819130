//! Sweeps split into shards (`usar sweep ... --shard I/N`, for a Slurm job array or any set of
//! machines) and merged back (`usar merge DIR`) into the same files a sweep on one machine
//! writes.
//!
//! Which jobs a shard runs ([`crate::data::shard_split`]), where it keeps its journal and plan
//! ([`crate::data::shard_folders`]) and what the sweep was asked to run
//! ([`crate::data::sweep_plan`]) are the sweep's data, re-exported here; [`plan_config`] rebuilds the
//! sweep's configuration from a plan, and [`merge`] combines the shards' journals.

pub mod merge;
pub mod plan_config;

pub use crate::data::shard_folders::{SHARDS_DIR, ShardRun, shard_dir, shard_folders};
pub use crate::data::shard_split::{
    MAX_SHARDS, Shard, ShardError, job_costs_ms, split, sweep_jobs,
};
pub use crate::data::sweep_plan::{PLAN_FILE, PlanError, SweepPlan, shell_join};
pub use merge::{MergeError, Merged, merge_shards};
