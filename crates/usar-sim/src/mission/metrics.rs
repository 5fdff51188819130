//! Per-trial metrics (paper, section VI.A): rescuees, energy and HP cost per task and per
//! rescuee, rounds, and per-robot figures. Tasks are indexed by their id (their index in
//! `Scenario::tasks`); [`TrialResult::tasks`] names them.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Why a task's group was sent out of its search area (`docs/mission-model.md`, "Leaving the
/// search area"); when several hold at once, the first in this order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub enum LeaveCause {
    /// The group's pool of rescuing resources is used up.
    ResourcesUsed,
    /// Its ground members' free carrying capacity is used up (every carrier full).
    CapacityFull,
    /// Nothing more is to be had: every ground member waits (nothing it can claim or sweep)
    /// and no observer is still flying in.
    NothingLeft,
    /// Its search time budget (`mission.search_time_budget_s`) is spent.
    SearchBudget,
    /// Its round's time is up (`mission.round_clock: Timer`): the group is recalled.
    RoundTimer,
}

impl LeaveCause {
    /// The cause's name as written in CSV files (`resources_used`, `capacity_full`,
    /// `nothing_left`, `search_budget`, `round_timer`).
    pub fn as_str(self) -> &'static str {
        match self {
            Self::ResourcesUsed => "resources_used",
            Self::CapacityFull => "capacity_full",
            Self::NothingLeft => "nothing_left",
            Self::SearchBudget => "search_budget",
            Self::RoundTimer => "round_timer",
        }
    }
}

/// One round: from the moment the team is grouped at the start until every grouped robot is
/// back at its start position (paper, section VI.B). Every per-task list has one entry per
/// task, by task id; the trip figures (`left_area_s` to `back_s`) are empty in results
/// journaled before they existed.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RoundRecord {
    /// Simulated time the round began, seconds since the trial start.
    pub start_s: f64,
    /// Simulated time the round ended, seconds; the trial's end for an unfinished round.
    pub end_s: f64,
    /// Whether every grouped robot got back to the start before the time limit.
    pub completed: bool,
    /// Robot ids grouped to each task this round, by task id (each sorted ascending; a group
    /// may be empty).
    pub groups: Vec<Vec<usize>>,
    /// Rescuees delivered to each task's drop-off during this round, by task id.
    pub rescued: Vec<u32>,
    /// When each task's group was sent out of its search area, seconds since the trial start
    /// (`None`: it never was this round, e.g. cut by the time limit, or an empty group).
    #[serde(default)]
    pub left_area_s: Vec<Option<f64>>,
    /// Why each task's group was sent out of its search area ([`LeaveCause`]; `None` as in
    /// `left_area_s`).
    #[serde(default)]
    pub left_because: Vec<Option<LeaveCause>>,
    /// Trips of each task's members that can carry rescuees (`carrying_capacity > 0`) that
    /// ended at the task's drop-off this round (deliveries, the empty ones included).
    #[serde(default)]
    pub deliveries: Vec<u32>,
    /// Of `deliveries`, those that brought no rescuee.
    #[serde(default)]
    pub empty_deliveries: Vec<u32>,
    /// Members of each task's group that left it this round for their needs (energy or HP
    /// below `mission.low_energy_pct` / `mission.low_hp_pct`).
    #[serde(default)]
    pub left_for_rest: Vec<u32>,
    /// When the last member still in each task's group got back to its start, seconds since
    /// the trial start (`None`: not every one was back when the round ended, or an empty
    /// group). The group then waits `end_s - back_s` for the other tasks' groups.
    #[serde(default)]
    pub back_s: Vec<Option<f64>>,
}

