//! Who owns an output folder: the kind of run whose files it holds, written in a small
//! manifest, [`OWNER_FILE`], before anything else of the run, and checked by every run and
//! merge before it writes or removes anything there.
//!
//! ```text
//! DIR/usar-owner.json   {"tool":"usar","kind":"sharded sweep","format":1}
//! ```
//!
//! Five kinds ([`RunKind`]): a sweep, a grid (a sweep with `--vary`), a sharded sweep (its
//! shards' folders `shards/<I>-of-<N>/` and the merge's files at the top; a sharded grid is
//! one too), a calibration and a multiverse (sharded or not). A run claims its folder with
//! [`claim`]: a folder owned by another kind is refused, with or without `--overwrite`, in a
//! one-line error naming both kinds and the file that shows the owner; `--overwrite` then only
//! ever removes what its own kind writes. A sweep and a grid are the one exception
//! ([`RunKind::may_use`]): `usar sweep` writes both under one journal, which refuses the other
//! and whose `--overwrite` removes exactly what it names; the run then records its kind
//! ([`record_kind`]). A shard's folder is claimed by the shard and checked by the merge
//! ([`check_owner`]).
//!
//! Folders written before the manifest existed are recognised by their files
//! ([`recognise`]): `journal.jsonl` (a sweep, or a grid when its header varies fields; in a
//! shard's folder, or under `shards/`, a sharded sweep, as is a shard's `plan.json`),
//! `trace.jsonl` (a calibration) and `multiverse.json` at the top or in a shard's folder (a
//! multiverse). A folder holding none of them belongs to no run yet: any kind may claim it
//! when it is new or empty, or holds only what usar itself leaves there before a run claims
//! it and hidden entries ([`before_claim`]), or is a folder a run made inside its own folder
//! for a run of its own ([`sub_runs`]). A folder of the user's own files is refused
//! ([`OwnerError::NotARunFolder`]): a run's files (`report.md`, `trials.csv`, ...) would
//! overwrite theirs.

use std::fmt;
use std::fs;
use std::io::ErrorKind;
use std::path::{Component, Path, PathBuf};

use serde::{Deserialize, Serialize};
use usar_sim::scenario::path_text;

use crate::atomic::FileError;
use crate::data::shard_folders::{SHARDS_DIR, shard_folders};
use crate::data::shard_split::Shard;
use crate::data::sweep_plan::PLAN_FILE as SHARD_PLAN_FILE;
use crate::journal::{JOURNAL_FILE, read_header_unverified};
use crate::lock::LOCK_FILE;

/// The manifest's name in an output folder.
pub const OWNER_FILE: &str = "usar-owner.json";

/// The manifest's format; a manifest of a later format is refused (written by a newer build).
const FORMAT: u32 = 1;

/// The files of the higher layers that show an owner in a folder without a manifest (see the
/// module docs): `calibrate::trace::TRACE_FILE` and `multiverse::plan::PLAN_FILE` are defined
/// as these. A sweep's journal and a shard's plan are [`JOURNAL_FILE`] and
/// [`crate::data::sweep_plan::PLAN_FILE`].
pub mod evidence {
    /// A calibration's trace.
    pub const TRACE: &str = "trace.jsonl";
    /// A multiverse's plan.
    pub const MULTIVERSE_PLAN: &str = "multiverse.json";
}

/// What a folder owned by no run may hold and still be claimed ([`claim`]): besides these,
/// the manifest ([`OWNER_FILE`], written by a run claiming the folder at the same moment), a
/// sweep's lock file ([`LOCK_FILE`]), hidden entries (`.DS_Store`, `.git`; the only hidden
/// files a run writes are its temporary files, the manifest's and those of
/// [`crate::atomic::write_atomic`]), and anything at the name of a run's record ([`JOURNAL_FILE`],
/// [`evidence`]'s files, [`SHARDS_DIR`]) that [`recognise`] did not take for one (a FIFO, a
/// dangling link, a folder): the run's own checks name what is wrong with it.
pub mod before_claim {
    /// `usar slurm`'s scripts (`crate::slurm::SLURM_DIR` is defined as this), written into
    /// the sweep's output folder before its shards run. Taken when it holds one of
    /// `usar slurm`'s scripts (the submit script, [`SLURM_SUBMIT`], or a job script,
    /// [`SLURM_JOB_EXT`]), whatever else the user added (edits, backups, other logs), or
    /// nothing but the logs' folder ([`SLURM_LOGS`]) and hidden entries; a `slurm/` of other
    /// files is the user's. No run writes into it but `usar slurm`.
    pub const SLURM_SCRIPTS: &str = "slurm";
    /// The script that submits the jobs, in [`SLURM_SCRIPTS`].
    pub const SLURM_SUBMIT: &str = "submit.sh";
    /// The jobs' logs' folder, in [`SLURM_SCRIPTS`].
    pub const SLURM_LOGS: &str = "logs";
    /// The extension of a job script in [`SLURM_SCRIPTS`] (`sweep.sbatch`, `merge.sbatch`).
    pub const SLURM_JOB_EXT: &str = "sbatch";
    /// The extension of a job's log in [`SLURM_LOGS`] (`sweep-1234_5.out`, `merge-1236.out`).
    pub const SLURM_LOG_EXT: &str = "out";
}

