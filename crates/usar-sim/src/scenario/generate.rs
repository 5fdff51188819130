//! Expansion of the spec's compact forms into the scenario's lists: start rows and grids into
//! start positions, rescuee grids into rescuee positions, debris fields into seeded, placed debris.
//! Each step checks what only it can (a row's step, a grid's size, whether a field fits) and
//! reports with the field path, through the validation context.

use nalgebra::{Point2, Vector2};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::context::{Ctx, R, fmt_pt};
use super::index::BoxIndex;
use super::limits::MAX_DEBRIS;
use super::model::{Circle, Debris, PointM, Rect, RobotKind, number_text};
use super::params::Arena;
use super::shape::DebrisShape;
use super::spec::{DebrisFieldSpec, DebrisShapeSpec, RescueeLayoutSpec, StartsSpec, XyM};

/// Most rescuees one grid layout may expand to.
pub(crate) const MAX_GRID_POINTS: usize = 1_000_000;
/// Placement attempts per generated shape before a debris field gives up.
pub(crate) const ATTEMPTS_PER_SHAPE: usize = 2_000;
/// Failed placement attempts in a row after which a debris field gives up (a field that is
/// full fails in this many attempts, not in `ATTEMPTS_PER_SHAPE * count`).
pub(crate) const FAILED_IN_A_ROW: usize = 10 * ATTEMPTS_PER_SHAPE;

/// A start position with the field path it came from and a label for messages
/// (`carrier robot 3`).
pub(crate) struct Start {
    pub(crate) path: String,
    pub(crate) label: String,
    pub(crate) position: PointM,
}

/// The start positions of kind `k` (`spec` its starts, `kind` the validated kind): a listed
/// position per robot, or `count` positions along a row.
pub(crate) fn start_positions(
    ctx: &Ctx<'_>,
    k: usize,
    spec: &StartsSpec,
    kind: &RobotKind,
) -> R<Vec<Start>> {
    let base = format!("kinds[{k}].starts");
    let label = |i: usize| format!("{} robot {i}", kind.name);
    match spec {
        StartsSpec::List(list) => {
            if list.len() != kind.count {
                return Err(ctx.err(
                    base,
                    format!(
                        "{} start position(s) listed but count is {}",
                        list.len(),
                        kind.count
                    ),
                ));
            }
            list.iter()
                .enumerate()
                .map(|(i, xy)| {
                    let path = format!("{base}[{i}]");
                    let position = ctx.point(&path, xy)?;
                    Ok(Start {
                        path,
                        label: label(i),
                        position,
                    })
                })
                .collect()
        }
        StartsSpec::Row { first_m, step_m } => {
            let first = ctx.point(&format!("{base}.first_m"), first_m)?;
            let step_path = format!("{base}.step_m");
            let step = ctx.point(&step_path, step_m)?.coords;
            if kind.count > 1 && step.norm() == 0.0 {
                return Err(ctx.err(
                    step_path,
                    "expected a non-zero step: robots of a row cannot share one position",
                ));
            }
            Ok((0..kind.count)
                .map(|i| Start {
                    path: base.clone(),
                    label: label(i),
                    position: first + step * i as f64,
                })
                .collect())
        }
        StartsSpec::Grid {
            first_m,
            columns,
            spacing_m,
        } => grid_starts(
            ctx,
            &base,
            (first_m, *columns, spacing_m),
            kind.count,
            label,
        ),
    }
}

/// The `count` positions of a `Grid` start layout `(first_m, columns, spacing_m)` (see
/// [`StartsSpec::Grid`]), all labelled by `label` and attributed to the field path `base`.
fn grid_starts(
    ctx: &Ctx<'_>,
    base: &str,
    (first_m, columns, spacing_m): (&XyM, u32, &XyM),
    count: usize,
    label: impl Fn(usize) -> String,
) -> R<Vec<Start>> {
    let first = ctx.point(&format!("{base}.first_m"), first_m)?;
    let spacing_path = format!("{base}.spacing_m");
    let spacing = ctx.point(&spacing_path, spacing_m)?.coords;
    if columns == 0 {
        return Err(ctx.err(format!("{base}.columns"), "expected at least 1 column"));
    }
    let columns = columns as usize;
    if count > 1 && columns > 1 && spacing.x == 0.0 {
        return Err(ctx.err(
            spacing_path,
            "expected a non-zero x spacing: robots of a grid row cannot share one position",
        ));
    }
    if count > columns && spacing.y == 0.0 {
        return Err(ctx.err(
            spacing_path,
            "expected a non-zero y spacing: grid rows cannot share one position",
        ));
    }
    Ok((0..count)
        .map(|i| {
            let offset = Vector2::new(
                spacing.x * (i % columns) as f64,
                spacing.y * (i / columns) as f64,
            );
            Start {
                path: base.to_string(),
                label: label(i),
                position: first + offset,
            }
        })
        .collect())
}

