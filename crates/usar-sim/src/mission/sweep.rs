//! The blind search of a group without an observer: a lawn-mower pattern over its search area
//! (paper, section IV: without an observer a group searches on its own, 30 % slower).

use crate::scenario::{Locomotion, PointM, Rect, Scenario};

/// Blind-search waypoints over a search area: a lawn-mower pattern of `ceil(height /
/// spacing_m)` rows (at least 1) at the centres of equal horizontal strips, alternating
/// direction, starting at the bottom-left; along each row `ceil(width / spacing_m)` points (at
/// least 1) at the centres of equal vertical strips. Rows and points are thus at most
/// `spacing_m` apart and at most `spacing_m / 2` from the area's edges, so a robot following
/// them passes within `spacing_m / 2` of every point between the first and the last column
/// and within `spacing_m / √2` of every point of the area (the corners). A robot that turns
/// within its waypoint tolerance of a row's end point covers less at the left and right
/// edges: see "Searching" in `docs/mission-model.md` (a known limitation).
///
/// # Panics
/// Unless `spacing_m` is finite and `> 0` and the pattern has at most
/// [`MAX_SWEEP_POINTS`](crate::scenario::limits::MAX_SWEEP_POINTS) points (a validated
/// scenario's spacing always passes both): a clear message instead of an allocation failure.
pub fn sweep_waypoints(area: &Rect, spacing_m: f64) -> Vec<PointM> {
    let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
    let (cols, rows) = (
        (w / spacing_m).ceil().max(1.0),
        (h / spacing_m).ceil().max(1.0),
    );
    assert!(
        spacing_m.is_finite()
            && spacing_m > 0.0
            && cols * rows <= crate::scenario::limits::MAX_SWEEP_POINTS,
        "sweep_waypoints: spacing {spacing_m} m over a {w} x {h} m area: the spacing must be \
         finite and > 0 and give at most {} points",
        crate::scenario::limits::MAX_SWEEP_POINTS
    );
    let (nx, ny) = (cols as usize, rows as usize);
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        let y = area.min.y + (j as f64 + 0.5) * h / ny as f64;
        for k in 0..nx {
            let i = if j % 2 == 0 { k } else { nx - 1 - k };
            out.push(PointM::new(
                area.min.x + (i as f64 + 0.5) * w / nx as f64,
                y,
            ));
        }
    }
    out
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A spacing too fine for the area is a clear panic, not an allocation failure that
    /// aborts the process (1e-7 m over 10 x 10 m asked for 1.6e17 bytes).
    #[test]
    #[should_panic(expected = "the spacing must be finite and > 0 and give at most")]
    fn a_spacing_too_fine_is_a_clear_panic() {
        let area = Rect {
            min: PointM::new(0.0, 0.0),
            max: PointM::new(10.0, 10.0),
        };
        sweep_waypoints(&area, 1e-7);
    }

    #[test]
    fn a_sweep_passes_within_half_its_spacing_of_every_point() {
        let area = Rect {
            min: PointM::new(6.0, 47.0),
            max: PointM::new(26.0, 59.0),
        };
        for spacing in [0.9, 2.0, 3.3] {
            let w = sweep_waypoints(&area, spacing);
            // Distance from p to the polyline through the waypoints.
            let dist = |p: &PointM| {
                w.windows(2)
                    .map(|s| {
                        let (a, b) = (s[0], s[1]);
                        let ab = b - a;
                        let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
                        (a + ab * t - p).norm()
                    })
                    .fold(f64::INFINITY, f64::min)
            };
            for i in 0..=40 {
                for j in 0..=24 {
                    let p = PointM::new(
                        area.min.x + (area.max.x - area.min.x) * f64::from(i) / 40.0,
                        area.min.y + (area.max.y - area.min.y) * f64::from(j) / 24.0,
                    );
                    let inner = p.x >= w[0].x && p.x <= w[1].x.max(w[w.len() - 1].x);
                    let bound = if inner {
                        spacing / 2.0
                    } else {
                        spacing / std::f64::consts::SQRT_2
                    };
                    assert!(
                        dist(&p) <= bound + 1e-9,
                        "spacing {spacing}: {p:?} is {} m from the sweep",
                        dist(&p)
                    );
                }
            }
        }
    }
}
