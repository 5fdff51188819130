//! Validating the radiation zones: each circle wholly inside the arena, with its dose-rate
//! factor.

use super::context::{Ctx, R};
use super::model::RadiationZone;
use super::params::Arena;
use super::spec::{CircleSpec, ScenarioSpec};

/// The radiation zones, each inside the arena, at `radiation_zones[i]`.
pub(crate) fn radiation_zones(
    ctx: &Ctx<'_>,
    spec: &ScenarioSpec,
    arena: &Arena,
) -> R<Vec<RadiationZone>> {
    spec.radiation_zones
        .iter()
        .enumerate()
        .map(|(i, z)| {
            let area = ctx.circle_in_arena(
                &format!("radiation_zones[{i}]"),
                &CircleSpec {
                    center_m: z.center_m,
                    radius_m: z.radius_m,
                },
                arena,
            )?;
            Ok(RadiationZone {
                area,
                dose_rate_factor: z.dose_rate_factor.get(),
            })
        })
        .collect()
}
