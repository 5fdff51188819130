//! Radiation zones as plain geometry (paper, section VI.B: HP is lost inside radioactive areas).

use crate::scenario::{PointM, RadiationZone};

/// Sum of `dose_rate_factor` over the zones containing `p` (boundary included); 0 outside all
/// zones. Dimensionless, `>= 0`. The mission layer multiplies it by
/// `mission.hp_pct_per_step_in_radiation` to get the HP lost per step.
pub fn radiation_factor_at(zones: &[RadiationZone], p: &PointM) -> f64 {
    zones
        .iter()
        .filter(|z| z.area.contains(p))
        .map(|z| z.dose_rate_factor)
        .sum()
}
