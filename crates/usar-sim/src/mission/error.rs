//! Errors of the mission layer.

use thiserror::Error;

use crate::world::WorldError;

/// Why a trial could not go on. Stepping a valid scenario with the built-in methods does not
/// fail; a user's grouping method may, and an internal inconsistency surfaces here rather than
/// as a panic.
#[derive(Debug, Clone, Error)]
pub enum MissionError {
    /// The grouping method failed or returned an assignment that is not a valid partition.
    #[error("grouping method {method}: {error}")]
    Grouping {
        /// The method's name.
        method: String,
        /// What rne-core reported (part of the one-line message, not also a `source()`, so a
        /// chain-printing caller does not repeat it).
        error: rne_core::RneError,
    },
    /// No grouping method, or an unknown method name.
    #[error("grouping method: {0}")]
    Method(String),
    /// The world refused a command (e.g. a NaN speed factor): a bug in the mission layer.
    /// The world's error is part of the one-line message, not also a `source()`.
    #[error("world: {0}")]
    World(WorldError),
    /// A trial length that is not a positive number of seconds, or that needs more steps than
    /// the limit allows.
    #[error("{0}")]
    Duration(String),
}

impl From<WorldError> for MissionError {
    fn from(e: WorldError) -> Self {
        Self::World(e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::NavError;

    /// Regression (issue 70): the world's error and its planning error were formatted into
    /// the message and also returned as sources, so a chain printer repeated them.
    #[test]
    fn a_chain_printer_gives_each_cause_once() {
        let e = MissionError::from(WorldError::Unreachable {
            id: 1,
            error: NavError::NoPath,
        });
        assert_eq!(
            rne_core::error_line(&e),
            "world: robot 1: no path between start and goal"
        );
        assert_eq!(rne_core::error_line(&e), e.to_string());
    }
}
