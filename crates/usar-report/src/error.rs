//! [`ReportError`]: why an output of a sweep (a table, a figure, a report, a picture or the
//! output date) could not be made or written.

use usar_sweep::atomic::FileError;

/// Why an output could not be made or written: one line (with its cause as the error's source,
/// which an error chain such as `{:#}` of `anyhow` appends).
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// A file that could not be written (atomically: the earlier file, if any, stays).
    #[error(transparent)]
    File(#[from] FileError),
    /// A CSV table that could not be made (`action`: `writing a trials.csv row`, `finishing
    /// summary.csv`).
    #[error("{action}")]
    Csv {
        /// What was being done, naming the table.
        action: &'static str,
        /// The csv crate's error.
        #[source]
        source: csv::Error,
    },
    /// A CSV record that could not be written.
    #[error(transparent)]
    Table(#[from] csv::Error),
    /// Text (the terminal summary) that could not be written.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// A figure that plotters could not draw.
    #[error("drawing a figure: {problem}")]
    Figure {
        /// plotters' error, as its `Debug` shows it.
        problem: String,
    },
    /// A picture (`usar render`) that plotters could not draw.
    #[error("drawing the SVG failed: {problem}")]
    Picture {
        /// plotters' error.
        problem: String,
    },
    /// A scenario that cannot be written as RON (not expected).
    #[error("writing the scenario as RON")]
    Ron(#[from] ron::Error),
    /// `SOURCE_DATE_EPOCH` set to something other than a whole number of seconds.
    #[error("SOURCE_DATE_EPOCH {text:?} is not a number of seconds")]
    SourceDateEpoch {
        /// Its value.
        text: String,
        /// The parser's error.
        #[source]
        source: std::num::ParseIntError,
    },
}

/// What the functions of this crate that make or write outputs return.
pub type Result<T, E = ReportError> = std::result::Result<T, E>;

impl ReportError {
    /// The [`ReportError::Csv`] of `action`, for `map_err` on a csv writer's result.
    pub fn csv(action: &'static str) -> impl FnOnce(csv::Error) -> Self {
        move |source| Self::Csv { action, source }
    }

    /// The [`ReportError::Csv`] of `action` for a csv writer that could not be finished.
    pub fn finish<W>(action: &'static str) -> impl FnOnce(csv::IntoInnerError<W>) -> Self {
        move |e| Self::Csv {
            action,
            source: e.into_error().into(),
        }
    }
}
