//! The scenario's limits: the largest team, debris list, navigation grid and number range the
//! simulator runs, checked by validation so that whatever `check` accepts, `run` can run (no
//! allocation abort, no overflowing index, no infinite derived quantity, no endless trial).
//! Each limit is documented in `docs/scenario-format.md` ("Limits"); a value beyond one is a
//! [`super::ScenarioError::Invalid`] at the field that sets it.
//!
//! Source: issue 11 (hardening), classes 1-3; the numbers are engineering choices well above
//! the paper's mission (12 robots, 3 kinds, 2 tasks, 24 debris shapes, a 320 x 240 grid).

use super::context::{Ctx, R};
use super::model::{Locomotion, RobotKind, count_text, number_text};
use super::params::{Arena, CollisionParams, NavigationParams, NeedsWeights, SimParams};
use super::search_pattern::{sweep_point_count, sweep_spacing_m};
use super::spec::KindSpec;
use super::validated::Scenario;

/// Longest scenario file, bytes (64 MiB): the shipped 1,000-robot scenario is under 10 KB,
/// and a file listing every start, debris shape and rescuee up to [`MAX_ROBOTS`],
/// [`MAX_DEBRIS`] and [`MAX_RESCUEES`] (about 20 bytes a point) stays under 25 MB.
pub const MAX_SCENARIO_BYTES: u64 = 64 << 20;
/// Most robot kinds a scenario may list (grouping merges kind by kind).
pub const MAX_KINDS: usize = 256;
/// Most tasks a scenario may list (`swarm-100000.ron` has 80).
pub const MAX_TASKS: usize = 128;
/// Most rest stations a scenario may list (each is a shared navigation goal with its own
/// distance field).
pub const MAX_REST_STATIONS: usize = 256;
/// Most robots of a team, over all kinds (the `count`s add up to at most this):
/// `swarm-100000.ron`'s team.
pub const MAX_ROBOTS: usize = 100_000;
/// Most rescuees over all tasks (one grid layout also expands to at most 1,000,000 points).
pub const MAX_RESCUEES: usize = 1_000_000;
/// Most waypoints of a blind group's lawn-mower sweep over one search area
/// ([`sweep_point_count`]: about `(width / spacing) * (height / spacing)`).
pub const MAX_SWEEP_POINTS: f64 = 1_000_000.0;
/// Most debris shapes, listed and generated together.
pub const MAX_DEBRIS: usize = 10_000;
/// Most cells of the navigation grid, `ceil(width_m / grid_cell_m) * ceil(height_m /
/// grid_cell_m)`: 2^24 cells (64 MiB of `f32` clearances, and 16 MiB for each of at most
/// four move tables), well inside a 32-bit cell index.
pub const MAX_NAV_CELLS: u64 = 1 << 24;
/// Longest arena side, metres: the world simulates in `f32`, whose spacing at 10 km is about
/// 1 mm.
pub const MAX_ARENA_SIDE_M: f64 = 10_000.0;
/// Largest `navigation.waypoint_tolerance_m`, metres: a robot counts as at a waypoint, goal,
/// rescuee or drop-off within this distance (plus its body radius for a rescuee), so a
/// tolerance near the arena's size would let robots pick up and deliver rescuees without
/// moving. 12.5 times the largest body radius of the shipped scenarios (0.4 m), about 17 times
/// the default (0.3 m).
pub const MAX_WAYPOINT_TOLERANCE_M: f64 = 5.0;
/// Smallest `navigation.waypoint_tolerance_m`, metres, in any arena: 1 mm. In a large arena
/// the bound is higher, [`min_waypoint_tolerance_m`]: the world keeps positions in `f32`, so
/// a tolerance near `f32`'s spacing at the arena's far corner can never be met and robots
/// stall short of their first waypoint (1e-6 m in a 30 m arena did).
pub const MIN_WAYPOINT_TOLERANCE_M: f64 = 1e-3;

/// The smallest `navigation.waypoint_tolerance_m` for an arena whose longer side is
/// `longest_side_m`, metres: the larger of [`MIN_WAYPOINT_TOLERANCE_M`] and 16 times `f32`'s
/// spacing there (`16 * f32::EPSILON * longest_side_m`, 0.019 m at the 10 km limit).
pub fn min_waypoint_tolerance_m(longest_side_m: f64) -> f64 {
    MIN_WAYPOINT_TOLERANCE_M.max(16.0 * f64::from(f32::EPSILON) * longest_side_m)
}

