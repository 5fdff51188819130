//! [`Simulation`]: one trial of the persistent USAR mission (paper, sections IV-VI) on top of
//! the physical [`World`].

use rne_core::NeedsVector;
use rne_core::grouping::GroupingMethod;

use super::error::MissionError;
use super::grouping::group_available;
use super::initial::{draw_initial_levels, trial_seed};
use super::metrics::{PerTask, RobotMetrics, RoundRecord, TrialResult};
use super::needs::{hp_factor, needs_vector};
use super::rescuees::{RescueeField, RescueeStatus};
use super::robot::{MissionRobot, Phase};
use crate::scenario::{
    LoadOnLeave, Locomotion, PointM, Rect, Refresh, Role, RoundStart, Scenario, TaskLevel,
};
use crate::world::World;

/// A claim on a rescuee is given up when the robot has not come `CLAIM_PROGRESS_M` closer to
/// it for `CLAIM_STALL_S` seconds (other robots stand in the way, or it is wedged): the
/// rescuee is then `Skipped` until the next round. Seconds.
pub const CLAIM_STALL_S: f64 = 10.0;
/// See [`CLAIM_STALL_S`]. Metres.
pub const CLAIM_PROGRESS_M: f64 = 0.5;

/// One trial: the world, the team's mission state, the rounds and the metrics.
///
/// ```no_run
/// use rne_core::{TrustModel, Weights, grouping::method_from_name};
/// use usar_sim::{mission::Simulation, scenario};
///
/// let s = scenario::load("scenarios/paper.ron")?;
/// let model = TrustModel::with_weights(Weights::new(s.needs_weights.to_vec())?);
/// let mut sim = Simulation::for_trial(&s, method_from_name("rne", &model)?, 0);
/// let result = sim.run_to_end()?;
/// println!("hard {} easy {}", result.rescued.hard, result.rescued.easy);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Simulation {
    scenario: Scenario,
    method: Box<dyn GroupingMethod>,
    world: World,
    robots: Vec<MissionRobot>,
    fields: [RescueeField; 2],
    sweeps: [Vec<PointM>; 2],
    rounds: Vec<RoundRecord>,
    round_open: bool,
    /// When the first ground member of each task's group entered its search area this round,
    /// seconds (for `mission.search_time_budget_s`).
    search_started_s: [Option<f64>; 2],
    steps_done: u64,
    total_steps: u64,
    trial: u32,
    seed: u64,
    metrics: Vec<RobotMetrics>,
    energy_by_task: PerTask<f64>,
    hp_by_task: PerTask<f64>,
    rescued: PerTask<u32>,
}

impl Simulation {
    /// A trial whose starting team is drawn from `seed` (see [`draw_initial_levels`]), grouped
    /// by `method`. The trial index recorded in the result is 0.
    pub fn new(scenario: &Scenario, method: Box<dyn GroupingMethod>, seed: u64) -> Self {
        let levels = draw_initial_levels(scenario, seed);
        let robots = levels
            .iter()
            .enumerate()
            .map(|(id, l)| {
                let kind = scenario.kind_of(id);
                MissionRobot {
                    id,
                    energy_pct: l.energy_pct,
                    hp_pct: l.hp_pct,
                    phase: Phase::AtStart,
                    task: None,
                    capacity_free: kind.carrying_capacity,
                    resources: kind.rescuing_resources,
                    load: Vec::new(),
                    claim: None,
                    target_best_m: 0.0,
                    target_progress_s: 0.0,
                    sweep_next: 0,
                    sweep_visited: 0,
                    leaving: false,
                    picking_until_s: None,
                }
            })
            .collect();
        let metrics = (0..scenario.robots.len())
            .map(|id| RobotMetrics {
                id,
                kind: scenario.kind_of(id).name.clone(),
                ..RobotMetrics::default()
            })
            .collect();
        let field = |l: TaskLevel| {
            let t = scenario.task(l);
            RescueeField::new(t.rescuees.clone(), t.search_area)
        };
        Self {
            world: World::new(scenario),
            fields: TaskLevel::ALL.map(field),
            sweeps: TaskLevel::ALL
                .map(|l| sweep_waypoints(&scenario.task(l).search_area, sweep_spacing_m(scenario))),
            scenario: scenario.clone(),
            method,
            robots,
            rounds: Vec::new(),
            round_open: false,
            search_started_s: [None; 2],
            steps_done: 0,
            total_steps: scenario.steps_per_trial(),
            trial: 0,
            seed,
            metrics,
            energy_by_task: PerTask::default(),
            hp_by_task: PerTask::default(),
            rescued: PerTask::default(),
        }
    }

