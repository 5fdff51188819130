//! Reading a file that usar wrote into an output folder and reads back whole (a shard's
//! `plan.json`, a multiverse's `multiverse.json`) with a size limit, through the one bounded
//! reader of the workspace, [`usar_sim::scenario::read_bounded`]: such a file may have been
//! replaced since by anything (a link to `/dev/zero`, a FIFO without a writer, a huge file),
//! which is refused in one line naming it instead of being read into memory or waited on.

use std::path::Path;

use usar_sim::scenario::limits::MAX_SCENARIO_BYTES;
use usar_sim::scenario::{BoundedReadError, path_text, read_bounded};

use crate::atomic::FileError;

/// The largest shard plan (`plan.json`, [`crate::shard::SweepPlan`]) read, bytes: it holds
/// the scenario file's text (at most [`MAX_SCENARIO_BYTES`]) as a JSON string, in which a
/// byte takes at most 6 (`\u0001`), and the sweep's options (1 MiB is ample): 385 MiB.
pub const MAX_SHARD_PLAN_BYTES: u64 = 6 * MAX_SCENARIO_BYTES + (1 << 20);

/// The largest multiverse plan (`multiverse.json`) read, bytes: 64 MiB, far above the JSON
/// of the largest axes, targets and claims files (1 MiB each as RON).
pub const MAX_MULTIVERSE_PLAN_BYTES: u64 = 64 << 20;

/// The bytes of the regular file at `path`, at most `max_bytes` of them.
///
/// # Errors
/// [`FileError::NotRead`] naming the path when it is not a regular file (after symbolic
/// links: a folder, a FIFO, a device such as `/dev/zero`) or holds more than `max_bytes`
/// bytes (refused from its size before a byte is read, or once a file growing while it is
/// read passes the limit); [`FileError::Io`] when it cannot be found, opened or read.
pub fn read_small(path: &Path, max_bytes: u64) -> Result<Vec<u8>, FileError> {
    let not_read = |why: String| FileError::NotRead {
        path: path_text(path),
        why,
    };
    let action = || format!("cannot read {}", path_text(path));
    // `read_bounded` refuses what is not a regular file; a file already past the limit is
    // refused here from its size, before a byte is read.
    let meta = std::fs::metadata(path).map_err(FileError::io(action()))?;
    if meta.is_file() && meta.len() > max_bytes {
        return Err(not_read(format!(
            "{} bytes, longer than the limit of {max_bytes} bytes",
            meta.len()
        )));
    }
    read_bounded(path, max_bytes).map_err(|e| match e {
        BoundedReadError::Io(source) => FileError::io(action())(source),
        other => not_read(other.to_string()),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_past_its_limit_or_not_regular_is_refused_by_name() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("plan.json");
        std::fs::write(&path, b"{}").unwrap();
        assert_eq!(read_small(&path, 2).unwrap(), b"{}");
        let long = read_small(&path, 1).unwrap_err().to_string();
        assert_eq!(
            long,
            format!(
                "cannot read {}: 2 bytes, longer than the limit of 1 bytes",
                path_text(&path)
            )
        );
        let folder = read_small(dir.path(), 10).unwrap_err().to_string();
        assert!(
            folder.ends_with(": not a regular file (a folder, FIFO or device)"),
            "{folder}"
        );
        let missing = read_small(&dir.path().join("none"), 10).unwrap_err();
        assert!(matches!(missing, FileError::Io { .. }), "{missing}");
        #[cfg(unix)]
        {
            let e = read_small(Path::new("/dev/zero"), 1 << 16).unwrap_err();
            assert!(e.to_string().contains("not a regular file"), "{e}");
        }
    }
}