/// The folders a run makes inside its own folder for runs of its own, by their names below
/// it ([`claim`] takes one whatever it holds, as its run's `--overwrite` clears it): a
/// multiverse's universes, `universes/<id>/calibration/` and `universes/<id>/comparison/` in
/// its top folder (`usar_study`'s `UNIVERSES_DIR`, `CALIBRATION_DIR` and `COMPARISON_DIR` are defined as
/// these), and a sharded run's shards, `shards/<I>-of-<N>/` ([`SHARDS_DIR`]).
pub mod sub_runs {
    /// The folder of a multiverse's universes, in its output folder.
    pub const UNIVERSES: &str = "universes";
    /// A universe's calibration, in the universe's folder.
    pub const CALIBRATION: &str = "calibration";
    /// A universe's comparison, in the universe's folder.
    pub const COMPARISON: &str = "comparison";
}

/// The kind of run an output folder belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RunKind {
    /// `usar sweep` without `--vary` or `--shard` (also a multiverse universe's comparison).
    #[serde(rename = "sweep")]
    Sweep,
    /// `usar sweep --vary` without `--shard`.
    #[serde(rename = "grid")]
    Grid,
    /// `usar sweep --shard I/N` (with or without `--vary`), `usar slurm`, `usar merge`.
    #[serde(rename = "sharded sweep")]
    ShardedSweep,
    /// `usar calibrate` (also a multiverse universe's calibration).
    #[serde(rename = "calibration")]
    Calibration,
    /// `usar multiverse`, with or without `--shard`.
    #[serde(rename = "multiverse")]
    Multiverse,
}

impl RunKind {
    /// The kind's name as the manifest and messages write it (`sharded sweep`).
    pub fn name(self) -> &'static str {
        match self {
            RunKind::Sweep => "sweep",
            RunKind::Grid => "grid",
            RunKind::ShardedSweep => "sharded sweep",
            RunKind::Calibration => "calibration",
            RunKind::Multiverse => "multiverse",
        }
    }
}

impl RunKind {
    /// Whether a run of this kind may use a folder owned by `owner`: the same kind, or a
    /// sweep and a grid, which `usar sweep` writes alike under one journal (whose header tells
    /// them apart: a run of the other is refused there, and its `--overwrite` removes exactly
    /// the files the journal names, [`crate::stale_outputs`]).
    pub fn may_use(self, owner: RunKind) -> bool {
        self == owner
            || matches!(
                (self, owner),
                (Self::Sweep, Self::Grid) | (Self::Grid, Self::Sweep)
            )
    }
}

impl fmt::Display for RunKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// The manifest's content.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
struct Manifest {
    /// Always `usar`.
    tool: String,
    /// The owner.
    kind: RunKind,
    /// [`FORMAT`].
    format: u32,
}

/// Why a folder cannot be used as a run's output folder: one line, naming the folder.
#[derive(Debug, thiserror::Error)]
pub enum OwnerError {
    /// The path is empty.
    #[error("the output folder is an empty path; name a folder (\".\" is the working folder)")]
    EmptyPath,
    /// Something other than a folder is at the path.
    #[error("{path}: is a {what}, not a folder; choose another output folder")]
    NotAFolder {
        /// The path, as given.
        path: String,
        /// `file`, `FIFO`, `device`, ...
        what: &'static str,
    },
    /// The folder belongs to another kind of run.
    #[error(
        "{dir} holds a {found} ({evidence}); a {wanted} never writes into another kind of \
         run's folder, even to overwrite it: choose another output folder"
    )]
    OtherKind {
        /// The folder.
        dir: String,
        /// Its owner.
        found: RunKind,
        /// The run that was refused.
        wanted: RunKind,
        /// The file that shows the owner.
        evidence: String,
    },
    /// The folder belongs to no run and holds something no usar run wrote there: a run's
    /// files would overwrite the user's own (with or without `--overwrite`).
    #[error(
        "{dir} holds {entry}, which no usar run wrote; a {wanted} writes only into a new or \
         empty folder or one of its own runs, so that it never overwrites your files: choose \
         another output folder"
    )]
    NotARunFolder {
        /// The folder.
        dir: String,
        /// The first foreign entry, by name (a folder's name ends in `/`).
        entry: String,
        /// The run that was refused.
        wanted: RunKind,
    },
    /// The manifest cannot be read or is not one this build writes.
    #[error(
        "{path}: {why}; it names the kind of run that owns the folder: remove it only if the \
         folder holds none of usar's results, or choose another output folder"
    )]
    BadManifest {
        /// The manifest's path.
        path: String,
        /// What is wrong.
        why: String,
    },
    /// The manifest names a kind of run that the folder's own files contradict: edited (or
    /// copied from another folder). Nothing is written or removed, with or without
    /// `--overwrite`.
    #[error(
        "{manifest} says the folder holds a {said}, but {evidence} shows a {found}: the \
         manifest was edited or copied, so nothing was changed; remove the manifest (usar then \
         knows the folder by its files), or choose another output folder"
    )]
    Contradicted {
        /// The manifest's path.
        manifest: String,
        /// The kind the manifest names.
        said: RunKind,
        /// The file that contradicts it.
        evidence: String,
        /// The kind that file shows.
        found: RunKind,
    },
    /// An I/O error.
    #[error("{what} {path}: {error}")]
    Io {
        /// What was being done (`creating folder`, `writing`).
        what: &'static str,
        /// The path.
        path: String,
        /// The error (part of the one-line message, not also a `source()`, so a
        /// chain-printing caller such as `rne_core::error_line` does not repeat it).
        error: std::io::Error,
    },
    /// The shard folders could not be listed, or one is misnamed
    /// ([`crate::data::shard_folders::shard_folders`]).
    #[error(transparent)]
    File(#[from] FileError),
}

