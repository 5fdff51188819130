//! Why a calibration's trace ([`crate::calibrate::trace`]) cannot be read or written:
//! [`TraceError`].

use usar_sweep::atomic::FileError;
use usar_sweep::checked_log::LogError;

/// What every message about a trace that cannot be used ends with.
pub(crate) const START_AFRESH: &str = "start afresh with --overwrite, or choose another --out";

/// Why a trace cannot be read (one line naming its path, and a line's 1-based number as
/// `path:line:`; each ends with how to start afresh) or written.
#[derive(Debug, thiserror::Error)]
pub enum TraceError {
    /// A line before the last that is not an evaluation (or not UTF-8).
    #[error(
        "{path}:{line}: not a valid trace line; delete that line (its point runs again), or \
         {START_AFRESH}"
    )]
    DamagedLine {
        /// The trace's path, as shown.
        path: String,
        /// The line's number, from 1.
        line: usize,
    },
    /// No complete first line.
    #[error("{path}: no complete header line; {START_AFRESH}")]
    NoHeader {
        /// The trace's path, as shown.
        path: String,
    },
    /// The first line is not a trace header.
    #[error("{path}:1: not a trace header; {START_AFRESH}")]
    NotAHeader {
        /// The trace's path, as shown.
        path: String,
    },
    /// The header's checksum is missing or wrong.
    #[error("{path}:1: the header does not verify (edited?); {START_AFRESH}")]
    HeaderUnverified {
        /// The trace's path, as shown.
        path: String,
    },
    /// A header of another trace format than
    /// [`TRACE_FORMAT`](crate::calibrate::trace::TRACE_FORMAT).
    #[error("{path}: trace format {found}, but this usar reads format {expected}; {START_AFRESH}")]
    Format {
        /// The trace's path, as shown.
        path: String,
        /// The format its header gives (`unknown` when none).
        found: String,
        /// The format this build reads.
        expected: u32,
    },
    /// An I/O error reading the trace, naming its path.
    #[error(transparent)]
    File(#[from] FileError),
    /// The trace could not be created or appended to.
    #[error(transparent)]
    Log(#[from] LogError),
}
