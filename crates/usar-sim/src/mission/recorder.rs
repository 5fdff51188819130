//! The metrics recorder: the one place a trial's figures are counted (paper, section VI.A).
//! The systems report events to it; [`Recorder::result`] turns the counts into a
//! [`TrialResult`].

use super::metrics::{LeaveCause, RobotMetrics, RoundRecord, TrialResult};
use super::robot::MissionRobot;
#[cfg(doc)]
use super::step_costs::charge_step_costs;
use super::step_costs::{RobotCosts, StepCost};
use crate::scenario::{RescuedAt, Scenario};
use crate::world::World;

/// Running counts of one trial: per robot, per task (by task id) and per round. Energy and HP
/// are in percentage points of a full battery and full health (`pct`); times in seconds
/// (`_s`).
///
/// # Panics
/// Every method that takes a robot id `id` or a task id `t`/`task` panics if it is not one of
/// the scenario's (`id >= robots`, `t >= tasks`), as slice indexing does; the mission passes
/// only its own ids.
#[derive(Debug, Clone)]
pub struct Recorder {
    robots: Vec<RobotMetrics>,
    /// Each robot's energy spent, HP lost and time in radiation so far, by id: kept apart
    /// from `robots` (24 bytes a robot instead of a metrics record) since every step adds to
    /// them.
    costs: Vec<RobotCosts>,
    energy_by_task: Vec<f64>,
    hp_by_task: Vec<f64>,
    rescued: Vec<u32>,
    rounds: Vec<RoundRecord>,
    rescued_at: RescuedAt,
    /// When each robot last got back to its start in the open round, seconds.
    back_at_start_s: Vec<Option<f64>>,
    /// Whether each robot's kind can carry rescuees (`carrying_capacity > 0`): only their
    /// drop-off arrivals count as trips.
    carries: Vec<bool>,
}

impl Recorder {
    /// Nothing counted yet, for `scenario`'s team and tasks.
    pub fn new(scenario: &Scenario) -> Self {
        let k = scenario.tasks.len();
        Self {
            robots: (0..scenario.robots.len())
                .map(|id| RobotMetrics {
                    id,
                    kind: scenario.kind_of(id).name.clone(),
                    ..RobotMetrics::default()
                })
                .collect(),
            costs: vec![RobotCosts::default(); scenario.robots.len()],
            energy_by_task: vec![0.0; k],
            hp_by_task: vec![0.0; k],
            rescued: vec![0; k],
            rounds: Vec::new(),
            rescued_at: scenario.mission.rescued_at,
            back_at_start_s: vec![None; scenario.robots.len()],
            carries: (0..scenario.robots.len())
                .map(|id| scenario.kind_of(id).carrying_capacity > 0)
                .collect(),
        }
    }

    /// The rounds so far (the last may be open).
    pub fn rounds(&self) -> &[RoundRecord] {
        &self.rounds
    }

    /// Each robot's running cost totals (by id), for [`charge_step_costs`] to add a step's
    /// energy spent, HP lost and time in radiation to robot by robot (copied into the robots'
    /// metrics by [`Recorder::result`]); the tasks' sums of those costs are added by
    /// [`Recorder::add_task_costs`].
    pub(crate) fn robot_costs_mut(&mut self) -> &mut [RobotCosts] {
        &mut self.costs
    }

    /// Adds a step's costs (one per robot, by id, from [`charge_step_costs`]) to the sums of
    /// the tasks they count for, in robot order.
    pub(crate) fn add_task_costs(&mut self, costs: &[StepCost]) {
        for c in costs {
            if let Some(t) = c.counted {
                self.energy_by_task[t] += c.spent_pct;
                self.hp_by_task[t] += c.lost_pct;
            }
        }
    }

    /// Robot `id` picked a rescuee of task `t` up (in the current round); it counts as rescued
    /// now under `mission.rescued_at: PickUp`.
    pub fn picked_up(&mut self, id: usize, t: usize) {
        self.robots[id].picked_up += 1;
        if self.rescued_at == RescuedAt::PickUp {
            self.rescue(t, 1);
        }
    }

    /// Robot `id` delivered `n` rescuees of task `t` (in the current round); they count as
    /// rescued now under `mission.rescued_at: DropOff`.
    pub fn delivered(&mut self, id: usize, t: usize, n: u32) {
        self.robots[id].delivered += n;
        if let Some(round) = self.rounds.last_mut().filter(|_| self.carries[id]) {
            round.deliveries[t] += 1;
            round.empty_deliveries[t] += u32::from(n == 0);
        }
        if self.rescued_at == RescuedAt::DropOff {
            self.rescue(t, n);
        }
    }

