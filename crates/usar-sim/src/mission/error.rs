//! Errors of the mission layer.

use thiserror::Error;

/// Why a trial could not go on. Stepping a valid scenario with the built-in methods does not
/// fail; a user's grouping method may.
#[derive(Debug, Clone, Error)]
pub enum MissionError {
    /// The grouping method failed or returned an assignment that is not a valid partition.
    #[error("grouping method {method}: {source}")]
    Grouping {
        /// The method's name.
        method: String,
        /// What rne-core reported.
        source: rne_core::RneError,
    },
}
