//! The lock on a sweep's output folder: one writer at a time.
//!
//! A sweep holds an exclusive advisory lock ([`std::fs::File::try_lock`], `flock(2)` on Linux)
//! on `sweep.lock` ([`LOCK_FILE`]) in its output folder from before it opens the journal until
//! its files are written. A second sweep, `--resume` or `--overwrite` into the same folder
//! fails at once, naming the holder's pid, which the holder writes into the file.
//!
//! The lock belongs to the open file; it ends when the [`OutputLock`] is dropped (on return, on an
//! error, on a panic) or with the process (an exit or a kill): a lock file left by a killed
//! sweep never blocks the next one, and the pid in it is only informative. The file itself
//! stays (removing it would let two sweeps lock two different files of the same name).

use std::fs::{self, File, OpenOptions, TryLockError};
use std::io::{Read, Write};
use std::path::{Path, PathBuf};

use usar_sim::scenario::path_text;

use crate::atomic::FileError;

/// Name of the lock file in the output folder.
pub const LOCK_FILE: &str = "sweep.lock";

/// Why an output folder could not be locked: one line naming the folder or the lock file.
#[derive(Debug, thiserror::Error)]
pub enum LockError {
    /// Another run holds the folder: an exclusive lock was asked for and any lock is held
    /// (`shared: false`), or a shared lock was asked for and an exclusive one is held
    /// (`shared: true`).
    #[error(
        "{dir} is in use by another {}; wait for it to end, or choose another {}",
        holder_text(*shared, *pid),
        crate::settings::Setting::Out
    )]
    InUse {
        /// The folder, as given.
        dir: String,
        /// The holder's process id, as it wrote it into the lock file (`None`: unreadable).
        pid: Option<u32>,
        /// Whether the lock asked for was a shared one.
        shared: bool,
    },
    /// The lock file is a link, a folder or another kind of file that is not regular.
    #[error("{path} is not a regular file; remove it (it only holds the pid of a running sweep)")]
    NotAFile {
        /// The lock file, as given.
        path: String,
    },
    /// Creating the folder, or opening, locking or writing the lock file failed.
    #[error(transparent)]
    File(#[from] FileError),
}

/// The holder as [`LockError::InUse`] names it.
fn holder_text(shared: bool, pid: Option<u32>) -> String {
    let pid = pid.map_or_else(|| "pid unknown".to_string(), |pid| format!("pid {pid}"));
    match shared {
        false => format!("sweep ({pid})"),
        true => format!("run ({pid}) that writes the whole folder"),
    }
}

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
    /// The folder is locked by another sweep ([`LockError::InUse`]: `<dir> is in use by
    /// another sweep (pid N)`), the lock file is not a regular file (a link, a folder), or an
    /// I/O error.
    pub fn acquire(dir: &Path) -> Result<Self, LockError> {
        let (path, mut file) = open_lock_file(dir)?;
        lock(file.try_lock(), &mut file, dir, &path, false)?;
        let action = format!("writing {}", path_text(&path));
        file.set_len(0)
            .and_then(|()| writeln!(file, "{}", std::process::id()))
            .and_then(|()| file.flush())
            .map_err(|e| FileError::Io { action, source: e })?;
        Ok(Self { path, _file: file })
    }

    /// Creates `dir` if needed and takes a shared lock on it ([`std::fs::File::try_lock_shared`]
    /// on [`LOCK_FILE`]): several holders of shared locks run side by side (the shards of a
    /// multiverse, each also holding the exclusive lock of its own shard folder), while an
    /// exclusive holder ([`OutputLock::acquire`]: a run without shards, a merge) excludes
    /// them and is excluded by them. Never waits; the file's pid is left as it is.
    ///
    /// # Errors
    /// The folder is locked exclusively by another run ([`LockError::InUse`]: `<dir> is in
    /// use by another run (pid N)`), the lock file is not a regular file, or an I/O error.
    pub fn acquire_shared(dir: &Path) -> Result<Self, LockError> {
        let (path, mut file) = open_lock_file(dir)?;
        lock(file.try_lock_shared(), &mut file, dir, &path, true)?;
        Ok(Self { path, _file: file })
    }

    /// Path of the lock file.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

impl Drop for OutputLock {
    /// Releases the lock itself (`flock(LOCK_UN)`) before the file closes: a lock belongs to
    /// the open file, which a child process forked meanwhile by any thread of this process
    /// shares until its exec, so closing this descriptor alone could leave the folder locked
    /// that long.
    fn drop(&mut self) {
        // An error here leaves what closing the file does: the lock ends with the last copy.
        let _ = self._file.unlock();
    }
}

/// Creates `dir` if needed and opens its lock file (created if missing, not truncated: a
/// holder's pid must stay readable until the lock is ours), refusing one that is not a
/// regular file.
fn open_lock_file(dir: &Path) -> Result<(PathBuf, File), LockError> {
    let io = |action: String| move |source| FileError::Io { action, source };
    fs::create_dir_all(dir).map_err(io(format!("creating folder {}", path_text(dir))))?;
    let path = dir.join(LOCK_FILE);
    if let Ok(m) = fs::symlink_metadata(&path)
        && !m.is_file()
    {
        return Err(LockError::NotAFile {
            path: path_text(&path),
        });
    }
    let file = OpenOptions::new()
        .read(true)
        .write(true)
        .create(true)
        .truncate(false)
        .open(&path)
        .map_err(io(format!("opening {}", path_text(&path))))?;
    Ok((path, file))
}

/// The outcome of a try-lock of `file` (the lock file at `path` in `dir`): `Ok`, or
/// [`LockError::InUse`] naming the pid the holder wrote, or the I/O error.
fn lock(
    tried: Result<(), TryLockError>,
    file: &mut File,
    dir: &Path,
    path: &Path,
    shared: bool,
) -> Result<(), LockError> {
    match tried {
        Ok(()) => Ok(()),
        Err(TryLockError::WouldBlock) => {
            let mut text = String::new();
            let pid = match file.read_to_string(&mut text) {
                Ok(_) => text.trim().parse::<u32>().ok(),
                Err(_) => None,
            };
            Err(LockError::InUse {
                dir: path_text(dir),
                pid,
                shared,
            })
        }
        Err(TryLockError::Error(source)) => Err(FileError::Io {
            action: format!("locking {}", path_text(path)),
            source,
        }
        .into()),
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
        let pid = Some(std::process::id());
        assert!(
            matches!(&e, LockError::InUse { pid: p, shared: false, .. } if *p == pid),
            "{e:?}"
        );
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
    fn a_dropped_lock_is_released_while_a_copy_of_its_descriptor_is_open() {
        // A copy of the descriptor, as a child forked before its exec holds: the lock of the
        // open file would outlive the dropped lock until the copy closed.
        let dir = tempfile::tempdir().unwrap();
        for shared in [false, true] {
            let first = if shared {
                OutputLock::acquire_shared(dir.path())
            } else {
                OutputLock::acquire(dir.path())
            }
            .unwrap();
            let copy = first._file.try_clone().unwrap();
            drop(first);
            drop(OutputLock::acquire(dir.path()).expect("released on drop"));
            drop(copy);
        }
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
        let e = OutputLock::acquire_shared(dir.path()).unwrap_err();
        assert!(matches!(e, LockError::InUse { shared: true, .. }), "{e:?}");
        let e = format!("{e:#}");
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
        assert!(matches!(e, LockError::NotAFile { .. }), "{e:?}");
        assert!(format!("{e:#}").contains("not a regular file"), "{e:#}");
        assert_eq!(fs::read_to_string(&victim).unwrap(), "keep me");
    }
}
