//! The input of a grouping method: robot snapshots, per-kind task quotas and the tasks'
//! difficulty order (paper Sec. V and VI.C, generalised from two tasks to `K`).

use serde::{Deserialize, Serialize};

use crate::error::{Result, RneError};
use crate::grouping::robot::RobotSnapshot;

/// A validated team-level grouping request over `K >= 1` tasks.
///
/// * `robots`: the team, stored sorted by id.
/// * `quotas[k][t]`: how many robots of kind `k` go to task `t` (`quotas.len()` kinds, each
///   list of length `K`). A quota may be 0, and a task may get no robot at all.
/// * `hardest_first`: the task indices `0..K` ordered from the hardest task to the easiest, a
///   permutation of `0..K` (paper, two tasks: `[hard, easy]`). Tasks are data: their indices
///   are only positions in the quota and distance lists, their difficulty is this order.
///
/// Invariants: `K >= 1`; ids unique; every kind `< quotas.len()`; every quota list and every
/// `distance_to_goal_m` has length `K`; for each kind the task quotas sum to its number of
/// robots; energy, HP and distances finite; at least one robot.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawRequest", into = "RawRequest")]
pub struct GroupingRequest {
    robots: Vec<RobotSnapshot>,
    quotas: Vec<Vec<usize>>,
    hardest_first: Vec<usize>,
    /// `rank[t]`: position of task `t` in `hardest_first` (0 = hardest).
    rank: Vec<usize>,
}

#[derive(Serialize, Deserialize)]
struct RawRequest {
    robots: Vec<RobotSnapshot>,
    quotas: Vec<Vec<usize>>,
    hardest_first: Vec<usize>,
}

impl TryFrom<RawRequest> for GroupingRequest {
    type Error = RneError;
    fn try_from(r: RawRequest) -> Result<Self> {
        Self::new(r.robots, r.quotas, r.hardest_first)
    }
}

impl From<GroupingRequest> for RawRequest {
    fn from(r: GroupingRequest) -> Self {
        Self {
            robots: r.robots,
            quotas: r.quotas,
            hardest_first: r.hardest_first,
        }
    }
}

/// Ranks of a difficulty order (`rank[t]` = position of task `t`), or `None` if the order is
/// not a permutation of `0..order.len()`.
fn ranks(order: &[usize]) -> Option<Vec<usize>> {
    let mut rank = vec![usize::MAX; order.len()];
    for (position, &task) in order.iter().enumerate() {
        let slot = rank.get_mut(task)?;
        if *slot != usize::MAX {
            return None;
        }
        *slot = position;
    }
    Some(rank)
}

/// Checks one robot's scalar state against `tasks` tasks and `kinds` kinds.
fn check_robot(r: &RobotSnapshot, tasks: usize, kinds: usize) -> Result<()> {
    for (field, value) in [("energy_pct", r.energy_pct), ("hp_pct", r.hp_pct)] {
        if !value.is_finite() {
            return Err(RneError::InvalidRobotState {
                id: r.id,
                field,
                value,
            });
        }
    }
    if r.distance_to_goal_m.len() != tasks {
        return Err(RneError::DistanceCount {
            id: r.id,
            tasks,
            actual: r.distance_to_goal_m.len(),
        });
    }
    if let Some((task, &value)) = r
        .distance_to_goal_m
        .iter()
        .enumerate()
        .find(|(_, d)| !d.is_finite())
    {
        return Err(RneError::InvalidDistance {
            id: r.id,
            task,
            value,
        });
    }
    if r.kind >= kinds {
        return Err(RneError::UnknownKind {
            id: r.id,
            kind: r.kind,
            kinds,
        });
    }
    Ok(())
}