/// Most rescuees a robot carries at once and most rescuing resources it brings
/// (`carrying_capacity`, `rescuing_resources`): a group's sums over [`MAX_ROBOTS`] robots stay
/// within a 32-bit count.
pub const MAX_UNITS_PER_ROBOT: u32 = 10_000;
/// Highest top speed of a kind, metres per second.
pub const MAX_SPEED_M_PER_S: f64 = 100.0;
/// Range `[min, max]` of every needs level at full HP/energy (`hp_needs_full`,
/// `energy_needs_full`, `sensing_range_m`, `observing_range_m`, `max_speed_m_per_s`) and of
/// every needs weight: products of a weight and a level stay normal `f64` numbers and the
/// sums over a team of [`MAX_ROBOTS`] stay finite (paper, Eqs. 8, 11 and 16).
pub const NEEDS_RANGE: (f64, f64) = (1e-9, 1e9);

/// Kind and task list lengths and each kind's count against [`MAX_KINDS`], [`MAX_TASKS`] and
/// the running total against [`MAX_ROBOTS`]; checked before any start is expanded.
pub(crate) fn check_lists(ctx: &Ctx<'_>, kinds: &[KindSpec], tasks: usize) -> R<()> {
    if kinds.len() > MAX_KINDS {
        return Err(ctx.err(
            "kinds",
            format!("{} kinds, more than the limit of {MAX_KINDS}", kinds.len()),
        ));
    }
    if tasks > MAX_TASKS {
        return Err(ctx.err(
            "tasks",
            format!("{tasks} tasks, more than the limit of {MAX_TASKS}"),
        ));
    }
    let mut total: usize = 0;
    for (k, s) in kinds.iter().enumerate() {
        total = total.saturating_add(s.count);
        if total > MAX_ROBOTS {
            return Err(ctx.err(
                format!("kinds[{k}].count"),
                format!(
                    "count {} brings the team to {total} robots, more than the limit of \
                     {MAX_ROBOTS}",
                    s.count
                ),
            ));
        }
    }
    Ok(())
}

/// A kind's needs levels against [`NEEDS_RANGE`], its speed against [`MAX_SPEED_M_PER_S`] and
/// its capacity and resources against [`MAX_UNITS_PER_ROBOT`].
pub(crate) fn check_kind(ctx: &Ctx<'_>, k: usize, kind: &RobotKind) -> R<()> {
    if kind.max_speed_m_per_s > MAX_SPEED_M_PER_S {
        return Err(ctx.err(
            format!("kinds[{k}].max_speed_m_per_s"),
            format!(
                "{} m/s is faster than the limit of {MAX_SPEED_M_PER_S} m/s",
                number_text(kind.max_speed_m_per_s)
            ),
        ));
    }
    for (name, n) in [
        ("carrying_capacity", kind.carrying_capacity),
        ("rescuing_resources", kind.rescuing_resources),
    ] {
        if n > MAX_UNITS_PER_ROBOT {
            return Err(ctx.err(
                format!("kinds[{k}].{name}"),
                format!("{n} is more than the limit of {MAX_UNITS_PER_ROBOT} per robot"),
            ));
        }
    }
    let (lo, hi) = NEEDS_RANGE;
    for (name, v) in [
        ("max_speed_m_per_s", kind.max_speed_m_per_s),
        ("sensing_range_m", kind.sensing_range_m),
        ("observing_range_m", kind.observing_range_m),
        ("hp_needs_full", kind.hp_needs_full),
        ("energy_needs_full", kind.energy_needs_full),
    ] {
        if !(lo..=hi).contains(&v) {
            return Err(ctx.err(
                format!("kinds[{k}].{name}"),
                format!(
                    "expected a number in [{lo:e}, {hi:e}] (a needs level), found {}",
                    number_text(v)
                ),
            ));
        }
    }
    Ok(())
}

/// The arena's sides and wall thickness, `navigation.clearance_m` and
/// `collision.safety_margin_m` against [`MAX_ARENA_SIDE_M`],
/// `navigation.waypoint_tolerance_m` against [`MAX_WAYPOINT_TOLERANCE_M`] and
/// [`min_waypoint_tolerance_m`], the navigation grid's cell against the arena's shorter side
/// and its cell count against [`MAX_NAV_CELLS`], the
/// needs weights against [`NEEDS_RANGE`], and every kind's distance per step: a robot at top
/// speed moves at most its body radius per step (`max_speed_m_per_s * dt_s <=
/// body_radius_m`), so it cannot pass through a wall or debris between two steps, and two
/// ground robots close at most the smaller body radius per step (`(v_a + v_b) * dt_s <=
/// min(r_a, r_b)`), so they cannot pass through each other.
pub(crate) fn check_derived(
    ctx: &Ctx<'_>,
    arena: &Arena,
    navigation: &NavigationParams,
    collision: &CollisionParams,
    weights: &NeedsWeights,
    kinds: &[RobotKind],
    sim: &SimParams,
) -> R<()> {
    check_lengths(ctx, arena, navigation, collision)?;
    check_waypoint_tolerance(ctx, arena, navigation)?;
    check_nav_grid(ctx, arena, navigation)?;
    check_weights(ctx, weights)?;
    let dt_s = sim.dt_s.get();
    check_step_lengths(ctx, kinds, dt_s)?;
    check_closing_speeds(ctx, kinds, dt_s)
}

