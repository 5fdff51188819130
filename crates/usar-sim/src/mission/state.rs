//! The mission's state: plain data that the systems ([`super::round_clock`], [`super::rest`], [`super::decide`],
//! [`super::account`]) update and [`super::Simulation`] owns, apart from the physical world.

use super::events::MissionEvent;
use super::initial::InitialLevels;
use super::recorder::Recorder;
use super::rescuees::RescueeField;
use super::robot::{MissionRobot, Phase};
use super::search_pattern::sweep_waypoints;
use super::step_costs::StepCost;
use crate::scenario::{PointM, Scenario, sweep_spacing_m};

/// Everything the mission layer knows about a trial besides the world: the team, the rescuees
/// of each task, the blind-search patterns, the rounds and the metrics so far. Per-task vectors
/// are indexed by task id.
#[derive(Debug, Clone)]
pub struct MissionState {
    /// The team, indexed by robot id.
    pub robots: Vec<MissionRobot>,
    /// The rescuees of each task.
    pub fields: Vec<RescueeField>,
    /// The blind-search waypoints of each task's search area.
    pub sweeps: Vec<Vec<PointM>>,
    /// Whether a round is under way.
    pub round_open: bool,
    /// The team's stock of rescuing resources left this round under `mission.resource_stock:
    /// TeamPerRound` (set at each round's start, drawn by both groups' pick-ups); `None` under
    /// the other rules, where each group draws on its members' resources.
    pub team_stock: Option<u32>,
    /// When the first ground member of each task's group entered its search area this round,
    /// seconds (for `mission.search_time_budget_s`).
    pub search_started_s: Vec<Option<f64>>,
    /// The metrics being recorded, rounds included.
    pub recorder: Recorder,
    /// What happened in the mission during the last step, in order (cleared at each step's
    /// start; the buffer is reused, so recording allocates only when a step has more events
    /// than any before it).
    pub events: Vec<MissionEvent>,
    /// Per-task figures of the decision system, recomputed each step in reused buffers.
    pub(crate) tally: TaskTally,
    /// Each robot's costs of the last step, by id (a reused buffer of the accounting system).
    pub(crate) step_costs: Vec<StepCost>,
}

/// Per-task figures the decision system computes once per step instead of once per robot
/// (buffers reused: no allocation per step).
#[derive(Debug, Clone, Default)]
pub(crate) struct TaskTally {
    /// Whether each task's group has an observer still in it.
    pub(crate) observer: Vec<bool>,
    /// Each task's [`MissionState::unclaimed_pool`], kept up to date as robots claim; under
    /// `resource_stock: TeamPerRound`, the team's stock less every group's claims, for each.
    pub(crate) unclaimed: Vec<u32>,
    /// Scratch of the tally: each task's claims.
    pub(crate) claims: Vec<u32>,
    /// Each task's figures for the decision to leave its search area.
    pub(crate) leave: Vec<LeaveFigures>,
}

/// What decides whether a task's group leaves its search area (see `decide::group_should_leave`),
/// gathered for every task in one pass over the team.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LeaveFigures {
    /// Some member is in the search phase (on the way, searching or waiting).
    pub(crate) any_on_task: bool,
    /// Resources held by the members not away for their needs ([`MissionState::group_pool`]);
    /// under `resource_stock: TeamPerRound`, the team's stock left.
    pub(crate) pool: u32,
    /// Free capacity of the ground members in the search phase, rescuees.
    pub(crate) free_capacity: u32,
    /// An observer in the search phase is still on its way to the area.
    pub(crate) observer_arriving: bool,
    /// Every ground member in the search phase waits.
    pub(crate) ground_all_waiting: bool,
    /// Every member in the search phase has entered the search area this round.
    pub(crate) all_arrived: bool,
}

impl Default for LeaveFigures {
    /// The figures of a task with no member.
    fn default() -> Self {
        Self {
            any_on_task: false,
            pool: 0,
            free_capacity: 0,
            observer_arriving: false,
            ground_all_waiting: true,
            all_arrived: true,
        }
    }
}

impl MissionState {
    /// The state at a trial's start: every robot at its start with the given levels, full
    /// capacity and resources and no task; every rescuee waiting and unknown; no round yet.
    pub fn new(scenario: &Scenario, levels: &[InitialLevels]) -> Self {
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
                    reached_area: false,
                    last_task: None,
                    rests_in_round: false,
                }
            })
            .collect();
        let spacing = sweep_spacing_m(scenario);
        Self {
            robots,
            fields: scenario
                .tasks
                .iter()
                .map(|t| RescueeField::new(t.rescuees.clone(), t.search_area))
                .collect(),
            sweeps: scenario
                .tasks
                .iter()
                .map(|t| sweep_waypoints(&t.search_area, spacing, scenario.mission.sweep_pattern))
                .collect(),
            round_open: false,
            team_stock: None,
            search_started_s: vec![None; scenario.tasks.len()],
            recorder: Recorder::new(scenario),
            events: Vec::new(),
            tally: TaskTally::default(),
            step_costs: Vec::new(),
        }
    }

    /// The members of task `t`'s group still in it (not away for their needs).
    pub fn members(&self, t: usize) -> impl Iterator<Item = &MissionRobot> {
        self.robots
            .iter()
            .filter(move |r| r.task == Some(t) && !r.is_resting())
    }

    /// The rescuing resources task `t`'s group draws on and how many of its members (those
    /// not away for their needs) hold a claim. The resources are the members' own, summed
    /// (saturating at `u32::MAX`); under `mission.resource_stock: TeamPerRound` (while
    /// [`MissionState::team_stock`] is set) they are the team's stock left, which every
    /// group draws on, for a task some robot belongs to (0 for a task nobody does), as the
    /// decision system counts them.
    pub fn group_pool(&self, t: usize) -> (u32, u32) {
        let (own, claims) = self.members(t).fold((0u32, 0u32), |(p, c), r| {
            (
                p.saturating_add(r.resources),
                c + u32::from(r.claim.is_some()),
            )
        });
        match self.team_stock {
            Some(stock) => {
                let has_group = self.robots.iter().any(|r| r.task == Some(t));
                (if has_group { stock } else { 0 }, claims)
            }
            None => (own, claims),
        }
    }

    /// The resources task `t`'s group may still promise to a claim: its pool less its
    /// members' claims ([`MissionState::group_pool`]); under `TeamPerRound` the team's stock
    /// less the claims of every group's members, the same for every task.
    pub fn unclaimed_pool(&self, t: usize) -> u32 {
        if let Some(stock) = self.team_stock {
            let claims = self
                .robots
                .iter()
                .filter(|r| r.task.is_some() && !r.is_resting() && r.claim.is_some())
                .count();
            return stock.saturating_sub(u32::try_from(claims).unwrap_or(u32::MAX));
        }
        let (pool, claims) = self.group_pool(t);
        pool.saturating_sub(claims)
    }
}
