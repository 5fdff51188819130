//! Validating the listed debris: at most [`MAX_DEBRIS`] shapes, each with finite numbers and
//! wholly inside the arena, named `debris[i]` in messages.
//!
//! Generated debris fields are laid out by [`super::generate`]; both end up in one
//! [`NamedDebris`] list that the later checks (starts, rescuees, reachable places) read.

use nalgebra::Vector2;

use super::context::{Ctx, R, fmt_arena, fmt_pt};
use super::limits::MAX_DEBRIS;
use super::model::{Circle, Debris, number_text};
use super::params::Arena;
use super::shape::DebrisShape;
use super::spec::DebrisSpec;

/// Debris with the names messages give them (`debris[3]`, `debris_fields[0] shape 2`).
pub(crate) type NamedDebris = Vec<(DebrisShape, String)>;

/// The listed debris, each inside the arena, named `debris[i]`.
pub(crate) fn listed_debris(ctx: &Ctx<'_>, specs: &[DebrisSpec], arena: &Arena) -> R<NamedDebris> {
    if specs.len() > MAX_DEBRIS {
        return Err(ctx.err(
            "debris",
            format!(
                "{} shapes, more than the limit of {MAX_DEBRIS} debris shapes",
                specs.len()
            ),
        ));
    }
    specs
        .iter()
        .enumerate()
        .map(|(i, d)| {
            let path = format!("debris[{i}]");
            Ok((one_debris(ctx, &path, d, arena)?, path))
        })
        .collect()
}

/// One listed shape at `path`: finite centre, sizes `> 0` and finite rotation, its bounding
/// box inside the arena.
fn one_debris(ctx: &Ctx<'_>, path: &str, d: &DebrisSpec, arena: &Arena) -> R<DebrisShape> {
    let shape = match d {
        DebrisSpec::Rect {
            center_m,
            size_m,
            rotation_deg,
        } => {
            let center = ctx.point(&format!("{path}.center_m"), center_m)?;
            if !(size_m.iter().all(|v| v.is_finite() && *v > 0.0)) {
                return Err(ctx.err(
                    format!("{path}.size_m"),
                    format!(
                        "expected width and height finite and > 0, found ({}, {})",
                        number_text(size_m[0]),
                        number_text(size_m[1])
                    ),
                ));
            }
            let rot = ctx.finite(&format!("{path}.rotation_deg"), *rotation_deg)?;
            Debris::Rect {
                center,
                half_extents_m: Vector2::new(size_m[0], size_m[1]) / 2.0,
                rotation_rad: rot.to_radians(),
            }
        }
        DebrisSpec::Circle { center_m, radius_m } => Debris::Circle(Circle {
            center: ctx.point(&format!("{path}.center_m"), center_m)?,
            radius_m: radius_m.get(),
        }),
    };
    let shape = shape.shape();
    let (lo, hi) = shape.aabb();
    if !(arena.contains(&lo) && arena.contains(&hi)) {
        return Err(ctx.err(
            path,
            format!(
                "debris spans {} - {}, not inside the arena {}",
                fmt_pt(&lo),
                fmt_pt(&hi),
                fmt_arena(arena)
            ),
        ));
    }
    Ok(shape)
}
