//! The output of a grouping method: which robots go to the easy and to the hard task.

use serde::{Deserialize, Serialize};

use crate::error::{Result, RneError};
use crate::grouping::request::{GroupingRequest, Task};

/// Robot ids per task, each list sorted ascending. Use [`Assignment::validate`] to check it
/// is a partition of a request's team that meets the quotas.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Assignment {
    /// Ids of the robots sent to the easy task.
    pub easy: Vec<usize>,
    /// Ids of the robots sent to the hard task.
    pub hard: Vec<usize>,
}

impl Assignment {
    /// Builds an assignment, sorting both lists.
    pub fn new(mut easy: Vec<usize>, mut hard: Vec<usize>) -> Self {
        easy.sort_unstable();
        hard.sort_unstable();
        Self { easy, hard }
    }

    /// The ids sent to `task`.
    pub fn ids(&self, task: Task) -> &[usize] {
        match task {
            Task::Easy => &self.easy,
            Task::Hard => &self.hard,
        }
    }

    /// The task robot `id` is sent to, if it is assigned.
    pub fn task_of(&self, id: usize) -> Option<Task> {
        if self.easy.contains(&id) {
            Some(Task::Easy)
        } else if self.hard.contains(&id) {
            Some(Task::Hard)
        } else {
            None
        }
    }

    /// Checks that every robot of `request` appears exactly once, no unknown id appears, and
    /// each task receives exactly its per-kind quota.
    ///
    /// # Errors
    /// [`RneError::InvalidAssignment`] describing the first violation (naming the robot id or
    /// kind).
    pub fn validate(&self, request: &GroupingRequest) -> Result<()> {
        let bad = |msg: String| Err(RneError::InvalidAssignment(msg));
        let mut seen = std::collections::HashSet::new();
        let mut counts = vec![[0usize; 2]; request.kinds()];
        for task in [Task::Easy, Task::Hard] {
            for &id in self.ids(task) {
                let Some(robot) = request.robot(id) else {
                    return bad(format!("robot id {id} is not in the team"));
                };
                if !seen.insert(id) {
                    return bad(format!("robot id {id} is assigned more than once"));
                }
                counts[robot.kind][task as usize] += 1;
            }
        }
        if let Some(r) = request.robots().iter().find(|r| !seen.contains(&r.id)) {
            return bad(format!("robot id {} is not assigned", r.id));
        }
        for (kind, (q, c)) in request.quotas().iter().zip(&counts).enumerate() {
            if [q.easy, q.hard] != *c {
                return bad(format!(
                    "kind {kind} got {} easy + {} hard but the quota is {} + {}",
                    c[0], c[1], q.easy, q.hard
                ));
            }
        }
        Ok(())
    }
}
