//! Diagnostics of the hierarchical RNE grouping ([`HierarchicalRne::group_detailed`]).
//!
//! [`HierarchicalRne::group_detailed`]: crate::grouping::HierarchicalRne::group_detailed

use serde::{Deserialize, Serialize};

use crate::grouping::assignment::Assignment;

/// One bisection of the K-task hierarchical RNE grouping: the remaining team split into the
/// group of the hardest remaining task and the group of all easier tasks (with two tasks,
/// hard vs easy: the paper's Algorithm 1 and Sec. VI.C).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Bisection {
    /// The task split off at this level (the hardest of the remaining tasks).
    pub task: usize,
    /// Symmetric RNE `J(R, H) = T(R||H) + T(H||R)` between the rest `R` and the task's group
    /// `H` (nats unless the model's log base says otherwise; `>= 0`, 0 if a side is empty).
    pub between_rne: f64,
    /// Within-group RNE (see
    /// [`HierarchicalRne::within_group_rne`](crate::grouping::HierarchicalRne::within_group_rne))
    /// of `[rest, task]`.
    pub within_rne: [f64; 2],
    /// `true` if unequal quotas fixed which merged group went to the task (the trust rule was
    /// not needed); `false` if the more trusted group was chosen for it.
    pub forced_by_quotas: bool,
    /// Kinds whose split exceeded the exact split limit and was found by the heuristic
    /// (empty when the whole level is exact, as for the paper's team).
    pub heuristic_kinds: Vec<usize>,
}

/// The result of [`HierarchicalRne::group_detailed`](crate::grouping::HierarchicalRne::group_detailed).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct HierarchicalOutcome {
    /// The final assignment (`K` groups).
    pub assignment: Assignment,
    /// One entry per bisection, hardest task first: `K - 1` entries, fewer if the harder
    /// tasks took every robot (then the easier tasks' groups are empty and need no split).
    pub bisections: Vec<Bisection>,
}
