//! The size of a blind search's lawn-mower pattern: the spacing of its rows and the number of
//! its waypoints over a search area, pure functions of the scenario's data.
//!
//! Validation bounds every task's pattern by
//! [`MAX_SWEEP_POINTS`](super::limits::MAX_SWEEP_POINTS) with these; the mission lays the
//! waypoints out (`mission::sweep_waypoints`) and re-exports both functions. See "Searching" in
//! `docs/mission-model.md`.

use super::choices::SweepPattern;
use super::model::{Locomotion, Rect};
use super::validated::Scenario;

/// How many waypoints the blind search's lawn-mower pattern (`mission::sweep_waypoints`) makes
/// over `area` at `spacing_m`: `(ceil(width / spacing_m) + 1) * ceil(height / spacing_m)` for
/// `EdgeToEdge`, `ceil(width / spacing_m) * ceil(height / spacing_m)` for `CentreToCentre`,
/// each ceiling at least 1; an `f64` so that it cannot overflow (`inf` or `NaN` for a spacing
/// that is not finite and `> 0`).
pub fn sweep_point_count(area: &Rect, spacing_m: f64, pattern: SweepPattern) -> f64 {
    let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
    let cols = (w / spacing_m).ceil().max(1.0);
    let per_row = match pattern {
        SweepPattern::EdgeToEdge => cols + 1.0,
        SweepPattern::CentreToCentre => cols,
    };
    per_row * (h / spacing_m).ceil().max(1.0)
}

/// The spacing of a scenario's blind-search rows, metres: `mission.sweep_spacing_m` if set,
/// otherwise the narrowest detection width of its ground kinds, `2 * (body_radius_m +
/// observing_range_m)` (at full HP), so that a sweep detects every rescuee of the area.
pub fn sweep_spacing_m(scenario: &Scenario) -> f64 {
    scenario.mission.sweep_spacing_m.map_or_else(
        || {
            scenario
                .kinds
                .iter()
                .filter(|k| k.locomotion == Locomotion::Ground)
                .map(|k| 2.0 * (k.body_radius_m + k.observing_range_m))
                .fold(f64::INFINITY, f64::min)
                .min(f64::MAX)
        },
        |s| s.get(),
    )
}
