//! Tests of the grouping methods: the paper's team, the baselines, the `K`-task recursion,
//! properties over random requests and the two-task oracle.

mod baselines;
pub(crate) mod common;
mod k_tasks;
mod oracle_two_task;
mod paper_team;
mod properties;
mod scale;
mod scorer;
