//! Shared helper of the ranking baselines (ENG, HP_DIS): rank each kind, send the top to the
//! hard task.

use std::cmp::Ordering;

use crate::grouping::assignment::Assignment;
use crate::grouping::request::{GroupingRequest, RobotSnapshot};

/// For each kind, sorts its robots with `better_first` (the first robot is the most suited to
/// the hard task) and sends the first `quota.hard` of them to the hard task, the rest to the
/// easy task. The sort is stable over the id order, so equal robots keep id order.
pub(crate) fn top_ranked_to_hard(
    request: &GroupingRequest,
    better_first: impl Fn(&RobotSnapshot, &RobotSnapshot) -> Ordering,
) -> Assignment {
    let (mut easy, mut hard) = (Vec::new(), Vec::new());
    for (kind, quota) in request.quotas().iter().enumerate() {
        let mut members = request.members_of_kind(kind);
        members.sort_by(|a, b| better_first(a, b));
        for (rank, robot) in members.into_iter().enumerate() {
            if rank < quota.hard {
                hard.push(robot.id)
            } else {
                easy.push(robot.id)
            }
        }
    }
    Assignment::new(easy, hard)
}