    /// Trial `trial` (0-based) of a sweep over `scenario`: seed
    /// `trial_seed(scenario.sim.seed, trial)`, so every method sees the same starting team.
    pub fn for_trial(scenario: &Scenario, method: Box<dyn GroupingMethod>, trial: u32) -> Self {
        let mut sim = Self::new(scenario, method, trial_seed(scenario.sim.seed, trial));
        sim.trial = trial;
        sim
    }

    /// Replaces the trial length, seconds (> 0), e.g. for short runs; default
    /// `mission.duration_s`.
    pub fn with_duration_s(mut self, duration_s: f64) -> Self {
        self.total_steps = (duration_s / self.scenario.sim.dt_s).ceil().max(0.0) as u64;
        self
    }

    /// The physical world (positions, velocities, resolver counters).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The team's mission state, indexed by robot id.
    pub fn robots(&self) -> &[MissionRobot] {
        &self.robots
    }

    /// Robot `id`'s needs vector now (Eqs. 19-21; see [`needs_vector`]): its current HP and
    /// energy, and the rescuing resources and free carrying capacity it holds at this step.
    /// (Grouping methods see the same vector with capacity and resources refilled, as at the
    /// start of a round.)
    ///
    /// # Panics
    /// If `id` is not a robot id.
    pub fn needs(&self, id: usize) -> NeedsVector {
        let r = &self.robots[id];
        needs_vector(
            self.scenario.kind_of(id),
            self.scenario.mission.min_hp_factor,
            r.hp_pct,
            r.energy_pct,
            r.resources,
            r.capacity_free,
        )
    }

    /// The rescuees of task `level`.
    pub fn rescuees(&self, level: TaskLevel) -> &RescueeField {
        &self.fields[level.index()]
    }

    /// The rounds so far (the last may be open).
    pub fn rounds(&self) -> &[RoundRecord] {
        &self.rounds
    }

    /// The scenario being run.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// Simulated time, seconds.
    pub fn time_s(&self) -> f64 {
        self.world.time_s()
    }

    /// Steps taken and steps in the whole trial.
    pub fn progress(&self) -> (u64, u64) {
        (self.steps_done, self.total_steps)
    }

    /// Whether the time limit has been reached.
    pub fn is_finished(&self) -> bool {
        self.steps_done >= self.total_steps
    }

    /// Advances the trial by one step of `sim.dt_s`: regroups if a round is due, lets every
    /// robot decide, steps the world, then accounts energy, HP, detections, pick-ups,
    /// deliveries and arrivals. Does nothing once the trial is finished.
    ///
    /// # Errors
    /// [`MissionError::Grouping`] if the grouping method fails.
    pub fn step(&mut self) -> Result<(), MissionError> {
        if self.is_finished() {
            return Ok(());
        }
        if !self.round_open {
            self.start_round()?;
        }
        self.decide();
        self.world.step();
        self.steps_done += 1;
        self.account();
        if self.round_open && self.round_complete() {
            self.close_round(true);
        }
        if self.is_finished() && self.round_open {
            self.close_round(false);
        }
        Ok(())
    }

    /// Runs the trial to its time limit and returns its metrics.
    ///
    /// # Errors
    /// As [`Simulation::step`].
    pub fn run_to_end(&mut self) -> Result<TrialResult, MissionError> {
        while !self.is_finished() {
            self.step()?;
        }
        Ok(self.result())
    }

    /// The metrics so far (complete once [`Simulation::is_finished`]).
    pub fn result(&self) -> TrialResult {
        let mut robots = self.metrics.clone();
        for (m, (r, w)) in robots
            .iter_mut()
            .zip(self.robots.iter().zip(self.world.robots()))
        {
            m.distance_m = w.distance_travelled_m;
            m.final_energy_pct = r.energy_pct;
            m.final_hp_pct = r.hp_pct;
            m.time_held_s = w.counters.time_held_s;
            m.collision_lists = w.counters.lists_joined as u32;
            m.deadlocks_resolved = w.counters.deadlocks_resolved as u32;
        }
        TrialResult {
            scenario: self.scenario.name.clone(),
            method: self.method.name().to_ascii_uppercase(),
            trial: self.trial,
            seed: self.seed,
            duration_s: self.total_steps as f64 * self.scenario.sim.dt_s,
            rescued: self.rescued,
            energy_spent_pct: self.energy_by_task,
            hp_lost_pct: self.hp_by_task,
            rounds: self.rounds.clone(),
            robots,
        }
    }

