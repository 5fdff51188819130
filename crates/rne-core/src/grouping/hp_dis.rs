//! HP_DIS, the health-points-then-distance baseline (paper Sec. VI.C).

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::method::GroupingMethod;
use crate::grouping::ranked::fill_from_hardest;
use crate::grouping::request::GroupingRequest;

/// HP_DIS: within each kind, sort robots by `hp_pct` descending; equal HP is broken by the
/// distance to the hardest task's goal ascending (the DIS idea: the robot nearer the hard goal
/// goes there), then by id. The tasks are filled from the hardest down, each with its quota
/// for the kind. Two tasks: the top `quota[hard]` go hard. `O(n log n)`.
///
/// # Reference
/// Sort key `(-hp_r, d_r[t_1], id_r)` with `t_1` the hardest task; the first `q[t_1]` go to
/// `t_1`, the next `q[t_2]` to the second hardest, ...; paper Sec. VI.C "HP_DIS".
#[derive(Debug, Clone, Copy, Default)]
pub struct HpDis;

impl GroupingMethod for HpDis {
    fn name(&self) -> &str {
        "hp_dis"
    }

    /// `HP_DIS`, the paper's name (Sec. VI.C).
    fn display_name(&self) -> &str {
        "HP_DIS"
    }

    fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
        let hardest = request.hardest_first()[0];
        Ok(fill_from_hardest(request, |a, b| {
            b.hp_pct
                .total_cmp(&a.hp_pct)
                .then(a.distance_to_goal_m[hardest].total_cmp(&b.distance_to_goal_m[hardest]))
        }))
    }
}
