//! Debris as parry2d shapes: the one description of debris geometry.
//!
//! [`Debris::shape`] turns a debris item into a [`DebrisShape`]: a parry2d-f64 ball or cuboid
//! placed by a pose in the world frame. Everything that needs debris geometry goes through it:
//! - validation and debris generation ask it for exact (`f64`) distances to points and to other
//!   debris and for bounding boxes ([`DebrisShape::distance_to_point`],
//!   [`DebrisShape::distance`], [`DebrisShape::aabb`]);
//! - the world's static colliders and clearance grid are its `f32` twins
//!   (`world::bodies::static_obstacles`);
//! - `usar render` draws [`DebrisShape::outline`].
//!
//! Validation stays in `f64` (parry2d-f64) so that the accept/reject decisions of the
//! debris-field generator and the distance rules do not depend on `f32` rounding; the world
//! converts to `f32` at its boundary, parameter by parameter.

use parry2d_f64::math::{Pose, Vector};
use parry2d_f64::query;
use parry2d_f64::shape::{Ball, Cuboid, Shape};

use super::model::{Circle, Debris, PointM};

/// A debris item as a parry2d-f64 shape in the world frame (metres, `f64`).
///
/// Build it with [`Debris::shape`] (or [`DebrisShape::new`]); building costs one `sin_cos` for
/// a rectangle, so keep shapes that are queried often.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DebrisShape {
    debris: Debris,
    primitive: Primitive,
    pose: Pose,
}

/// The shape of a debris item in its local frame (parry2d-f64).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Primitive {
    /// A disc of the debris circle's radius.
    Ball(Ball),
    /// A rectangle of the debris rectangle's half extents.
    Cuboid(Cuboid),
}

fn vector(p: &PointM) -> Vector {
    Vector::new(p.x, p.y)
}

fn point(v: Vector) -> PointM {
    PointM::new(v.x, v.y)
}

impl Debris {
    /// This debris item as a parry2d-f64 shape (see [`DebrisShape`]).
    pub fn shape(&self) -> DebrisShape {
        DebrisShape::new(self)
    }
}

impl DebrisShape {
    /// The shape of `debris`: a cuboid of its half extents rotated by `rotation_rad` about its
    /// centre, or a ball of its radius at its centre.
    pub fn new(debris: &Debris) -> Self {
        let (primitive, pose) = match debris {
            Debris::Rect {
                center,
                half_extents_m: h,
                rotation_rad,
            } => (
                Primitive::Cuboid(Cuboid::new(Vector::new(h.x, h.y))),
                Pose::new(vector(center), *rotation_rad),
            ),
            Debris::Circle(c) => (
                Primitive::Ball(Ball::new(c.radius_m)),
                Pose::from_translation(vector(&c.center)),
            ),
        };
        Self {
            debris: *debris,
            primitive,
            pose,
        }
    }

    /// The debris item this shape was built from.
    pub fn debris(&self) -> &Debris {
        &self.debris
    }

    fn as_shape(&self) -> &dyn Shape {
        match &self.primitive {
            Primitive::Ball(b) => b,
            Primitive::Cuboid(c) => c,
        }
    }

    /// Distance from `p` to the shape, metres: 0 when `p` is inside or on it (parry's solid
    /// point query).
    pub fn distance_to_point(&self, p: &PointM) -> f64 {
        self.as_shape()
            .distance_to_point(&self.pose, vector(p), true)
    }

    /// Smallest distance between this shape and `other`, metres: 0 when they touch or overlap
    /// (parry's `query::distance`).
    pub fn distance(&self, other: &DebrisShape) -> f64 {
        query::distance(&self.pose, self.as_shape(), &other.pose, other.as_shape())
            .map(|d| d.distance)
            .unwrap_or_else(|_| unreachable!("parry measures every pair of balls and cuboids"))
    }

    /// Axis-aligned bounding box `(min, max)` in the world frame, metres (tight for both a disc
    /// and a rotated rectangle).
    pub fn aabb(&self) -> (PointM, PointM) {
        let bb = self.as_shape().compute_aabb(&self.pose);
        (point(bb.mins), point(bb.maxs))
    }

