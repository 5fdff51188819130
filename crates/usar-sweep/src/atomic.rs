//! Writing output files (`usar run --json`, `usar render --out`, a sweep's files) without
//! ever leaving something half-written under the final name, without replacing what the path
//! names, and without leaving temporary files behind.
//!
//! What [`write_atomic`] does with the path it is given:
//!
//! | the path is | what happens |
//! |---|---|
//! | a regular file, or nothing yet | the bytes go to a temporary file next to it, flushed to disk, renamed over it (atomic on POSIX); parent folders are created; a replaced file keeps its permissions |
//! | a symbolic link (to any of these) | the link is followed and stays: its target gets the new content, as above (a dangling link's target is created) |
//! | a FIFO or a character device (`/dev/null`, `/dev/stdout` on a terminal or pipe) | written directly with a plain write, never replaced (a FIFO waits for its reader) |
//! | a folder, a block device or a socket | refused with a one-line error; nothing is written |
//!
//! [`FileSet`] writes several files as a set: every temporary file first, then every rename, so
//! an error before the renames leaves every file of the set as it was.
//!
//! A temporary file is made by the `tempfile` crate, named `.<name>.tmp-<pid>-<random>`
//! ([`is_temp_name`]), and is removed when the write fails (a full disk, a failed rename) or
//! panics. Only a kill leaves one behind:
//! [`remove_stale_temps`] clears a folder of them (a sweep does so in its output folder on
//! every start and resume, under its lock).

use std::fs::{self, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};

use tempfile::NamedTempFile;
use usar_sim::scenario::path_text;

/// Why a file could not be written, or a folder cleaned: one line naming the path (and, for
/// an I/O error, the error as its source, which a caller's `{:#}` or error chain appends:
/// `cannot write out/a.csv: Permission denied (os error 13)`).
#[derive(Debug, thiserror::Error)]
pub enum FileError {
    /// An I/O error while doing what `action` says, naming the path (`cannot write
    /// out/a.csv`, `renaming out/.a.csv.tmp-1-x to out/a.csv`, `removing out/b.tmp`).
    #[error("{action}")]
    Io {
        /// What was being done, with the path.
        action: String,
        /// The error the system gave.
        #[source]
        source: std::io::Error,
    },
    /// The path is a folder.
    #[error("{path}: is a folder, not a file")]
    Folder {
        /// The path, as given.
        path: String,
    },
    /// The path is a block device, a socket or another special file, none of which is
    /// written.
    #[error("{path}: is a {kind}; usar writes only regular files, FIFOs and character devices")]
    Special {
        /// The path, as given.
        path: String,
        /// `block device`, `socket` or `special file`.
        kind: &'static str,
    },
    /// A chain of symbolic links longer than the kernel's limit (40).
    #[error("{path}: too many levels of symbolic links")]
    LinkLoop {
        /// The path, as given.
        path: String,
    },
    /// The path resolves to no file name (`..`, `/`).
    #[error("{path} has no file name")]
    NoFileName {
        /// The path, resolved.
        path: String,
    },
    /// A file that is not read ([`crate::bounded_file::read_small`]): not a regular file, or
    /// longer than its limit.
    #[error("cannot read {path}: {why}")]
    NotRead {
        /// The path, as given.
        path: String,
        /// Why (`not a regular file (a folder, FIFO or device)`, `longer than the limit of
        /// 1048576 bytes`).
        why: String,
    },
    /// A name in a folder that usar reads by name which has not the form it must have
    /// (`shards/2-of-2`), so that it would be skipped without a word.
    #[error("{path}: {why}; rename it or move it away")]
    Misnamed {
        /// The path, as given.
        path: String,
        /// What the name must be.
        why: String,
    },
}