impl GroupingRequest {
    /// Validates and builds a request over `K = hardest_first.len()` tasks.
    ///
    /// `quotas[k][t]` robots of kind `k` go to task `t`; `hardest_first` lists the task
    /// indices from the hardest to the easiest. The paper's two tasks with easy = 0 and
    /// hard = 1: `quotas = [[3, 3], [2, 2], [1, 1]]`, `hardest_first = [1, 0]`.
    ///
    /// # Errors
    /// [`RneError::Empty`] (no task, or no robot); [`RneError::InvalidTaskOrder`] if
    /// `hardest_first` is not a permutation of `0..K`; [`RneError::DuplicateRobot`];
    /// [`RneError::InvalidRobotState`] (non-finite energy or HP); [`RneError::DistanceCount`]
    /// and [`RneError::InvalidDistance`] (distances not `K` finite values);
    /// [`RneError::UnknownKind`]; [`RneError::QuotaTaskCount`] (a kind's quota list is not of
    /// length `K`); [`RneError::QuotaMismatch`] (a kind's quotas do not sum to its robots).
    pub fn new(
        mut robots: Vec<RobotSnapshot>,
        quotas: Vec<Vec<usize>>,
        hardest_first: Vec<usize>,
    ) -> Result<Self> {
        if hardest_first.is_empty() {
            return Err(RneError::Empty { what: "task list" });
        }
        let rank = ranks(&hardest_first).ok_or_else(|| RneError::InvalidTaskOrder {
            order: hardest_first.clone(),
        })?;
        let tasks = hardest_first.len();
        if robots.is_empty() {
            return Err(RneError::Empty { what: "team" });
        }
        robots.sort_by_key(|r| r.id);
        if let Some(w) = robots.windows(2).find(|w| w[0].id == w[1].id) {
            return Err(RneError::DuplicateRobot(w[0].id));
        }
        let mut counts = vec![0usize; quotas.len()];
        for r in &robots {
            check_robot(r, tasks, quotas.len())?;
            counts[r.kind] += 1;
        }
        for (kind, (q, &available)) in quotas.iter().zip(&counts).enumerate() {
            if q.len() != tasks {
                return Err(RneError::QuotaTaskCount {
                    kind,
                    tasks,
                    actual: q.len(),
                });
            }
            if q.iter().try_fold(0usize, |sum, &x| sum.checked_add(x)) != Some(available) {
                return Err(RneError::QuotaMismatch {
                    kind,
                    available,
                    quotas: q.clone(),
                });
            }
        }
        Ok(Self {
            robots,
            quotas,
            hardest_first,
            rank,
        })
    }

    /// The robots, sorted by id.
    pub fn robots(&self) -> &[RobotSnapshot] {
        &self.robots
    }

    /// The per-kind task quotas: `quotas()[k][t]` robots of kind `k` for task `t`.
    pub fn quotas(&self) -> &[Vec<usize>] {
        &self.quotas
    }

    /// Number of kinds (length of the quota list).
    pub fn kinds(&self) -> usize {
        self.quotas.len()
    }

    /// Number of tasks `K >= 1`.
    pub fn tasks(&self) -> usize {
        self.hardest_first.len()
    }

    /// The task indices from the hardest to the easiest (a permutation of `0..K`).
    pub fn hardest_first(&self) -> &[usize] {
        &self.hardest_first
    }

    /// Difficulty rank of each task: `difficulty_ranks()[t]` is task `t`'s position in
    /// [`hardest_first`](Self::hardest_first) (0 = hardest, `K - 1` = easiest).
    pub fn difficulty_ranks(&self) -> &[usize] {
        &self.rank
    }

    /// The robots of kind `kind`, sorted by id (empty for an unknown kind).
    pub fn members_of_kind(&self, kind: usize) -> Vec<&RobotSnapshot> {
        self.robots.iter().filter(|r| r.kind == kind).collect()
    }

