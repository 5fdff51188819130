//! Regrouping at a round's start: robot snapshots, quotas adapted to who is available, and the
//! grouping method's assignment (paper, sections V and VI.B-C), over the scenario's tasks.

use rne_core::grouping::{GroupingMethod, GroupingRequest, RobotSnapshot};

use super::error::MissionError;
use super::needs::needs_vector;
use super::robot::MissionRobot;
use crate::scenario::{AwayQuotas, ResourceStock, Scenario};

/// One kind's task quotas (by task id) shrunk to `n` robots (`n <= ` their sum) by `rule`,
/// with tasks `hardest_first`:
/// - `HardestFirst`: tasks are filled from the hardest down, each with `min(quota, left)`;
/// - `EasiestFirst`: the same from the easiest up;
/// - `Even`: one robot at a time is taken from the task whose quota is currently largest
///   (ties: the easiest of them).
///
/// For two tasks `(q_easy, q_hard)` these are `hard = min(q_hard, n)`, `easy = min(q_easy,
/// n - hard)` and its mirror, and "take from the larger, easy on a tie".
///
/// # Panics
/// If `quota` is empty (no task) or `hardest_first` is not a permutation of its indices; a
/// validated scenario's quotas and task order always are.
pub fn shrink_quotas(
    quota: &[usize],
    n: usize,
    rule: AwayQuotas,
    hardest_first: &[usize],
) -> Vec<usize> {
    let fill = |order: &mut dyn Iterator<Item = &usize>| {
        let mut out = vec![0; quota.len()];
        let mut left = n;
        for &t in order {
            out[t] = quota[t].min(left);
            left -= out[t];
        }
        out
    };
    match rule {
        AwayQuotas::HardestFirst => fill(&mut hardest_first.iter()),
        AwayQuotas::EasiestFirst => fill(&mut hardest_first.iter().rev()),
        AwayQuotas::Even => {
            let mut out = quota.to_vec();
            let mut total: usize = out.iter().sum();
            while total > n {
                // Largest quota; among equals the easiest (last in the hardest-first order).
                let &t = hardest_first
                    .iter()
                    .max_by_key(|&&t| (out[t], position(hardest_first, t)))
                    .expect("at least one task");
                out[t] -= 1;
                total -= 1;
            }
            out
        }
    }
}

fn position(order: &[usize], t: usize) -> usize {
    order.iter().position(|&x| x == t).unwrap_or(usize::MAX)
}

/// Quotas for the robots available this round: one list per kind, by task id, the scenario's
/// quotas shrunk by `mission.away_quotas` ([`shrink_quotas`]) to the `available_per_kind`
/// robots of each kind. See `docs/mission-model.md`.
pub fn adapted_quotas(scenario: &Scenario, available_per_kind: &[usize]) -> Vec<Vec<usize>> {
    let order = scenario.hardest_first();
    scenario
        .kinds
        .iter()
        .zip(available_per_kind)
        .map(|(kind, &n)| shrink_quotas(&kind.quota, n, scenario.mission.away_quotas, &order))
        .collect()
}

/// The snapshot of robot `r` standing at its start position, as grouping methods see it: its
/// needs vector (Eqs. 19-21 with full capacity and resources, refilled each round; under
/// `mission.resource_stock: AtRest` the resources it holds), energy,
/// HP, and the straight-line distance from its start position to each task's goal point (by
/// task id).
pub fn snapshot(scenario: &Scenario, r: &MissionRobot) -> RobotSnapshot {
    let start = scenario.robots[r.id].start_in_world;
    let kind = scenario.kind_of(r.id);
    let resources = match scenario.mission.resource_stock {
        ResourceStock::AtRest => r.resources,
        ResourceStock::PerRound | ResourceStock::TeamPerRound { .. } => kind.rescuing_resources,
    };
    RobotSnapshot {
        id: r.id,
        kind: scenario.robots[r.id].kind,
        needs: needs_vector(
            kind,
            &scenario.mission,
            r.hp_pct,
            r.energy_pct,
            resources,
            kind.carrying_capacity,
        ),
        energy_pct: r.energy_pct,
        hp_pct: r.hp_pct,
        distance_to_goal_m: scenario
            .tasks
            .iter()
            .map(|t| (t.goal - start).norm())
            .collect(),
    }
}