    // ----- rounds -------------------------------------------------------------------------

    fn start_round(&mut self) -> Result<(), MissionError> {
        let available: Vec<usize> = self
            .robots
            .iter()
            .filter(|r| r.phase == Phase::AtStart)
            .map(|r| r.id)
            .collect();
        let everyone_back = available.len() == self.robots.len();
        if available.is_empty()
            || (self.scenario.mission.round_start == RoundStart::AllBack && !everyone_back)
        {
            return Ok(());
        }
        let groups = group_available(
            &self.scenario,
            self.method.as_ref(),
            &self.robots,
            &available,
        )?;
        for field in &mut self.fields {
            field.forget();
        }
        self.search_started_s = [None; 2];
        for level in TaskLevel::ALL {
            let ids = groups.get(level);
            let sweep_len = self.sweeps[level.index()].len().max(1);
            for (ordinal, &id) in ids.iter().enumerate() {
                let kind = self.scenario.kind_of(id);
                let r = &mut self.robots[id];
                r.task = Some(level);
                r.phase = Phase::ToSearchArea;
                r.capacity_free = kind.carrying_capacity;
                r.resources = kind.rescuing_resources;
                r.claim = None;
                r.sweep_next = ordinal * sweep_len / ids.len();
                r.sweep_visited = 0;
                let task = self.scenario.task(level);
                let target = match kind.locomotion {
                    Locomotion::Ground => task.goal,
                    Locomotion::Aerial => task.search_area.center(),
                };
                let _ = self.world.set_goal(id, Some(target));
            }
        }
        self.rounds.push(RoundRecord {
            start_s: self.world.time_s(),
            end_s: self.world.time_s(),
            completed: false,
            groups,
            rescued: PerTask::default(),
        });
        self.round_open = true;
        Ok(())
    }

    fn round_complete(&self) -> bool {
        self.robots
            .iter()
            .filter(|r| r.task.is_some())
            .all(|r| r.phase == Phase::AtStart)
    }

    fn close_round(&mut self, completed: bool) {
        if let Some(round) = self.rounds.last_mut() {
            round.end_s = self.world.time_s();
            round.completed = completed;
        }
        for r in &mut self.robots {
            r.task = None;
        }
        self.round_open = false;
    }

    // ----- decisions before the physics step ----------------------------------------------

    fn has_observer(&self, level: TaskLevel) -> bool {
        self.robots.iter().any(|r| {
            r.task == Some(level)
                && !r.is_resting()
                && self.scenario.kind_of(r.id).role == Role::Observer
        })
    }

    /// The group pool of `level`: rescuing resources held by its members that are not away
    /// resting, and how many of those members hold a claim.
    fn group_pool(&self, level: TaskLevel) -> (u32, u32) {
        self.robots
            .iter()
            .filter(|r| r.task == Some(level) && !r.is_resting())
            .fold((0, 0), |(p, c), r| {
                (p + r.resources, c + u32::from(r.claim.is_some()))
            })
    }

    /// Resources of the members of `level`'s group not yet promised to a claim.
    fn unclaimed_pool(&self, level: TaskLevel) -> u32 {
        let (pool, claims) = self.group_pool(level);
        pool.saturating_sub(claims)
    }

    fn decide(&mut self) {
        for level in TaskLevel::ALL {
            if self.group_should_leave(level) {
                self.leave_search_area(level);
            }
        }
        let observer = TaskLevel::ALL.map(|l| self.has_observer(l));
        for id in 0..self.robots.len() {
            let kind = self.scenario.kind_of(id);
            let r = &self.robots[id];
            let f = hp_factor(r.hp_pct, self.scenario.mission.min_hp_factor);
            let blind = r.task.is_some_and(|t| !observer[t.index()]);
            let penalty = if blind {
                self.scenario.mission.no_observer_speed_factor
            } else {
                1.0
            };
            // Factors are finite and >= 0 and ids are valid, so the setters cannot fail.
            let _ = self.world.set_speed_factor(id, f * penalty);
            let _ = self.world.set_sensing_factor(id, f);
            let _ = self.world.set_priority_key(id, r.energy_pct);
            if kind.locomotion == Locomotion::Ground && r.is_on_task() {
                self.decide_ground_on_task(id, blind);
            }
        }
    }