/// A place generated debris must keep away from (a start, the rest station, a drop-off, a
/// goal), with how to name it in messages.
pub(crate) struct Protected {
    pub(crate) center: PointM,
    pub(crate) radius_m: f64,
    pub(crate) what: String,
}

/// The protected places with an index of their bounding boxes, built once for every debris
/// field of a scenario (a field used to build its own: at 100,000 starts the 70 fields of
/// `swarm-100000.ron` spent most of a load inserting the same boxes again).
pub(crate) struct ProtectedPlaces<'a> {
    /// The places, in the order the index numbers them.
    pub(crate) list: &'a [Protected],
    /// Bounding boxes of the places' discs (same order as `list`).
    index: BoxIndex,
}

impl<'a> ProtectedPlaces<'a> {
    /// `list` with an index of its discs' bounding boxes.
    pub(crate) fn new(list: &'a [Protected]) -> Self {
        let mut index = BoxIndex::new();
        for p in list {
            let r = Vector2::new(p.radius_m, p.radius_m);
            index.push(&(p.center - r), &(p.center + r));
        }
        Self { list, index }
    }
}

fn size_range(ctx: &Ctx<'_>, path: &str, (lo, hi): (f64, f64)) -> R<(f64, f64)> {
    if lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi {
        Ok((lo, hi))
    } else {
        Err(ctx.err(
            path,
            format!(
                "expected (min, max) with 0 < min <= max, both finite, found ({}, {})",
                number_text(lo),
                number_text(hi)
            ),
        ))
    }
}

/// What a debris field draws: disc radii `(lo, hi)` or rectangle sides `(lo, hi)` and the
/// largest rotation, radians.
#[derive(Clone, Copy)]
enum Draw {
    Circles(f64, f64),
    Rects(f64, f64, f64),
}

/// The checked shape family of field `base` (its region is `w x h` metres).
fn draw_of(ctx: &Ctx<'_>, base: &str, shape: &DebrisShapeSpec, w: f64, h: f64) -> R<Draw> {
    match shape {
        DebrisShapeSpec::Circles { radius_m } => {
            let (lo, hi) = size_range(ctx, &format!("{base}.shape.radius_m"), *radius_m)?;
            if 2.0 * lo > w.min(h) {
                return Err(ctx.err(
                    format!("{base}.shape.radius_m"),
                    format!(
                        "the smallest disc (radius {} m) does not fit in the region ({} x {} m)",
                        number_text(lo),
                        number_text(w),
                        number_text(h)
                    ),
                ));
            }
            Ok(Draw::Circles(lo, hi))
        }
        DebrisShapeSpec::Rects {
            side_m,
            max_rotation_deg,
        } => {
            let (lo, hi) = size_range(ctx, &format!("{base}.shape.side_m"), *side_m)?;
            let rot = ctx.in_range(
                &format!("{base}.shape.max_rotation_deg"),
                *max_rotation_deg,
                0.0,
                180.0,
            )?;
            if lo > w.min(h) {
                return Err(ctx.err(
                    format!("{base}.shape.side_m"),
                    format!(
                        "the smallest rectangle (side {} m) does not fit in the region ({} x \
                         {} m)",
                        number_text(lo),
                        number_text(w),
                        number_text(h)
                    ),
                ));
            }
            Ok(Draw::Rects(lo, hi, rot.to_radians()))
        }
    }
}

/// One random shape at the origin and the half extents of its bounding box.
fn draw_shape(rng: &mut ChaCha8Rng, draw: Draw) -> (Debris, Vector2<f64>) {
    match draw {
        Draw::Circles(lo, hi) => {
            let r = rng.random_range(lo..=hi);
            (
                Debris::Circle(Circle {
                    center: Point2::origin(),
                    radius_m: r,
                }),
                Vector2::new(r, r),
            )
        }
        Draw::Rects(lo, hi, rot) => {
            let sx = rng.random_range(lo..=hi);
            let sy = rng.random_range(lo..=hi);
            let rot = if rot > 0.0 {
                rng.random_range(-rot..=rot)
            } else {
                0.0
            };
            let d = Debris::Rect {
                center: Point2::origin(),
                half_extents_m: Vector2::new(sx, sy) / 2.0,
                rotation_rad: rot,
            };
            let (_, e) = d.shape().aabb();
            (d, e.coords)
        }
    }
}

