//! Regrouping at a round's start: robot snapshots, quotas adapted to who is available, and the
//! grouping method's assignment (paper, sections V and VI.B-C).

use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest, KindQuota, RobotSnapshot};

use super::error::MissionError;
use super::needs::needs_vector;
use super::robot::MissionRobot;
use crate::scenario::{Scenario, TaskLevel};

/// Quotas for the robots available this round: per kind with `n` available and scenario quotas
/// `(q_easy, q_hard)`, the hard task is served first: `hard = min(q_hard, n)`,
/// `easy = min(q_easy, n - hard)`. Robots beyond both quotas cannot occur (`count = q_easy +
/// q_hard`). Returns one quota per kind. See `docs/mission-model.md`.
pub fn adapted_quotas(scenario: &Scenario, available_per_kind: &[usize]) -> Vec<KindQuota> {
    scenario
        .kinds
        .iter()
        .zip(available_per_kind)
        .map(|(kind, &n)| {
            let hard = kind.quota[TaskLevel::Hard.index()].min(n);
            let easy = kind.quota[TaskLevel::Easy.index()].min(n - hard);
            KindQuota { easy, hard }
        })
        .collect()
}

/// The snapshot of robot `r` standing at its start position, as grouping methods see it: its
/// needs vector (Eqs. 19-21 with full capacity and resources, refilled each round), energy,
/// HP, and the straight-line distance from its start position to each task's goal point.
pub fn snapshot(scenario: &Scenario, r: &MissionRobot) -> RobotSnapshot {
    let start = scenario.robots[r.id].start_in_world;
    let kind = scenario.kind_of(r.id);
    RobotSnapshot {
        id: r.id,
        kind: scenario.robots[r.id].kind,
        needs: needs_vector(
            kind,
            r.hp_pct,
            r.energy_pct,
            kind.rescuing_resources,
            kind.carrying_capacity,
        ),
        energy_pct: r.energy_pct,
        hp_pct: r.hp_pct,
        distance_to_goal_m: TaskLevel::ALL.map(|l| (scenario.task(l).goal - start).norm()),
    }
}

/// Groups the robots with ids `available` (at their start positions, not resting) with
/// `method`. When one task's adapted quotas are all zero, every available robot goes to the
/// other task without asking the method (a method needs two non-empty groups).
///
/// # Errors
/// [`MissionError::Grouping`] when the method fails or returns an invalid assignment.
pub fn group_available(
    scenario: &Scenario,
    method: &dyn GroupingMethod,
    robots: &[MissionRobot],
    available: &[usize],
) -> Result<Assignment, MissionError> {
    let mut per_kind = vec![0usize; scenario.kinds.len()];
    for &id in available {
        per_kind[scenario.robots[id].kind] += 1;
    }
    let quotas = adapted_quotas(scenario, &per_kind);
    if quotas.iter().all(|q| q.easy == 0) {
        return Ok(Assignment::new(Vec::new(), available.to_vec()));
    }
    if quotas.iter().all(|q| q.hard == 0) {
        return Ok(Assignment::new(available.to_vec(), Vec::new()));
    }
    let snapshots = available
        .iter()
        .map(|&id| snapshot(scenario, &robots[id]))
        .collect();
    let request =
        GroupingRequest::new(snapshots, quotas).map_err(|source| MissionError::Grouping {
            method: method.name().to_string(),
            source,
        })?;
    method
        .group(&request)
        .map_err(|source| MissionError::Grouping {
            method: method.name().to_string(),
            source,
        })
}