fn io(what: &'static str, path: &Path) -> impl FnOnce(std::io::Error) -> OwnerError {
    let path = path_text(path);
    move |error| OwnerError::Io { what, path, error }
}

/// Checks that `dir` can be an output folder: not empty, and nothing but a folder (or a link
/// to one) at that path if something is.
///
/// # Errors
/// [`OwnerError::EmptyPath`], [`OwnerError::NotAFolder`] (a file, a FIFO, a device, a socket,
/// a dangling link).
pub fn check_out_dir(dir: &Path) -> Result<(), OwnerError> {
    if dir.as_os_str().is_empty() {
        return Err(OwnerError::EmptyPath);
    }
    let what = match fs::metadata(dir) {
        Ok(m) if m.is_dir() => return Ok(()),
        Ok(m) => file_type_name(&m),
        Err(e) if e.kind() == ErrorKind::NotFound => {
            if fs::symlink_metadata(dir).is_ok() {
                "link to nothing"
            } else {
                return Ok(());
            }
        }
        Err(e) => return Err(io("reading", dir)(e)),
    };
    Err(OwnerError::NotAFolder {
        path: path_text(dir),
        what,
    })
}

#[cfg(unix)]
fn file_type_name(m: &fs::Metadata) -> &'static str {
    use std::os::unix::fs::FileTypeExt;
    let t = m.file_type();
    if t.is_file() {
        "file"
    } else if t.is_fifo() {
        "FIFO"
    } else if t.is_char_device() || t.is_block_device() {
        "device"
    } else if t.is_socket() {
        "socket"
    } else {
        "special file"
    }
}

#[cfg(not(unix))]
fn file_type_name(m: &fs::Metadata) -> &'static str {
    if m.is_file() { "file" } else { "special file" }
}

/// Claims `dir` for a run of `kind`: checks the path ([`check_out_dir`]), creates the folder,
/// refuses it when it belongs to another kind (its manifest, or for a folder without one, its
/// files: [`recognise`]) or to no run but holds the user's own files (anything but what
/// [`before_claim`] lists), and writes the manifest if there is none yet. A manifest is
/// created only if absent (never replaced), so two runs claiming one folder at the same time
/// cannot both win. Call it before anything else of the run touches `dir`.
///
/// # Errors
/// See [`check_out_dir`]; [`OwnerError::OtherKind`]; [`OwnerError::NotARunFolder`];
/// [`OwnerError::BadManifest`]; an I/O error creating or listing the folder or writing the
/// manifest.
pub fn claim(dir: &Path, kind: RunKind) -> Result<(), OwnerError> {
    check_out_dir(dir)?;
    fs::create_dir_all(dir).map_err(io("creating folder", dir))?;
    refuse_unusable(dir, kind)?;
    match write_new_manifest(dir, kind) {
        Ok(()) => Ok(()),
        // Another run wrote one since: its kind decides.
        Err(OwnerError::Io { error, .. }) if error.kind() == ErrorKind::AlreadyExists => {
            match owner(dir)? {
                Some(found) => refuse_other(dir, kind, found),
                None => Ok(()),
            }
        }
        Err(e) => Err(e),
    }
}

/// Checks, without writing anything, that a run of `kind` could claim `dir` ([`claim`]): a
/// path that is no folder yet, or a folder of that kind or of none that holds none of the
/// user's files. What `usar slurm` asks before it writes the scripts whose shards will claim
/// the folder on the cluster.
///
/// # Errors
/// As [`claim`], but for creating the folder and writing the manifest.
pub fn check_claimable(dir: &Path, kind: RunKind) -> Result<(), OwnerError> {
    check_out_dir(dir)?;
    if !dir.exists() {
        return Ok(());
    }
    refuse_unusable(dir, kind)
}

/// Refuses the existing folder `dir` for a run of `kind` when it belongs to another kind (its
/// manifest, or for a folder without one, its files: [`recognise`]) or to no run but holds
/// the user's own files ([`foreign_entry`]). A folder a run made for a run of its own
/// ([`sub_run_folder`]) is that run's to clear, so what it holds is not refused.
fn refuse_unusable(dir: &Path, kind: RunKind) -> Result<(), OwnerError> {
    if let Some(found) = checked_manifest(dir)? {
        return refuse_other(dir, kind, Owner::of_manifest(dir, found));
    }
    if let Some(found) = recognise(dir)? {
        return refuse_other(dir, kind, found);
    }
    let Some(entry) = foreign_entry(dir)? else {
        return Ok(());
    };
    // A run of this folder that claimed it since this one looked (its manifest comes first,
    // then its files) decides, as in `claim`'s race.
    if let Some(found) = checked_manifest(dir)? {
        return refuse_other(dir, kind, Owner::of_manifest(dir, found));
    }
    if sub_run_folder(dir) {
        return Ok(());
    }
    Err(OwnerError::NotARunFolder {
        dir: path_text(dir),
        entry,
        wanted: kind,
    })
}

