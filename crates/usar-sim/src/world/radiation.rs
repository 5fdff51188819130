//! Radiation zones as plain geometry (paper, section VI.B: HP is lost inside radioactive areas).

use crate::scenario::{PointM, RadiationFalloff, RadiationOverlap, RadiationZone};

/// How the zones' doses are read at a point: how overlapping zones combine and how a zone's
/// dose falls off inside it (the scenario's `mission.radiation_overlap` and
/// `mission.radiation_falloff`). The default is the sum of uniform discs.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct DoseRule {
    /// How overlapping zones combine.
    pub overlap: RadiationOverlap,
    /// How a zone's dose varies inside its disc.
    pub falloff: RadiationFalloff,
}

/// The dose factor of one zone at `p`: 0 outside the disc (boundary included as inside), the
/// zone's `dose_rate_factor` inside under [`RadiationFalloff::Uniform`], or
/// `dose_rate_factor * (1 - d / r)` at distance `d` from the centre under
/// [`RadiationFalloff::Linear`]. Dimensionless, `>= 0`.
pub fn zone_factor_at(zone: &RadiationZone, p: &PointM, falloff: RadiationFalloff) -> f64 {
    let d2 = (p - zone.area.center).norm_squared();
    let r = zone.area.radius_m;
    if d2 > r * r {
        return 0.0;
    }
    match falloff {
        RadiationFalloff::Uniform => zone.dose_rate_factor,
        RadiationFalloff::Linear => zone.dose_rate_factor * (1.0 - d2.sqrt() / r).max(0.0),
    }
}

/// The dose factor at `p` over all `zones` under `rule` (0 outside all zones): the sum of the
/// zones' factors ([`RadiationOverlap::Sum`]) or the largest ([`RadiationOverlap::Max`]), each
/// from [`zone_factor_at`]. Dimensionless, finite and `>= 0`: a sum past `f64::MAX` (zones'
/// factors are finite but may be as large as `f64::MAX`) is `f64::MAX`, so a rate of 0 still
/// costs nothing (`0 * inf` would be NaN). The mission layer multiplies it by
/// `mission.hp_pct_per_step_in_radiation` to get the HP lost per step.
pub fn radiation_factor_at(zones: &[RadiationZone], p: &PointM, rule: DoseRule) -> f64 {
    let factors = zones.iter().map(|z| zone_factor_at(z, p, rule.falloff));
    match rule.overlap {
        RadiationOverlap::Sum => factors.sum::<f64>().min(f64::MAX),
        RadiationOverlap::Max => factors.fold(0.0, f64::max),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Circle;

    fn zone(x: f64, r: f64, f: f64) -> RadiationZone {
        RadiationZone {
            area: Circle {
                center: PointM::new(x, 0.0),
                radius_m: r,
            },
            dose_rate_factor: f,
        }
    }

    #[test]
    fn overlapping_huge_factors_stay_finite() {
        let zones = [zone(0.0, 4.0, 1e308), zone(1.0, 4.0, 1e308)];
        let p = PointM::new(0.5, 0.0);
        for overlap in [RadiationOverlap::Sum, RadiationOverlap::Max] {
            let rule = DoseRule {
                overlap,
                falloff: RadiationFalloff::Uniform,
            };
            let f = radiation_factor_at(&zones, &p, rule);
            assert!(f.is_finite() && f >= 1e308, "{overlap:?}: {f}");
            // A zero HP rate costs nothing however strong the zones.
            assert_eq!(0.0 * f, 0.0, "{overlap:?}");
        }
    }

    #[test]
    fn overlap_and_falloff_rules() {
        let zones = [zone(0.0, 4.0, 1.0), zone(2.0, 4.0, 1.5)];
        let p = PointM::new(1.0, 0.0);
        let rule = |overlap, falloff| DoseRule { overlap, falloff };
        let uniform = RadiationFalloff::Uniform;
        let linear = RadiationFalloff::Linear;
        assert_eq!(
            radiation_factor_at(&zones, &p, rule(RadiationOverlap::Sum, uniform)),
            2.5
        );
        assert_eq!(
            radiation_factor_at(&zones, &p, rule(RadiationOverlap::Max, uniform)),
            1.5
        );
        // Linear: 1.0 * (1 - 1/4) + 1.5 * (1 - 1/4) = 1.875; max 1.125.
        let sum = radiation_factor_at(&zones, &p, rule(RadiationOverlap::Sum, linear));
        assert!((sum - 1.875).abs() < 1e-12, "{sum}");
        let max = radiation_factor_at(&zones, &p, rule(RadiationOverlap::Max, linear));
        assert!((max - 1.125).abs() < 1e-12, "{max}");
        // Outside every disc: nothing; at the rim under Linear: nothing.
        let far = PointM::new(10.0, 0.0);
        assert_eq!(radiation_factor_at(&zones, &far, DoseRule::default()), 0.0);
        assert_eq!(
            zone_factor_at(&zones[0], &PointM::new(4.0, 0.0), linear),
            0.0
        );
        assert_eq!(
            zone_factor_at(&zones[0], &PointM::new(4.0, 0.0), uniform),
            1.0
        );
    }
}
