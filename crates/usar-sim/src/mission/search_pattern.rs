//! The blind search's route: the waypoints of a lawn-mower search pattern over a search area
//! (paper, section IV: without an observer a group searches on its own, 30 % slower).
//!
//! A search pattern, not an experiment sweep. The pattern's row spacing and waypoint count
//! ([`sweep_spacing_m`](crate::scenario::sweep_spacing_m), [`sweep_point_count`]) are
//! scenario data, defined in `scenario::search_pattern` (validation bounds them) and
//! re-exported by this module's parent.

use crate::scenario::{PointM, Rect, SweepPattern, sweep_point_count};

/// Blind-search waypoints over a search area: a lawn-mower pattern of `ceil(height /
/// spacing_m)` rows (at least 1) at the centres of equal horizontal strips, alternating
/// direction, starting at the bottom-left.
///
/// - [`SweepPattern::EdgeToEdge`]: each row runs from the area's left edge to its right edge,
///   `ceil(width / spacing_m) + 1` evenly spaced points, the first and the last exactly on
///   the edges (`x == area.min.x` or `area.max.x`: the turns, which the mission has a robot
///   drive to itself). Rows are at most `spacing_m` apart and at most `spacing_m / 2` from
///   the bottom and top edges, so every point of the area lies within `spacing_m / 2` of the
///   polyline through the points (the rows, and the turns along the left and right edges).
/// - [`SweepPattern::CentreToCentre`] (the model before 2026-11-24): `ceil(width /
///   spacing_m)` points (at least 1) per row at the centres of equal vertical strips, so a
///   row ends half a column from the edge; the polyline passes within `spacing_m / 2` of
///   every point between the first and the last column and within `spacing_m / √2` of the
///   corners, and a robot turning within its waypoint tolerance of a row's end misses more.
///
/// See "Searching" in `docs/mission-model.md`.
///
/// # Panics
/// Unless `spacing_m` is finite and `> 0` and the pattern has at most
/// [`MAX_SWEEP_POINTS`](crate::scenario::limits::MAX_SWEEP_POINTS) points (a validated
/// scenario's spacing always passes both): a clear message instead of an allocation failure.
pub fn sweep_waypoints(area: &Rect, spacing_m: f64, pattern: SweepPattern) -> Vec<PointM> {
    let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
    let points = sweep_point_count(area, spacing_m, pattern);
    assert!(
        spacing_m.is_finite()
            && spacing_m > 0.0
            && points <= crate::scenario::limits::MAX_SWEEP_POINTS,
        "sweep_waypoints: spacing {spacing_m} m over a {w} x {h} m area: the spacing must be \
         finite and > 0 and give at most {} points",
        crate::scenario::limits::MAX_SWEEP_POINTS
    );
    let cols = (w / spacing_m).ceil().max(1.0) as usize;
    let ny = (h / spacing_m).ceil().max(1.0) as usize;
    let nx = match pattern {
        SweepPattern::EdgeToEdge => cols + 1,
        SweepPattern::CentreToCentre => cols,
    };
    let x_at = |i: usize| match pattern {
        // The last point exactly on the right edge (no rounding of i * w / cols).
        SweepPattern::EdgeToEdge if i == cols => area.max.x,
        SweepPattern::EdgeToEdge => area.min.x + i as f64 * w / cols as f64,
        SweepPattern::CentreToCentre => area.min.x + (i as f64 + 0.5) * w / cols as f64,
    };
    let mut out = Vec::with_capacity(nx * ny);
    for j in 0..ny {
        let y = area.min.y + (j as f64 + 0.5) * h / ny as f64;
        for k in 0..nx {
            let i = if j % 2 == 0 { k } else { nx - 1 - k };
            out.push(PointM::new(x_at(i), y));
        }
    }
    out
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
        sweep_waypoints(&area, 1e-7, SweepPattern::EdgeToEdge);
    }

    /// The two patterns' points over a 10 x 4 m area at 2 m: rows at y = 1 and 3, the second
    /// reversed; columns from edge to edge, or at the centres of five 2 m strips.
    #[test]
    fn each_pattern_places_its_rows_and_turns() {
        let area = Rect {
            min: PointM::new(0.0, 0.0),
            max: PointM::new(10.0, 4.0),
        };
        let xy = |pattern| -> Vec<(f64, f64)> {
            sweep_waypoints(&area, 2.0, pattern)
                .iter()
                .map(|p| (p.x, p.y))
                .collect()
        };
        let row = |xs: &[f64], y: f64| xs.iter().map(|&x| (x, y)).collect::<Vec<_>>();
        let edges = [0.0, 2.0, 4.0, 6.0, 8.0, 10.0];
        let back: Vec<f64> = edges.iter().rev().copied().collect();
        assert_eq!(
            xy(SweepPattern::EdgeToEdge),
            [row(&edges, 1.0), row(&back, 3.0)].concat()
        );
        let centres = [1.0, 3.0, 5.0, 7.0, 9.0];
        let back: Vec<f64> = centres.iter().rev().copied().collect();
        assert_eq!(
            xy(SweepPattern::CentreToCentre),
            [row(&centres, 1.0), row(&back, 3.0)].concat()
        );
        for pattern in [SweepPattern::EdgeToEdge, SweepPattern::CentreToCentre] {
            let n = sweep_waypoints(&area, 2.0, pattern).len();
            assert!((sweep_point_count(&area, 2.0, pattern) - n as f64).abs() < 1e-12);
        }
    }

    #[test]
    fn a_sweep_passes_within_half_its_spacing_of_every_point() {
        // Regression: rows ended at the centres of their last columns, so the corners were
        // spacing / sqrt(2) from the pattern.
        let area = Rect {
            min: PointM::new(6.0, 47.0),
            max: PointM::new(26.0, 59.0),
        };
        for spacing in [0.9, 2.0, 3.3] {
            let w = sweep_waypoints(&area, spacing, SweepPattern::EdgeToEdge);
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
                    assert!(
                        dist(&p) <= spacing / 2.0 + 1e-9,
                        "spacing {spacing}: {p:?} is {} m from the sweep",
                        dist(&p)
                    );
                }
            }
        }
    }
}
