//! The persistent USAR mission on top of the world: needs, rounds, rescuing, regrouping and
//! metrics (paper, sections IV-VI). The rules are in `docs/mission-model.md`.
//!
//! - [`needs`](needs_vector): a robot's 7-entry needs vector (Eqs. 19-21).
//! - [`draw_initial_levels`]: the trial's starting energy and HP (common random numbers).
//! - [`group_available`]: regrouping at each round's start with adapted quotas.
//! - [`Simulation`]: one trial; [`TrialResult`]: its metrics.

mod error;
mod grouping;
mod initial;
mod metrics;
mod needs;
mod rescuees;
mod robot;
mod simulation;

pub use error::MissionError;
pub use grouping::{adapted_quotas, group_available, snapshot};
pub use initial::{InitialLevels, draw_initial_levels, trial_seed};
pub use metrics::{PerTask, RobotMetrics, RoundRecord, TrialResult, TrialRow};
pub use needs::{entry, hp_factor, needs_vector};
pub use rescuees::{RescueeField, RescueeStatus};
pub use robot::{MissionRobot, Phase};
pub use simulation::{Simulation, sweep_spacing_m, sweep_waypoints};
