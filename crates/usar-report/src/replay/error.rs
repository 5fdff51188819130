//! [`ReplayError`]: why a replay could not be recorded or written.

use usar_sweep::atomic::FileError;

use thiserror::Error;
use usar_sim::mission::MissionError;

/// Why a replay could not be recorded, encoded or written.
#[derive(Debug, Error)]
pub enum ReplayError {
    /// A bad sampling rate, method, trial or `--replay` list (the message names it).
    #[error("{0}")]
    Spec(String),
    /// The trial failed (as the simulation reports it; part of the one-line message, not
    /// also a `source()`, so a chain-printing caller does not repeat it).
    #[error("trial: {0}")]
    Trial(MissionError),
    /// Drawing the arena failed.
    #[error("drawing the arena: {0}")]
    Draw(String),
    /// The recording's data do not decode (a truncated or corrupt stream).
    #[error("decoding the recording: {0}")]
    Decode(String),
    /// Compressing or serialising the page's data failed.
    #[error("encoding the page: {0}")]
    Encode(String),
    /// Writing the page failed (the error of
    /// [`write_atomic`](usar_sweep::atomic::write_atomic), naming the path).
    #[error(transparent)]
    Write(#[from] FileError),
}

impl From<MissionError> for ReplayError {
    fn from(e: MissionError) -> Self {
        Self::Trial(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Regression (issue 70): the trial's error was formatted into the message and also
    /// returned as the source, so a chain printer repeated it.
    #[test]
    fn a_chain_printer_gives_the_trials_error_once() {
        let e = ReplayError::from(MissionError::Method("x is unknown".into()));
        assert_eq!(
            rne_core::error_line(&e),
            "trial: grouping method: x is unknown"
        );
    }
}