    /// The robot with id `id`, if any (binary search, `O(log n)`).
    pub fn robot(&self, id: usize) -> Option<&RobotSnapshot> {
        self.robots
            .binary_search_by_key(&id, |r| r.id)
            .ok()
            .map(|i| &self.robots[i])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::NeedsVector;

    fn robot(id: usize, kind: usize) -> RobotSnapshot {
        RobotSnapshot {
            id,
            kind,
            needs: NeedsVector::new(vec![1.0]).unwrap(),
            energy_pct: 80.0,
            hp_pct: 90.0,
            distance_to_goal_m: vec![10.0, 20.0],
        }
    }

    fn two(robots: Vec<RobotSnapshot>, quotas: Vec<Vec<usize>>) -> Result<GroupingRequest> {
        GroupingRequest::new(robots, quotas, vec![1, 0])
    }

    #[test]
    fn validation_errors_name_the_problem() {
        let q = vec![vec![1, 1]];
        assert!(two(vec![robot(0, 0), robot(1, 0)], q.clone()).is_ok());
        assert_eq!(
            two(vec![robot(0, 0), robot(0, 0)], q.clone()),
            Err(RneError::DuplicateRobot(0))
        );
        assert_eq!(
            two(vec![robot(0, 0), robot(1, 1)], q.clone()),
            Err(RneError::UnknownKind {
                id: 1,
                kind: 1,
                kinds: 1
            })
        );
        assert_eq!(
            two(vec![robot(0, 0)], q.clone()),
            Err(RneError::QuotaMismatch {
                kind: 0,
                available: 1,
                quotas: vec![1, 1]
            })
        );
        // Quotas whose sum overflows a usize are a mismatch too (it wrapped to a match).
        let e = two(vec![robot(0, 0)], vec![vec![usize::MAX, 2]]).unwrap_err();
        assert!(matches!(e, RneError::QuotaMismatch { available: 1, .. }));
        assert_eq!(
            e.to_string(),
            format!(
                "kind 0 has 1 robots but its task quotas [{}, 2] sum to {}",
                usize::MAX,
                usize::MAX as u128 + 2
            )
        );
        assert_eq!(two(vec![], q), Err(RneError::Empty { what: "team" }));
        let mut bad = robot(3, 0);
        bad.hp_pct = f64::NAN;
        assert!(matches!(
            two(vec![bad, robot(1, 0)], vec![vec![1, 1]]),
            Err(RneError::InvalidRobotState {
                id: 3,
                field: "hp_pct",
                ..
            })
        ));
    }

    #[test]
    fn task_lists_are_checked() {
        let r = || vec![robot(0, 0), robot(1, 0)];
        assert_eq!(
            GroupingRequest::new(r(), vec![vec![2]], vec![]),
            Err(RneError::Empty { what: "task list" })
        );
        for order in [vec![0, 0], vec![0, 2], vec![1]] {
            assert_eq!(
                GroupingRequest::new(r(), vec![vec![1, 1]], order.clone()),
                Err(RneError::InvalidTaskOrder { order })
            );
        }
        assert_eq!(
            GroupingRequest::new(r(), vec![vec![1, 1]], vec![0, 1, 2]),
            Err(RneError::DistanceCount {
                id: 0,
                tasks: 3,
                actual: 2
            })
        );
        let mut far = robot(1, 0);
        far.distance_to_goal_m[1] = f64::INFINITY;
        assert_eq!(
            two(vec![robot(0, 0), far], vec![vec![1, 1]]),
            Err(RneError::InvalidDistance {
                id: 1,
                task: 1,
                value: f64::INFINITY
            })
        );
        assert_eq!(
            two(r(), vec![vec![2]]),
            Err(RneError::QuotaTaskCount {
                kind: 0,
                tasks: 2,
                actual: 1
            })
        );
    }

    #[test]
    fn empty_groups_and_one_task_are_allowed() {
        let r = || vec![robot(0, 0), robot(1, 0)];
        let all_hard = two(r(), vec![vec![0, 2]]).unwrap();
        assert_eq!(all_hard.difficulty_ranks(), &[1, 0]);
        let mut solo = robot(0, 0);
        solo.distance_to_goal_m = vec![5.0];
        let one = GroupingRequest::new(vec![solo], vec![vec![1]], vec![0]).unwrap();
        assert_eq!((one.tasks(), one.kinds()), (1, 1));
    }
}
