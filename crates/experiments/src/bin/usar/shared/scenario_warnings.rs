//! The warnings about a valid scenario (tasks no group can rescue from, goals some robots cannot
//! reach), as text and on stderr; `usar check`, `usar run` and `usar sweep` give them.

pub use usar_sim::mission::scenario_warnings;
use usar_sim::scenario::Scenario;

/// Warns on stderr, one line each, about [`scenario_warnings`] of `s`: `warning: ORIGIN:
/// tasks.hard.goal_m (6.0, 16.0): no path ...`. The scenario stays valid (a trial runs; such
/// tasks yield nothing, such robots stand still).
pub fn warn_about(origin: &str, s: &Scenario) {
    for w in scenario_warnings(s) {
        crate::shared::stderr_lines::warn(format!("warning: {origin}: {w}"));
    }
}
