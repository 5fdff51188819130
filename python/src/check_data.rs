//! `Scenario.check()`: what `usar check` prints about a valid scenario (arena and timing, the
//! kinds with their quotas, the tasks, every robot's start and distances, debris, radiation,
//! rest stations, the scenario hash) and the mission's parameters, as a Python dict of plain
//! values (metres, seconds).

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use usar_sim::scenario::{Debris, Locomotion, PointM, Scenario};

use crate::errors::chain_value_error;

fn xy(p: &PointM) -> (f64, f64) {
    (p.x, p.y)
}

fn dist(a: PointM, b: PointM) -> f64 {
    ((a.x - b.x).powi(2) + (a.y - b.y).powi(2)).sqrt()
}

/// The summary of `s` (keys in docs/python.md and `usar/_usar.pyi`).
///
/// # Errors
/// A scenario hash that cannot be computed (not expected), as a `ValueError`.
pub fn summary<'py>(py: Python<'py>, s: &Scenario) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("name", s.name())?;
    d.set_item("description", s.description())?;
    let arena = PyDict::new(py);
    arena.set_item("width_m", s.arena().width())?;
    arena.set_item("height_m", s.arena().height())?;
    arena.set_item("wall_thickness_m", s.arena().wall_thickness_m.get())?;
    d.set_item("arena", arena)?;
    let (dt_s, duration_s) = (s.sim().dt_s.get(), s.mission().duration_s.get());
    d.set_item("dt_s", dt_s)?;
    d.set_item("duration_s", duration_s)?;
    d.set_item(
        "simulated_s",
        usar_sweep::sweep::simulated_length_s(duration_s, dt_s),
    )?;
    d.set_item("steps", s.steps_per_trial())?;
    d.set_item("seed", s.sim().seed)?;
    d.set_item(
        "control_period_s",
        s.sim().control_period_s.map(|p| p.get()),
    )?;
    d.set_item("physics", format!("{:?}", s.sim().physics))?;
    d.set_item("kinds", kinds(py, s)?)?;
    d.set_item("tasks", tasks(py, s)?)?;
    d.set_item("robots", robots(py, s)?)?;
    let rests: Vec<((f64, f64), f64)> = s
        .rest_stations()
        .iter()
        .map(|c| (xy(&c.center), c.radius_m))
        .collect();
    d.set_item("rest_stations", rests)?;
    let rects = s
        .debris()
        .iter()
        .filter(|x| matches!(x, Debris::Rect { .. }))
        .count();
    d.set_item("debris_rects", rects)?;
    d.set_item("debris_circles", s.debris().len() - rects)?;
    let zones: Vec<((f64, f64), f64, f64)> = s
        .radiation_zones()
        .iter()
        .map(|z| (xy(&z.area.center), z.area.radius_m, z.dose_rate_factor))
        .collect();
    d.set_item("radiation_zones", zones)?;
    let hash = usar_sweep::fingerprint::scenario_hash(s).map_err(|e| chain_value_error(&e))?;
    d.set_item("hash", hash)?;
    d.set_item("needs_len", usar_sim::scenario::NEEDS_LEN)?;
    // The mission's parameters as the scenario file writes them (every field, defaults too).
    let mission = serde_json::to_value(&s.spec().mission).map_err(|e| chain_value_error(&e))?;
    d.set_item("mission", crate::json_value::to_python(py, &mission)?)?;
    Ok(d)
}

fn kinds<'py>(py: Python<'py>, s: &Scenario) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for k in s.kinds() {
        let d = PyDict::new(py);
        d.set_item("name", &k.name)?;
        d.set_item("role", format!("{:?}", k.role))?;
        let moves = match k.locomotion {
            Locomotion::Ground => "ground",
            Locomotion::Aerial => "aerial",
        };
        d.set_item("locomotion", moves)?;
        d.set_item("count", k.count)?;
        let quota = PyDict::new(py);
        for (t, q) in s.tasks().iter().zip(&k.quota) {
            quota.set_item(&t.name, q)?;
        }
        d.set_item("quota", quota)?;
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

fn tasks<'py>(py: Python<'py>, s: &Scenario) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    let order = s.hardest_first();
    for (t, task) in s.tasks().iter().enumerate() {
        let d = PyDict::new(py);
        d.set_item("name", &task.name)?;
        d.set_item("difficulty", task.difficulty)?;
        // 0 = the hardest task, as `GroupingRequest`'s tasks count.
        let rank = order.iter().position(|&x| x == t).unwrap_or(0);
        d.set_item("rank", rank)?;
        d.set_item("rescuees", task.rescuees.len())?;
        let area = &task.search_area;
        d.set_item("search_area_m", (xy(&area.min), xy(&area.max)))?;
        d.set_item("goal_m", xy(&task.goal))?;
        d.set_item(
            "drop_off",
            (xy(&task.drop_off.center), task.drop_off.radius_m),
        )?;
        let quota = PyDict::new(py);
        for k in s.kinds() {
            quota.set_item(&k.name, k.quota[t])?;
        }
        d.set_item("quota", quota)?;
        let ds: Vec<f64> = s
            .robots()
            .iter()
            .map(|r| dist(r.start_in_world, task.goal))
            .collect();
        let lo = ds.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = ds.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mean = ds.iter().sum::<f64>() / ds.len().max(1) as f64;
        d.set_item("start_to_goal_m", (lo, hi, mean))?;
        out.append(d)?;
    }
    Ok(out)
}

fn robots<'py>(py: Python<'py>, s: &Scenario) -> PyResult<Bound<'py, PyList>> {
    let out = PyList::empty(py);
    for (id, r) in s.robots().iter().enumerate() {
        let d = PyDict::new(py);
        d.set_item("id", id)?;
        d.set_item("kind", &s.kind_of(id).name)?;
        d.set_item("kind_index", r.kind)?;
        d.set_item("start_m", xy(&r.start_in_world))?;
        let to = PyDict::new(py);
        for t in s.tasks() {
            to.set_item(&t.name, dist(r.start_in_world, t.goal))?;
        }
        d.set_item("distance_to_goal_m", to)?;
        out.append(d)?;
    }
    Ok(out)
}
