//! The input of a grouping method: robot snapshots and per-kind quotas (paper Sec. VI.C).

use serde::{Deserialize, Serialize};

use crate::error::{Result, RneError};
use crate::needs::NeedsVector;

/// The two tasks of the paper's USAR mission (Sec. V). `Task::Easy as usize == 0` and
/// `Task::Hard as usize == 1` index [`RobotSnapshot::distance_to_goal_m`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Task {
    /// The easy task (index 0).
    Easy = 0,
    /// The hard task (index 1): more debris and radiation, longer distance.
    Hard = 1,
}

impl Task {
    /// The other task.
    pub fn other(self) -> Self {
        match self {
            Self::Easy => Self::Hard,
            Self::Hard => Self::Easy,
        }
    }
}

/// One robot's state at grouping time.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotSnapshot {
    /// Unique robot id.
    pub id: usize,
    /// Kind index into the request's kinds order, which is also the merge order of the
    /// hierarchical RNE grouping (paper: 0 = carrier, 1 = supplier, 2 = observer).
    pub kind: usize,
    /// The robot's needs vector (`j` categories; paper: hp, v, sen, eng, res, cap, obs).
    pub needs: NeedsVector,
    /// Battery level in percent (finite; normally `0..=100`). Used by ENG.
    pub energy_pct: f64,
    /// Health points in percent (finite; normally `0..=100`). Used by HP_DIS.
    pub hp_pct: f64,
    /// Distance in metres from the robot to the goal of `[easy, hard]` (finite). Used by DIS
    /// and as HP_DIS's tie-break.
    pub distance_to_goal_m: [f64; 2],
}

/// How many robots of one kind go to each task.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct KindQuota {
    /// Robots of this kind for the easy task.
    pub easy: usize,
    /// Robots of this kind for the hard task.
    pub hard: usize,
}

impl KindQuota {
    /// The quota for `task`.
    pub fn of(self, task: Task) -> usize {
        match task {
            Task::Easy => self.easy,
            Task::Hard => self.hard,
        }
    }
}

/// A validated team-level grouping request: the robots (stored sorted by id) and one
/// [`KindQuota`] per kind (`quotas[k]` for kind `k`).
///
/// Invariants: ids unique; every kind `< quotas.len()`; for each kind, `easy + hard` equals
/// its number of robots; both tasks receive at least one robot; scalar states finite.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawRequest", into = "RawRequest")]
pub struct GroupingRequest {
    robots: Vec<RobotSnapshot>,
    quotas: Vec<KindQuota>,
}

#[derive(Serialize, Deserialize)]
struct RawRequest {
    robots: Vec<RobotSnapshot>,
    quotas: Vec<KindQuota>,
}

impl TryFrom<RawRequest> for GroupingRequest {
    type Error = RneError;
    fn try_from(r: RawRequest) -> Result<Self> {
        Self::new(r.robots, r.quotas)
    }
}

impl From<GroupingRequest> for RawRequest {
    fn from(r: GroupingRequest) -> Self {
        Self {
            robots: r.robots,
            quotas: r.quotas,
        }
    }
}