/// The arena's sides and wall thickness, `navigation.clearance_m` and
/// `collision.safety_margin_m` against [`MAX_ARENA_SIDE_M`].
fn check_lengths(
    ctx: &Ctx<'_>,
    arena: &Arena,
    navigation: &NavigationParams,
    collision: &CollisionParams,
) -> R<()> {
    for (name, v) in [
        ("width_m", arena.width()),
        ("height_m", arena.height()),
        ("wall_thickness_m", arena.wall_thickness_m.get()),
    ] {
        if v > MAX_ARENA_SIDE_M {
            return Err(ctx.err(
                format!("arena.{name}"),
                format!(
                    "{} m is longer than the limit of {MAX_ARENA_SIDE_M} m",
                    number_text(v)
                ),
            ));
        }
    }
    for (name, v) in [
        ("navigation.clearance_m", navigation.clearance_m.get()),
        ("collision.safety_margin_m", collision.safety_margin_m.get()),
    ] {
        if v > MAX_ARENA_SIDE_M {
            return Err(ctx.err(
                name,
                format!(
                    "{} m is longer than the limit of {MAX_ARENA_SIDE_M} m",
                    number_text(v)
                ),
            ));
        }
    }
    Ok(())
}

/// `navigation.waypoint_tolerance_m` against [`MAX_WAYPOINT_TOLERANCE_M`] and
/// [`min_waypoint_tolerance_m`] of the arena's longer side.
fn check_waypoint_tolerance(ctx: &Ctx<'_>, arena: &Arena, navigation: &NavigationParams) -> R<()> {
    let tolerance_m = navigation.waypoint_tolerance_m.get();
    if tolerance_m > MAX_WAYPOINT_TOLERANCE_M {
        return Err(ctx.err(
            "navigation.waypoint_tolerance_m",
            format!(
                "{} m is more than the limit of {MAX_WAYPOINT_TOLERANCE_M} m (robots would count \
                 as at goals and rescuees that far away)",
                number_text(tolerance_m)
            ),
        ));
    }
    let least_m = min_waypoint_tolerance_m(arena.width().max(arena.height()));
    if tolerance_m < least_m {
        return Err(ctx.err(
            "navigation.waypoint_tolerance_m",
            format!(
                "{} m is less than the least of {} m for this arena (positions are f32: robots \
                 could never come that close to a waypoint)",
                number_text(tolerance_m),
                number_text(least_m)
            ),
        ));
    }
    Ok(())
}

/// The navigation grid's cell (`navigation.grid_cell_m`) against the arena's shorter side,
/// and its cell count against [`MAX_NAV_CELLS`].
fn check_nav_grid(ctx: &Ctx<'_>, arena: &Arena, navigation: &NavigationParams) -> R<()> {
    let cell_m = navigation.grid_cell_m.get();
    let shorter_side_m = arena.width().min(arena.height());
    if cell_m > shorter_side_m {
        return Err(ctx.err(
            "navigation.grid_cell_m",
            format!(
                "cells of {} m are larger than the arena's shorter side ({} m): the navigation \
                 grid could not see the debris",
                number_text(cell_m),
                number_text(shorter_side_m)
            ),
        ));
    }
    let (nx, ny) = (
        (arena.width() / cell_m).ceil().max(1.0),
        (arena.height() / cell_m).ceil().max(1.0),
    );
    if nx * ny > MAX_NAV_CELLS as f64 {
        return Err(ctx.err(
            "navigation.grid_cell_m",
            format!(
                "cells of {} m make a {} x {} navigation grid, more than the limit of \
                 {MAX_NAV_CELLS} cells; use larger cells",
                number_text(cell_m),
                number_text(nx),
                number_text(ny)
            ),
        ));
    }
    Ok(())
}

