//! Errors of the world API. Stepping itself never fails; only the setters report errors.

use thiserror::Error;

/// Why a ground robot's path could not be planned.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Error)]
pub enum NavError {
    /// The goal is not a finite point inside the arena.
    #[error("goal is not a finite point inside the arena")]
    GoalOutsideArena,
    /// The start lies inside the inflated obstacles and no free cell is near enough.
    #[error("start is inside an obstacle and no free cell is near")]
    StartBlocked,
    /// The goal lies inside the inflated obstacles and no free cell is near enough.
    #[error("goal is inside an obstacle and no free cell is near")]
    GoalBlocked,
    /// Start and goal are in different free regions of the occupancy grid.
    #[error("no path between start and goal")]
    NoPath,
}

/// Errors of [`crate::world::World`]'s setters.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum WorldError {
    /// The robot id is not an index into the scenario's robots.
    #[error("unknown robot id {0}")]
    UnknownRobot(usize),
    /// A factor or key was NaN, infinite or (for factors) negative.
    #[error("invalid value {value} for {what}")]
    InvalidValue {
        /// Which setter argument.
        what: &'static str,
        /// The rejected value.
        value: f64,
    },
    /// Path planning failed; the robot's goal was cleared (it stands still).
    #[error("robot {id}: {error}")]
    Unreachable {
        /// The robot.
        id: usize,
        /// Why planning failed (part of the one-line message, not also a `source()`, so a
        /// chain-printing caller such as `rne_core::error_line` does not repeat it).
        error: NavError,
    },
}

impl WorldError {
    /// `Ok` for a finite factor `>= 0`, else [`WorldError::InvalidValue`] naming `what`.
    pub(super) fn check_factor(what: &'static str, value: f64) -> Result<(), Self> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(Self::InvalidValue { what, value })
        }
    }

    /// `Ok` for any value but NaN, else [`WorldError::InvalidValue`] naming `what`.
    pub(super) fn check_not_nan(what: &'static str, value: f64) -> Result<(), Self> {
        if value.is_nan() {
            Err(Self::InvalidValue { what, value })
        } else {
            Ok(())
        }
    }
}
