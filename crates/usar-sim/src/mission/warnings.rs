//! The warnings about a valid scenario, one line each: what a check finds that will make
//! trials yield less than the scenario suggests, although they run. `usar check`, `usar run`,
//! `usar sweep` and the Python package (`usar.ScenarioWarning`) give the same lines.

use super::reachability::unreachable_goals;
use super::rescue_capacity::tasks_without_rescue;
use crate::scenario::Scenario;

/// The warnings about the valid scenario `s`, one line each, without an origin: first the
/// tasks no group can rescue from ([`tasks_without_rescue`]: `tasks.west: no kind has a quota
/// for it; the task is never worked`), then the goals some robots cannot reach from their
/// starts ([`unreachable_goals`]). Empty for a scenario without either. Cost: one labelling
/// of the clearance grid's regions per clearance class; no trial runs.
pub fn scenario_warnings(s: &Scenario) -> Vec<String> {
    let idle = tasks_without_rescue(s).into_iter().map(|t| t.to_string());
    idle.chain(unreachable_goals(s).iter().map(ToString::to_string))
        .collect()
}
