//! The physical world of the USAR mission (paper, sections IV-VI), stepped with Rapier 2D.
//!
//! - [`bodies`]: Rapier bodies, colliders and collision groups (walls, debris, robot discs).
//! - [`navigation`]: clearance grid (parry2d distance queries), grid A*, path smoothing.
//! - [`resolver`]: priority-based collision avoidance and deadlock solving (section V,
//!   Algorithm 5).
//! - [`radiation`]: radiation zones.
//! - `robot`: the per-robot state the mission layer reads ([`RobotState`]).
//! - `simulation`: [`World`], the API the mission layer drives.
//!
//! See `docs/world-model.md` for the model and its rules.

pub mod bodies;
mod error;
pub mod navigation;
pub mod radiation;
pub mod resolver;
mod robot;
mod simulation;

pub use error::{NavError, WorldError};
pub use robot::{Motion, RobotCounters, RobotState};
pub use simulation::{
    CORNER_PASS_M, MOVED_TOLERANCE_M, PATH_CHECK_INTERVAL_STEPS, PATH_CHECK_MAX_M, World,
    WorldStats,
};
