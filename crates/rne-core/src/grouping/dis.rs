//! DIS, the distance-based baseline (paper Sec. VI.C).

use std::cmp::Ordering;

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::request::GroupingRequest;
use crate::grouping::robot::RobotSnapshot;

/// DIS: robots choose in **nearest-first** order (ascending distance to their nearest task
/// goal over all `K` tasks, ties by id); each takes the nearest task whose quota for its kind
/// still has room (equal distances: the easier task first). Two tasks: the nearer task if it
/// has room, otherwise the other.
///
/// Nearest-first (rather than id order) makes the result independent of how ids were
/// numbered: the robot with the strongest claim to a goal is served first. `O(n (log n + K))`.
///
/// # Reference
/// Greedy: for `r` in order of `(min_t d_r[t], id_r)`: `task_r = argmin_{t : room_{kind_r}(t) > 0}
/// (d_r[t], -rank(t))`, where `rank` 0 is the hardest task; paper Sec. VI.C "DIS".
#[derive(Debug, Clone, Copy, Default)]
pub struct Dis;

/// Distance from `r` to its nearest task goal (IEEE `<`, so of equal values the first).
fn nearest_distance(r: &RobotSnapshot) -> f64 {
    let d = &r.distance_to_goal_m;
    d.iter()
        .fold(d[0], |best, &x| if x < best { x } else { best })
}

impl GroupingMethod for Dis {
    fn name(&self) -> &str {
        "dis"
    }

    /// `DIS`, the paper's name (Sec. VI.C).
    fn display_name(&self) -> &str {
        "DIS"
    }

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        let rank = request.difficulty_ranks();
        // Task `a` is preferred to `b` by robot `r`: nearer (IEEE order; distances are
        // finite), then easier (higher rank).
        let prefer = |r: &RobotSnapshot, a: usize, b: usize| -> Ordering {
            let d = &r.distance_to_goal_m;
            let by_distance = d[a].partial_cmp(&d[b]).unwrap_or(Ordering::Equal);
            by_distance.then(rank[b].cmp(&rank[a]))
        };
        let mut order: Vec<_> = request.robots().iter().collect();
        order.sort_by(|a, b| {
            nearest_distance(a)
                .total_cmp(&nearest_distance(b))
                .then(a.id.cmp(&b.id))
        });
        let mut left: Vec<Vec<usize>> = request.quotas().to_vec();
        let mut groups = vec![Vec::new(); request.tasks()];
        for robot in order {
            let room = &mut left[robot.kind];
            // The kind's quotas sum to its robots, so some task still has room.
            let Some(task) = (0..room.len())
                .filter(|&t| room[t] > 0)
                .min_by(|&a, &b| prefer(robot, a, b))
            else {
                continue;
            };
            room[task] -= 1;
            groups[task].push(robot.id);
        }
        Ok(Assignment::new(groups))
    }
}
