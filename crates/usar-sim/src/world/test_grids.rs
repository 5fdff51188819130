//! Test fixtures of the navigation tests: obstacles and a 10 m clearance grid.

use parry2d::math::{Pose, Vector as Vec2};
use parry2d::shape::{Ball, Cuboid};

use super::bodies::{StaticObstacle, StaticShape};
use super::clearance_grid::ClearanceGrid;
use crate::scenario::{Arena, Positive};

/// Cell side of the test grids, metres.
pub(super) const CELL: f64 = 0.25;
/// Planning inflation of the tests, metres (a 0.4 m body, 0.075 m clearance, half a cell).
pub(super) const INFL: f32 = 0.6;

/// A rectangle of half extents `hx`, `hy` centred on (`cx`, `cy`), metres.
pub(super) fn block(cx: f32, cy: f32, hx: f32, hy: f32) -> StaticObstacle {
    StaticObstacle {
        shape: StaticShape::Cuboid(Cuboid::new(Vec2::new(hx, hy))),
        pose: Pose::translation(cx, cy),
        is_wall: false,
    }
}

/// A disc of radius `r` centred on (`cx`, `cy`), metres.
pub(super) fn disc(cx: f32, cy: f32, r: f32) -> StaticObstacle {
    StaticObstacle {
        shape: StaticShape::Ball(Ball::new(r)),
        pose: Pose::translation(cx, cy),
        is_wall: false,
    }
}

/// A 10 m x 10 m grid of 0.25 m cells, clearance capped at 2 m.
pub(super) fn grid(statics: &[StaticObstacle]) -> ClearanceGrid {
    let arena = Arena {
        width_m: Positive::new(10.0).unwrap(),
        height_m: Positive::new(10.0).unwrap(),
        wall_thickness_m: Positive::new(0.5).unwrap(),
    };
    ClearanceGrid::build(&arena, statics, CELL, 2.0)
}

/// Exact distance from `p` to the nearest of `statics`.
pub(super) fn exact(statics: &[StaticObstacle], p: Vec2) -> f32 {
    statics
        .iter()
        .map(|o| o.distance_to_point(p))
        .fold(f32::INFINITY, f32::min)
}

/// Asserts that every point of every leg of `path` (sampled each centimetre) keeps at least
/// `min` metres from `statics` (the exact distance, [`exact`]).
pub(super) fn legs_clear(statics: &[StaticObstacle], path: &[Vec2], min: f32) {
    for leg in path.windows(2) {
        let n = ((leg[1] - leg[0]).length() / 0.01).ceil() as u32;
        for k in 0..=n {
            let p = leg[0] + (leg[1] - leg[0]) * (k as f32 / n.max(1) as f32);
            let d = exact(statics, p);
            assert!(d >= min, "{p:?} on leg {leg:?} is {d} m from debris");
        }
    }
}
