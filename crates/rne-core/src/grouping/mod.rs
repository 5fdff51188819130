//! Grouping a team into an easy-task and a hard-task group (paper Sec. V and VI.C).
//!
//! [`GroupingMethod`] is the common trait; [`HierarchicalRne`] (Algorithm 1), [`Dis`],
//! [`Eng`] and [`HpDis`] are the built-in methods; [`method_from_name`] builds one from its name.

mod assignment;
mod dis;
mod eng;
mod hierarchical;
mod hp_dis;
mod method;
mod ranked;
mod registry;
mod request;

#[cfg(test)]
mod tests;

pub use assignment::Assignment;
pub use dis::Dis;
pub use eng::Eng;
pub use hierarchical::{HierarchicalOutcome, HierarchicalRne};
pub use hp_dis::HpDis;
pub use method::GroupingMethod;
pub use registry::{METHOD_NAMES, method_from_name};
pub use request::{GroupingRequest, KindQuota, RobotSnapshot, Task};
