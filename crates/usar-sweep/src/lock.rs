//! The lock on a sweep's output folder: one writer at a time.
//!
//! A sweep holds an exclusive advisory lock ([`std::fs::File::try_lock`], `flock(2)` on Linux)
//! on `sweep.lock` ([`LOCK_FILE`]) in its output folder from before it opens the journal until
//! its files are written. A second sweep, `--resume` or `--overwrite` into the same folder
//! fails at once, naming the holder's pid, which the holder writes into the file.
//!
//! The lock belongs to the open file, so it ends with the [`OutputLock`] (on return, on an
//! error, on a panic) or with the process (an exit or a kill): a lock file left by a killed
//! sweep never blocks the next one, and the pid in it is only informative. The file itself
//! stays (removing it would let two sweeps lock two different files of the same name).

use std::fs::{self, File, OpenOptions, TryLockError};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use usar_sim::scenario::path_text;

/// Name of the lock file in the output folder.
pub const LOCK_FILE: &str = "sweep.lock";

/// An exclusive lock on an output folder, held until dropped.
#[derive(Debug)]
pub struct OutputLock {
    path: PathBuf,
    // Holds the lock: closing the file releases it.
    _file: File,
}

impl OutputLock {
    /// Creates `dir` if needed and locks it for this process, writing the process id into
    /// [`LOCK_FILE`]. Never waits.
    ///
    /// # Errors
    /// The folder is locked by another sweep (`<dir> is in use by another sweep (pid N)`), the
    /// lock file is not a regular file (a link, a folder), or an I/O error.
    pub fn acquire(dir: &Path) -> Result<Self> {
        fs::create_dir_all(dir).with_context(|| format!("creating folder {}", path_text(dir)))?;
        let path = dir.join(LOCK_FILE);
        if let Ok(m) = fs::symlink_metadata(&path)
            && !m.is_file()
        {
            bail!(
                "{} is not a regular file; remove it (it only holds the pid of a running sweep)",
                path_text(&path)
            );
        }
        // Not truncated before the lock is ours: the holder's pid must stay readable.
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .with_context(|| format!("opening {}", path_text(&path)))?;
        match file.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => {
                let mut text = String::new();
                let holder = match file.read_to_string(&mut text) {
                    Ok(_) => text.trim().parse::<u32>().ok(),
                    Err(_) => None,
                }
                .map_or_else(|| "pid unknown".to_string(), |pid| format!("pid {pid}"));
                bail!(
                    "{} is in use by another sweep ({holder}); wait for it to end, or choose \
                     another --out",
                    path_text(dir)
                );
            }
            Err(TryLockError::Error(e)) => {
                return Err(e).with_context(|| format!("locking {}", path_text(&path)));
            }
        }
        file.set_len(0)
            .and_then(|()| writeln!(file, "{}", std::process::id()))
            .and_then(|()| file.flush())
            .with_context(|| format!("writing {}", path_text(&path)))?;
        Ok(Self { path, _file: file })
    }

    /// Creates `dir` if needed and takes a shared lock on it ([`std::fs::File::try_lock_shared`]
    /// on [`LOCK_FILE`]): several holders of shared locks run side by side (the shards of a
    /// multiverse, each also holding the exclusive lock of its own shard folder), while an
    /// exclusive holder ([`OutputLock::acquire`]: a run without shards, a merge) excludes
    /// them and is excluded by them. Never waits; the file's pid is left as it is.
    ///
    /// # Errors
    /// The folder is locked exclusively by another run (`<dir> is in use by another run
    /// (pid N)`), the lock file is not a regular file, or an I/O error.
    pub fn acquire_shared(dir: &Path) -> Result<Self> {
        fs::create_dir_all(dir).with_context(|| format!("creating folder {}", path_text(dir)))?;
        let path = dir.join(LOCK_FILE);
        if let Ok(m) = fs::symlink_metadata(&path)
            && !m.is_file()
        {
            bail!(
                "{} is not a regular file; remove it (it only holds the pid of a running sweep)",
                path_text(&path)
            );
        }
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .create(true)
            .truncate(false)
            .open(&path)
            .with_context(|| format!("opening {}", path_text(&path)))?;
        match file.try_lock_shared() {
            Ok(()) => Ok(Self { path, _file: file }),
            Err(TryLockError::WouldBlock) => {
                let mut text = String::new();
                let holder = match file.read_to_string(&mut text) {
                    Ok(_) => text.trim().parse::<u32>().ok(),
                    Err(_) => None,
                }
                .map_or_else(|| "pid unknown".to_string(), |pid| format!("pid {pid}"));
                bail!(
                    "{} is in use by another run ({holder}) that writes the whole folder; wait \
                     for it to end, or choose another --out",
                    path_text(dir)
                )
            }
            Err(TryLockError::Error(e)) => {
                Err(e).with_context(|| format!("locking {}", path_text(&path)))
            }
        }
    }

    /// Path of the lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_second_lock_is_refused_naming_the_holder_until_the_first_is_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let out = dir.path().join("out");
        let first = OutputLock::acquire(&out).unwrap();
        assert_eq!(
            fs::read_to_string(first.path()).unwrap(),
            format!("{}\n", std::process::id())
        );
        let e = OutputLock::acquire(&out).unwrap_err();
        let msg = format!("{e:#}");
        assert!(
            msg.contains("is in use by another sweep")
                && msg.contains(&format!("pid {}", std::process::id())),
            "{msg}"
        );
        assert!(!msg.contains('\n'), "{msg}");
        drop(first);
        // The file stays, with a stale pid: it does not block.
        fs::write(out.join(LOCK_FILE), "999999999\n").unwrap();
        let again = OutputLock::acquire(&out).unwrap();
        assert_eq!(
            fs::read_to_string(again.path()).unwrap(),
            format!("{}\n", std::process::id())
        );
    }

    #[test]
    fn shared_locks_go_together_and_exclude_an_exclusive_one() {
        let dir = tempfile::tempdir().unwrap();
        let a = OutputLock::acquire_shared(dir.path()).unwrap();
        let b = OutputLock::acquire_shared(dir.path()).unwrap();
        let e = format!("{:#}", OutputLock::acquire(dir.path()).unwrap_err());
        assert!(e.contains("is in use by another sweep"), "{e}");
        drop((a, b));
        let x = OutputLock::acquire(dir.path()).unwrap();
        let e = format!("{:#}", OutputLock::acquire_shared(dir.path()).unwrap_err());
        assert!(
            e.contains("is in use by another run")
                && e.contains(&format!("pid {}", std::process::id())),
            "{e}"
        );
        drop(x);
        assert!(OutputLock::acquire_shared(dir.path()).is_ok());
    }

    #[cfg(unix)]
    #[test]
    fn a_lock_file_that_is_a_link_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let victim = dir.path().join("victim");
        fs::write(&victim, "keep me").unwrap();
        std::os::unix::fs::symlink(&victim, dir.path().join(LOCK_FILE)).unwrap();
        let e = OutputLock::acquire(dir.path()).unwrap_err();
        assert!(format!("{e:#}").contains("not a regular file"), "{e:#}");
        assert_eq!(fs::read_to_string(&victim).unwrap(), "keep me");
    }
}
