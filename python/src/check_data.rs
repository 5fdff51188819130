//! `Scenario.check()`: what `usar check` prints about a valid scenario (arena and timing, the
//! kinds with their quotas, the tasks, every robot's start and distances, debris, radiation,
//! rest stations, the scenario hash) and the mission's parameters, as a Python dict of plain
//! values (metres, seconds): the library's [`ScenarioSummary`], rendered as a dict.

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use usar_report::scenario_summary::ScenarioSummary;
use usar_sim::scenario::Scenario;

use crate::errors::chain_value_error;

/// A dict of `(name, value)` pairs, in their order.
fn pairs<'py, T: IntoPyObject<'py> + Copy>(
    py: Python<'py>,
    items: &[(String, T)],
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, v) in items {
        d.set_item(name, *v)?;
    }
    Ok(d)
}

/// The summary of `s` ([`ScenarioSummary`], which `usar check` prints; keys in
/// docs/python.md and `usar/_usar.pyi`).
///
/// # Errors
/// A scenario hash that cannot be computed (not expected), as a `ValueError`.
pub fn summary<'py>(py: Python<'py>, s: &Scenario) -> PyResult<Bound<'py, PyDict>> {
    let sum = ScenarioSummary::of(s).map_err(|e| chain_value_error(&e))?;
    let d = PyDict::new(py);
    d.set_item("name", &sum.name)?;
    d.set_item("description", &sum.description)?;
    let arena = PyDict::new(py);
    arena.set_item("width_m", sum.arena.width_m)?;
    arena.set_item("height_m", sum.arena.height_m)?;
    arena.set_item("wall_thickness_m", sum.arena.wall_thickness_m)?;
    d.set_item("arena", arena)?;
    d.set_item("dt_s", sum.dt_s)?;
    d.set_item("duration_s", sum.duration_s)?;
    d.set_item("simulated_s", sum.simulated_s)?;
    d.set_item("steps", sum.steps)?;
    d.set_item("seed", sum.seed)?;
    d.set_item("control_period_s", sum.control_period_s)?;
    d.set_item("physics", &sum.physics)?;
    d.set_item("kinds", kinds(py, &sum)?)?;
    d.set_item("tasks", tasks(py, &sum)?)?;
    d.set_item("robots", robots(py, &sum)?)?;
    d.set_item("rest_stations", &sum.rest_stations)?;
    d.set_item("debris_rects", sum.debris_rects)?;
    d.set_item("debris_circles", sum.debris_circles)?;
    d.set_item("radiation_zones", &sum.radiation_zones)?;
    d.set_item("hash", &sum.hash)?;
    d.set_item("needs_len", sum.needs_len)?;
    d.set_item("mission", crate::json_value::to_python(py, &sum.mission)?)?;
    Ok(d)
}

fn kinds<'py>(py: Python<'py>, s: &ScenarioSummary) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for k in &s.kinds {
        let d = PyDict::new(py);
        d.set_item("name", &k.name)?;
        d.set_item("role", &k.role)?;
        d.set_item("locomotion", k.locomotion)?;
        d.set_item("count", k.count)?;
        d.set_item("quota", pairs(py, &k.quota)?)?;
        d.set_item("max_speed_m_per_s", k.max_speed_m_per_s)?;
        d.set_item("sensing_range_m", k.sensing_range_m)?;
        d.set_item("observing_range_m", k.observing_range_m)?;
        d.set_item("body_radius_m", k.body_radius_m)?;
        d.set_item("carrying_capacity", k.carrying_capacity)?;
        d.set_item("rescuing_resources", k.rescuing_resources)?;
        out.append(d)?;
    }
    Ok(out)
}

fn tasks<'py>(py: Python<'py>, s: &ScenarioSummary) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for t in &s.tasks {
        let d = PyDict::new(py);
        d.set_item("name", &t.name)?;
        d.set_item("difficulty", t.difficulty)?;
        // 0 = the hardest task, as `GroupingRequest`'s tasks count.
        d.set_item("rank", t.rank)?;
        d.set_item("rescuees", t.rescuees)?;
        d.set_item("search_area_m", t.search_area_m)?;
        d.set_item("goal_m", t.goal_m)?;
        d.set_item("drop_off", t.drop_off)?;
        d.set_item("quota", pairs(py, &t.quota)?)?;
        d.set_item("start_to_goal_m", t.start_to_goal_m)?;
        out.append(d)?;
    }
    Ok(out)
}

fn robots<'py>(py: Python<'py>, s: &ScenarioSummary) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for r in &s.robots {
        let d = PyDict::new(py);
        d.set_item("id", r.id)?;
        d.set_item("kind", &r.kind)?;
        d.set_item("kind_index", r.kind_index)?;
        d.set_item("start_m", r.start_m)?;
        d.set_item("distance_to_goal_m", pairs(py, &r.distance_to_goal_m)?)?;
        out.append(d)?;
    }
    Ok(out)
}
