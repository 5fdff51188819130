//! [`RadiationField`]: the scenario's radiation zones with their dose rule, read robot by
//! robot every step; looks only at the zones whose discs may hold a point (by the buckets of
//! `static_buckets.rs`) instead of all of them.
//!
//! Not in the paper (the dose itself is `radiation.rs`, paper section VI.B). The answers are
//! those of [`radiation_factor_at`] over every zone, bit for bit: a zone whose disc does not
//! hold the point adds exactly `0.0` to the sum (which leaves any other partial sum as it is)
//! and does not change the largest factor.

use parry2d::bounding_volume::Aabb;
use parry2d::math::Vector as Vec2;

use super::radiation::{DoseRule, radiation_factor_at, zone_factor_at};
use super::static_buckets::StaticBuckets;
use crate::scenario::{PointM, RadiationOverlap, RadiationZone};

/// What a zone's bucketed box adds to its disc, metres, and relative to its coordinates: far
/// above the rounding of the `f64` geometry to the buckets' `f32` (a point in the disc always
/// lies in the box).
const BOX_PAD_M: f32 = 0.01;
const BOX_PAD_REL: f32 = 1e-5;

/// The radiation zones of a world with their [`DoseRule`].
#[derive(Debug, Clone)]
pub struct RadiationField {
    zones: Vec<RadiationZone>,
    rule: DoseRule,
    buckets: StaticBuckets,
}

impl RadiationField {
    /// The field of `zones` under `rule` over an arena of `width_m` x `height_m` metres (zones
    /// and points outside it are still exact: the buckets clamp).
    pub fn new(zones: Vec<RadiationZone>, rule: DoseRule, width_m: f32, height_m: f32) -> Self {
        let boxes: Vec<Aabb> = zones
            .iter()
            .map(|z| {
                let c = Vec2::new(z.area.center.x as f32, z.area.center.y as f32);
                let r = z.area.radius_m as f32;
                let pad = BOX_PAD_M + BOX_PAD_REL * (c.x.abs() + c.y.abs() + r);
                let half = Vec2::splat(r + pad);
                Aabb::new(c - half, c + half)
            })
            .collect();
        Self {
            buckets: StaticBuckets::new(&boxes, width_m, height_m),
            zones,
            rule,
        }
    }

    /// The dose factor at `p` ([`radiation_factor_at`] over every zone, the same bits),
    /// dimensionless, finite and `>= 0`. A point with a NaN or infinite coordinate (a body
    /// thrown out by a blow-up) is answered by the scan of every zone: a NaN distance counts
    /// as inside every uniform zone there, which no bucket can say.
    pub fn factor_at(&self, p: &PointM) -> f64 {
        if self.zones.is_empty() || !(p.x.is_finite() && p.y.is_finite()) {
            return radiation_factor_at(&self.zones, p, self.rule);
        }
        let at = Vec2::new(p.x as f32, p.y as f32);
        let factors = self
            .buckets
            .at(at)
            .map(|k| zone_factor_at(&self.zones[k], p, self.rule.falloff));
        match self.rule.overlap {
            // From +0.0: a sum over every zone, one of them at least, is never -0.0.
            RadiationOverlap::Sum => factors.fold(0.0, |a, f| a + f).min(f64::MAX),
            RadiationOverlap::Max => factors.fold(0.0, f64::max),
        }
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::scenario::{Circle, RadiationFalloff};

    proptest! {
        /// The bucketed factor is the scan's, bit for bit, for points in, near and far from
        /// overlapping zones (inside and outside the arena), under every rule.
        #[test]
        fn the_same_bits_as_every_zone(
            zones in prop::collection::vec(
                (-50.0f64..250.0, -50.0f64..250.0, 0.0f64..40.0, 0.0f64..5.0), 1..12),
            points in prop::collection::vec((-80.0f64..280.0, -80.0f64..280.0), 1..40),
            sum in any::<bool>(),
            linear in any::<bool>(),
        ) {
            let zones: Vec<RadiationZone> = zones
                .iter()
                .map(|&(x, y, r, f)| RadiationZone {
                    area: Circle { center: PointM::new(x, y), radius_m: r },
                    dose_rate_factor: f,
                })
                .collect();
            let rule = DoseRule {
                overlap: if sum { RadiationOverlap::Sum } else { RadiationOverlap::Max },
                falloff: if linear { RadiationFalloff::Linear } else { RadiationFalloff::Uniform },
            };
            let field = RadiationField::new(zones.clone(), rule, 200.0, 200.0);
            let mut probes: Vec<PointM> =
                points.iter().map(|&(x, y)| PointM::new(x, y)).collect();
            // On the rims and at the centres, and off every bucket.
            for (x, y) in [(f64::NAN, 1.0), (1.0, f64::NAN), (f64::INFINITY, 0.0), (0.0, f64::NEG_INFINITY)] {
                probes.push(PointM::new(x, y));
            }
            for z in &zones {
                probes.push(z.area.center);
                probes.push(z.area.center + nalgebra::Vector2::new(z.area.radius_m, 0.0));
            }
            for p in &probes {
                let want = radiation_factor_at(&zones, p, rule);
                prop_assert_eq!(field.factor_at(p).to_bits(), want.to_bits(), "at {:?}", p);
            }
        }
    }
}
