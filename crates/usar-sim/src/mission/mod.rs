//! The persistent USAR mission on top of the world: needs, rounds, rescuing, regrouping and
//! metrics (paper, sections IV-VI). The rules are in `docs/mission-model.md`.
//!
//! Data apart from the systems that update it: [`MissionState`] holds the team, the rescuees,
//! the rounds and the [`Recorder`] of metrics; each step runs the round system (`round_clock`, with the rest lifecycle in `rest`), the
//! decision system (`decide`), the world's physics step, and the accounting system
//! (`account`), each a function over the scenario, the world and the state.
//!
//! - [`needs`](needs_vector): a robot's 7-entry needs vector (Eqs. 19-21).
//! - [`draw_initial_levels`]: the trial's starting energy and HP (common random numbers).
//! - [`group_available`]: regrouping at each round's start with adapted quotas.
//! - [`Simulation`]: one trial, set up by [`Simulation::builder`], watched by a
//!   [`StepObserver`]; [`TrialResult`]: its metrics; [`MissionEvent`]: what happened in the
//!   last step ([`Simulation::events`]).
//! - [`unreachable_goals`]: the goals some robots cannot reach from their starts (a check
//!   before a trial; `usar check` warns about them).
//! - [`tasks_without_rescue`]: the tasks no group can rescue from, whatever the method (a
//!   check before a trial; `usar check` warns about them).
//! - [`scenario_warnings`]: both checks' findings as warning lines.

mod account;
mod decide;
mod error;
mod events;
mod goals;
mod grouping;
mod initial;
mod metrics;
mod needs;
mod reachability;
mod recorder;
mod rescue_capacity;
mod rescuees;
mod rest;
mod robot;
mod round_clock;
mod search_pattern;
mod simulation;
mod state;
mod step_costs;
mod warnings;

pub use crate::scenario::{sweep_point_count, sweep_spacing_m};
pub use decide::{CLAIM_PROGRESS_M, CLAIM_STALL_S};
pub use error::MissionError;
pub use events::{MissionEvent, MissionEventKind};
pub use grouping::{adapted_quotas, group_available, shrink_quotas, snapshot};
pub use initial::{InitialLevels, draw_initial_levels, trial_seed};
pub use metrics::{LeaveCause, RobotMetrics, RoundRecord, TrialResult, per};
pub use needs::{entry, hp_factor, needs_vector};
pub use reachability::{UnreachableGoal, unreachable_goals};
pub use recorder::{Recorder, TrialInfo};
pub use rescue_capacity::{NoRescue, TaskWithoutRescue, tasks_without_rescue};
pub use rescuees::{RescueeField, RescueeStatus};
pub use robot::{MissionRobot, Phase};
pub use search_pattern::sweep_waypoints;
pub use simulation::{Simulation, StepObserver, TrialBuilder, trial_steps, trust_model};
pub use state::MissionState;
pub use warnings::scenario_warnings;
