//! Validating the robots' starts: expanded in kind order, each inside the arena with its body,
//! ground robots clear of debris, and robots on one layer clear of each other (within
//! [`START_TOLERANCE`]).

use super::check_debris::NamedDebris;
use super::context::{Ctx, R, disc_inside, fmt_arena, fmt_pt};
use super::generate::{Start, debris_index, start_positions};
use super::model::{Locomotion, RobotKind, RobotStart, number_text, number_text_3dp};
use super::params::Arena;
use super::spec::ScenarioSpec;

/// Every robot's start (with its path and label), in kind order, each inside the arena with
/// its body.
pub(crate) fn expand_starts(
    ctx: &Ctx<'_>,
    spec: &ScenarioSpec,
    kinds: &[RobotKind],
    arena: &Arena,
) -> R<Vec<(Start, RobotStart)>> {
    let mut out = Vec::new();
    for (k, (ks, kind)) in spec.kinds.iter().zip(kinds).enumerate() {
        for start in start_positions(ctx, k, &ks.starts, kind)? {
            let p = start.position;
            if !disc_inside(arena, &p, kind.body_radius_m) {
                return Err(ctx.err(
                    start.path,
                    format!(
                        "{}: start {} with body radius {} m is not inside the arena {}",
                        start.label,
                        fmt_pt(&p),
                        number_text(kind.body_radius_m),
                        fmt_arena(arena)
                    ),
                ));
            }
            out.push((
                start,
                RobotStart {
                    kind: k,
                    start_in_world: p,
                },
            ));
        }
    }
    Ok(out)
}

/// Relative tolerance of the start rules: two starts at least `(1 - START_TOLERANCE)` times
/// the sum of their body radii apart are accepted, so starts placed exactly one body apart
/// (`0.8` m for two 0.4 m radii, which float rounding of the positions may turn into
/// 0.79999999999999716 m) pass; likewise a ground robot's start at `(1 - START_TOLERANCE)`
/// times its body radius from debris (a start touching a disc of radius 1.1 m at 1.5 m from
/// its centre is 0.3999999999999999 m from it).
pub const START_TOLERANCE: f64 = 1e-9;

/// Ground robots' starts clear of all debris by their body radius; starts of robots on the
/// same layer at least the sum of their radii apart (both within [`START_TOLERANCE`]).
pub(crate) fn check_starts(
    ctx: &Ctx<'_>,
    starts: &[(Start, RobotStart)],
    kinds: &[RobotKind],
    debris: &NamedDebris,
) -> R<()> {
    let index = debris_index(debris);
    for (s, r) in starts {
        let kind = &kinds[r.kind];
        if kind.locomotion != Locomotion::Ground {
            continue;
        }
        let p = &r.start_in_world;
        for i in index.near(p, p, kind.body_radius_m) {
            let (d, name) = &debris[i];
            let dist = d.distance_to_point(&r.start_in_world);
            if dist < kind.body_radius_m * (1.0 - START_TOLERANCE) {
                return Err(ctx.err(
                    s.path.clone(),
                    format!(
                        "{}: start {} of a ground robot overlaps {name}: its centre is \
                         {} m from it, need at least the body radius {} m",
                        s.label,
                        fmt_pt(&r.start_in_world),
                        number_text_3dp(dist),
                        number_text(kind.body_radius_m)
                    ),
                ));
            }
        }
    }
    for (i, (sa, a)) in starts.iter().enumerate() {
        for (sb, b) in &starts[i + 1..] {
            let (ka, kb) = (&kinds[a.kind], &kinds[b.kind]);
            if ka.locomotion != kb.locomotion {
                continue;
            }
            let need = ka.body_radius_m + kb.body_radius_m;
            let dist = (a.start_in_world - b.start_in_world).norm();
            if dist < need * (1.0 - START_TOLERANCE) {
                return Err(ctx.err(
                    sb.path.clone(),
                    format!(
                        "{}: start {} overlaps {} at {}: {} m apart, need at least {} m \
                         (sum of body radii)",
                        sb.label,
                        fmt_pt(&b.start_in_world),
                        sa.label,
                        fmt_pt(&a.start_in_world),
                        number_text_3dp(dist),
                        number_text(need)
                    ),
                ));
            }
        }
    }
    Ok(())
}