/// Expands debris field `j` (see [`DebrisFieldSpec`]): shapes drawn from the field's seeded
/// generator and kept when at least `min_gap_m` from `existing` debris, from the shapes placed
/// before them and from every `protected` place.
///
/// # Errors
/// A bad region, count (more than [`MAX_DEBRIS`] shapes with those before it), size range,
/// rotation or gap, or a field that cannot place all its shapes within `ATTEMPTS_PER_SHAPE *
/// count` attempts or gives up after `FAILED_IN_A_ROW` failed attempts in a row (naming the
/// protected places that lie in its region).
pub(crate) fn generate_debris_field(
    ctx: &Ctx<'_>,
    j: usize,
    f: &DebrisFieldSpec,
    arena: &Arena,
    sim_seed: u64,
    existing: &[DebrisShape],
    protected: &ProtectedPlaces<'_>,
) -> R<Vec<DebrisShape>> {
    let base = format!("debris_fields[{j}]");
    let region = ctx.rect_in_arena(&format!("{base}.region"), &f.region, arena)?;
    check_field_count(ctx, &base, f.count, existing.len())?;
    let gap = ctx.non_negative(&format!("{base}.min_gap_m"), f.min_gap_m)?;
    let (w, h) = (region.max.x - region.min.x, region.max.y - region.min.y);
    let draw = draw_of(ctx, &base, &f.shape, w, h)?;
    let seed = f.seed.unwrap_or(sim_seed.wrapping_add(j as u64));
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut keepout = Keepout::new(existing, protected, gap, f.count);
    let max_attempts = ATTEMPTS_PER_SHAPE * f.count;
    let (mut attempts, mut failed_in_a_row) = (0, 0);
    while keepout.all.len() - existing.len() < f.count
        && attempts < max_attempts
        && failed_in_a_row < FAILED_IN_A_ROW
    {
        attempts += 1;
        failed_in_a_row += 1;
        let Some(shape) = draw_in_region(&mut rng, draw, &region) else {
            continue;
        };
        if keepout.is_clear(&shape) {
            keepout.push(shape);
            failed_in_a_row = 0;
        }
    }
    let placed = keepout.all.split_off(existing.len());
    if placed.len() < f.count {
        return Err(field_full(
            ctx,
            &base,
            f.count,
            placed.len(),
            attempts,
            &region,
            protected.list,
        ));
    }
    Ok(placed)
}

/// Field `base`'s `count` against zero and against the room [`MAX_DEBRIS`] leaves after the
/// `before` shapes placed earlier.
fn check_field_count(ctx: &Ctx<'_>, base: &str, count: usize, before: usize) -> R<()> {
    if count == 0 {
        return Err(ctx.err(
            format!("{base}.count"),
            "expected at least 1 shape, found 0",
        ));
    }
    if count > MAX_DEBRIS.saturating_sub(before) {
        return Err(ctx.err(
            format!("{base}.count"),
            format!(
                "{count} shapes after the {before} before them make more than the limit of \
                 {MAX_DEBRIS} debris shapes"
            ),
        ));
    }
    Ok(())
}

/// One shape drawn by `draw` at a uniform position in `region` (the draws of
/// [`draw_shape`], then x, then y), or `None` when the shape is larger than the region (no
/// position is drawn then).
fn draw_in_region(rng: &mut ChaCha8Rng, draw: Draw, region: &Rect) -> Option<DebrisShape> {
    let (mut shape, half) = draw_shape(rng, draw);
    let (x_lo, x_hi) = (region.min.x + half.x, region.max.x - half.x);
    let (y_lo, y_hi) = (region.min.y + half.y, region.max.y - half.y);
    if x_lo > x_hi || y_lo > y_hi {
        return None;
    }
    let c = Point2::new(rng.random_range(x_lo..=x_hi), rng.random_range(y_lo..=y_hi));
    match &mut shape {
        Debris::Circle(circle) => circle.center = c,
        Debris::Rect { center, .. } => *center = c,
    }
    Some(shape.shape())
}