    /// Whether `level`'s group must leave its search area (see `docs/mission-model.md`): its
    /// pool of resources or its ground members' free capacity is used up, nothing more is
    /// to be had (every ground member waits and no observer is still flying in), or its search
    /// time budget (`mission.search_time_budget_s`) is spent. Called every step, so it
    /// allocates nothing.
    fn group_should_leave(&self, level: TaskLevel) -> bool {
        let on_task = || {
            self.robots
                .iter()
                .filter(move |r| r.task == Some(level) && r.is_on_task())
        };
        let ground =
            |r: &&MissionRobot| self.scenario.kind_of(r.id).locomotion == Locomotion::Ground;
        if on_task().next().is_none() {
            return false;
        }
        let (pool, _) = self.group_pool(level);
        let free_capacity: u32 = on_task().filter(ground).map(|r| r.capacity_free).sum();
        let observer_arriving = on_task().any(|r| {
            self.scenario.kind_of(r.id).role == Role::Observer && r.phase == Phase::ToSearchArea
        });
        let nothing_more =
            on_task().filter(ground).all(|r| r.phase == Phase::Waiting) && !observer_arriving;
        let out_of_time = match (
            self.scenario.mission.search_time_budget_s,
            self.search_started_s[level.index()],
        ) {
            (Some(budget_s), Some(start_s)) => self.world.time_s() - start_s >= budget_s,
            _ => false,
        };
        pool == 0 || free_capacity == 0 || nothing_more || out_of_time
    }

    fn leave_search_area(&mut self, level: TaskLevel) {
        let drop_off = self.scenario.task(level).drop_off.center;
        for id in 0..self.robots.len() {
            let r = &mut self.robots[id];
            if r.task != Some(level) || !r.is_on_task() {
                continue;
            }
            if let Some(i) = r.claim.take() {
                self.fields[level.index()].release(i);
            }
            r.picking_until_s = None;
            r.phase = Phase::ToDropOff;
            let _ = self.world.set_goal(id, Some(drop_off));
        }
    }

    fn decide_ground_on_task(&mut self, id: usize, blind: bool) {
        let Some(level) = self.robots[id].task else {
            return;
        };
        if self.robots[id].claim.is_some() {
            return;
        }
        let pos = self.world.robot(id).position;
        let can_rescue = self.robots[id].capacity_free > 0 && self.unclaimed_pool(level) > 0;
        if can_rescue {
            // A rescuee where this robot's body would overlap another ground robot's body plus
            // the safety margin cannot be reached.
            let reach = self.world.robot(id).radius_m + self.scenario.collision.safety_margin_m;
            let occupied: Vec<(PointM, f64)> = self
                .world
                .robots()
                .iter()
                .filter(|o| o.id != id && o.locomotion == Locomotion::Ground)
                .map(|o| (o.position, o.radius_m + reach))
                .collect();
            let free = |p: &PointM| occupied.iter().all(|(c, r)| (c - p).norm() > *r);
            let field = &mut self.fields[level.index()];
            while let Some(i) = field.nearest_known_waiting(&pos, free) {
                let target = field.position(i);
                if self.world.set_goal(id, Some(target)).is_ok() {
                    field.claim(i, id);
                    let r = &mut self.robots[id];
                    r.claim = Some(i);
                    r.target_best_m = (target - pos).norm();
                    r.target_progress_s = self.world.time_s();
                    r.phase = Phase::Searching;
                    return;
                }
                field.settle(i, RescueeStatus::Unreachable);
            }
        }
        let r = &self.robots[id];
        match r.phase {
            Phase::ToSearchArea => {}
            _ if blind && can_rescue && r.sweep_visited < self.sweeps[level.index()].len() => {
                let w = self.world.robot(id);
                let stalled = match w.goal {
                    None => true,
                    Some(g) => w.goal_reached || self.sweep_stalled(id, (g - w.position).norm()),
                };
                if stalled {
                    self.next_sweep_waypoint(id, level);
                }
            }
            Phase::Waiting => {}
            _ => {
                self.robots[id].phase = Phase::Waiting;
                let _ = self.world.set_goal(id, None);
            }
        }
    }