/// Per-robot figures over a whole trial.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RobotMetrics {
    /// Robot id (index into the scenario's robots).
    pub id: usize,
    /// Name of the robot's kind.
    pub kind: String,
    /// Path length travelled, metres.
    pub distance_m: f64,
    /// Energy at the end of the trial, percent.
    pub final_energy_pct: f64,
    /// HP at the end of the trial, percent.
    pub final_hp_pct: f64,
    /// Energy spent over the trial, percent points (sum of all decreases).
    pub energy_spent_pct: f64,
    /// HP lost over the trial, percent points (sum of all decreases).
    pub hp_lost_pct: f64,
    /// Visits to the rest station that ended in a recharge.
    pub recharges: u32,
    /// Simulated time spent inside radiation zones, seconds.
    pub time_in_radiation_s: f64,
    /// Simulated time held still by the collision resolver, seconds.
    pub time_held_s: f64,
    /// Collision lists this robot joined.
    pub collision_lists: u32,
    /// Deadlocks resolved in collision lists this robot belonged to.
    pub deadlocks_resolved: u32,
    /// Rescuees this robot picked up.
    pub picked_up: u32,
    /// Rescuees this robot delivered to a drop-off.
    pub delivered: u32,
    /// Goals the path planner could not reach from where the robot stood (it then stopped until
    /// its next goal; see `docs/mission-model.md`).
    pub unreachable_goals: u32,
}

/// Everything measured in one trial: the record `usar run` prints and `usar sweep` tabulates.
/// Per-task vectors are indexed by task id and have one entry per task of
/// [`TrialResult::tasks`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TrialResult {
    /// Scenario name.
    pub scenario: String,
    /// The grouping method's display name as its author wrote it
    /// (`GroupingMethod::display_name`: `RNE`, `DIS`, `ENG`, `HP_DIS` for the built-ins).
    pub method: String,
    /// Trial index within a sweep, 0-based.
    pub trial: u32,
    /// Seed of the trial's starting team (see [`crate::mission::trial_seed`]).
    pub seed: u64,
    /// Simulated duration, seconds.
    pub duration_s: f64,
    /// The tasks' names, by task id (the scenario's order).
    pub tasks: Vec<String>,
    /// Rescuees delivered per task.
    pub rescued: Vec<u32>,
    /// Energy spent by robots while in each task's group, percent points summed over robots.
    pub energy_spent_pct: Vec<f64>,
    /// HP lost by robots while in each task's group, percent points summed over robots.
    pub hp_lost_pct: Vec<f64>,
    /// Rounds, in order; the last may be unfinished.
    pub rounds: Vec<RoundRecord>,
    /// Per-robot figures, indexed by robot id.
    pub robots: Vec<RobotMetrics>,
}

/// `cost / count`, or `None` when nothing was counted.
pub fn per(cost: f64, count: u32) -> Option<f64> {
    (count > 0).then(|| cost / f64::from(count))
}

impl TrialResult {
    /// The id of the task called `name`.
    pub fn task_id(&self, name: &str) -> Option<usize> {
        self.tasks.iter().position(|t| t == name)
    }

    /// Rescuees delivered in all tasks.
    pub fn rescued_total(&self) -> u32 {
        self.rescued.iter().sum()
    }

    /// Energy spent in all tasks' groups, percent points (summed in task order).
    pub fn energy_total_pct(&self) -> f64 {
        self.energy_spent_pct.iter().sum()
    }

    /// HP lost in all tasks' groups, percent points (summed in task order).
    pub fn hp_total_pct(&self) -> f64 {
        self.hp_lost_pct.iter().sum()
    }

    /// Energy spent per rescuee in task `t`, percent points; `None` if it rescued nobody.
    ///
    /// # Panics
    /// If `t` is not a task id.
    pub fn energy_per_rescuee(&self, t: usize) -> Option<f64> {
        per(self.energy_spent_pct[t], self.rescued[t])
    }

    /// HP lost per rescuee in task `t`, percent points; `None` if it rescued nobody.
    ///
    /// # Panics
    /// If `t` is not a task id.
    pub fn hp_per_rescuee(&self, t: usize) -> Option<f64> {
        per(self.hp_lost_pct[t], self.rescued[t])
    }

    /// Mean duration of completed rounds, seconds; `None` if no round completed.
    pub fn mean_round_s(&self) -> Option<f64> {
        let done: Vec<f64> = self
            .rounds
            .iter()
            .filter(|r| r.completed)
            .map(|r| r.end_s - r.start_s)
            .collect();
        (!done.is_empty()).then(|| done.iter().sum::<f64>() / done.len() as f64)
    }
}
