//! Shared helper of the ranking baselines (ENG, HP_DIS): rank each kind, fill the tasks from
//! the hardest down.

use std::cmp::Ordering;

use crate::grouping::assignment::Assignment;
use crate::grouping::request::GroupingRequest;
use crate::grouping::robot::RobotSnapshot;

/// For each kind, sorts its robots with `better_first` (the first robot is the most suited to
/// hard work) and deals them out in that order to the tasks from the hardest to the easiest,
/// each task taking its quota for the kind. The sort is stable over the id order, so equal
/// robots keep id order. With two tasks: the top `quota[hard]` go hard, the rest easy.
/// `O(n log n)`.
pub(crate) fn fill_from_hardest(
    request: &GroupingRequest,
    better_first: impl Fn(&RobotSnapshot, &RobotSnapshot) -> Ordering,
) -> Assignment {
    let mut groups = vec![Vec::new(); request.tasks()];
    for (kind, quota) in request.quotas().iter().enumerate() {
        let mut members = request.members_of_kind(kind);
        members.sort_by(|a, b| better_first(a, b));
        let mut ranked = members.into_iter();
        for &task in request.hardest_first() {
            groups[task].extend(ranked.by_ref().take(quota[task]).map(|r| r.id));
        }
    }
    Assignment::new(groups)
}