/// Whether `dir` is a folder a run made inside its own folder for a run of its own
/// ([`sub_runs`]): `universes/<id>/calibration` or `universes/<id>/comparison` three folders
/// below a manifest ([`OWNER_FILE`]; a multiverse's folder), or
/// `shards/<I>-of-<N>` two below one (a sharded run's folder). Any other folder inside a run's
/// folder (`results/paper/mine`) is the user's, as is one named so outside a run.
fn sub_run_folder(dir: &Path) -> bool {
    let names: Vec<Option<&str>> = dir
        .components()
        .rev()
        .take(3)
        .map(|c| match c {
            Component::Normal(name) => name.to_str(),
            _ => None,
        })
        .collect();
    let manifest_up = |levels: usize| {
        dir.ancestors()
            .nth(levels)
            .is_some_and(|a| fs::symlink_metadata(a.join(OWNER_FILE)).is_ok_and(|m| m.is_file()))
    };
    match names.as_slice() {
        [Some(run), Some(_), Some(sub_runs::UNIVERSES)]
            if [sub_runs::CALIBRATION, sub_runs::COMPARISON].contains(run) =>
        {
            manifest_up(3)
        }
        [Some(shard), Some(parent), ..]
            if *parent == SHARDS_DIR && Shard::from_dir_name(shard).is_some() =>
        {
            manifest_up(2)
        }
        _ => false,
    }
}

/// Records that `dir`, claimed by a run of `kind` ([`claim`]), now holds that kind's files:
/// rewrites the manifest when it names another kind (a grid's folder that a sweep overwrote).
/// Call it once the run has taken the folder over (its journal opened).
///
/// # Errors
/// [`OwnerError::BadManifest`], or an I/O error writing the manifest.
pub fn record_kind(dir: &Path, kind: RunKind) -> Result<(), OwnerError> {
    if read_manifest(dir)? == Some(kind) {
        return Ok(());
    }
    let path = dir.join(OWNER_FILE);
    let tmp = dir.join(format!(".{OWNER_FILE}.tmp-{}-owner", std::process::id()));
    fs::write(&tmp, manifest_text(kind)).map_err(io("writing", &tmp))?;
    fs::rename(&tmp, &path).map_err(io("writing", &path))
}

/// Checks that `dir` (which must exist) belongs to a run of `kind`, or to none yet, without
/// writing anything: what a merge asks of each shard's folder.
///
/// # Errors
/// [`OwnerError::OtherKind`], [`OwnerError::BadManifest`], or an I/O error reading the folder.
pub fn check_owner(dir: &Path, kind: RunKind) -> Result<(), OwnerError> {
    match owner(dir)? {
        Some(found) => refuse_other(dir, kind, found),
        None => Ok(()),
    }
}

/// The owner of `dir`: from its manifest, or recognised by its files; `None` when neither
/// names one.
///
/// # Errors
/// [`OwnerError::BadManifest`], or an I/O error listing the folder.
pub fn owner(dir: &Path) -> Result<Option<Owner>, OwnerError> {
    if let Some(kind) = checked_manifest(dir)? {
        return Ok(Some(Owner::of_manifest(dir, kind)));
    }
    recognise(dir)
}

/// A folder's owner as found: the kinds it may be (one, from a manifest; from files, a journal
/// whose header cannot be read may be a sweep's or a grid's) and the file that shows it.
#[derive(Debug, Clone, PartialEq)]
pub struct Owner {
    /// The kinds the folder may belong to; never empty.
    pub kinds: Vec<RunKind>,
    /// The file that shows it.
    pub evidence: PathBuf,
}

impl Owner {
    /// The owner the manifest in `dir` names.
    fn of_manifest(dir: &Path, kind: RunKind) -> Self {
        Self {
            kinds: vec![kind],
            evidence: dir.join(OWNER_FILE),
        }
    }
}

fn refuse_other(dir: &Path, wanted: RunKind, found: Owner) -> Result<(), OwnerError> {
    if found.kinds.iter().any(|k| wanted.may_use(*k)) {
        return Ok(());
    }
    Err(OwnerError::OtherKind {
        dir: path_text(dir),
        found: found.kinds[0],
        wanted,
        evidence: path_text(&found.evidence),
    })
}

/// The manifest's kind; `None` without one.
fn read_manifest(dir: &Path) -> Result<Option<RunKind>, OwnerError> {
    let path = dir.join(OWNER_FILE);
    let bad = |why: String| OwnerError::BadManifest {
        path: path_text(&path),
        why,
    };
    match fs::symlink_metadata(&path) {
        Err(e) if e.kind() == ErrorKind::NotFound => return Ok(None),
        Err(e) => return Err(io("reading", &path)(e)),
        Ok(m) if !m.is_file() => return Err(bad("not a regular file".into())),
        Ok(m) if m.len() > 4096 => return Err(bad("longer than a manifest".into())),
        Ok(_) => {}
    }
    let text = fs::read_to_string(&path).map_err(io("reading", &path))?;
    let m: Manifest = serde_json::from_str(text.trim_end())
        .map_err(|e| bad(format!("not a usar manifest ({e})")))?;
    if m.tool != "usar" {
        return Err(bad(format!("written by {:?}, not usar", m.tool)));
    }
    if m.format != FORMAT {
        return Err(bad(format!(
            "format {} (this build reads format {FORMAT})",
            m.format
        )));
    }
    Ok(Some(m.kind))
}

/// Writes the manifest of `kind` into `dir` unless one is there: the bytes go to a temporary
/// file, which is then hard-linked to the final name (refused if the name exists) and removed.
fn write_new_manifest(dir: &Path, kind: RunKind) -> Result<(), OwnerError> {
    let path = dir.join(OWNER_FILE);
    let tmp = dir.join(format!(".{OWNER_FILE}.tmp-{}-owner", std::process::id()));
    fs::write(&tmp, manifest_text(kind)).map_err(io("writing", &tmp))?;
    let linked = fs::hard_link(&tmp, &path).map_err(io("writing", &path));
    let removed = fs::remove_file(&tmp).map_err(io("removing", &tmp));
    linked.and(removed)
}

