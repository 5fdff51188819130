//! Grouping a team into one group per task, `K >= 1` tasks of different difficulty (paper
//! Sec. V and VI.C: an easy and a hard task).
//!
//! [`GroupingRequest`] holds the team ([`RobotSnapshot`]s), per-kind task quotas and the
//! tasks' difficulty order; a method returns an [`Assignment`]. [`GroupingMethod`] is the
//! common trait; [`HierarchicalRne`] (Algorithm 1), [`Dis`], [`Eng`] and [`HpDis`] are the
//! built-in methods; [`method_from_name`] builds one from its name.

mod assignment;
mod dis;
mod eng;
mod hierarchical;
mod hp_dis;
mod method;
mod outcome;
mod ranked;
mod registry;
mod request;
mod robot;
mod score_tie;
mod split_heuristic;
mod split_scorer;
mod two_way;

#[cfg(test)]
pub(crate) mod tests;

pub use assignment::Assignment;
pub use dis::Dis;
pub use eng::Eng;
pub use hierarchical::{DEFAULT_EXACT_SPLIT_LIMIT, HierarchicalRne};
pub use hp_dis::HpDis;
pub use method::GroupingMethod;
pub use outcome::{Bisection, HierarchicalOutcome};
pub use registry::{METHOD_NAMES, builtin_name, method_from_name, method_key};
pub use request::GroupingRequest;
pub use robot::RobotSnapshot;
