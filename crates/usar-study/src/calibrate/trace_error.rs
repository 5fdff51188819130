//! Why a calibration's trace ([`crate::calibrate::trace`]) cannot be read or written:
//! [`TraceError`].

use usar_sweep::atomic::FileError;
use usar_sweep::checked_log::LogError;
use usar_sweep::settings::Setting;

/// What every message about a trace that cannot be used ends with: `start afresh with
/// --overwrite, or choose another --out`, its settings in the front end's words.
pub(crate) fn start_afresh() -> String {
    format!(
        "start afresh with {}, or choose another {}",
        Setting::Overwrite,
        Setting::Out
    )
}

/// Why a trace cannot be read (one line naming its path, and a line's 1-based number as
/// `path:line:`; each ends with how to start afresh) or written.
#[derive(Debug, thiserror::Error)]
pub enum TraceError {
    /// A line before the last that is not an evaluation (or not UTF-8).
    #[error(
        "{path}:{line}: not a valid trace line; delete that line (its point runs again), or \
         {}",
        start_afresh()
    )]
    DamagedLine {
        /// The trace's path, as shown.
        path: String,
        /// The line's number, from 1.
        line: usize,
    },
    /// No complete first line.
    #[error("{path}: no complete header line; {}", start_afresh())]
    NoHeader {
        /// The trace's path, as shown.
        path: String,
    },
    /// The first line is not a trace header.
    #[error("{path}:1: not a trace header; {}", start_afresh())]
    NotAHeader {
        /// The trace's path, as shown.
        path: String,
    },
    /// The header's checksum is missing or wrong.
    #[error("{path}:1: the header does not verify (edited?); {}", start_afresh())]
    HeaderUnverified {
        /// The trace's path, as shown.
        path: String,
    },
    /// A header of another trace format than
    /// [`TRACE_FORMAT`](crate::calibrate::trace::TRACE_FORMAT).
    #[error(
        "{path}: trace format {found}, but this usar reads format {expected}; {}",
        start_afresh()
    )]
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