    /// Whether a sweeping robot, `d` metres from its waypoint, has stalled (no
    /// `CLAIM_PROGRESS_M` of progress for `CLAIM_STALL_S`, e.g. a robot parked on the
    /// waypoint); records progress otherwise.
    fn sweep_stalled(&mut self, id: usize, d: f64) -> bool {
        let now = self.world.time_s();
        let r = &mut self.robots[id];
        if d < r.target_best_m - CLAIM_PROGRESS_M {
            r.target_best_m = d;
            r.target_progress_s = now;
        }
        now - r.target_progress_s > CLAIM_STALL_S
    }

    fn next_sweep_waypoint(&mut self, id: usize, level: TaskLevel) {
        let sweep = &self.sweeps[level.index()];
        let pos = self.world.robot(id).position;
        let now = self.world.time_s();
        while self.robots[id].sweep_visited < sweep.len() {
            let r = &mut self.robots[id];
            let p = sweep[r.sweep_next % sweep.len()];
            r.sweep_next = (r.sweep_next + 1) % sweep.len();
            r.sweep_visited += 1;
            r.phase = Phase::Searching;
            r.target_best_m = (p - pos).norm();
            r.target_progress_s = now;
            if self.world.set_goal(id, Some(p)).is_ok() {
                return;
            }
        }
    }

    // ----- accounting after the physics step ----------------------------------------------

    fn account(&mut self) {
        let m = self.scenario.mission.clone();
        let dt = self.scenario.sim.dt_s;
        let now = self.world.time_s();
        for id in 0..self.robots.len() {
            let w = self.world.robot(id);
            let (moved, step_m, pos, reached, radius) = (
                w.moved_this_step,
                w.step_distance_m,
                w.position,
                w.goal_reached,
                w.radius_m,
            );
            let rad = self.world.radiation_factor(id);
            let r = &mut self.robots[id];
            let met = &mut self.metrics[id];
            if moved {
                let cost = m.energy_pct_per_moving_step + m.energy_pct_per_m * step_m;
                let spent = cost.min(r.energy_pct);
                r.energy_pct -= spent;
                met.energy_spent_pct += spent;
                if let Some(t) = r.task {
                    *self.energy_by_task.get_mut(t) += spent;
                }
            }
            if rad > 0.0 {
                let lost = (m.hp_pct_per_step_in_radiation * rad).min(r.hp_pct);
                r.hp_pct -= lost;
                met.hp_lost_pct += lost;
                met.time_in_radiation_s += dt;
                if let Some(t) = r.task {
                    *self.hp_by_task.get_mut(t) += lost;
                }
            }
            let kind = self.scenario.kind_of(id);
            if let Some(t) = r.task
                && r.is_on_task()
            {
                let range = radius + kind.observing_range_m * hp_factor(r.hp_pct, m.min_hp_factor);
                self.fields[t.index()].detect(&pos, range);
            }
            self.advance_phase(id, pos, reached, now);
            let r = &self.robots[id];
            if !r.is_resting() && (r.energy_pct < m.low_energy_pct || r.hp_pct < m.low_hp_pct) {
                self.go_rest(id);
            }
        }
    }