impl FileError {
    /// The error and its source on one line, as an error chain prints them (`cannot write
    /// out/a.csv: Permission denied (os error 13)`): for a caller that keeps the message as
    /// text.
    pub fn line(&self) -> String {
        match self {
            Self::Io { action, source } => format!("{action}: {source}"),
            other => other.to_string(),
        }
    }

    /// The [`FileError::Io`] of `source` while doing `action` (what was being done, naming
    /// the path: `creating folder out/cells`), for `map_err`.
    pub fn io(action: String) -> impl FnOnce(std::io::Error) -> Self {
        move |source| Self::Io { action, source }
    }
}

/// What the functions of this module return.
type Result<T> = std::result::Result<T, FileError>;

/// Symbolic links followed at most when resolving a link whose target does not exist yet
/// (as the kernel's own limit, `ELOOP`).
const MAX_LINKS: usize = 40;

/// Writes `bytes` to `path`: atomically through a temporary file when `path` is (or links to)
/// a regular file or nothing yet, directly when it is a FIFO or a character device. See the
/// [module documentation](self) for every case.
///
/// # Errors
/// `path` is a folder, a block device or a socket, a link loop, or an I/O error. Every message
/// names the path it was about (the file written, and its temporary file), so a caller adds no
/// "writing ..." context of its own. No temporary file is left behind on any error.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    match target_of(path)? {
        Target::Replace(target) => replace_via_temp(&target, bytes),
        Target::Stream => write_directly(path, bytes),
    }
}

/// How `path` is written.
enum Target {
    /// A regular file (existing or not), at this path with every link resolved.
    Replace(PathBuf),
    /// A FIFO or character device: opened and written as it is.
    Stream,
}

/// Decides how `path` is written, following symbolic links.
fn target_of(path: &Path) -> Result<Target> {
    match fs::metadata(path) {
        Ok(m) if m.is_file() => fs::canonicalize(path)
            .map(Target::Replace)
            .map_err(FileError::io(format!("resolving {}", path_text(path)))),
        Ok(m) if m.is_dir() => Err(FileError::Folder {
            path: path_text(path),
        }),
        Ok(m) => match special_kind(&m) {
            None => Ok(Target::Stream),
            Some(kind) => Err(FileError::Special {
                path: path_text(path),
                kind,
            }),
        },
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => {
            resolve_missing(path).map(Target::Replace)
        }
        Err(e) => Err(FileError::io(format!("cannot write {}", path_text(path)))(
            e,
        )),
    }
}

/// `None` for a file type written directly (a FIFO, a character device), otherwise the name
/// of a kind that is refused.
#[cfg(unix)]
fn special_kind(m: &fs::Metadata) -> Option<&'static str> {
    use std::os::unix::fs::FileTypeExt;
    let t = m.file_type();
    if t.is_fifo() || t.is_char_device() {
        None
    } else if t.is_block_device() {
        Some("block device")
    } else if t.is_socket() {
        Some("socket")
    } else {
        Some("special file")
    }
}

/// `None` for a file type written directly, otherwise the name of a kind that is refused.
#[cfg(not(unix))]
fn special_kind(_: &fs::Metadata) -> Option<&'static str> {
    None
}

/// Where a path that does not resolve to an existing file is created: the path itself, or the
/// end of its chain of (dangling) symbolic links.
fn resolve_missing(path: &Path) -> Result<PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        match fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let to = fs::read_link(&p)
                    .map_err(FileError::io(format!("reading the link {}", path_text(&p))))?;
                // A relative link is relative to the folder holding it; `join` keeps an
                // absolute one as it is.
                p = p.parent().map_or_else(|| to.clone(), |dir| dir.join(&to));
            }
            _ => return Ok(p),
        }
    }
    Err(FileError::LinkLoop {
        path: path_text(path),
    })
}

