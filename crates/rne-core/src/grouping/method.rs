//! The [`GroupingMethod`] trait shared by every grouping method (paper Sec. VI.C).

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::request::GroupingRequest;

/// A way to split a team into one group per task (`K >= 1` tasks; the paper: an easy and a
/// hard task) under per-kind quotas.
///
/// Object safe and `Send + Sync`, so methods can be stored as `Box<dyn GroupingMethod>` and
/// shared across threads. To add a method, implement [`name`](Self::name) and
/// [`assign`](Self::assign) on your own type; nothing else needs to change:
///
/// ```
/// use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
/// use rne_core::Result;
///
/// /// Deals each kind's robots out in id order, easiest task first.
/// struct ById;
///
/// impl GroupingMethod for ById {
///     fn name(&self) -> &str {
///         "by_id"
///     }
///     fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
///         let mut groups = vec![Vec::new(); request.tasks()];
///         for (kind, quota) in request.quotas().iter().enumerate() {
///             let mut ids = request.members_of_kind(kind).into_iter().map(|r| r.id);
///             for &task in request.hardest_first().iter().rev() {
///                 groups[task].extend(ids.by_ref().take(quota[task]));
///             }
///         }
///         Ok(Assignment::new(groups))
///     }
/// }
///
/// let methods: Vec<Box<dyn GroupingMethod>> = vec![Box::new(ById)];
/// assert_eq!(methods[0].name(), "by_id");
/// ```
pub trait GroupingMethod: Send + Sync {
    /// Short lower-case name (e.g. `"rne"`, `"dis"`), used in tables and on the command line.
    fn name(&self) -> &str;

    /// Computes the assignment. Implementations should return a partition meeting the
    /// request's quotas; [`group`](Self::group) checks it.
    ///
    /// # Errors
    /// Method-specific (e.g. RNE needs consistent needs-vector lengths).
    fn assign(&self, request: &GroupingRequest) -> Result<Assignment>;

    /// [`assign`](Self::assign), then [`Assignment::validate`].
    ///
    /// # Errors
    /// Those of `assign`, or [`crate::RneError::InvalidAssignment`].
    fn group(&self, request: &GroupingRequest) -> Result<Assignment> {
        let assignment = self.assign(request)?;
        assignment.validate(request)?;
        Ok(assignment)
    }
}
