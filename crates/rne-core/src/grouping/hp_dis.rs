//! HP_DIS, the health-points-then-distance baseline (paper Sec. VI.C).

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::ranked::top_ranked_to_hard;
use crate::grouping::request::{GroupingRequest, Task};

/// HP_DIS: within each kind, sort robots by `hp_pct` descending; equal HP is broken by the
/// distance to the hard task's goal ascending (the DIS idea: the robot nearer the hard goal
/// goes there), then by id. The top `quota.hard` go to the hard task.
///
/// # Reference
/// Sort key `(-hp_r, d_r[hard], id_r)`, first `h_k` to hard; paper Sec. VI.C "HP_DIS".
#[derive(Debug, Clone, Copy, Default)]
pub struct HpDis;

impl GroupingMethod for HpDis {
    fn name(&self) -> &str {
        "hp_dis"
    }

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        let hard = Task::Hard as usize;
        Ok(top_ranked_to_hard(request, |a, b| {
            b.hp_pct
                .total_cmp(&a.hp_pct)
                .then(a.distance_to_goal_m[hard].total_cmp(&b.distance_to_goal_m[hard]))
        }))
    }
}
