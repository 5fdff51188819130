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

use usar_sim::scenario::path_text;

use crate::atomic::FileError;
use crate::data::shard_split::Shard;
use crate::data::sweep_plan::SweepPlan;

/// Name of the folder, under a sweep's output folder, that holds the shards' folders.
pub const SHARDS_DIR: &str = "shards";

/// The folder of `shard` of the sweep whose output folder is `out_dir`:
/// `<out_dir>/shards/<I>-of-<N>` ([`Shard::dir_name`]).
pub fn shard_dir(out_dir: &Path, shard: Shard) -> PathBuf {
    out_dir.join(SHARDS_DIR).join(shard.dir_name())
}

/// The shard folders under `<out_dir>/shards/`, ordered by shard count, then index; a folder
/// or file whose name is not `<I>-of-<N>` is skipped, and there are none when `shards/` does
/// not exist.
///
/// # Errors
/// An I/O error listing `<out_dir>/shards/`.
pub fn shard_folders(out_dir: &Path) -> Result<Vec<(Shard, PathBuf)>, FileError> {
    let root = out_dir.join(SHARDS_DIR);
    if !root.is_dir() {
        return Ok(Vec::new());
    }
    let mut found = Vec::new();
    let reading = || FileError::io(format!("reading {}", path_text(&root)));
    for e in std::fs::read_dir(&root).map_err(reading())? {
        let e = e.map_err(reading())?;
        if let Some(s) = e.file_name().to_str().and_then(Shard::from_dir_name) {
            found.push((s, e.path()));
        }
    }
    found.sort_by_key(|(s, _)| (s.count, s.index));
    Ok(found)
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
