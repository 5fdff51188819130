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

/// What a shard folder's name must be, for messages.
pub const SHARD_NAME_FORM: &str = "a shard's folder is named <I>-of-<N>, the shard index I \
     from 0 to N-1 zero-padded to the digits of N-1 (0-of-2, 03-of-12)";

/// The shard folders under `<out_dir>/shards/`, ordered by shard count, then index; there are
/// none when `shards/` does not exist. A file there whose name is not of a shard (a user's
/// notes, a hidden file) is skipped, but a folder whose name is not `<I>-of-<N>`
/// ([`Shard::dir_name`]), or any entry named like one (`2-of-2`, `0-of-0`, `3-of-12`), is
/// refused: a merge or an `--overwrite` would otherwise pass over it without a word.
///
/// # Errors
/// [`FileError::Misnamed`] naming such an entry and the form of a shard's folder
/// ([`SHARD_NAME_FORM`]), or an I/O error listing `<out_dir>/shards/`.
pub fn shard_folders(out_dir: &Path) -> Result<Vec<(Shard, PathBuf)>, FileError> {
    let root = out_dir.join(SHARDS_DIR);
    if !root.is_dir() {
        return Ok(Vec::new());
    }
    let mut found = Vec::new();
    let reading = || FileError::io(format!("reading {}", path_text(&root)));
    for e in std::fs::read_dir(&root).map_err(reading())? {
        let e = e.map_err(reading())?;
        let name = e.file_name();
        match name.to_str().and_then(Shard::from_dir_name) {
            Some(s) => found.push((s, e.path())),
            None if looks_like_a_shard(&name, &e.path()) => {
                return Err(FileError::Misnamed {
                    path: path_text(&e.path()),
                    why: format!("not a shard's folder name: {SHARD_NAME_FORM}"),
                });
            }
            None => {}
        }
    }
    found.sort_by_key(|(s, _)| (s.count, s.index));
    Ok(found)
}

/// Whether the entry `name` at `path` under `shards/`, not a valid shard folder name, would be
/// taken for a shard's folder: a folder (or a link to one) that is not hidden, or a name of
/// the form `<I>-of-<N>`.
fn looks_like_a_shard(name: &std::ffi::OsStr, path: &Path) -> bool {
    let name = name.to_string_lossy();
    name.contains("-of-") || (!name.starts_with('.') && path.is_dir())
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