    /// Counts `n` rescuees for task `t` and the current round.
    fn rescue(&mut self, t: usize, n: u32) {
        self.rescued[t] += n;
        if let Some(round) = self.rounds.last_mut() {
            round.rescued[t] += n;
        }
    }

    /// Task `t`'s group was sent out of its search area at `time_s` because of `cause`.
    pub fn left_area(&mut self, t: usize, time_s: f64, cause: LeaveCause) {
        if let Some(round) = self.rounds.last_mut() {
            round.left_area_s[t] = Some(time_s);
            round.left_because[t] = Some(cause);
        }
    }

    /// A member of task `t`'s group left it for its needs (a level below its threshold).
    pub fn left_for_rest(&mut self, t: usize) {
        if let Some(round) = self.rounds.last_mut() {
            round.left_for_rest[t] += 1;
        }
    }

    /// Robot `id` got back to its start at `time_s`.
    pub fn back_at_start(&mut self, id: usize, time_s: f64) {
        self.back_at_start_s[id] = Some(time_s);
    }

    /// Robot `id` ended a stay at the rest station.
    pub fn recharged(&mut self, id: usize) {
        self.robots[id].recharges += 1;
    }

    /// The planner could not reach a goal of robot `id`.
    pub fn unreachable_goal(&mut self, id: usize) {
        self.robots[id].unreachable_goals += 1;
    }

    /// A round started at `time_s` with `groups` (robot ids by task id).
    pub fn round_started(&mut self, time_s: f64, groups: Vec<Vec<usize>>) {
        let k = groups.len();
        self.back_at_start_s.fill(None);
        self.rounds.push(RoundRecord {
            start_s: time_s,
            end_s: time_s,
            completed: false,
            groups,
            rescued: vec![0; k],
            left_area_s: vec![None; k],
            left_because: vec![None; k],
            deliveries: vec![0; k],
            empty_deliveries: vec![0; k],
            left_for_rest: vec![0; k],
            back_s: vec![None; k],
        });
    }

    /// The open round ended at `time_s`, with every grouped robot back (`completed`) or cut by
    /// the time limit; `members` are the robots still in a group, with their task ids.
    pub fn round_closed(
        &mut self,
        time_s: f64,
        completed: bool,
        members: impl Iterator<Item = (usize, usize)>,
    ) {
        let Some(round) = self.rounds.last_mut() else {
            return;
        };
        round.end_s = time_s;
        round.completed = completed;
        let mut all_back = vec![true; round.back_s.len()];
        for (id, t) in members {
            match self.back_at_start_s[id] {
                Some(s) => round.back_s[t] = Some(round.back_s[t].map_or(s, |b: f64| b.max(s))),
                None => all_back[t] = false,
            }
        }
        for (back, all) in round.back_s.iter_mut().zip(all_back) {
            if !all {
                *back = None;
            }
        }
    }

    /// The trial's metrics: the counts so far with each robot's final levels and the world's
    /// distances and resolver counters.
    pub fn result(
        &self,
        scenario: &Scenario,
        robots: &[MissionRobot],
        world: &World,
        run: TrialInfo<'_>,
    ) -> TrialResult {
        let mut metrics = self.robots.clone();
        for ((m, c), (r, w)) in metrics
            .iter_mut()
            .zip(&self.costs)
            .zip(robots.iter().zip(world.robots()))
        {
            m.energy_spent_pct = c.energy_spent_pct;
            m.hp_lost_pct = c.hp_lost_pct;
            m.time_in_radiation_s = c.time_in_radiation_s;
            m.distance_m = w.distance_travelled_m;
            m.final_energy_pct = r.energy_pct;
            m.final_hp_pct = r.hp_pct;
            m.time_held_s = w.counters.time_held_s;
            m.collision_lists = w.counters.lists_joined as u32;
            m.deadlocks_resolved = w.counters.deadlocks_resolved as u32;
        }
        TrialResult {
            scenario: scenario.name.clone(),
            method: run.method.to_string(),
            trial: run.trial,
            seed: run.seed,
            duration_s: run.duration_s,
            tasks: scenario.task_names(),
            rescued: self.rescued.clone(),
            energy_spent_pct: self.energy_by_task.clone(),
            hp_lost_pct: self.hp_by_task.clone(),
            rounds: self.rounds.clone(),
            robots: metrics,
        }
    }
}

/// What identifies a trial in its result.
#[derive(Debug, Clone, Copy)]
pub struct TrialInfo<'a> {
    /// The grouping method's display name (`GroupingMethod::display_name`), kept as written.
    pub method: &'a str,
    /// Trial index.
    pub trial: u32,
    /// Seed of the starting team.
    pub seed: u64,
    /// Simulated length, seconds.
    pub duration_s: f64,
}
