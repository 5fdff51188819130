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
    #[error("world: {0}")]
    World(#[from] WorldError),
    /// A trial length that is not a positive number of seconds, or that needs more steps than
    /// the limit allows.
    #[error("{0}")]
    Duration(String),
}
