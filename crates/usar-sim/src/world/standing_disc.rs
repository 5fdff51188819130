//! A robot standing in the way of a detour, as a keep-out disc.
//!
//! The point and segment tests a detour's cells and smoothed legs must pass.

use parry2d::math::Vector as Vec2;

/// A robot standing in the way of a detour ([`super::path_planner::PathPlanner::plan_around`]): no cell centre and
/// no smoothed leg may come nearer to `center` than `radius_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandingDisc {
    /// Centre of the standing robot, metres.
    pub center: Vec2,
    /// Keep-out radius around it (its body radius plus the planning inflation), metres.
    pub radius_m: f32,
}

impl StandingDisc {
    /// Whether point `p` lies inside the disc (`|p - center|^2 < radius_m^2` in `f32`; the
    /// detour's [`super::disc_mask::DiscMask`] marks cells by this test).
    pub(super) fn contains(&self, p: Vec2) -> bool {
        (p - self.center).length_squared() < self.radius_m * self.radius_m
    }

    /// The disc, shrunk if needed so that none of `points` lies inside it (to 0.999 of the
    /// nearest one's distance); `None` when a point is at its centre.
    pub(super) fn leaving_out(&self, points: &[Vec2]) -> Option<Self> {
        let nearest = points
            .iter()
            .map(|&p| (p - self.center).length())
            .fold(f32::INFINITY, f32::min);
        let radius_m = self.radius_m.min(nearest * 0.999);
        (radius_m > 0.0).then_some(Self {
            center: self.center,
            radius_m,
        })
    }

    /// Whether segment `a`-`b` passes through the disc.
    pub(super) fn crosses(&self, a: Vec2, b: Vec2) -> bool {
        let d = b - a;
        let len2 = d.length_squared();
        let t = if len2 > 0.0 {
            ((self.center - a).dot(d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.contains(a + d * t)
    }
}