/// What a new debris shape keeps at least `gap` metres from: every shape so far (`all`: the
/// existing ones, then those placed) and the `protected` places, each behind an index of its
/// bounding boxes.
struct Keepout<'a> {
    /// The existing shapes, then the placed ones.
    all: Vec<DebrisShape>,
    /// Bounding boxes of `all` (same order).
    shapes: BoxIndex,
    /// Places no debris may come near (starts, goals, drop-offs...), with their index.
    places: &'a ProtectedPlaces<'a>,
    /// The least gap, metres (>= 0).
    gap: f64,
}

impl<'a> Keepout<'a> {
    /// The keep-out of `existing` shapes and `protected` places, with room for `count` more.
    fn new(
        existing: &[DebrisShape],
        places: &'a ProtectedPlaces<'a>,
        gap: f64,
        count: usize,
    ) -> Self {
        let mut k = Self {
            all: Vec::with_capacity(existing.len() + count),
            shapes: BoxIndex::new(),
            places,
            gap,
        };
        for d in existing {
            k.push(*d);
        }
        k
    }

    /// Whether `shape` is at least `gap` from every shape and protected place.
    fn is_clear(&self, shape: &DebrisShape) -> bool {
        let gap = self.gap;
        let (lo, hi) = shape.aabb();
        let clear_of_debris = self
            .shapes
            .near(&lo, &hi, gap)
            .into_iter()
            .all(|i| shape.distance(&self.all[i]) >= gap);
        let clear_of_places = self.places.index.near(&lo, &hi, gap).into_iter().all(|i| {
            let p = &self.places.list[i];
            shape.distance_to_point(&p.center) >= p.radius_m + gap
        });
        clear_of_debris && clear_of_places
    }

    /// Adds `shape` to the shapes kept clear of.
    fn push(&mut self, shape: DebrisShape) {
        let (lo, hi) = shape.aabb();
        self.shapes.push(&lo, &hi);
        self.all.push(shape);
    }
}

/// The error of a debris field that could not place all its shapes, naming the most likely
/// culprit: protected places inside its region.
fn field_full(
    ctx: &Ctx<'_>,
    base: &str,
    count: usize,
    placed: usize,
    attempts: usize,
    region: &Rect,
    protected: &[Protected],
) -> super::ScenarioError {
    let inside: Vec<&str> = protected
        .iter()
        .filter(|p| region.contains(&p.center))
        .map(|p| p.what.as_str())
        .take(3)
        .collect();
    let hint = if inside.is_empty() {
        String::new()
    } else {
        format!(" (the region holds {})", inside.join(", "))
    };
    ctx.err(
        format!("{base}.count"),
        format!(
            "placed only {placed} of {count} shapes in {attempts} attempts{hint}; enlarge the \
             region or reduce count, sizes or min_gap_m"
        ),
    )
}

/// The rescuee positions of one task (`path` its `rescuees` field, `area` its search area):
/// a grid's points not covered by debris, or a checked list. A point is covered when it lies
/// inside debris or closer to it than `reach` (the smallest ground body radius).
///
/// # Errors
/// A bad spacing or margin, a grid of more than [`MAX_GRID_POINTS`] points or with every point
/// covered, an empty list, or a listed rescuee outside the area or covered by debris.
pub(crate) fn expand_rescuees(
    ctx: &Ctx<'_>,
    path: &str,
    layout: &RescueeLayoutSpec,
    area: &Rect,
    debris: &[(DebrisShape, String)],
    reach: f64,
) -> R<Vec<PointM>> {
    let index = debris_index(debris);
    let near_debris = |p: &PointM| {
        index.near(p, p, reach).into_iter().find_map(|i| {
            let (d, name) = &debris[i];
            let dist = d.distance_to_point(p);
            (dist == 0.0 || dist < reach).then_some(name)
        })
    };
    match layout {
        RescueeLayoutSpec::Grid {
            spacing_m,
            margin_m,
        } => {
            let pts: Vec<PointM> = grid_points(ctx, path, spacing_m.get(), *margin_m, area)?
                .into_iter()
                .filter(|p| near_debris(p).is_none())
                .collect();
            if pts.is_empty() {
                return Err(ctx.err(
                    path,
                    "every grid point is covered by debris; expected at least one rescuee",
                ));
            }
            Ok(pts)
        }
        RescueeLayoutSpec::List(list) => {
            if list.is_empty() {
                return Err(ctx.err(path, "expected at least one rescuee"));
            }
            let mut pts = Vec::with_capacity(list.len());
            for (i, xy) in list.iter().enumerate() {
                let p_path = format!("{path}[{i}]");
                let p = ctx.point(&p_path, xy)?;
                if !area.contains(&p) {
                    return Err(ctx.err(
                        p_path,
                        format!(
                            "rescuee {} is outside the search area {} - {}",
                            fmt_pt(&p),
                            fmt_pt(&area.min),
                            fmt_pt(&area.max)
                        ),
                    ));
                }
                if let Some(name) = near_debris(&p) {
                    return Err(ctx.err(
                        p_path,
                        format!(
                            "rescuee {} is covered by {name} (closer than {reach} m, the \
                             smallest ground body radius)",
                            fmt_pt(&p)
                        ),
                    ));
                }
                pts.push(p);
            }
            Ok(pts)
        }
    }
}

