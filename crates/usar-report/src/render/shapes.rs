//! Scenario shapes as polygons in world coordinates: discs, their closed outlines and debris.

use usar_sim::scenario::{Circle as Disc, Debris, PointM};

/// Vertices used to draw a circle as a polygon in world coordinates.
pub(crate) const CIRCLE_VERTICES: usize = 40;

/// `CIRCLE_VERTICES` points on a disc's rim ([`Disc::outline`]).
pub(crate) fn disc_polygon(c: &Disc) -> Vec<(f64, f64)> {
    xy(c.outline(CIRCLE_VERTICES))
}

pub(crate) fn xy(points: Vec<PointM>) -> Vec<(f64, f64)> {
    points.into_iter().map(|p| (p.x, p.y)).collect()
}

/// The closed outline of a disc (first vertex repeated at the end).
pub(crate) fn disc_outline(c: &Disc) -> Vec<(f64, f64)> {
    let mut pts = disc_polygon(c);
    pts.push(pts[0]);
    pts
}

/// A debris item's outline from its parry shape ([`Debris::shape`]): a rectangle's corners, or
/// `CIRCLE_VERTICES` points of a disc.
pub(crate) fn debris_polygon(d: &Debris) -> Vec<(f64, f64)> {
    xy(d.shape().outline(CIRCLE_VERTICES))
}
