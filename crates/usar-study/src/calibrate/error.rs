//! [`CalibrationError`]: why a calibration ([`crate::calibrate::calibrate`]) did not finish.

use usar_report::error::ReportError;
use usar_sweep::atomic::FileError;
use usar_sweep::data::hooks::Stopped;
use usar_sweep::data::owner::OwnerError;
use usar_sweep::lock::LockError;
use usar_sweep::settings::Setting;

use super::setup::SetupError;
use super::trace_error::TraceError;

/// Why a calibration did not finish: one line (with its cause as the error's source, which an
/// error chain such as `{:#}` of `anyhow` appends). Failing trials and free values that break
/// a rule are not errors: their evaluation's loss is +inf.
#[derive(Debug, thiserror::Error)]
pub enum CalibrationError {
    /// The setup does not fit its scenario, or an option is refused.
    #[error(transparent)]
    Setup(#[from] SetupError),
    /// The trace in the output folder cannot be continued (damaged, edited, another format).
    #[error(transparent)]
    Trace(#[from] TraceError),
    /// An evaluation could not be appended to the trace: the search stopped (the evaluations
    /// recorded so far are kept, and running it again continues).
    #[error("the trace could not be written; the calibration stopped")]
    TraceStopped(#[source] TraceError),
    /// The trace's path is a folder, a FIFO or a device.
    #[error(
        "{path}: not a regular file; remove it, or choose another {}",
        Setting::Out
    )]
    TraceNotAFile {
        /// The trace's path, as shown.
        path: String,
    },
    /// The output folder's trace is another calibration's.
    #[error(
        "{path} holds another calibration ({diff}): pass {} to start afresh, or choose \
         another {}",
        Setting::Overwrite,
        Setting::Out
    )]
    OtherCalibration {
        /// The trace's path, as shown.
        path: String,
        /// The differences of the headers.
        diff: String,
    },
    /// The search evaluated no point (a budget of none).
    #[error("no evaluation ran")]
    NoEvaluation,
    /// The best point, as every other, gives no valid scenario.
    #[error("no evaluated point gives a valid scenario; the best one: {problem}")]
    NoValidPoint {
        /// The rule the best point breaks.
        problem: String,
    },
    /// The stop flag was set: the finished evaluations are in the trace.
    #[error(transparent)]
    Stopped(#[from] Stopped),
    /// The worker threads could not be started.
    #[error("starting the thread pool")]
    ThreadPool(#[source] rayon::ThreadPoolBuildError),
    /// The scenario cannot be written as JSON to hash it (not expected).
    #[error("serialising the scenario")]
    Serialise(#[source] serde_json::Error),
    /// An output (a file, a figure's table) could not be made or written.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// A file could not be removed or written.
    #[error(transparent)]
    File(#[from] FileError),
    /// The output folder is another run's, or not a folder.
    #[error(transparent)]
    Owner(#[from] OwnerError),
    /// The output folder is locked by another run.
    #[error(transparent)]
    Lock(#[from] LockError),
}

impl CalibrationError {
    /// Whether the calibration stopped because its stop flag was set.
    pub fn is_stopped(&self) -> bool {
        matches!(self, Self::Stopped(_))
    }
}
