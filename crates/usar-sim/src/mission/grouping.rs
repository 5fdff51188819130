//! Regrouping at a round's start: robot snapshots, quotas adapted to who is available, and the
//! grouping method's assignment (paper, sections V and VI.B-C).

use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest, KindQuota, RobotSnapshot};

use super::error::MissionError;
use super::needs::needs_vector;
use super::robot::MissionRobot;
use crate::scenario::{AwayQuotas, Scenario, TaskLevel};

/// Quotas for the robots available this round, one per kind. Per kind with `n` robots available
/// and scenario quotas `(q_easy, q_hard)` (`n <= q_easy + q_hard = count`), the shortfall
/// `q_easy + q_hard - n` is taken from the quotas by `mission.away_quotas`:
/// - `HardestFirst`: `hard = min(q_hard, n)`, `easy = min(q_easy, n - hard)`;
/// - `EasiestFirst`: `easy = min(q_easy, n)`, `hard = min(q_hard, n - easy)`;
/// - `Even`: one robot at a time from the task whose quota is currently larger (ties: easy).
///
/// See `docs/mission-model.md`.
pub fn adapted_quotas(scenario: &Scenario, available_per_kind: &[usize]) -> Vec<KindQuota> {
    let rule = scenario.mission.away_quotas;
    scenario
        .kinds
        .iter()
        .zip(available_per_kind)
        .map(|(kind, &n)| {
            let (q_easy, q_hard) = (
                kind.quota[TaskLevel::Easy.index()],
                kind.quota[TaskLevel::Hard.index()],
            );
            match rule {
                AwayQuotas::HardestFirst => {
                    let hard = q_hard.min(n);
                    KindQuota {
                        easy: q_easy.min(n - hard),
                        hard,
                    }
                }
                AwayQuotas::EasiestFirst => {
                    let easy = q_easy.min(n);
                    KindQuota {
                        easy,
                        hard: q_hard.min(n - easy),
                    }
                }
                AwayQuotas::Even => {
                    let (mut easy, mut hard) = (q_easy, q_hard);
                    while easy + hard > n {
                        if easy >= hard {
                            easy -= 1;
                        } else {
                            hard -= 1;
                        }
                    }
                    KindQuota { easy, hard }
                }
            }
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
            scenario.mission.min_hp_factor,
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::load;

    fn paper_with(rule: AwayQuotas) -> Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
        let mut s = load(path).expect("paper.ron loads");
        s.mission.away_quotas = rule;
        s
    }

    /// (easy, hard) per kind for carriers (quota 3 + 3) with `n` available.
    fn carriers(rule: AwayQuotas, n: usize) -> (usize, usize) {
        let s = paper_with(rule);
        let q = adapted_quotas(&s, &[n, 4, 2])[0];
        (q.easy, q.hard)
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
        // Everyone available: the scenario's quotas under every rule.
        for rule in [HardestFirst, EasiestFirst, Even] {
            let s = paper_with(rule);
            let q = adapted_quotas(&s, &[6, 4, 2]);
            assert_eq!(
                q.iter().map(|q| (q.easy, q.hard)).collect::<Vec<_>>(),
                [(3, 3), (2, 2), (1, 1)]
            );
        }
    }
}