/// The boxes of `debris`, numbered as listed.
pub(crate) fn debris_index(debris: &[(DebrisShape, String)]) -> BoxIndex {
    let mut index = BoxIndex::new();
    for (d, _) in debris {
        let (lo, hi) = d.aabb();
        index.push(&lo, &hi);
    }
    index
}

/// A square grid of spacing `s` filling `area`, centred in it, at least `margin` from its
/// edges, row by row from the bottom-left.
fn grid_points(ctx: &Ctx<'_>, path: &str, s: f64, margin: f64, area: &Rect) -> R<Vec<PointM>> {
    let m = ctx.non_negative(&format!("{path}.margin_m"), margin)?;
    let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
    let (uw, uh) = (w - 2.0 * m, h - 2.0 * m);
    if uw < 0.0 || uh < 0.0 {
        return Err(ctx.err(
            format!("{path}.margin_m"),
            format!(
                "margin {} m leaves no room in a {} x {} m search area",
                number_text(m),
                number_text(w),
                number_text(h)
            ),
        ));
    }
    // Counted in f64 (a huge ratio cannot overflow), cast once known to be small.
    let nx = (uw / s + 1e-9).floor() + 1.0;
    let ny = (uh / s + 1e-9).floor() + 1.0;
    if nx * ny > MAX_GRID_POINTS as f64 {
        return Err(ctx.err(
            format!("{path}.spacing_m"),
            format!(
                "spacing {} m gives {} x {} rescuees, more than {MAX_GRID_POINTS}",
                number_text(s),
                number_text(nx),
                number_text(ny)
            ),
        ));
    }
    let (nx, ny) = (nx as usize, ny as usize);
    let x0 = area.min.x + (w - (nx - 1) as f64 * s) / 2.0;
    let y0 = area.min.y + (h - (ny - 1) as f64 * s) / 2.0;
    Ok((0..ny)
        .flat_map(|iy| (0..nx).map(move |ix| Point2::new(x0 + ix as f64 * s, y0 + iy as f64 * s)))
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::numbers::Positive;

    #[test]
    fn grid_is_centred_and_row_major_from_bottom_left() {
        let ctx = Ctx {
            origin: "t",
            map: None,
        };
        let area = Rect {
            min: Point2::new(0.0, 0.0),
            max: Point2::new(2.5, 1.0),
        };
        let grid = RescueeLayoutSpec::Grid {
            spacing_m: Positive::known(1.0),
            margin_m: 0.0,
        };
        let pts = expand_rescuees(&ctx, "r", &grid, &area, &[], 0.4).expect("grid");
        // 3 x 2 points, centred: x = 0.25, 1.25, 2.25; y = 0, 1.
        let xy: Vec<(f64, f64)> = pts.iter().map(|p| (p.x, p.y)).collect();
        assert_eq!(
            xy,
            vec![
                (0.25, 0.0),
                (1.25, 0.0),
                (2.25, 0.0),
                (0.25, 1.0),
                (1.25, 1.0),
                (2.25, 1.0)
            ]
        );
        // Debris removes covered points.
        let d = Debris::Circle(Circle {
            center: Point2::new(1.25, 0.0),
            radius_m: 0.1,
        })
        .shape();
        let pts = expand_rescuees(&ctx, "r", &grid, &area, &[(d, "debris[0]".into())], 0.4)
            .expect("grid");
        assert_eq!(pts.len(), 5);
    }
}