/// Groups the robots with ids `available` (at their start positions, not resting) with
/// `method`: a grouping request over the scenario's tasks (in its difficulty order) with the
/// adapted quotas; returns one sorted id list per task id (a task whose adapted quotas are all
/// zero gets an empty group).
///
/// # Errors
/// [`MissionError::Grouping`] when the method fails or returns an invalid assignment.
pub fn group_available(
    scenario: &Scenario,
    method: &dyn GroupingMethod,
    robots: &[MissionRobot],
    available: &[usize],
) -> Result<Vec<Vec<usize>>, MissionError> {
    let mut per_kind = vec![0usize; scenario.kinds.len()];
    for &id in available {
        per_kind[scenario.robots[id].kind] += 1;
    }
    let quotas = adapted_quotas(scenario, &per_kind);
    let snapshots = available
        .iter()
        .map(|&id| snapshot(scenario, &robots[id]))
        .collect();
    let failed = |error| MissionError::Grouping {
        method: method.name().to_string(),
        error,
    };
    let request =
        GroupingRequest::new(snapshots, quotas, scenario.hardest_first()).map_err(failed)?;
    Ok(method.group(&request).map_err(failed)?.groups)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Carriers (quota 3 + 3, task 0 the harder) with `n` available: `(task 1, task 0)`, i.e.
    /// `(easy, hard)`.
    fn carriers(rule: AwayQuotas, n: usize) -> (usize, usize) {
        let q = shrink_quotas(&[3, 3], n, rule, &[0, 1]);
        (q[1], q[0])
    }

    #[test]
    fn away_quota_rules_shrink_the_documented_task() {
        use AwayQuotas::{EasiestFirst, Even, HardestFirst};
        let all = |rule| (0..=6).map(|n| carriers(rule, n)).collect::<Vec<_>>();
        assert_eq!(
            all(HardestFirst),
            [(0, 0), (0, 1), (0, 2), (0, 3), (1, 3), (2, 3), (3, 3)]
        );
        assert_eq!(
            all(EasiestFirst),
            [(0, 0), (1, 0), (2, 0), (3, 0), (3, 1), (3, 2), (3, 3)]
        );
        assert_eq!(
            all(Even),
            [(0, 0), (0, 1), (1, 1), (1, 2), (2, 2), (2, 3), (3, 3)]
        );
    }

    #[test]
    fn three_tasks_shrink_by_difficulty() {
        // Task 2 hardest, then 0, then 1; quotas 2 each, 3 robots left.
        let order = [2, 0, 1];
        assert_eq!(
            shrink_quotas(&[2, 2, 2], 3, AwayQuotas::HardestFirst, &order),
            [1, 0, 2]
        );
        assert_eq!(
            shrink_quotas(&[2, 2, 2], 3, AwayQuotas::EasiestFirst, &order),
            [1, 2, 0]
        );
        // Even: take from the easiest of the largest first: task 1, then 0, then 2.
        assert_eq!(
            shrink_quotas(&[2, 2, 2], 3, AwayQuotas::Even, &order),
            [1, 1, 1]
        );
        assert_eq!(
            shrink_quotas(&[2, 2, 2], 4, AwayQuotas::Even, &order),
            [1, 1, 2]
        );
        // Everyone available: the quotas unchanged under every rule.
        for rule in [
            AwayQuotas::HardestFirst,
            AwayQuotas::EasiestFirst,
            AwayQuotas::Even,
        ] {
            assert_eq!(shrink_quotas(&[3, 1, 2], 6, rule, &order), [3, 1, 2]);
        }
    }
}
