//! Why a sweep journal ([`crate::journal`]) cannot be read, continued or written.

use crate::atomic::FileError;
use crate::checked_log::LogError;
use crate::settings::Setting;

/// The end of every message about a journal that cannot be used (a merge names the shard's
/// own command instead: `crate::shard::merge`): `start the sweep afresh with --overwrite (in
/// place of --resume), or move the journal away`, its settings in the front end's words.
pub(crate) const START_AFRESH: StartAfresh = StartAfresh;

/// The type of [`START_AFRESH`].
#[derive(Debug, Clone, Copy)]
pub(crate) struct StartAfresh;

impl std::fmt::Display for StartAfresh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "start the sweep afresh with {} (in place of {}), or move the journal away",
            Setting::Overwrite,
            Setting::Resume
        )
    }
}

/// Why a journal cannot be used: one line naming its path (and, for a line, its 1-based
/// number as `path:line:`). Every variant about a journal that cannot be trusted ends with how
/// to start afresh.
#[derive(Debug, thiserror::Error)]
pub enum JournalError {
    /// A record line that is not JSON of a record's shape (or not UTF-8).
    #[error(
        "{path}:{line}: not a valid journal line; the journal is damaged: delete that line (a \
         trial it held runs again), or {START_AFRESH}"
    )]
    DamagedLine {
        /// The journal's path, as shown.
        path: String,
        /// The line's number, from 1.
        line: usize,
    },
    /// The first line is not a journal header.
    #[error("{path}:1: not a journal header; {START_AFRESH}")]
    NotAHeader {
        /// The journal's path, as shown.
        path: String,
    },
    /// The header line has no newline: a kill cut it short.
    #[error("{path}:1: the header line is cut short; {START_AFRESH}")]
    HeaderCut {
        /// The journal's path, as shown.
        path: String,
    },
    /// The header's checksum is missing or wrong.
    #[error(
        "{path}:1: the header does not verify (edited?), so no record of the journal can be \
         trusted; {START_AFRESH}"
    )]
    HeaderUnverified {
        /// The journal's path, as shown.
        path: String,
    },
    /// The file is empty.
    #[error("{path}: empty journal (no header line)")]
    Empty {
        /// The journal's path, as shown.
        path: String,
    },
    /// The header names another journal format than
    /// [`JOURNAL_FORMAT`](crate::journal::JOURNAL_FORMAT).
    #[error(
        "{path}: journal format {found}, but this usar reads format {expected}; {START_AFRESH}"
    )]
    Format {
        /// The journal's path, as shown.
        path: String,
        /// The format its header gives.
        found: u64,
        /// The format this build reads.
        expected: u32,
    },
    /// The path is a folder (or a link to one): no `--overwrite` removes it, so the message
    /// says what works instead.
    #[error(
        "{path}: is a folder, not a journal; move it away or remove it yourself (usar removes \
         no folder in a journal's place, even with {}), then run again",
        Setting::Overwrite
    )]
    Folder {
        /// The journal's path, as shown.
        path: String,
    },
    /// The path is a FIFO or a device.
    #[error("{path}: not a regular file (a FIFO or device); {START_AFRESH}")]
    NotAFile {
        /// The journal's path, as shown.
        path: String,
    },
    /// The path is a symbolic link to a missing file.
    #[error("{path}: a symbolic link to a missing file; {START_AFRESH}")]
    DanglingLink {
        /// The journal's path, as shown.
        path: String,
    },
    /// Resuming a journal whose header is another sweep's.
    #[error(
        "{}: {path} was written by a sweep with other parameters ({diff}); run with \
         another {}, or with {} (in place of {}) to start afresh",
        Setting::Resume,
        Setting::Out,
        Setting::Overwrite,
        Setting::Resume
    )]
    OtherParameters {
        /// The journal's path, as shown.
        path: String,
        /// The differences ([`header_diff`](crate::journal::header_diff)).
        diff: String,
    },
    /// An I/O error reading the journal, naming the path.
    #[error(transparent)]
    File(#[from] FileError),
    /// The journal could not be created or appended to.
    #[error(transparent)]
    Log(#[from] LogError),
}

impl JournalError {
    /// Whether the message ends with how to start afresh (`--overwrite`): the journal
    /// cannot be trusted or read as one (a merge then names the shard's own command instead).
    pub fn says_start_afresh(&self) -> bool {
        self.to_string().contains(&START_AFRESH.to_string())
    }
}