/// The first entry of `dir` (by name) that no usar run leaves in a folder before claiming it
/// ([`before_claim`]), as `name` or, for a folder, `name/`; `None` when there is none.
///
/// # Errors
/// An I/O error listing the folder.
fn foreign_entry(dir: &Path) -> Result<Option<String>, OwnerError> {
    let listing = fs::read_dir(dir).map_err(io("listing", dir))?;
    let mut foreign: Option<(String, bool)> = None;
    for entry in listing {
        let entry = entry.map_err(io("listing", dir))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
        let usar = match name.as_str() {
            // A hidden entry (`.DS_Store`, `.git`): no run writes one but its temporary files.
            hidden if hidden.starts_with('.') => true,
            OWNER_FILE | LOCK_FILE => !is_dir,
            before_claim::SLURM_SCRIPTS => is_dir && holds_slurm_scripts(&dir.join(&name)),
            JOURNAL_FILE | evidence::TRACE | evidence::MULTIVERSE_PLAN | SHARDS_DIR => true,
            _ => false,
        };
        if !usar && foreign.as_ref().is_none_or(|(first, _)| name < *first) {
            foreign = Some((name, is_dir));
        }
    }
    let shown = |name: String| path_text(Path::new(&name));
    Ok(foreign.map(|(name, is_dir)| {
        if is_dir {
            format!("{}/", shown(name))
        } else {
            shown(name)
        }
    }))
}

/// Whether the folder `slurm` is `usar slurm`'s ([`before_claim::SLURM_SCRIPTS`]): it holds
/// one of its scripts (a file or a link to one), or nothing but the logs' folder and hidden
/// entries; a folder that cannot be listed is not.
fn holds_slurm_scripts(slurm: &Path) -> bool {
    use before_claim::{SLURM_JOB_EXT, SLURM_LOGS, SLURM_SUBMIT};
    let Ok(listing) = fs::read_dir(slurm) else {
        return false;
    };
    let (mut script, mut other) = (false, false);
    for entry in listing {
        let Ok(entry) = entry else {
            return false;
        };
        let name = entry.file_name();
        let name = name.to_string_lossy();
        if name.starts_with('.') || name == SLURM_LOGS {
            continue;
        }
        let is_file = fs::metadata(entry.path()).is_ok_and(|m| m.is_file());
        let named = name == SLURM_SUBMIT
            || Path::new(&*name)
                .extension()
                .is_some_and(|e| e == SLURM_JOB_EXT);
        script |= is_file && named;
        other = true;
    }
    script || !other
}

/// The manifest of `kind`, one JSON line.
fn manifest_text(kind: RunKind) -> String {
    let m = Manifest {
        tool: "usar".into(),
        kind,
        format: FORMAT,
    };
    let mut text = serde_json::to_string(&m).expect("a manifest serialises");
    text.push('\n');
    text
}

/// The owner of a folder without a manifest, recognised by its files (see the module docs);
/// `None` when none of them is there.
///
/// # Errors
/// An I/O error listing the folder's shard folders, a misnamed one, or a shard's manifest
/// that cannot be read.
pub fn recognise(dir: &Path) -> Result<Option<Owner>, OwnerError> {
    if let Some(found) = own_files(dir) {
        return Ok(Some(found));
    }
    for (_, shard) in shard_folders(dir)? {
        if let Some(kind) = read_manifest(&shard)? {
            return Ok(Some(Owner::of_manifest(&shard, kind)));
        }
        if let Some(found) = own_files(&shard) {
            return Ok(Some(found));
        }
    }
    Ok(None)
}

/// The owner the files at the top of `dir` show (not its shards' nor its manifest), the
/// first of: a journal, a shard's plan (in a shard's folder), a trace, a multiverse plan.
fn own_files(dir: &Path) -> Option<Owner> {
    let found = |kinds: Vec<RunKind>, evidence: PathBuf| Some(Owner { kinds, evidence });
    let is_file = |p: &Path| fs::symlink_metadata(p).is_ok_and(|m| m.is_file());
    let in_shard = is_shard_folder(dir);
    let journal = dir.join(JOURNAL_FILE);
    if is_file(&journal) {
        if in_shard {
            return found(vec![RunKind::ShardedSweep], journal);
        }
        let kinds = match read_header_unverified(&journal) {
            Some(h) if h.grid.fields.is_empty() => vec![RunKind::Sweep],
            Some(_) => vec![RunKind::Grid],
            None => vec![RunKind::Sweep, RunKind::Grid],
        };
        return found(kinds, journal);
    }
    let shard_plan = dir.join(SHARD_PLAN_FILE);
    if in_shard && is_file(&shard_plan) {
        return found(vec![RunKind::ShardedSweep], shard_plan);
    }
    let trace = dir.join(evidence::TRACE);
    if is_file(&trace) {
        return found(vec![RunKind::Calibration], trace);
    }
    let plan = dir.join(evidence::MULTIVERSE_PLAN);
    if is_file(&plan) {
        return found(vec![RunKind::Multiverse], plan);
    }
    None
}

