//! Per-trial metrics (paper, section VI.A): rescuees, energy and HP cost per task and per
//! rescuee, rounds, and per-robot figures.

use serde::{Deserialize, Serialize};

use crate::scenario::TaskLevel;

/// A value per task: `easy` and `hard`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub struct PerTask<T> {
    /// Value for the easy task.
    pub easy: T,
    /// Value for the hard task.
    pub hard: T,
}

impl<T> PerTask<T> {
    /// The value for `level`.
    pub fn get(&self, level: TaskLevel) -> &T {
        match level {
            TaskLevel::Easy => &self.easy,
            TaskLevel::Hard => &self.hard,
        }
    }

    /// Mutable access to the value for `level`.
    pub fn get_mut(&mut self, level: TaskLevel) -> &mut T {
        match level {
            TaskLevel::Easy => &mut self.easy,
            TaskLevel::Hard => &mut self.hard,
        }
    }
}

/// One round: from the moment the team is grouped at the start until every grouped robot is
/// back at its start position (paper, section VI.B).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoundRecord {
    /// Simulated time the round began, seconds since the trial start.
    pub start_s: f64,
    /// Simulated time the round ended, seconds; the trial's end for an unfinished round.
    pub end_s: f64,
    /// Whether every grouped robot got back to the start before the time limit.
    pub completed: bool,
    /// Robot ids grouped to each task this round.
    pub groups: PerTask<Vec<usize>>,
    /// Rescuees delivered to each task's drop-off during this round.
    pub rescued: PerTask<u32>,
}

/// Per-robot figures over a whole trial.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
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
}

/// Everything measured in one trial: the record `usar run` prints and `usar sweep` tabulates.
///
/// Serialises to JSON with serde; [`TrialResult::row`] flattens it into one CSV row.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialResult {
    /// Scenario name.
    pub scenario: String,
    /// Grouping method name (e.g. `RNE`).
    pub method: String,
    /// Trial index within a sweep, 0-based.
    pub trial: u32,
    /// Seed of the trial's starting team (see [`crate::mission::trial_seed`]).
    pub seed: u64,
    /// Simulated duration, seconds.
    pub duration_s: f64,
    /// Rescuees delivered per task.
    pub rescued: PerTask<u32>,
    /// Energy spent by robots while in each task's group, percent points summed over robots.
    pub energy_spent_pct: PerTask<f64>,
    /// HP lost by robots while in each task's group, percent points summed over robots.
    pub hp_lost_pct: PerTask<f64>,
    /// Rounds, in order; the last may be unfinished.
    pub rounds: Vec<RoundRecord>,
    /// Per-robot figures, indexed by robot id.
    pub robots: Vec<RobotMetrics>,
}

/// One flat CSV row of a [`TrialResult`] (the columns of the paper's experiment sheet).
/// Per-rescuee costs are empty when a task rescued nobody.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialRow {
    /// Scenario name.
    pub scenario: String,
    /// Grouping method.
    pub method: String,
    /// Trial index, 0-based.
    pub trial: u32,
    /// Seed of the starting team.
    pub seed: u64,
    /// Rescuees, both tasks.
    pub rescued_total: u32,
    /// Rescuees, hard task.
    pub rescued_hard: u32,
    /// Rescuees, easy task.
    pub rescued_easy: u32,
    /// Energy spent in the hard task's group, percent points.
    pub energy_hard_pct: f64,
    /// Energy spent in the easy task's group, percent points.
    pub energy_easy_pct: f64,
    /// Energy spent in both groups, percent points.
    pub energy_total_pct: f64,
    /// HP lost in the hard task's group, percent points.
    pub hp_hard_pct: f64,
    /// HP lost in the easy task's group, percent points.
    pub hp_easy_pct: f64,
    /// HP lost in both groups, percent points.
    pub hp_total_pct: f64,
    /// Rounds started (the last may be unfinished).
    pub rounds: u32,
    /// Energy per hard-task rescuee, percent points.
    pub energy_per_hard_rescuee_pct: Option<f64>,
    /// Energy per easy-task rescuee, percent points.
    pub energy_per_easy_rescuee_pct: Option<f64>,
    /// Energy per rescuee over both tasks, percent points.
    pub energy_per_rescuee_pct: Option<f64>,
    /// HP per hard-task rescuee, percent points.
    pub hp_per_hard_rescuee_pct: Option<f64>,
    /// HP per easy-task rescuee, percent points.
    pub hp_per_easy_rescuee_pct: Option<f64>,
    /// HP per rescuee over both tasks, percent points.
    pub hp_per_rescuee_pct: Option<f64>,
    /// Mean duration of the completed rounds, seconds (empty if none completed).
    pub mean_round_s: Option<f64>,
}

fn per(cost: f64, count: u32) -> Option<f64> {
    (count > 0).then(|| cost / f64::from(count))
}

impl TrialResult {
    /// Rescuees delivered in both tasks.
    pub fn rescued_total(&self) -> u32 {
        self.rescued.easy + self.rescued.hard
    }

    /// Energy spent per rescuee in task `level`, percent points; `None` if it rescued nobody.
    pub fn energy_per_rescuee(&self, level: TaskLevel) -> Option<f64> {
        per(*self.energy_spent_pct.get(level), *self.rescued.get(level))
    }

    /// HP lost per rescuee in task `level`, percent points; `None` if it rescued nobody.
    pub fn hp_per_rescuee(&self, level: TaskLevel) -> Option<f64> {
        per(*self.hp_lost_pct.get(level), *self.rescued.get(level))
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

    /// The flat CSV row of this trial.
    pub fn row(&self) -> TrialRow {
        let e = &self.energy_spent_pct;
        let h = &self.hp_lost_pct;
        TrialRow {
            scenario: self.scenario.clone(),
            method: self.method.clone(),
            trial: self.trial,
            seed: self.seed,
            rescued_total: self.rescued_total(),
            rescued_hard: self.rescued.hard,
            rescued_easy: self.rescued.easy,
            energy_hard_pct: e.hard,
            energy_easy_pct: e.easy,
            energy_total_pct: e.hard + e.easy,
            hp_hard_pct: h.hard,
            hp_easy_pct: h.easy,
            hp_total_pct: h.hard + h.easy,
            rounds: self.rounds.len() as u32,
            energy_per_hard_rescuee_pct: self.energy_per_rescuee(TaskLevel::Hard),
            energy_per_easy_rescuee_pct: self.energy_per_rescuee(TaskLevel::Easy),
            energy_per_rescuee_pct: per(e.hard + e.easy, self.rescued_total()),
            hp_per_hard_rescuee_pct: self.hp_per_rescuee(TaskLevel::Hard),
            hp_per_easy_rescuee_pct: self.hp_per_rescuee(TaskLevel::Easy),
            hp_per_rescuee_pct: per(h.hard + h.easy, self.rescued_total()),
            mean_round_s: self.mean_round_s(),
        }
    }
}
