//! Regrouping at a round's start: robot snapshots, quotas adapted to who is available, and the
//! grouping method's assignment (paper, sections V and VI.B-C).

use rne_core::grouping::{GroupingMethod, GroupingRequest, RobotSnapshot};

use super::error::MissionError;
use super::metrics::PerTask;
use super::needs::needs_vector;
use super::robot::MissionRobot;
use crate::scenario::{AwayQuotas, Scenario, TaskLevel};

/// Quotas for the robots available this round, one `[easy, hard]` pair per kind (indexed by
/// [`TaskLevel::index`]). Per kind with `n` robots available
/// and scenario quotas `(q_easy, q_hard)` (`n <= q_easy + q_hard = count`), the shortfall
/// `q_easy + q_hard - n` is taken from the quotas by `mission.away_quotas`:
/// - `HardestFirst`: `hard = min(q_hard, n)`, `easy = min(q_easy, n - hard)`;
/// - `EasiestFirst`: `easy = min(q_easy, n)`, `hard = min(q_hard, n - easy)`;
/// - `Even`: one robot at a time from the task whose quota is currently larger (ties: easy).
///
/// See `docs/mission-model.md`.
pub fn adapted_quotas(scenario: &Scenario, available_per_kind: &[usize]) -> Vec<[usize; 2]> {
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
                    [q_easy.min(n - hard), hard]
                }
                AwayQuotas::EasiestFirst => {
                    let easy = q_easy.min(n);
                    [easy, q_hard.min(n - easy)]
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
                    [easy, hard]
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
        distance_to_goal_m: TaskLevel::ALL
            .map(|l| (scenario.task(l).goal - start).norm())
            .to_vec(),
    }
}

/// Groups the robots with ids `available` (at their start positions, not resting) with
/// `method`: a two-task grouping request (tasks indexed by [`TaskLevel::index`], the hard task
/// the harder) with the adapted quotas, and the method's groups as easy and hard ids. A task
/// whose adapted quotas are all zero gets an empty group.
///
/// # Errors
/// [`MissionError::Grouping`] when the method fails or returns an invalid assignment.
pub fn group_available(
    scenario: &Scenario,
    method: &dyn GroupingMethod,
    robots: &[MissionRobot],
    available: &[usize],
) -> Result<PerTask<Vec<usize>>, MissionError> {
    let mut per_kind = vec![0usize; scenario.kinds.len()];
    for &id in available {
        per_kind[scenario.robots[id].kind] += 1;
    }
    let quotas = adapted_quotas(scenario, &per_kind)
        .into_iter()
        .map(Vec::from)
        .collect();
    let snapshots = available
        .iter()
        .map(|&id| snapshot(scenario, &robots[id]))
        .collect();
    let hardest_first = vec![TaskLevel::Hard.index(), TaskLevel::Easy.index()];
    let failed = |source| MissionError::Grouping {
        method: method.name().to_string(),
        source,
    };
    let request = GroupingRequest::new(snapshots, quotas, hardest_first).map_err(failed)?;
    let mut groups = method.group(&request).map_err(failed)?.groups;
    Ok(PerTask {
        hard: std::mem::take(&mut groups[TaskLevel::Hard.index()]),
        easy: std::mem::take(&mut groups[TaskLevel::Easy.index()]),
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
        let [easy, hard] = adapted_quotas(&s, &[n, 4, 2])[0];
        (easy, hard)
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
            assert_eq!(q, [[3, 3], [2, 2], [1, 1]]);
        }
    }
}