/// Files written as a set: [`FileSet::stage`] writes each file's bytes to a temporary file
/// next to it (flushed to disk) and [`FileSet::commit`] renames them all into place, in the
/// order staged. An error while staging (a folder in the way, a read-only folder, a full
/// disk) leaves every file of the set as it was, and dropping the set before its commit
/// removes every temporary file. Only a failed rename during the commit (not expected once
/// the temporary file exists in the same folder) can leave the files before it new and the
/// rest old. FIFOs and character devices are not replaced but written directly, at the
/// commit. Each path is handled as [`write_atomic`] handles it.
#[derive(Default)]
pub struct FileSet {
    staged: Vec<StagedFile>,
}

/// One file of a [`FileSet`].
enum StagedFile {
    /// A temporary file (removed on drop unless renamed) and the file it replaces.
    Temp {
        tmp: NamedTempFile,
        target: PathBuf,
        path: PathBuf,
    },
    /// A FIFO or character device and the bytes it gets at the commit.
    Stream { path: PathBuf, bytes: Vec<u8> },
}

impl FileSet {
    /// An empty set.
    pub fn new() -> Self {
        Self::default()
    }

    /// Stages `bytes` for `path`: written to a temporary file next to what `path` resolves to
    /// (parent folders created), or kept for a FIFO or character device.
    ///
    /// # Errors
    /// As [`write_atomic`]: a folder, a block device or a socket, a link loop, or an I/O
    /// error; the temporary file of this path is removed, the set's others stay staged.
    pub fn stage(&mut self, path: &Path, bytes: &[u8]) -> Result<()> {
        let file = match target_of(path)? {
            Target::Replace(target) => StagedFile::Temp {
                tmp: write_temp(&target, bytes)?,
                target,
                path: path.to_path_buf(),
            },
            Target::Stream => StagedFile::Stream {
                path: path.to_path_buf(),
                bytes: bytes.to_vec(),
            },
        };
        self.staged.push(file);
        Ok(())
    }

    /// Renames every staged file into place (and writes the streams), in the order staged;
    /// returns the paths as given to [`FileSet::stage`].
    ///
    /// # Errors
    /// A failed rename or stream write, naming the file; the temporary files not yet renamed
    /// are removed.
    pub fn commit(self) -> Result<Vec<PathBuf>> {
        let mut paths = Vec::with_capacity(self.staged.len());
        for file in self.staged {
            paths.push(match file {
                StagedFile::Temp { tmp, target, path } => rename_over(tmp, &target).map(|()| path),
                StagedFile::Stream { path, bytes } => write_directly(&path, &bytes).map(|()| path),
            }?);
        }
        Ok(paths)
    }
}

/// Writes `bytes` to a temporary file next to `target` and renames it over `target`; the
/// temporary file is removed if anything fails.
fn replace_via_temp(target: &Path, bytes: &[u8]) -> Result<()> {
    rename_over(write_temp(target, bytes)?, target)
}

/// Renames the temporary file `tmp` over `target`; on failure it is removed.
fn rename_over(tmp: NamedTempFile, target: &Path) -> Result<()> {
    let from = tmp.path().to_path_buf();
    // A failed persist hands the file back inside the error; dropping it removes it.
    tmp.persist(target).map(drop).map_err(|e| {
        let action = format!("renaming {} to {}", path_text(&from), path_text(target));
        FileError::io(action)(e.error)
    })
}

