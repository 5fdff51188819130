//! DIS, the distance-based baseline (paper Sec. VI.C).

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::request::{GroupingRequest, Task};

/// DIS: robots choose in **nearest-first** order (ascending distance to their nearer goal,
/// ties by id); each takes its nearer task (equal distances: easy) if its kind's quota for
/// that task still has room, otherwise the other task.
///
/// Nearest-first (rather than id order) makes the result independent of how ids were
/// numbered: the robot with the strongest claim to a goal is served first.
///
/// # Reference
/// Greedy: for `r` in order of `min_t d_r[t]`: `task_r = argmin_t d_r[t]` if
/// `|task ∩ kind_r| < quota_{kind_r}(task)` else the other; paper Sec. VI.C "DIS".
#[derive(Debug, Clone, Copy, Default)]
pub struct Dis;

impl GroupingMethod for Dis {
    fn name(&self) -> &str {
        "dis"
    }

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        let nearer = |d: [f64; 2]| if d[1] < d[0] { Task::Hard } else { Task::Easy };
        let mut order: Vec<_> = request.robots().iter().collect();
        order.sort_by(|a, b| {
            let da = a.distance_to_goal_m[nearer(a.distance_to_goal_m) as usize];
            let db = b.distance_to_goal_m[nearer(b.distance_to_goal_m) as usize];
            da.total_cmp(&db).then(a.id.cmp(&b.id))
        });
        let mut left: Vec<[usize; 2]> = request.quotas().iter().map(|q| [q.easy, q.hard]).collect();
        let (mut easy, mut hard) = (Vec::new(), Vec::new());
        for robot in order {
            let mut task = nearer(robot.distance_to_goal_m);
            if left[robot.kind][task as usize] == 0 {
                task = task.other();
            }
            left[robot.kind][task as usize] -= 1;
            match task {
                Task::Easy => easy.push(robot.id),
                Task::Hard => hard.push(robot.id),
            }
        }
        Ok(Assignment::new(easy, hard))
    }
}