    fn advance_phase(&mut self, id: usize, pos: PointM, reached: bool, now: f64) {
        let r = &self.robots[id];
        match r.phase {
            Phase::ToSearchArea | Phase::Searching | Phase::Waiting => {
                let level = r.task.expect("robots on a task belong to a group");
                if r.claim.is_some() {
                    self.try_pick_up(id, level, pos, reached);
                }
                let in_area = self.scenario.task(level).search_area.contains(&pos);
                if in_area && self.scenario.kind_of(id).locomotion == Locomotion::Ground {
                    self.search_started_s[level.index()].get_or_insert(now);
                }
                let r = &mut self.robots[id];
                if r.phase == Phase::ToSearchArea && (reached || in_area) {
                    r.phase = Phase::Searching;
                    if r.claim.is_none() {
                        // In the area now: the approach goal (the task's goal point, where
                        // others may stand) is dropped; the next decision picks a rescuee, a
                        // sweep waypoint, or waiting.
                        let _ = self.world.set_goal(id, None);
                    }
                }
            }
            Phase::ToDropOff => {
                let level = r
                    .task
                    .expect("robots going to a drop-off belong to a group");
                if reached || self.scenario.task(level).drop_off.contains(&pos) {
                    self.deliver(id, level);
                    if self.robots[id].leaving {
                        self.go_rest(id);
                    } else {
                        self.robots[id].phase = Phase::ToStart;
                        let start = self.scenario.robots[id].start_in_world;
                        let _ = self.world.set_goal(id, Some(start));
                    }
                }
            }
            Phase::ToStart | Phase::RestToStart => {
                if reached {
                    self.robots[id].phase = Phase::AtStart;
                    let _ = self.world.set_goal(id, None);
                }
            }
            Phase::ToRest => {
                if reached || self.scenario.rest_station.contains(&pos) {
                    self.robots[id].phase = Phase::Recharging {
                        until_s: now + self.scenario.mission.recharge_s,
                    };
                    let _ = self.world.set_goal(id, None);
                }
            }
            Phase::Recharging { until_s } => {
                if now + 1e-9 >= until_s {
                    let m = &self.scenario.mission;
                    let r = &mut self.robots[id];
                    let both = m.refresh == Refresh::Both;
                    if both || r.energy_pct < m.low_energy_pct {
                        r.energy_pct = 100.0;
                    }
                    if both || r.hp_pct < m.low_hp_pct {
                        r.hp_pct = 100.0;
                    }
                    r.phase = Phase::RestToStart;
                    self.metrics[id].recharges += 1;
                    let start = self.scenario.robots[id].start_in_world;
                    let _ = self.world.set_goal(id, Some(start));
                }
            }
            Phase::AtStart => {}
        }
    }

    fn try_pick_up(&mut self, id: usize, level: TaskLevel, pos: PointM, reached: bool) {
        let Some(i) = self.robots[id].claim else {
            return;
        };
        let field = &mut self.fields[level.index()];
        let reach =
            self.scenario.kind_of(id).body_radius_m + self.scenario.navigation.waypoint_tolerance_m;
        let d = (field.position(i) - pos).norm();
        if d > reach + 1e-9 {
            if reached {
                // Arrived at the effective goal but the rescuee is out of reach (it lies
                // inside inflated debris): nobody will get it.
                field.settle(i, RescueeStatus::Unreachable);
                self.robots[id].claim = None;
            } else {
                let now = self.world.time_s();
                let r = &mut self.robots[id];
                if d < r.target_best_m - CLAIM_PROGRESS_M {
                    r.target_best_m = d;
                    r.target_progress_s = now;
                } else if now - r.target_progress_s > CLAIM_STALL_S {
                    field.settle(i, RescueeStatus::Skipped);
                    r.claim = None;
                }
            }
            return;
        }
        // Within reach: the rescue takes `pickup_s` of standing still (0: at once).
        let pickup_s = self.scenario.mission.pickup_s;
        if pickup_s > 0.0 {
            let now = self.world.time_s();
            match self.robots[id].picking_until_s {
                None => {
                    self.robots[id].picking_until_s = Some(now + pickup_s);
                    let _ = self.world.set_goal(id, None);
                    return;
                }
                Some(until_s) if now + 1e-9 < until_s => return,
                Some(_) => self.robots[id].picking_until_s = None,
            }
        }
        let Some(donor) = self
            .robots
            .iter()
            .position(|r| r.task == Some(level) && !r.is_resting() && r.resources > 0)
        else {
            field.release(i);
            self.robots[id].claim = None;
            return;
        };
        self.robots[donor].resources -= 1;
        field.pick_up(i, id);
        let r = &mut self.robots[id];
        r.claim = None;
        r.capacity_free -= 1;
        r.load.push(i);
        self.metrics[id].picked_up += 1;
        let _ = self.world.set_goal(id, None);
    }

    fn deliver(&mut self, id: usize, level: TaskLevel) {
        let load = std::mem::take(&mut self.robots[id].load);
        let n = load.len() as u32;
        for i in load {
            self.fields[level.index()].settle(i, RescueeStatus::Delivered);
        }
        *self.rescued.get_mut(level) += n;
        self.metrics[id].delivered += n;
        if let Some(round) = self.rounds.last_mut() {
            *round.rescued.get_mut(level) += n;
        }
    }