/// Writes `bytes` to a new temporary file next to `target` (creating its folders), flushed to
/// disk and with `target`'s permissions if it exists (else those a new file gets: 0666 less
/// the umask); removed when dropped.
fn write_temp(target: &Path, bytes: &[u8]) -> Result<NamedTempFile> {
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    fs::create_dir_all(dir)
        .map_err(FileError::io(format!("creating folder {}", path_text(dir))))?;
    let name = target
        .file_name()
        .ok_or_else(|| FileError::NoFileName {
            path: path_text(target),
        })?
        .to_string_lossy();
    let prefix = format!(".{name}.tmp-{}-", std::process::id());
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).rand_bytes(6);
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        // As a file created by `File::create`, not tempfile's owner-only default.
        builder.permissions(fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder.tempfile_in(dir).map_err(FileError::io(format!(
        "creating a temporary file for {} in {}",
        path_text(target),
        path_text(dir)
    )))?;
    if let Err(e) = tmp.write_all(bytes).and_then(|()| tmp.as_file().sync_all()) {
        let tmp_name = tmp.path().file_name().unwrap_or_default().to_string_lossy();
        let action = format!(
            "writing {} (its temporary file {tmp_name})",
            path_text(target)
        );
        return Err(FileError::io(action)(e));
    }
    if let Ok(old) = fs::metadata(target) {
        let action = format!("setting the permissions of {}", path_text(tmp.path()));
        fs::set_permissions(tmp.path(), old.permissions()).map_err(FileError::io(action))?;
    }
    Ok(tmp)
}

/// Writes `bytes` to an existing FIFO or device as it is (no temporary file, no rename).
fn write_directly(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut f = OpenOptions::new()
        .write(true)
        .open(path)
        .map_err(FileError::io(format!("opening {}", path_text(path))))?;
    f.write_all(bytes)
        .and_then(|()| f.flush())
        .map_err(FileError::io(format!("writing {}", path_text(path))))
}

/// Whether `name` is the name of a temporary file of [`write_atomic`]:
/// `.<name>.tmp-<pid>-<random>` (ASCII letters and digits), or `.<name>.tmp-<pid>-<n>` and
/// `.<name>.tmp-<pid>` as written by earlier versions.
pub fn is_temp_name(name: &str) -> bool {
    let Some((stem, tail)) = name.rsplit_once(".tmp-") else {
        return false;
    };
    let mut parts = tail.split('-');
    let all = |s: Option<&str>, ok: fn(&u8) -> bool| {
        s.is_some_and(|s| !s.is_empty() && s.bytes().all(|b| ok(&b)))
    };
    stem.len() > 1
        && stem.starts_with('.')
        && all(parts.next(), u8::is_ascii_digit)
        && match parts.next() {
            None => true,
            n => all(n, u8::is_ascii_alphanumeric) && parts.next().is_none(),
        }
}

/// Removes from `dir` (not its subfolders) the regular files whose names are temporary-file
/// names of [`write_atomic`] ([`is_temp_name`]): what killed runs left behind. A missing
/// folder has none. Call it only while nothing else writes into `dir` (a sweep holds the
/// lock on its output folder, [`crate::lock`]). Returns the files removed.
///
/// # Errors
/// An I/O error listing `dir` or removing a file.
pub fn remove_stale_temps(dir: &Path) -> Result<Vec<PathBuf>> {
    remove_files_where(dir, is_temp_name)
}

/// Removes from `dir` the files (regular files or symbolic links, never folders) of these
/// names that are there; the rest stays. Returns the files removed.
///
/// # Errors
/// An I/O error removing a file.
pub fn remove_named(dir: &Path, names: &[&str]) -> Result<Vec<PathBuf>> {
    let mut removed = Vec::new();
    for name in names {
        let p = dir.join(name);
        if fs::symlink_metadata(&p).is_ok_and(|m| m.is_file() || m.is_symlink()) {
            fs::remove_file(&p).map_err(FileError::io(format!("removing {}", path_text(&p))))?;
            removed.push(p);
        }
    }
    Ok(removed)
}

/// Removes the folder `dir` if it is empty; a missing or non-empty folder stays as it is.
///
/// # Errors
/// Another I/O error removing it.
pub fn remove_dir_if_empty(dir: &Path) -> Result<()> {
    match fs::remove_dir(dir) {
        Ok(()) => Ok(()),
        Err(e)
            if matches!(
                e.kind(),
                std::io::ErrorKind::DirectoryNotEmpty | std::io::ErrorKind::NotFound
            ) =>
        {
            Ok(())
        }
        Err(e) => Err(FileError::io(format!("removing {}", path_text(dir)))(e)),
    }
}

