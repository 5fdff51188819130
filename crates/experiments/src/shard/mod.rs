//! Sweeps split into shards (`usar sweep ... --shard I/N`, for a Slurm job array or any set of
//! machines) and merged back (`usar merge DIR`) into the same files a sweep on one machine
//! writes.
//!
//! [`spec`] says which jobs a shard runs, [`run`] where it keeps its journal and plan,
//! [`plan`] what the sweep was asked to run, and [`merge`] combines the shards' journals.

pub mod merge;
pub mod plan;
pub mod run;
pub mod spec;

pub use merge::{MergeError, Merged, merge_shards};
pub use plan::{SweepPlan, shell_join};
pub use run::{SHARDS_DIR, ShardRun, shard_dir, shard_folders};
pub use spec::{MAX_SHARDS, Shard, ShardError, split};