impl GroupingRequest {
    /// Validates and builds a request.
    ///
    /// # Errors
    /// [`RneError::Empty`] (no robots, or a task that would get no robot),
    /// [`RneError::DuplicateRobot`], [`RneError::UnknownKind`], [`RneError::QuotaMismatch`],
    /// [`RneError::InvalidRobotState`] (non-finite energy, HP or distance).
    pub fn new(mut robots: Vec<RobotSnapshot>, quotas: Vec<KindQuota>) -> Result<Self> {
        if robots.is_empty() {
            return Err(RneError::Empty { what: "team" });
        }
        robots.sort_by_key(|r| r.id);
        if let Some(w) = robots.windows(2).find(|w| w[0].id == w[1].id) {
            return Err(RneError::DuplicateRobot(w[0].id));
        }
        let mut counts = vec![0usize; quotas.len()];
        for r in &robots {
            let fields = [
                ("energy_pct", r.energy_pct),
                ("hp_pct", r.hp_pct),
                ("distance_to_goal_m[0]", r.distance_to_goal_m[0]),
                ("distance_to_goal_m[1]", r.distance_to_goal_m[1]),
            ];
            if let Some((field, value)) = fields.into_iter().find(|(_, v)| !v.is_finite()) {
                return Err(RneError::InvalidRobotState {
                    id: r.id,
                    field,
                    value,
                });
            }
            match counts.get_mut(r.kind) {
                Some(c) => *c += 1,
                None => {
                    return Err(RneError::UnknownKind {
                        id: r.id,
                        kind: r.kind,
                        kinds: quotas.len(),
                    });
                }
            }
        }
        for (kind, (q, &available)) in quotas.iter().zip(&counts).enumerate() {
            if q.easy + q.hard != available {
                return Err(RneError::QuotaMismatch {
                    kind,
                    available,
                    easy: q.easy,
                    hard: q.hard,
                });
            }
        }
        if quotas.iter().all(|q| q.easy == 0) {
            return Err(RneError::Empty {
                what: "easy-task group",
            });
        }
        if quotas.iter().all(|q| q.hard == 0) {
            return Err(RneError::Empty {
                what: "hard-task group",
            });
        }
        Ok(Self { robots, quotas })
    }

    /// The robots, sorted by id.
    pub fn robots(&self) -> &[RobotSnapshot] {
        &self.robots
    }

    /// The per-kind quotas (`quotas()[k]` for kind `k`).
    pub fn quotas(&self) -> &[KindQuota] {
        &self.quotas
    }

    /// Number of kinds.
    pub fn kinds(&self) -> usize {
        self.quotas.len()
    }

    /// The robots of kind `kind`, sorted by id (empty for an unknown kind).
    pub fn members_of_kind(&self, kind: usize) -> Vec<&RobotSnapshot> {
        self.robots.iter().filter(|r| r.kind == kind).collect()
    }

    /// The robot with id `id`, if any.
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

    fn robot(id: usize, kind: usize) -> RobotSnapshot {
        RobotSnapshot {
            id,
            kind,
            needs: NeedsVector::new(vec![1.0]).unwrap(),
            energy_pct: 80.0,
            hp_pct: 90.0,
            distance_to_goal_m: [10.0, 20.0],
        }
    }

    #[test]
    fn validation_errors_name_the_problem() {
        let q = vec![KindQuota { easy: 1, hard: 1 }];
        assert!(GroupingRequest::new(vec![robot(0, 0), robot(1, 0)], q.clone()).is_ok());
        assert_eq!(
            GroupingRequest::new(vec![robot(0, 0), robot(0, 0)], q.clone()),
            Err(RneError::DuplicateRobot(0))
        );
        assert_eq!(
            GroupingRequest::new(vec![robot(0, 0), robot(1, 1)], q.clone()),
            Err(RneError::UnknownKind {
                id: 1,
                kind: 1,
                kinds: 1
            })
        );
        assert_eq!(
            GroupingRequest::new(vec![robot(0, 0)], q.clone()),
            Err(RneError::QuotaMismatch {
                kind: 0,
                available: 1,
                easy: 1,
                hard: 1
            })
        );
        assert_eq!(
            GroupingRequest::new(vec![], q),
            Err(RneError::Empty { what: "team" })
        );
        assert_eq!(
            GroupingRequest::new(vec![robot(0, 0)], vec![KindQuota { easy: 0, hard: 1 }]),
            Err(RneError::Empty {
                what: "easy-task group"
            })
        );
        let mut bad = robot(3, 0);
        bad.hp_pct = f64::NAN;
        assert!(matches!(
            GroupingRequest::new(vec![bad, robot(1, 0)], vec![KindQuota { easy: 1, hard: 1 }]),
            Err(RneError::InvalidRobotState {
                id: 3,
                field: "hp_pct",
                ..
            })
        ));
    }
}