/// Removes from `dir` (not its subfolders) the regular files whose names `matches` accepts
/// (names that are not UTF-8 never match); a missing folder has none. Returns the files
/// removed.
///
/// # Errors
/// An I/O error listing `dir` or removing a file.
pub(crate) fn remove_files_where(dir: &Path, matches: fn(&str) -> bool) -> Result<Vec<PathBuf>> {
    let entries = match fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(FileError::io(format!("listing {}", path_text(dir)))(e)),
    };
    let mut removed = Vec::new();
    for entry in entries {
        let entry = entry.map_err(FileError::io(format!("listing {}", path_text(dir))))?;
        let is_file = entry.file_type().is_ok_and(|t| t.is_file());
        if is_file && entry.file_name().to_str().is_some_and(matches) {
            let p = entry.path();
            fs::remove_file(&p).map_err(FileError::io(format!("removing {}", path_text(&p))))?;
            removed.push(p);
        }
    }
    Ok(removed)
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The names in `dir`, sorted.
    pub(crate) fn names(dir: &Path) -> Vec<String> {
        let mut v: Vec<String> = fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    }

    #[test]
    fn writes_and_replaces_without_leftovers() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub/out.txt");
        write_atomic(&path, b"first").unwrap();
        write_atomic(&path, b"second").unwrap();
        assert_eq!(fs::read_to_string(&path).unwrap(), "second");
        assert_eq!(names(path.parent().unwrap()), ["out.txt"]);
    }

    #[test]
    fn a_file_set_changes_nothing_until_its_commit() {
        let dir = tempfile::tempdir().unwrap();
        let (a, b) = (dir.path().join("a.csv"), dir.path().join("sub/b.csv"));
        write_atomic(&a, b"old a").unwrap();
        let mut set = FileSet::new();
        set.stage(&a, b"new a").unwrap();
        set.stage(&b, b"new b").unwrap();
        // Staged: the old file as it was, the new one not there, two temporary files.
        assert_eq!(fs::read_to_string(&a).unwrap(), "old a");
        assert!(!b.exists());
        assert_eq!(names(dir.path()).len(), 3, "{:?}", names(dir.path()));
        assert_eq!(set.commit().unwrap(), [a.clone(), b.clone()]);
        assert_eq!(fs::read_to_string(&a).unwrap(), "new a");
        assert_eq!(fs::read_to_string(&b).unwrap(), "new b");
        assert_eq!(names(dir.path()), ["a.csv", "sub"]);
        assert_eq!(names(&dir.path().join("sub")), ["b.csv"]);
        // A set dropped after an error while staging: nothing changed, nothing left.
        let mut set = FileSet::new();
        set.stage(&a, b"newer a").unwrap();
        fs::create_dir(dir.path().join("c.csv")).unwrap();
        let e = set.stage(&dir.path().join("c.csv"), b"c").unwrap_err();
        assert!(format!("{e:#}").contains("is a folder"), "{e:#}");
        drop(set);
        assert_eq!(fs::read_to_string(&a).unwrap(), "new a");
        assert_eq!(names(dir.path()), ["a.csv", "c.csv", "sub"]);
    }

    #[test]
    fn a_folder_is_refused_and_leaves_no_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.svg");
        fs::create_dir(&target).unwrap();
        let e = write_atomic(&target, b"x").unwrap_err();
        assert!(
            matches!(&e, FileError::Folder { path } if path.ends_with("out.svg")),
            "{e}"
        );
        assert!(format!("{e:#}").contains("is a folder"), "{e:#}");
        assert_eq!(names(dir.path()), ["out.svg"]);
        assert!(target.is_dir());
    }

    #[test]
    fn an_io_error_names_the_path_and_keeps_the_systems_error_as_its_source() {
        let dir = tempfile::tempdir().unwrap();
        // A path through a regular file: the I/O error is the source, and the chain reads as
        // one line, the action then the system's message.
        let file = dir.path().join("plain");
        fs::write(&file, "x").unwrap();
        let through = file.join("out.csv");
        let e = write_atomic(&through, b"x").unwrap_err();
        let FileError::Io { action, .. } = &e else {
            panic!("not an I/O error: {e:?}")
        };
        assert_eq!(action, &format!("cannot write {}", path_text(&through)));
        let system = fs::metadata(&through).unwrap_err().to_string();
        let line = format!("cannot write {}: {system}", path_text(&through));
        assert_eq!(e.line(), line);
        let source = std::error::Error::source(&e).map(ToString::to_string);
        assert_eq!(format!("{e}: {}", source.unwrap()), line);
    }

    #[test]
    fn a_failed_rename_removes_the_temporary_file() {
        // Past the checks of write_atomic (as when the target turns into a folder meanwhile):
        // the rename fails and the temporary file must go.
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("out.csv");
        fs::create_dir(&target).unwrap();
        fs::write(target.join("inside"), "x").unwrap();
        assert!(replace_via_temp(&target, b"data").is_err());
        assert_eq!(names(dir.path()), ["out.csv"]);
    }

    #[test]
    fn temp_names_are_recognised() {
        for yes in [
            ".trials.csv.tmp-123",
            ".trials.csv.tmp-123-0",
            ".a.tmp-1-22",
            ".trials.csv.tmp-123-x7Qz9a",
        ] {
            assert!(is_temp_name(yes), "{yes}");
        }
        for no in [
            "trials.csv.tmp-123",
            ".trials.csv.tmp-",
            ".trials.csv.tmp-12a",
            ".trials.csv.tmp-1-2-3",
            ".trials.csv.tmp-1-",
            ".trials.csv.tmp-1-x_y",
            ".tmp-1",
            "..tmp-1",
            ".hidden",
            "journal.jsonl",
        ] {
            assert!(!is_temp_name(no), "{no}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_new_file_gets_a_new_files_permissions_and_its_temp_name_is_known() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let mode = |p: &Path| fs::metadata(p).unwrap().permissions().mode() & 0o777;
        fs::write(dir.path().join("plain"), "x").unwrap();
        write_atomic(&dir.path().join("atomic"), b"x").unwrap();
        // Not tempfile's owner-only 0600: what `File::create` gives under the same umask.
        assert_eq!(
            mode(&dir.path().join("atomic")),
            mode(&dir.path().join("plain"))
        );
        let tmp = write_temp(&dir.path().join("trials.csv"), b"x").unwrap();
        let name = tmp
            .path()
            .file_name()
            .unwrap()
            .to_string_lossy()
            .into_owned();
        assert!(is_temp_name(&name), "{name}");
        drop(tmp);
        assert_eq!(names(dir.path()), ["atomic", "plain"]);
    }

    #[test]
    fn stale_temps_are_removed_and_nothing_else() {
        let dir = tempfile::tempdir().unwrap();
        for n in [
            ".trials.csv.tmp-4242",
            ".report.md.tmp-4242-7",
            "trials.csv",
            ".hidden",
            "notes.tmp-1",
        ] {
            fs::write(dir.path().join(n), "x").unwrap();
        }
        fs::create_dir(dir.path().join(".cell.tmp-1")).unwrap();
        let removed = remove_stale_temps(dir.path()).unwrap();
        assert_eq!(removed.len(), 2);
        assert_eq!(
            names(dir.path()),
            [".cell.tmp-1", ".hidden", "notes.tmp-1", "trials.csv"]
        );
        assert!(
            remove_stale_temps(&dir.path().join("none"))
                .unwrap()
                .is_empty()
        );
    }

    #[cfg(unix)]
    mod unix {
        use super::*;
        use std::os::unix::fs::{FileTypeExt, symlink};
        use std::time::Duration;

        #[test]
        fn a_symlink_is_followed_and_stays_a_symlink() {
            let dir = tempfile::tempdir().unwrap();
            let real_dir = dir.path().join("real");
            fs::create_dir(&real_dir).unwrap();
            let real = real_dir.join("data.json");
            fs::write(&real, "old").unwrap();
            let link = dir.path().join("out.json");
            symlink("real/data.json", &link).unwrap();
            // A link to the link: both stay.
            let link2 = dir.path().join("out2.json");
            symlink(&link, &link2).unwrap();
            write_atomic(&link2, b"new").unwrap();
            for l in [&link, &link2] {
                assert!(fs::symlink_metadata(l).unwrap().file_type().is_symlink());
            }
            assert_eq!(fs::read_to_string(&real).unwrap(), "new");
            assert_eq!(names(&real_dir), ["data.json"]);
            assert_eq!(names(dir.path()), ["out.json", "out2.json", "real"]);
        }

        #[test]
        fn a_dangling_symlink_creates_its_target() {
            let dir = tempfile::tempdir().unwrap();
            let link = dir.path().join("out.svg");
            symlink("made/by/usar.svg", &link).unwrap();
            write_atomic(&link, b"<svg/>").unwrap();
            assert!(
                fs::symlink_metadata(&link)
                    .unwrap()
                    .file_type()
                    .is_symlink()
            );
            assert_eq!(
                fs::read_to_string(dir.path().join("made/by/usar.svg")).unwrap(),
                "<svg/>"
            );
            let looped = dir.path().join("loop");
            symlink("loop", &looped).unwrap();
            assert!(write_atomic(&looped, b"x").is_err());
        }

        #[test]
        fn a_replaced_file_keeps_its_permissions() {
            use std::os::unix::fs::PermissionsExt;
            let dir = tempfile::tempdir().unwrap();
            let p = dir.path().join("t.csv");
            fs::write(&p, "a").unwrap();
            fs::set_permissions(&p, fs::Permissions::from_mode(0o640)).unwrap();
            write_atomic(&p, b"b").unwrap();
            assert_eq!(
                fs::metadata(&p).unwrap().permissions().mode() & 0o777,
                0o640
            );
        }

        #[test]
        fn dev_null_through_a_link_is_written_not_replaced() {
            // Through a link, so that a regression replaces the link, never /dev/null itself.
            let dir = tempfile::tempdir().unwrap();
            let link = dir.path().join("null.json");
            symlink("/dev/null", &link).unwrap();
            write_atomic(&link, b"{}").unwrap();
            assert!(
                fs::symlink_metadata(&link)
                    .unwrap()
                    .file_type()
                    .is_symlink()
            );
            assert!(
                fs::metadata("/dev/null")
                    .unwrap()
                    .file_type()
                    .is_char_device()
            );
            assert_eq!(names(dir.path()), ["null.json"]);
        }

        #[test]
        fn a_fifo_is_written_to_its_reader_not_replaced() {
            let dir = tempfile::tempdir().unwrap();
            let fifo = dir.path().join("pipe.svg");
            let made = std::process::Command::new("mkfifo").arg(&fifo).status();
            if !made.is_ok_and(|s| s.success()) {
                eprintln!("no mkfifo here: skipped");
                return;
            }
            let (tx, rx) = std::sync::mpsc::channel();
            let reader_path = fifo.clone();
            std::thread::spawn(move || {
                let _ = tx.send(fs::read(reader_path));
            });
            write_atomic(&fifo, b"through the pipe").unwrap();
            let got = rx
                .recv_timeout(Duration::from_secs(20))
                .expect("the reader got nothing: the FIFO was not written")
                .unwrap();
            assert_eq!(got, b"through the pipe");
            assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
            assert_eq!(names(dir.path()), ["pipe.svg"]);
        }
    }
}