    /// Robot `id` leaves its task and group for the rest station (energy or HP below its
    /// threshold). Its claim is released; its load is abandoned, put back, or first delivered
    /// (`mission.load_on_leave`). A robot delivering first stays in its group, marked
    /// [`MissionRobot::leaving`], until it reaches the drop-off, and comes back here then.
    fn go_rest(&mut self, id: usize) {
        let rule = self.scenario.mission.load_on_leave;
        let r = &mut self.robots[id];
        if let Some(level) = r.task {
            let field = &mut self.fields[level.index()];
            if let Some(i) = r.claim.take() {
                field.release(i);
            }
            r.picking_until_s = None;
            if rule == LoadOnLeave::DeliverFirst && !r.leaving && !r.load.is_empty() {
                r.leaving = true;
                r.phase = Phase::ToDropOff;
                let drop_off = self.scenario.task(level).drop_off.center;
                let _ = self.world.set_goal(id, Some(drop_off));
                return;
            }
            for i in r.load.drain(..) {
                match rule {
                    LoadOnLeave::ReturnToArea => field.put_back(i),
                    LoadOnLeave::Abandon | LoadOnLeave::DeliverFirst => {
                        field.settle(i, RescueeStatus::Abandoned);
                    }
                }
            }
        }
        r.leaving = false;
        r.task = None;
        r.phase = Phase::ToRest;
        let _ = self
            .world
            .set_goal(id, Some(self.scenario.rest_station.center));
    }
}

/// Blind-search waypoints over a search area: a lawn-mower pattern of `ceil(height /
/// spacing_m)` rows (at least 1) at the centres of equal horizontal strips, alternating
/// direction, starting at the bottom-left; along each row `ceil(width / spacing_m)` points (at
/// least 1) at the centres of equal vertical strips. Rows and points are thus at most
/// `spacing_m` apart and at most `spacing_m / 2` from the area's edges, so a robot following
/// them passes within `spacing_m / 2` of every point between the first and the last column
/// and within `spacing_m / √2` of every point of the area (the corners). `spacing_m` is finite
/// and `> 0`.
pub fn sweep_waypoints(area: &Rect, spacing_m: f64) -> Vec<PointM> {
    let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
    let nx = ((w / spacing_m).ceil() as usize).max(1);
    let ny = ((h / spacing_m).ceil() as usize).max(1);
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        let y = area.min.y + (j as f64 + 0.5) * h / ny as f64;
        for k in 0..nx {
            let i = if j % 2 == 0 { k } else { nx - 1 - k };
            out.push(PointM::new(
                area.min.x + (i as f64 + 0.5) * w / nx as f64,
                y,
            ));
        }
    }
    out
}

/// The spacing of a scenario's blind-search rows, metres: `mission.sweep_spacing_m` if set,
/// otherwise the narrowest detection width of its ground kinds, `2 * (body_radius_m +
/// observing_range_m)` (at full HP), so that a sweep detects every rescuee of the area.
pub fn sweep_spacing_m(scenario: &Scenario) -> f64 {
    scenario.mission.sweep_spacing_m.unwrap_or_else(|| {
        scenario
            .kinds
            .iter()
            .filter(|k| k.locomotion == Locomotion::Ground)
            .map(|k| 2.0 * (k.body_radius_m + k.observing_range_m))
            .fold(f64::INFINITY, f64::min)
            .min(f64::MAX)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sweep_passes_within_half_its_spacing_of_every_point() {
        let area = Rect {
            min: PointM::new(6.0, 47.0),
            max: PointM::new(26.0, 59.0),
        };
        for spacing in [0.9, 2.0, 3.3] {
            let w = sweep_waypoints(&area, spacing);
            // Distance from p to the polyline through the waypoints.
            let dist = |p: &PointM| {
                w.windows(2)
                    .map(|s| {
                        let (a, b) = (s[0], s[1]);
                        let ab = b - a;
                        let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
                        (a + ab * t - p).norm()
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            for i in 0..=40 {
                for j in 0..=24 {
                    let p = PointM::new(
                        area.min.x + (area.max.x - area.min.x) * f64::from(i) / 40.0,
                        area.min.y + (area.max.y - area.min.y) * f64::from(j) / 24.0,
                    );
                    let inner = p.x >= w[0].x && p.x <= w[1].x.max(w[w.len() - 1].x);
                    let bound = if inner {
                        spacing / 2.0
                    } else {
                        spacing / std::f64::consts::SQRT_2
                    };
                    assert!(
                        dist(&p) <= bound + 1e-9,
                        "spacing {spacing}: {p:?} is {} m from the sweep",
                        dist(&p)
                    );
                }
            }
        }
    }
}