/// The kind the manifest of `dir` names, cross-checked with what the folder holds: its own
/// files ([`own_files`]), and the manifest and files of its first shard folder that holds
/// any (all shards of a run are of its kind; one is enough to catch an edited manifest
/// without reading every shard's on every claim). The manifest is refused when none of them
/// shows its kind and one shows another: a folder that also holds files of its kind is the
/// run's, and a file of another kind put into it is named by the run's own checks (a
/// merge's "the journal of another sweep"). `None` without a manifest.
///
/// # Errors
/// [`OwnerError::Contradicted`] naming the manifest and the first file that shows another
/// kind; the errors of reading the manifests or listing the shard folders.
fn checked_manifest(dir: &Path) -> Result<Option<RunKind>, OwnerError> {
    let Some(kind) = read_manifest(dir)? else {
        return Ok(None);
    };
    let mut shown = vec![own_files(dir)];
    for (_, shard) in shard_folders(dir)? {
        let manifest = read_manifest(&shard)?.map(|k| Owner::of_manifest(&shard, k));
        let files = own_files(&shard);
        if manifest.is_some() || files.is_some() {
            shown.extend([manifest, files]);
            break;
        }
    }
    let shown: Vec<Owner> = shown.into_iter().flatten().collect();
    if shown
        .iter()
        .any(|o| o.kinds.iter().any(|k| kind.may_use(*k)))
    {
        return Ok(Some(kind));
    }
    match shown.first() {
        Some(o) => Err(OwnerError::Contradicted {
            manifest: path_text(&dir.join(OWNER_FILE)),
            said: kind,
            evidence: path_text(&o.evidence),
            found: o.kinds[0],
        }),
        None => Ok(Some(kind)),
    }
}