/// Every needs weight against [`NEEDS_RANGE`].
fn check_weights(ctx: &Ctx<'_>, weights: &NeedsWeights) -> R<()> {
    let (lo, hi) = NEEDS_RANGE;
    let names = ["hp", "v", "sen", "eng", "res", "cap", "obs"];
    for (name, w) in names.iter().zip(weights.to_array()) {
        if !(lo..=hi).contains(&w) {
            return Err(ctx.err(
                format!("needs_weights.{name}"),
                format!(
                    "expected a number in [{lo:e}, {hi:e}], found {}",
                    number_text(w)
                ),
            ));
        }
    }
    Ok(())
}

/// Every kind's distance per step of `dt_s` seconds at top speed against its body radius.
fn check_step_lengths(ctx: &Ctx<'_>, kinds: &[RobotKind], dt_s: f64) -> R<()> {
    for (k, kind) in kinds.iter().enumerate() {
        let step_m = kind.max_speed_m_per_s * dt_s;
        if step_m > kind.body_radius_m {
            return Err(ctx.err(
                format!("kinds[{k}].max_speed_m_per_s"),
                format!(
                    "at {} m/s a {} robot moves {} m per step of {} s (sim.dt_s), more than \
                     its body radius {} m; lower the speed or the step",
                    number_text(kind.max_speed_m_per_s),
                    kind.name,
                    number_text(step_m),
                    number_text(dt_s),
                    number_text(kind.body_radius_m)
                ),
            ));
        }
    }
    Ok(())
}

/// Two ground robots driving at each other close `(v_a + v_b) * dt_s` per step: that must not
/// exceed the smaller body radius, or they could pass through each other between two steps
/// (in a run with collision avoidance off, two 0.4 m robots at 20 m/s did). Aerial robots
/// fly over everything and are not checked. Blamed on the faster kind's `max_speed_m_per_s`
/// (a kind with itself included).
fn check_closing_speeds(ctx: &Ctx<'_>, kinds: &[RobotKind], dt_s: f64) -> R<()> {
    let ground: Vec<(usize, &RobotKind)> = kinds
        .iter()
        .enumerate()
        .filter(|(_, k)| k.locomotion == Locomotion::Ground)
        .collect();
    for (i, &(a, ka)) in ground.iter().enumerate() {
        for &(b, kb) in &ground[i..] {
            let closing_m = (ka.max_speed_m_per_s + kb.max_speed_m_per_s) * dt_s;
            let radius_m = ka.body_radius_m.min(kb.body_radius_m);
            if closing_m <= radius_m {
                continue;
            }
            let (k, fast) = if kb.max_speed_m_per_s > ka.max_speed_m_per_s {
                (b, kb)
            } else {
                (a, ka)
            };
            let pair = if a == b {
                format!("two {} robots", ka.name)
            } else {
                format!("a {} and a {} robot", ka.name, kb.name)
            };
            return Err(ctx.err(
                format!("kinds[{k}].max_speed_m_per_s"),
                format!(
                    "at {} m/s, {pair} driving at each other close {} m per step of {} s \
                     (sim.dt_s), more than the smaller body radius {} m: they could pass \
                     through each other; lower the speed or the step",
                    number_text(fast.max_speed_m_per_s),
                    number_text(closing_m),
                    number_text(dt_s),
                    number_text(radius_m)
                ),
            ));
        }
    }
    Ok(())
}

/// Every task's blind-search sweep (`mission::sweep_waypoints` at [`sweep_spacing_m`])
/// against [`MAX_SWEEP_POINTS`]; blamed on `mission.sweep_spacing_m` when the file sets it,
/// else on the `observing_range_m` of the ground kind whose detection width sets the default.
pub(crate) fn check_sweeps(ctx: &Ctx<'_>, s: &Scenario) -> R<()> {
    let spacing_m = sweep_spacing_m(s);
    for t in &s.tasks {
        let points = sweep_point_count(&t.search_area, spacing_m, s.mission.sweep_pattern);
        if points > MAX_SWEEP_POINTS {
            let field = match s.mission.sweep_spacing_m {
                Some(_) => "mission.sweep_spacing_m".to_owned(),
                None => {
                    let k = (0..s.kinds.len())
                        .filter(|&k| s.kinds[k].locomotion == Locomotion::Ground)
                        .min_by(|&a, &b| {
                            let width =
                                |k: usize| s.kinds[k].body_radius_m + s.kinds[k].observing_range_m;
                            width(a).total_cmp(&width(b))
                        })
                        .unwrap_or(0);
                    format!("kinds[{k}].observing_range_m")
                }
            };
            return Err(ctx.err(
                field,
                format!(
                    "sweep rows {} m apart make {} waypoints over the search area of task {:?}, \
                     more than the limit of {MAX_SWEEP_POINTS}",
                    number_text(spacing_m),
                    count_text(points),
                    t.name
                ),
            ));
        }
    }
    Ok(())
}
