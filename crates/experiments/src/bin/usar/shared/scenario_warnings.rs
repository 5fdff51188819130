//! The warnings about a valid scenario (tasks no group can rescue from, goals some robots cannot
//! reach), as text and on stderr; `usar check`, `usar run` and `usar sweep` give them.

use usar_sim::mission::{tasks_without_rescue, unreachable_goals};
use usar_sim::scenario::Scenario;

/// The warnings about a valid scenario `s`, one line each without the `warning: ORIGIN: `
/// head: the tasks no group can rescue from ([`tasks_without_rescue`]), then the goals some
/// robots cannot reach from their starts ([`unreachable_goals`]).
pub fn scenario_warnings(s: &Scenario) -> Vec<String> {
    let idle = tasks_without_rescue(s).into_iter().map(|t| t.to_string());
    idle.chain(unreachable_goals(s).iter().map(ToString::to_string))
        .collect()
}

/// Warns on stderr, one line each, about [`scenario_warnings`] of `s`: `warning: ORIGIN:
/// tasks.hard.goal_m (6.0, 16.0): no path ...`. The scenario stays valid (a trial runs; such
/// tasks yield nothing, such robots stand still).
pub fn warn_about(origin: &str, s: &Scenario) {
    for w in scenario_warnings(s) {
        experiments::console::warn(format!("warning: {origin}: {w}"));
    }
}
