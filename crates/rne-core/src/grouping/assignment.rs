//! The output of a grouping method: which robots go to which of the `K` tasks.

use serde::{Deserialize, Serialize};

use crate::error::{Result, RneError};
use crate::grouping::request::GroupingRequest;

/// Robot ids per task: `groups[t]` holds the ids sent to task `t` (`K` lists, each sorted
/// ascending; a list may be empty). Use [`Assignment::validate`] to check it is a partition of
/// a request's team that meets the quotas.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Assignment {
    /// `groups[t]`: ids of the robots sent to task `t`, ascending.
    pub groups: Vec<Vec<usize>>,
}

impl Assignment {
    /// Builds an assignment from one id list per task, sorting each list.
    pub fn new(mut groups: Vec<Vec<usize>>) -> Self {
        for g in &mut groups {
            g.sort_unstable();
        }
        Self { groups }
    }

    /// Number of tasks (lists).
    pub fn tasks(&self) -> usize {
        self.groups.len()
    }

    /// The ids sent to task `task` (empty for an unknown task).
    pub fn ids(&self, task: usize) -> &[usize] {
        self.groups.get(task).map_or(&[], Vec::as_slice)
    }

    /// The task robot `id` is sent to, if it is assigned (the first such task if it appears
    /// twice). `O(K log n)`: binary search in each sorted list.
    pub fn task_of(&self, id: usize) -> Option<usize> {
        self.groups
            .iter()
            .position(|g| g.binary_search(&id).is_ok())
    }

    /// Checks that there is one list per task of `request`, every robot of `request` appears
    /// exactly once, no unknown id appears, and each task receives exactly its per-kind
    /// quota. `O(n log n)`.
    ///
    /// # Errors
    /// [`RneError::InvalidAssignment`] describing the first violation (naming the robot id,
    /// task or kind).
    pub fn validate(&self, request: &GroupingRequest) -> Result<()> {
        let bad = |msg: String| Err(RneError::InvalidAssignment(msg));
        if self.groups.len() != request.tasks() {
            return bad(format!(
                "{} groups for {} tasks",
                self.groups.len(),
                request.tasks()
            ));
        }
        let robots = request.robots();
        let mut seen = vec![false; robots.len()];
        let mut counts = vec![vec![0usize; request.tasks()]; request.kinds()];
        for (task, group) in self.groups.iter().enumerate() {
            for &id in group {
                let Ok(at) = robots.binary_search_by_key(&id, |r| r.id) else {
                    return bad(format!("robot id {id} is not in the team"));
                };
                if std::mem::replace(&mut seen[at], true) {
                    return bad(format!("robot id {id} is assigned more than once"));
                }
                counts[robots[at].kind][task] += 1;
            }
        }
        if let Some(at) = seen.iter().position(|s| !s) {
            return bad(format!("robot id {} is not assigned", robots[at].id));
        }
        for (kind, (q, c)) in request.quotas().iter().zip(&counts).enumerate() {
            if q != c {
                return bad(format!(
                    "kind {kind} got {c:?} robots per task but the quotas are {q:?}"
                ));
            }
        }
        Ok(())
    }
}
