//! One robot's state at grouping time (paper Sec. VI.B-C).

use serde::{Deserialize, Serialize};

use crate::needs::NeedsVector;

/// One robot's state at grouping time, as every grouping method sees it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotSnapshot {
    /// Unique robot id.
    pub id: usize,
    /// Kind index into the request's quota list, which is also the merge order of the
    /// hierarchical RNE grouping (paper: 0 = carrier, 1 = supplier, 2 = observer).
    pub kind: usize,
    /// The robot's needs vector (`j` categories; paper: hp, v, sen, eng, res, cap, obs).
    pub needs: NeedsVector,
    /// Battery level in percent (finite; normally `0..=100`). Used by ENG.
    pub energy_pct: f64,
    /// Health points in percent (finite; normally `0..=100`). Used by HP_DIS.
    pub hp_pct: f64,
    /// Distance in metres from the robot to each task's goal, indexed by task
    /// (`distance_to_goal_m[t]` for task `t`; length `K`, each finite). Used by DIS and as
    /// HP_DIS's tie-break.
    pub distance_to_goal_m: Vec<f64>,
}