    /// The outline to draw, world frame, metres: a rectangle's four corners counter-clockwise
    /// from its local `(-x, -y)` corner, or `circle_vertices` points of a disc (see
    /// [`Circle::outline`]). Not closed (the first point is not repeated).
    pub fn outline(&self, circle_vertices: usize) -> Vec<PointM> {
        match &self.primitive {
            Primitive::Ball(b) => Circle {
                center: point(self.pose.translation),
                radius_m: b.radius,
            }
            .outline(circle_vertices),
            Primitive::Cuboid(c) => {
                let h = c.half_extents;
                [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                    .into_iter()
                    .map(|(sx, sy)| point(self.pose * Vector::new(sx * h.x, sy * h.y)))
                    .collect()
            }
        }
    }

    /// The shape in its local frame, for the world's `f32` twin.
    pub(crate) fn primitive(&self) -> &Primitive {
        &self.primitive
    }

    /// The centre, world frame, metres.
    pub(crate) fn center(&self) -> PointM {
        point(self.pose.translation)
    }

    /// The rotation about the centre as given in the scenario, radians (0 for a disc). The world
    /// rebuilds its `f32` pose from this angle, not from the pose's `f64` sine and cosine.
    pub(crate) fn rotation_rad(&self) -> f64 {
        match self.debris {
            Debris::Rect { rotation_rad, .. } => rotation_rad,
            Debris::Circle(_) => 0.0,
        }
    }
}

impl Circle {
    /// `vertices` points on the circle, world frame, metres, counter-clockwise from angle 0
    /// (`center + radius (cos t, sin t)`, `t = 2 pi i / vertices`); for drawing. Not closed.
    pub fn outline(&self, vertices: usize) -> Vec<PointM> {
        (0..vertices)
            .map(|i| {
                let t = i as f64 / vertices as f64 * std::f64::consts::TAU;
                PointM::new(
                    self.center.x + self.radius_m * t.cos(),
                    self.center.y + self.radius_m * t.sin(),
                )
            })
            .collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;
    use nalgebra::{Point2, Vector2};

    fn rect(x: f64, y: f64, hx: f64, hy: f64, rot: f64) -> DebrisShape {
        Debris::Rect {
            center: Point2::new(x, y),
            half_extents_m: Vector2::new(hx, hy),
            rotation_rad: rot,
        }
        .shape()
    }

    fn disc(x: f64, y: f64, r: f64) -> DebrisShape {
        Debris::Circle(Circle {
            center: Point2::new(x, y),
            radius_m: r,
        })
        .shape()
    }

    #[test]
    fn point_distances() {
        let r = rect(0.0, 0.0, 1.0, 0.5, 0.0);
        assert_eq!(r.distance_to_point(&Point2::new(0.5, 0.2)), 0.0);
        assert_relative_eq!(r.distance_to_point(&Point2::new(3.0, 0.0)), 2.0);
        assert_relative_eq!(r.distance_to_point(&Point2::new(4.0, 4.5)), 5.0);
        let rr = rect(0.0, 0.0, 1.0, 0.5, std::f64::consts::FRAC_PI_2);
        assert_relative_eq!(rr.distance_to_point(&Point2::new(0.0, 3.0)), 2.0);
        let c = disc(1.0, 1.0, 1.0);
        assert_relative_eq!(c.distance_to_point(&Point2::new(4.0, 5.0)), 4.0);
        assert_eq!(c.distance_to_point(&Point2::new(1.5, 1.0)), 0.0);
    }

    #[test]
    fn aabb_of_rotated_rect_and_disc() {
        let r = rect(0.0, 0.0, 1.0, 1.0, std::f64::consts::FRAC_PI_4);
        let (lo, hi) = r.aabb();
        assert_relative_eq!(hi.x, 2f64.sqrt(), epsilon = 1e-12);
        assert_relative_eq!(lo.y, -(2f64.sqrt()), epsilon = 1e-12);
        let (lo, hi) = disc(3.0, 4.0, 0.5).aabb();
        assert_eq!((lo, hi), (Point2::new(2.5, 3.5), Point2::new(3.5, 4.5)));
    }

    #[test]
    fn shape_distances() {
        let a = rect(0.0, 0.0, 1.0, 1.0, 0.0);
        let b = rect(5.0, 0.0, 1.0, 1.0, 0.0);
        assert_relative_eq!(a.distance(&b), 3.0);
        // A cross: no corner inside the other, edges cross.
        let h = rect(0.0, 0.0, 3.0, 0.2, 0.0);
        let v = rect(0.0, 0.0, 0.2, 3.0, 0.0);
        assert_eq!(h.distance(&v), 0.0);
        // One inside the other.
        assert_eq!(a.distance(&rect(0.2, 0.1, 0.3, 0.3, 0.4)), 0.0);
        // Corner to corner, one rotated by 45 degrees: its corner is at x = 5 - sqrt(2).
        let d = rect(5.0, 0.0, 1.0, 1.0, std::f64::consts::FRAC_PI_4);
        assert_relative_eq!(a.distance(&d), 4.0 - 2f64.sqrt(), epsilon = 1e-12);
        let c = disc(0.0, 4.0, 1.0);
        assert_relative_eq!(a.distance(&c), 2.0);
        assert_relative_eq!(c.distance(&a), 2.0);
        assert_relative_eq!(c.distance(&disc(0.0, 7.0, 0.5)), 1.5);
    }

    #[test]
    fn outlines() {
        let r = rect(1.0, 2.0, 2.0, 1.0, std::f64::consts::FRAC_PI_2);
        let corners = r.outline(40);
        // Rotated by 90 degrees: local (-2, -1) lands at (1 + 1, 2 - 2).
        let expected = [(2.0, 0.0), (2.0, 4.0), (0.0, 4.0), (0.0, 0.0)];
        assert_eq!(corners.len(), 4);
        for (p, (x, y)) in corners.iter().zip(expected) {
            assert_relative_eq!(p.x, x, epsilon = 1e-12);
            assert_relative_eq!(p.y, y, epsilon = 1e-12);
        }
        let c = disc(1.0, 1.0, 2.0).outline(4);
        assert_eq!(c.len(), 4);
        assert_eq!(c[0], Point2::new(3.0, 1.0));
        assert_relative_eq!(c[1].y, 3.0, epsilon = 1e-12);
        assert_relative_eq!(c[2].x, -1.0, epsilon = 1e-12);
    }
}
