//! The [`GroupingMethod`] trait shared by every grouping method (paper Sec. VI.C).

use crate::error::Result;
use crate::grouping::assignment::Assignment;
use crate::grouping::request::GroupingRequest;

/// A way to split a team into one group per task (`K >= 1` tasks; the paper: an easy and a
/// hard task) under per-kind quotas.
///
/// Object safe, so methods can be stored as `Box<dyn GroupingMethod>`. To add a method,
/// implement [`name`](Self::name) and [`assign`](Self::assign) on your own type; nothing else
/// needs to change:
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
/// assert_eq!(methods[0].display_name(), "by_id");
/// ```
///
/// # Why `Send` and not `Sync`
/// A trial owns its method: a sweep builds one method per trial, inside the worker thread
/// that runs the trial, and never shares it. `Send` lets the trial that owns it
/// (`usar_sim::mission::Simulation`) move to another thread, e.g. be built on one thread and
/// run on a worker. `Sync` is not required because no two threads ever call the same method,
/// so a method may keep state between rounds behind `&self` in a `Cell` or `RefCell` (a random
/// number generator, a counter). An `Rc` is not `Send`; use an `Arc`.
///
/// ```
/// use std::cell::Cell;
/// use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
/// use rne_core::Result;
///
/// /// Deals each kind's robots out in id order, starting at a task that moves on by one
/// /// every round (state kept in a `Cell`, which is `Send` but not `Sync`).
/// struct Rotating {
///     round: Cell<usize>,
/// }
///
/// impl GroupingMethod for Rotating {
///     fn name(&self) -> &str {
///         "rotating"
///     }
///     fn assign(&self, request: &GroupingRequest) -> Result<Assignment> {
///         let first = self.round.replace(self.round.get() + 1);
///         let tasks = request.tasks();
///         let mut groups = vec![Vec::new(); tasks];
///         for (kind, quota) in request.quotas().iter().enumerate() {
///             let mut ids = request.members_of_kind(kind).into_iter().map(|r| r.id);
///             for t in (0..tasks).map(|i| (first + i) % tasks) {
///                 groups[t].extend(ids.by_ref().take(quota[t]));
///             }
///         }
///         Ok(Assignment::new(groups))
///     }
/// }
///
/// let method: Box<dyn GroupingMethod> = Box::new(Rotating { round: Cell::new(0) });
/// std::thread::spawn(move || assert_eq!(method.name(), "rotating")).join().unwrap();
/// ```
///
/// A method that draws random numbers should take its generator from the trial it runs in,
/// so that a sweep stays reproducible: `usar_sweep::sweep::TrialContext::rng` gives each
/// trial's method its own seeded stream.
pub trait GroupingMethod: Send {
    /// The method's name as its author wrote it (e.g. `"rne"`, `"hp_sort"`): how a method
    /// factory or the command line knows it. Any non-empty string; it is not re-cased.
    fn name(&self) -> &str;

    /// The name results show (`TrialResult::method`, tables, figures, replays): by default
    /// [`name`](Self::name), as written. The built-in methods override it with the paper's
    /// names `RNE`, `DIS`, `ENG` and `HP_DIS`.
    fn display_name(&self) -> &str {
        self.name()
    }

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
