//! Small exact 2-D geometry on [`Debris`] used by validation and debris generation.

use nalgebra::Vector2;

use super::model::{Debris, PointM};

/// The four corners of a rotated rectangle, counter-clockwise.
fn rect_corners(center: &PointM, half: &Vector2<f64>, rot: f64) -> [PointM; 4] {
    let (s, c) = rot.sin_cos();
    let r = |x: f64, y: f64| center + Vector2::new(c * x - s * y, s * x + c * y);
    [
        r(-half.x, -half.y),
        r(half.x, -half.y),
        r(half.x, half.y),
        r(-half.x, half.y),
    ]
}

/// Distance from `p` to the shape (0 when `p` is inside or on it).
pub(crate) fn distance_to_point(d: &Debris, p: &PointM) -> f64 {
    match d {
        Debris::Circle(c) => ((p - c.center).norm() - c.radius_m).max(0.0),
        Debris::Rect {
            center,
            half_extents_m,
            rotation_rad,
        } => {
            let (s, c) = rotation_rad.sin_cos();
            let v = p - center;
            // Rotate into the rectangle's frame.
            let local = Vector2::new(c * v.x + s * v.y, -s * v.x + c * v.y);
            let q = Vector2::new(
                (local.x.abs() - half_extents_m.x).max(0.0),
                (local.y.abs() - half_extents_m.y).max(0.0),
            );
            q.norm()
        }
    }
}

/// Axis-aligned bounding box `(min, max)` of the shape.
pub(crate) fn aabb(d: &Debris) -> (PointM, PointM) {
    match d {
        Debris::Circle(c) => {
            let r = Vector2::new(c.radius_m, c.radius_m);
            (c.center - r, c.center + r)
        }
        Debris::Rect {
            center,
            half_extents_m: h,
            rotation_rad,
        } => {
            let (s, c) = rotation_rad.sin_cos();
            let e = Vector2::new(c.abs() * h.x + s.abs() * h.y, s.abs() * h.x + c.abs() * h.y);
            (center - e, center + e)
        }
    }
}

fn cross(o: &PointM, a: &PointM, b: &PointM) -> f64 {
    (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
}

/// Whether closed segments `ab` and `cd` intersect.
fn segments_intersect(a: &PointM, b: &PointM, c: &PointM, d: &PointM) -> bool {
    let d1 = cross(c, d, a);
    let d2 = cross(c, d, b);
    let d3 = cross(a, b, c);
    let d4 = cross(a, b, d);
    if ((d1 > 0.0 && d2 < 0.0) || (d1 < 0.0 && d2 > 0.0))
        && ((d3 > 0.0 && d4 < 0.0) || (d3 < 0.0 && d4 > 0.0))
    {
        return true;
    }
    let on = |p: &PointM, q: &PointM, r: &PointM| {
        r.x >= p.x.min(q.x) && r.x <= p.x.max(q.x) && r.y >= p.y.min(q.y) && r.y <= p.y.max(q.y)
    };
    (d1 == 0.0 && on(c, d, a))
        || (d2 == 0.0 && on(c, d, b))
        || (d3 == 0.0 && on(a, b, c))
        || (d4 == 0.0 && on(a, b, d))
}

/// Smallest distance between two shapes (0 when they touch or overlap).
pub(crate) fn distance_between(a: &Debris, b: &Debris) -> f64 {
    match (a, b) {
        (Debris::Circle(c), other) | (other, Debris::Circle(c)) => {
            (distance_to_point(other, &c.center) - c.radius_m).max(0.0)
        }
        (
            Debris::Rect {
                center: ca,
                half_extents_m: ha,
                rotation_rad: ra,
            },
            Debris::Rect {
                center: cb,
                half_extents_m: hb,
                rotation_rad: rb,
            },
        ) => {
            let pa = rect_corners(ca, ha, *ra);
            let pb = rect_corners(cb, hb, *rb);
            for i in 0..4 {
                for j in 0..4 {
                    if segments_intersect(&pa[i], &pa[(i + 1) % 4], &pb[j], &pb[(j + 1) % 4]) {
                        return 0.0;
                    }
                }
            }
            // No edges cross: either one contains the other (a corner distance is 0) or the
            // closest pair involves a corner.
            let ab = pa.iter().map(|p| distance_to_point(b, p));
            let ba = pb.iter().map(|p| distance_to_point(a, p));
            ab.chain(ba).fold(f64::INFINITY, f64::min)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::model::Circle;
    use approx::assert_relative_eq;
    use nalgebra::Point2;

    fn rect(x: f64, y: f64, hx: f64, hy: f64, rot: f64) -> Debris {
        Debris::Rect {
            center: Point2::new(x, y),
            half_extents_m: Vector2::new(hx, hy),
            rotation_rad: rot,
        }
    }

    #[test]
    fn point_distances() {
        let r = rect(0.0, 0.0, 1.0, 0.5, 0.0);
        assert_eq!(distance_to_point(&r, &Point2::new(0.5, 0.2)), 0.0);
        assert_relative_eq!(distance_to_point(&r, &Point2::new(3.0, 0.0)), 2.0);
        assert_relative_eq!(distance_to_point(&r, &Point2::new(4.0, 4.5)), 5.0);
        let rr = rect(0.0, 0.0, 1.0, 0.5, std::f64::consts::FRAC_PI_2);
        assert_relative_eq!(distance_to_point(&rr, &Point2::new(0.0, 3.0)), 2.0);
        let c = Debris::Circle(Circle {
            center: Point2::new(1.0, 1.0),
            radius_m: 1.0,
        });
        assert_relative_eq!(distance_to_point(&c, &Point2::new(4.0, 5.0)), 4.0);
    }

    #[test]
    fn aabb_of_rotated_rect() {
        let r = rect(0.0, 0.0, 1.0, 1.0, std::f64::consts::FRAC_PI_4);
        let (lo, hi) = aabb(&r);
        assert_relative_eq!(hi.x, 2f64.sqrt(), epsilon = 1e-12);
        assert_relative_eq!(lo.y, -(2f64.sqrt()), epsilon = 1e-12);
    }

    #[test]
    fn shape_distances() {
        let a = rect(0.0, 0.0, 1.0, 1.0, 0.0);
        let b = rect(5.0, 0.0, 1.0, 1.0, 0.0);
        assert_relative_eq!(distance_between(&a, &b), 3.0);
        // A cross: no corner inside the other, edges cross.
        let h = rect(0.0, 0.0, 3.0, 0.2, 0.0);
        let v = rect(0.0, 0.0, 0.2, 3.0, 0.0);
        assert_eq!(distance_between(&h, &v), 0.0);
        let c = Debris::Circle(Circle {
            center: Point2::new(0.0, 4.0),
            radius_m: 1.0,
        });
        assert_relative_eq!(distance_between(&a, &c), 2.0);
        assert_relative_eq!(distance_between(&c, &a), 2.0);
    }
}
