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
    if let Some((i, j)) = first_overlap(starts, kinds) {
        let ((sa, a), (sb, b)) = (&starts[i], &starts[j]);
        let need = kinds[a.kind].body_radius_m + kinds[b.kind].body_radius_m;
        let dist = (a.start_in_world - b.start_in_world).norm();
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
    Ok(())
}

/// Whether starts `a` and `b` overlap: same layer and closer than the sum of their body radii
/// (within [`START_TOLERANCE`]).
fn overlaps(a: &RobotStart, b: &RobotStart, kinds: &[RobotKind]) -> bool {
    let (ka, kb) = (&kinds[a.kind], &kinds[b.kind]);
    if ka.locomotion != kb.locomotion {
        return false;
    }
    let need = ka.body_radius_m + kb.body_radius_m;
    (a.start_in_world - b.start_in_world).norm() < need * (1.0 - START_TOLERANCE)
}

/// The first overlapping pair `(i, j)`, `i < j`, in the order of a scan of every pair (the
/// smallest `i`, then the smallest `j`), found through a uniform grid of cells twice the
/// largest body radius wide: two starts that overlap lie in the same or adjacent cells, so
/// the check costs `O(n)` for starts spread out (`O(n^2)` over every pair before; 10,000
/// robots took 0.3 s).
fn first_overlap(starts: &[(Start, RobotStart)], kinds: &[RobotKind]) -> Option<(usize, usize)> {
    let cell = 2.0 * kinds.iter().map(|k| k.body_radius_m).fold(0.0, f64::max);
    if !(cell.is_finite() && cell > 0.0) {
        return None;
    }
    let key = |r: &RobotStart| {
        let p = &r.start_in_world;
        ((p.x / cell).floor() as i64, (p.y / cell).floor() as i64)
    };
    let mut cells: std::collections::HashMap<(i64, i64), Vec<usize>> =
        std::collections::HashMap::new();
    for (i, (_, r)) in starts.iter().enumerate() {
        cells.entry(key(r)).or_default().push(i);
    }
    for (i, (_, a)) in starts.iter().enumerate() {
        let (cx, cy) = key(a);
        let mut first: Option<usize> = None;
        for dx in -1..=1 {
            for dy in -1..=1 {
                let Some(ids) = cells.get(&(cx.saturating_add(dx), cy.saturating_add(dy))) else {
                    continue;
                };
                for &j in ids {
                    if j > i && first.is_none_or(|f| j < f) && overlaps(a, &starts[j].1, kinds) {
                        first = Some(j);
                    }
                }
            }
        }
        if let Some(j) = first {
            return Some((i, j));
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::PointM;
    use crate::scenario::model::Role;
    use proptest::prelude::*;

    fn kind(radius_m: f64, locomotion: Locomotion) -> RobotKind {
        RobotKind {
            name: "k".into(),
            role: Role::Carrier,
            locomotion,
            count: 0,
            quota: vec![],
            body_radius_m: radius_m,
            max_speed_m_per_s: 1.0,
            sensing_range_m: 1.0,
            observing_range_m: 1.0,
            carrying_capacity: 1,
            rescuing_resources: 1,
            hp_needs_full: 1.0,
            energy_needs_full: 1.0,
        }
    }

    /// The scan of every pair that `first_overlap` replaces.
    fn first_overlap_by_scan(
        starts: &[(Start, RobotStart)],
        kinds: &[RobotKind],
    ) -> Option<(usize, usize)> {
        (0..starts.len()).find_map(|i| {
            (i + 1..starts.len())
                .find(|&j| overlaps(&starts[i].1, &starts[j].1, kinds))
                .map(|j| (i, j))
        })
    }

    proptest! {
        /// The grid finds the pair a scan of every pair finds first, for crowded and sparse
        /// starts of three kinds on two layers, some exactly one body apart.
        #[test]
        fn the_grid_finds_the_first_overlap_of_the_scan(
            points in proptest::collection::vec((0u8..3, 0.0f64..12.0, 0.0f64..12.0, any::<bool>()), 0..60),
        ) {
            let kinds = [
                kind(0.4, Locomotion::Ground),
                kind(0.25, Locomotion::Ground),
                kind(0.3, Locomotion::Aerial),
            ];
            let starts: Vec<(Start, RobotStart)> = points
                .iter()
                .map(|&(k, x, y, snap)| {
                    // Snapped to a 0.8 m lattice: many pairs exactly one body apart.
                    let (x, y) = if snap { ((x / 0.8).round() * 0.8, (y / 0.8).round() * 0.8) } else { (x, y) };
                    let start = Start { path: String::new(), label: String::new(), position: PointM::new(x, y) };
                    (start, RobotStart { kind: usize::from(k), start_in_world: PointM::new(x, y) })
                })
                .collect();
            prop_assert_eq!(first_overlap(&starts, &kinds), first_overlap_by_scan(&starts, &kinds));
        }
    }
}
