//! Where a shard of a sweep runs: its folder under the sweep's output folder, and what it
//! keeps there.
//!
//! ```text
//! <out>/shards/<I>-of-<N>/
//!   journal.jsonl   the shard's journal: the sweep's own header, records of the shard's jobs
//!   plan.json       the sweep's scenario text and options (crate::shard::SweepPlan)
//!   sweep.lock      the shard's lock: shards of one sweep run at the same time
//! ```

use std::path::{Path, PathBuf};

use crate::shard::{Shard, SweepPlan};

/// Name of the folder, under a sweep's output folder, that holds the shards' folders.
pub const SHARDS_DIR: &str = "shards";

/// The folder of `shard` of the sweep whose output folder is `out_dir`:
/// `<out_dir>/shards/<I>-of-<N>` ([`Shard::dir_name`]).
pub fn shard_dir(out_dir: &Path, shard: Shard) -> PathBuf {
    out_dir.join(SHARDS_DIR).join(shard.dir_name())
}

/// A sweep run as one shard (`usar sweep ... --shard I/N`): which shard, and the plan written
/// beside its journal for `usar merge`.
#[derive(Debug, Clone, PartialEq)]
pub struct ShardRun {
    /// The shard.
    pub shard: Shard,
    /// The sweep's plan (scenario text and options).
    pub plan: SweepPlan,
}