/// Whether `dir` is a shard's folder: `<out>/shards/<I>-of-<N>`.
fn is_shard_folder(dir: &Path) -> bool {
    let name = dir.file_name().and_then(|n| n.to_str());
    let parent = dir.parent().and_then(Path::file_name);
    name.and_then(Shard::from_dir_name).is_some() && parent.is_some_and(|p| p == SHARDS_DIR)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(r: Result<(), OwnerError>) -> String {
        let e = r.unwrap_err().to_string();
        assert!(!e.contains('\n'), "{e}");
        e
    }

    #[test]
    fn a_claim_writes_the_manifest_once_and_refuses_other_kinds() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path().join("out");
        claim(&d, RunKind::Multiverse).unwrap();
        let text = fs::read_to_string(d.join(OWNER_FILE)).unwrap();
        assert_eq!(
            text,
            "{\"tool\":\"usar\",\"kind\":\"multiverse\",\"format\":1}\n"
        );
        claim(&d, RunKind::Multiverse).unwrap();
        assert_eq!(fs::read_dir(&d).unwrap().count(), 1, "no temporary file");
        for other in [RunKind::Sweep, RunKind::ShardedSweep, RunKind::Calibration] {
            let e = err(claim(&d, other));
            assert!(
                e.contains(&format!("holds a multiverse ({}", path_text(&d)))
                    && e.contains(&format!("a {other} never writes")),
                "{e}"
            );
        }
        assert_eq!(fs::read_to_string(d.join(OWNER_FILE)).unwrap(), text);
        check_owner(&d, RunKind::Multiverse).unwrap();
        assert!(check_owner(&d, RunKind::Grid).is_err());
    }

    /// A folder of the user's own files is refused by every kind, naming the first foreign
    /// entry, and nothing is written there; one holding only what usar leaves before a claim
    /// (`usar slurm`'s scripts, a lock, temporary files) is claimed.
    #[test]
    fn a_folder_of_the_users_files_is_refused_and_usars_own_leftovers_are_not() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path().join("mine");
        fs::create_dir_all(d.join("figures")).unwrap();
        fs::write(d.join("report.md"), "my notes").unwrap();
        for kind in [
            RunKind::Sweep,
            RunKind::Grid,
            RunKind::ShardedSweep,
            RunKind::Calibration,
            RunKind::Multiverse,
        ] {
            let e = err(claim(&d, kind));
            let want = format!(
                "{} holds figures/, which no usar run wrote; a {kind} writes only",
                path_text(&d)
            );
            assert!(e.starts_with(&want), "{e}");
        }
        fs::remove_dir(d.join("figures")).unwrap();
        assert!(err(claim(&d, RunKind::Sweep)).contains("holds report.md,"));
        assert!(check_claimable(&d, RunKind::ShardedSweep).is_err());
        assert!(!d.join(OWNER_FILE).exists());
        assert_eq!(fs::read_to_string(d.join("report.md")).unwrap(), "my notes");
        check_claimable(&tmp.path().join("new"), RunKind::ShardedSweep).unwrap();
        assert!(!tmp.path().join("new").exists());

        let ours = tmp.path().join("ours");
        fs::create_dir_all(ours.join(before_claim::SLURM_SCRIPTS)).unwrap();
        fs::write(ours.join(LOCK_FILE), "").unwrap();
        fs::write(ours.join(".trials.csv.tmp-12-a1B2"), "").unwrap();
        fs::write(ours.join(format!(".{OWNER_FILE}.tmp-7-owner")), "").unwrap();
        fs::write(ours.join(".DS_Store"), "").unwrap();
        check_claimable(&ours, RunKind::ShardedSweep).unwrap();
        assert!(!ours.join(OWNER_FILE).exists());
        claim(&ours, RunKind::ShardedSweep).unwrap();
        assert!(check_claimable(&ours, RunKind::Calibration).is_err());
        // A file named as usar's folder, and a folder named as its file, are the user's.
        for (name, folder) in [(before_claim::SLURM_SCRIPTS, false), (LOCK_FILE, true)] {
            let d = tmp.path().join(format!("odd-{name}"));
            fs::create_dir_all(&d).unwrap();
            if folder {
                fs::create_dir(d.join(name)).unwrap();
            } else {
                fs::write(d.join(name), "").unwrap();
            }
            assert!(err(claim(&d, RunKind::Sweep)).contains(&format!(" holds {name}")));
        }
        // A name with a line break is shown escaped: the error stays one line.
        let odd = tmp.path().join("odd-name");
        fs::create_dir_all(&odd).unwrap();
        fs::write(odd.join("a\nb"), "").unwrap();
        let e = err(claim(&odd, RunKind::Sweep));
        assert!(e.contains("holds a\\nb,"), "{e}");
    }

    #[test]
    fn a_runs_own_sub_run_folders_are_taken_and_other_folders_inside_it_are_not() {
        let tmp = tempfile::tempdir().unwrap();
        let with_notes = |d: &Path| {
            fs::create_dir_all(d).unwrap();
            fs::write(d.join("notes.txt"), "mine").unwrap();
        };
        // A universe's calibration and comparison after the multiverse's `--overwrite`, which
        // leaves what else they hold, and a shard's folder: their sub-runs claim them.
        let top = tmp.path().join("mv");
        claim(&top, RunKind::Multiverse).unwrap();
        for (sub, kind) in [
            ("universes/u000/comparison", RunKind::Sweep),
            ("universes/u000/calibration", RunKind::Calibration),
        ] {
            let sub = top.join(sub);
            with_notes(&sub);
            claim(&sub, kind).unwrap();
            assert_eq!(fs::read_to_string(sub.join("notes.txt")).unwrap(), "mine");
        }
        let sweep = tmp.path().join("sweep");
        claim(&sweep, RunKind::ShardedSweep).unwrap();
        with_notes(&sweep.join("shards/1-of-2"));
        claim(&sweep.join("shards/1-of-2"), RunKind::ShardedSweep).unwrap();
        // Any other folder inside a run's folder, and one named as a sub-run's outside a
        // run, holds the user's files.
        for d in [
            sweep.join("mine"),
            top.join("universes/u000/mine"),
            top.join("mine/u000/comparison"),
            sweep.join("shards/mine"),
            tmp.path().join("alone/universes/u000/comparison"),
            tmp.path().join("alone/shards/1-of-2"),
        ] {
            with_notes(&d);
            assert!(
                err(claim(&d, RunKind::Sweep)).contains(" holds notes.txt,"),
                "{d:?}"
            );
            assert!(!d.join(OWNER_FILE).exists());
        }
    }

    #[test]
    fn a_slurm_folder_is_usars_while_it_holds_usar_slurms_scripts() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path().join("out");
        let slurm = d.join(before_claim::SLURM_SCRIPTS);
        fs::create_dir_all(slurm.join("logs")).unwrap();
        fs::write(slurm.join("logs/sweep-1234_5.out"), "").unwrap();
        check_claimable(&d, RunKind::ShardedSweep).unwrap();
        fs::write(slurm.join("notes.txt"), "").unwrap();
        let e = err(check_claimable(&d, RunKind::ShardedSweep));
        assert!(e.contains(" holds slurm/,"), "{e}");
        // A folder named as a script is not one.
        fs::create_dir(slurm.join("sweep.sbatch")).unwrap();
        assert!(check_claimable(&d, RunKind::ShardedSweep).is_err());
        // One script, edited and backed up beside the user's files, makes it usar's.
        for script in ["submit.sh", "merge.sbatch"] {
            fs::write(slurm.join(script), "").unwrap();
            fs::write(slurm.join(format!("{script}~")), "").unwrap();
            check_claimable(&d, RunKind::ShardedSweep).unwrap();
            fs::remove_file(slurm.join(script)).unwrap();
        }
        assert!(check_claimable(&d, RunKind::ShardedSweep).is_err());
        fs::write(slurm.join("sweep.sbatch~"), "").unwrap();
        std::os::unix::fs::symlink("sweep.sbatch~", slurm.join("array.sbatch")).unwrap();
        claim(&d, RunKind::ShardedSweep).unwrap();
    }

    #[test]
    fn old_folders_are_recognised_by_their_files() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        let kinds = |dir: &Path| recognise(dir).unwrap().map(|o| o.kinds);
        assert_eq!(kinds(d), None);
        fs::write(d.join("notes.txt"), "mine").unwrap();
        assert_eq!(kinds(d), None);
        // A sharded sweep: a shard's plan, then its journal.
        let shard = d.join("shards/0-of-2");
        fs::create_dir_all(&shard).unwrap();
        fs::write(shard.join("plan.json"), "{}").unwrap();
        assert_eq!(kinds(d), Some(vec![RunKind::ShardedSweep]));
        assert_eq!(kinds(&shard), Some(vec![RunKind::ShardedSweep]));
        fs::write(shard.join("journal.jsonl"), "x").unwrap();
        assert_eq!(kinds(&shard), Some(vec![RunKind::ShardedSweep]));
        let e = err(claim(d, RunKind::Multiverse));
        assert!(
            e.contains("holds a sharded sweep") && e.contains("shards/0-of-2/journal.jsonl"),
            "{e}"
        );
        assert!(!d.join(OWNER_FILE).exists());
        claim(d, RunKind::ShardedSweep).unwrap();
        // A journal whose header cannot be read may be a sweep's or a grid's.
        let s = tmp.path().join("s");
        fs::create_dir(&s).unwrap();
        fs::write(s.join("journal.jsonl"), "garbage\n").unwrap();
        assert_eq!(kinds(&s), Some(vec![RunKind::Sweep, RunKind::Grid]));
        claim(&s, RunKind::Grid).unwrap();
        assert!(
            claim(&s, RunKind::ShardedSweep).is_err(),
            "the manifest decides now"
        );
        assert_eq!(read_manifest(&s).unwrap(), Some(RunKind::Grid));
        // A sweep may take a grid's folder over (its journal decides), and records itself.
        claim(&s, RunKind::Sweep).unwrap();
        record_kind(&s, RunKind::Sweep).unwrap();
        assert_eq!(read_manifest(&s).unwrap(), Some(RunKind::Sweep));
        // A calibration, and a multiverse's shard.
        let c = tmp.path().join("c");
        fs::create_dir(&c).unwrap();
        fs::write(c.join("trace.jsonl"), "x").unwrap();
        assert_eq!(kinds(&c), Some(vec![RunKind::Calibration]));
        let m = tmp.path().join("m/shards/1-of-4");
        fs::create_dir_all(&m).unwrap();
        fs::write(m.join("multiverse.json"), "x").unwrap();
        assert_eq!(
            kinds(&tmp.path().join("m")),
            Some(vec![RunKind::Multiverse])
        );
        assert_eq!(kinds(&m), Some(vec![RunKind::Multiverse]));
    }

    /// Regression (issue 70): a manifest edited to name another kind let that kind's
    /// `--overwrite` remove the folder's files. The folder's own files and its first shard's
    /// are checked against it; a sweep's and a grid's, which share a journal, stay one.
    #[test]
    fn a_manifest_that_the_folders_files_contradict_is_refused() {
        let tmp = tempfile::tempdir().unwrap();
        let manifest = |d: &Path, kind: &str| {
            let text = format!("{{\"tool\":\"usar\",\"kind\":\"{kind}\",\"format\":1}}\n");
            fs::write(d.join(OWNER_FILE), text).unwrap();
        };
        let s = tmp.path().join("s");
        fs::create_dir(&s).unwrap();
        fs::write(s.join("journal.jsonl"), "garbage\n").unwrap();
        manifest(&s, "sweep");
        claim(&s, RunKind::Grid).unwrap();
        manifest(&s, "calibration");
        let e = err(claim(&s, RunKind::Calibration));
        assert!(
            e.contains("usar-owner.json says the folder holds a calibration, but ")
                && e.contains("journal.jsonl shows a sweep"),
            "{e}"
        );
        assert!(check_owner(&s, RunKind::Calibration).is_err());
        let m = tmp.path().join("m");
        let shard = m.join("shards/1-of-2");
        fs::create_dir_all(&shard).unwrap();
        fs::write(shard.join("journal.jsonl"), "x").unwrap();
        manifest(&m, "multiverse");
        let e = err(claim(&m, RunKind::Multiverse));
        assert!(
            e.contains("shards/1-of-2/journal.jsonl shows a sharded sweep"),
            "{e}"
        );
        // A file of another kind beside files of the manifest's is not a contradiction (the
        // run's own checks name it).
        fs::write(m.join("trace.jsonl"), "x").unwrap();
        manifest(&m, "sharded sweep");
        claim(&m, RunKind::ShardedSweep).unwrap();
        fs::remove_file(shard.join("journal.jsonl")).unwrap();
        fs::remove_file(m.join("trace.jsonl")).unwrap();
        manifest(&shard, "multiverse");
        let e = err(claim(&m, RunKind::ShardedSweep));
        assert!(
            e.contains("shards/1-of-2/usar-owner.json shows a multiverse"),
            "{e}"
        );
    }

    #[test]
    fn paths_that_are_not_folders_are_refused() {
        let tmp = tempfile::tempdir().unwrap();
        assert_eq!(
            err(claim(Path::new(""), RunKind::Sweep)),
            "the output folder is an empty path; name a folder (\".\" is the working folder)"
        );
        let f = tmp.path().join("f");
        fs::write(&f, "x").unwrap();
        assert!(
            err(claim(&f, RunKind::Sweep))
                .ends_with("f: is a file, not a folder; choose another output folder")
        );
        #[cfg(unix)]
        {
            assert!(err(check_out_dir(Path::new("/dev/null"))).contains("is a device"));
            let link = tmp.path().join("dangling");
            std::os::unix::fs::symlink(tmp.path().join("nowhere"), &link).unwrap();
            assert!(err(check_out_dir(&link)).contains("is a link to nothing"));
        }
        check_out_dir(Path::new(".")).unwrap();
        check_out_dir(&tmp.path().join("new/folder")).unwrap();
    }

    #[test]
    fn a_bad_manifest_is_named() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        for (text, says) in [
            ("{}", "not a usar manifest"),
            (
                "{\"tool\":\"x\",\"kind\":\"sweep\",\"format\":1}",
                "written by \"x\"",
            ),
            (
                "{\"tool\":\"usar\",\"kind\":\"sweep\",\"format\":2}",
                "format 2",
            ),
            (
                "{\"tool\":\"usar\",\"kind\":\"walk\",\"format\":1}",
                "not a usar manifest",
            ),
        ] {
            fs::write(d.join(OWNER_FILE), text).unwrap();
            let e = err(claim(d, RunKind::Sweep));
            assert!(e.contains("usar-owner.json: ") && e.contains(says), "{e}");
        }
    }
}
