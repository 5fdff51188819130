//! A robot's mission state: levels, phase, group, load (paper, section VI.B).

use serde::{Deserialize, Serialize};

use crate::scenario::MissionParams;

/// What a robot is doing in the mission.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Phase {
    /// At its start position, waiting for the next round.
    AtStart,
    /// Going to its task's search area.
    ToSearchArea,
    /// In the search area: rescuing (ground robots) or observing (observers).
    Searching,
    /// Nothing left to do in the search area (full, or nothing to claim): standing still until
    /// its group leaves.
    Waiting,
    /// Carrying its load to the task's drop-off.
    ToDropOff,
    /// Going back to its start position after the drop-off (or, carrying nothing, from its
    /// search area under `mission.empty_on_leave: StraightToStart`).
    ToStart,
    /// Left its task with low energy or HP; going to where it recharges (the rest station, or
    /// its own start under `mission.rest_at: OwnStart`).
    ToRest,
    /// Recharging (at the rest station, or at its start under `mission.rest_at: OwnStart`)
    /// until the given simulated time, seconds.
    Recharging {
        /// When recharging ends, seconds since the trial start.
        until_s: f64,
    },
    /// Recharged; going back to its start position.
    RestToStart,
}

/// A robot's mission-level state (the physical state is [`crate::world::RobotState`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MissionRobot {
    /// Robot id.
    pub id: usize,
    /// Energy (battery), percent, in `[0, 100]`.
    pub energy_pct: f64,
    /// Health points, percent, in `[0, 100]`.
    pub hp_pct: f64,
    /// What it is doing.
    pub phase: Phase,
    /// The task (its id, an index into `Scenario::tasks`) whose group the robot belongs to
    /// this round, if any.
    pub task: Option<usize>,
    /// Free carrying capacity, rescuees.
    pub capacity_free: u32,
    /// Rescuing resources it still holds.
    pub resources: u32,
    /// Rescuees it carries (indices into its task's rescuees).
    pub load: Vec<usize>,
    /// The rescuee it is driving to, if any.
    pub claim: Option<usize>,
    /// Closest the robot has come to its current search target (claimed rescuee or sweep
    /// waypoint), in steps of at least `CLAIM_PROGRESS_M`, metres.
    pub target_best_m: f64,
    /// When it last came `CLAIM_PROGRESS_M` closer to its current search target, seconds.
    pub target_progress_s: f64,
    /// Next blind-search waypoint (groups without an observer), index into the task's sweep.
    pub sweep_next: usize,
    /// Sweep waypoints visited this round.
    pub sweep_visited: usize,
    /// Set when the robot has left its task for the rest station but first delivers its load
    /// at the drop-off (`mission.load_on_leave: DeliverFirst`): it is then away for its needs
    /// although its phase is `ToDropOff`.
    pub leaving: bool,
    /// While the robot is rescuing its claimed rescuee (standing within reach for
    /// `mission.pickup_s`): when the rescue is done, seconds since the trial start.
    pub picking_until_s: Option<f64>,
    /// Whether the robot has come within reach of its task's search area this round (its body
    /// radius plus `navigation.waypoint_tolerance_m`, the distance at which it rescues: a robot
    /// can rescue at the area's edge without entering it); reset when a round groups it. The
    /// search clock of `mission.search_clock: LastArrival` waits for every member's.
    pub reached_area: bool,
    /// The task of the latest group the robot was in (kept after the group dissolves; `None`
    /// before its first round). Costs count for it under `mission.costs_count: Every`.
    #[serde(default)]
    pub last_task: Option<usize>,
    /// Whether the robot left for a rest in the open round's slack (`mission.rest_timing:
    /// InSlack`): the round waits for its rest to end (up to the round's timer). Cleared when
    /// the round closes.
    #[serde(default)]
    pub rests_in_round: bool,
}

impl MissionRobot {
    /// Whether the robot is away for its safety or basic needs (recharging or on the way,
    /// including a last delivery on the way there; see [`MissionRobot::leaving`]).
    pub fn is_resting(&self) -> bool {
        self.leaving
            || matches!(
                self.phase,
                Phase::ToRest | Phase::Recharging { .. } | Phase::RestToStart
            )
    }

    /// Whether its energy is below `mission.low_energy_pct` and whether its HP is below
    /// `mission.low_hp_pct` (either sends it to the rest station, paper section VI.B).
    pub fn low_levels(&self, mission: &MissionParams) -> (bool, bool) {
        (
            self.energy_pct < mission.low_energy_pct.get(),
            self.hp_pct < mission.low_hp_pct.get(),
        )
    }

    /// Whether the robot is in its group's search phase (on the way, searching or waiting).
    pub fn is_on_task(&self) -> bool {
        matches!(
            self.phase,
            Phase::ToSearchArea | Phase::Searching | Phase::Waiting
        )
    }
}
