//! Validation: [`ScenarioSpec`] -> [`Scenario`], once ("parse, don't validate").
//!
//! Checks, in order (the first failure is reported, with its field path):
//! name; arena; kinds (names, counts and quotas, ranges); listed debris (sizes, inside the
//! arena); rest station and tasks (search areas, goals, drop-offs inside the arena; goals and the
//! centres of drop-offs and the rest station not within reach of debris); start positions
//! (count, inside the arena with the body); generated debris (expanded deterministically);
//! start positions against debris (ground robots) and against each other (same locomotion);
//! rescuees; radiation zones; needs weights; mission, navigation, collision and sim parameters.

use nalgebra::{Point2, Vector2};
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::error::{ScenarioError, SourceLocation};
use super::locate::SourceMap;
use super::model::{
    Arena, Circle, ClampedNormal, CollisionParams, Debris, Locomotion, MissionParams, NEEDS_LEN,
    NavigationParams, PointM, RadiationZone, Rect, RobotKind, RobotStart, Scenario, SimParams,
    Task, TaskLevel,
};
use super::shape::DebrisShape;
use super::spec::{
    CircleSpec, ClampedNormalSpec, DebrisFieldSpec, DebrisShapeSpec, DebrisSpec, KindSpec,
    RectSpec, RescueeLayoutSpec, ScenarioSpec, StartsSpec, TaskSpec, XyM,
};

type R<T> = Result<T, ScenarioError>;

/// Most rescuees one grid layout may expand to.
const MAX_GRID_POINTS: usize = 1_000_000;
/// Placement attempts per generated shape before a debris field gives up.
const ATTEMPTS_PER_SHAPE: usize = 2_000;

/// Error context: the origin name and, when validating a file's text, its source map.
pub(crate) struct Ctx<'a> {
    pub(crate) origin: &'a str,
    pub(crate) map: Option<&'a SourceMap>,
}

impl Ctx<'_> {
    /// An [`ScenarioError::Invalid`] at `field` (positioned at the field or its nearest
    /// ancestor in the source).
    fn err(&self, field: impl Into<String>, message: impl Into<String>) -> ScenarioError {
        let field = field.into();
        ScenarioError::Invalid {
            location: SourceLocation {
                origin: self.origin.to_owned(),
                line_col: self.map.and_then(|m| m.line_col_of(&field)),
            },
            field,
            message: message.into(),
        }
    }

    fn finite(&self, field: &str, v: f64) -> R<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("expected a finite number, found {v}")))
        }
    }

    fn positive(&self, field: &str, v: f64) -> R<f64> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(self.err(field, format!("expected a finite number > 0, found {v}")))
        }
    }

    fn non_negative(&self, field: &str, v: f64) -> R<f64> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(field, format!("expected a finite number >= 0, found {v}")))
        }
    }

    fn in_range(&self, field: &str, v: f64, lo: f64, hi: f64) -> R<f64> {
        if v.is_finite() && v >= lo && v <= hi {
            Ok(v)
        } else {
            Err(self.err(
                field,
                format!("expected a number in [{lo}, {hi}], found {v}"),
            ))
        }
    }

    fn point(&self, field: &str, xy: &XyM) -> R<PointM> {
        if xy.iter().all(|v| v.is_finite()) {
            Ok(Point2::new(xy[0], xy[1]))
        } else {
            Err(self.err(
                field,
                format!("expected finite coordinates, found ({}, {})", xy[0], xy[1]),
            ))
        }
    }

    fn point_in_arena(&self, field: &str, xy: &XyM, arena: &Arena) -> R<PointM> {
        let p = self.point(field, xy)?;
        if arena.contains(&p) {
            Ok(p)
        } else {
            Err(self.err(
                field,
                format!(
                    "point {} is outside the arena {}",
                    fmt_pt(&p),
                    fmt_arena(arena)
                ),
            ))
        }
    }

    fn rect_in_arena(&self, field: &str, spec: &RectSpec, arena: &Arena) -> R<Rect> {
        let min = self.point(&format!("{field}.min_m"), &spec.min_m)?;
        let max = self.point(&format!("{field}.max_m"), &spec.max_m)?;
        if !(max.x > min.x && max.y > min.y) {
            return Err(self.err(
                field,
                format!(
                    "expected max_m > min_m in both coordinates, found min_m {} and max_m {}",
                    fmt_pt(&min),
                    fmt_pt(&max)
                ),
            ));
        }
        if !(arena.contains(&min) && arena.contains(&max)) {
            return Err(self.err(
                field,
                format!(
                    "rectangle {} - {} is not inside the arena {}",
                    fmt_pt(&min),
                    fmt_pt(&max),
                    fmt_arena(arena)
                ),
            ));
        }
        Ok(Rect { min, max })
    }

    fn circle_in_arena(&self, field: &str, spec: &CircleSpec, arena: &Arena) -> R<Circle> {
        let center = self.point(&format!("{field}.center_m"), &spec.center_m)?;
        let radius_m = self.positive(&format!("{field}.radius_m"), spec.radius_m)?;
        if !disc_inside(arena, &center, radius_m) {
            return Err(self.err(
                field,
                format!(
                    "circle at {} with radius {} m is not inside the arena {}",
                    fmt_pt(&center),
                    radius_m,
                    fmt_arena(arena)
                ),
            ));
        }
        Ok(Circle { center, radius_m })
    }
}

fn fmt_pt(p: &PointM) -> String {
    format!("({}, {})", p.x, p.y)
}

fn fmt_arena(a: &Arena) -> String {
    format!("[0, {}] x [0, {}] m", a.width_m, a.height_m)
}

fn disc_inside(arena: &Arena, c: &PointM, r: f64) -> bool {
    c.x - r >= 0.0 && c.y - r >= 0.0 && c.x + r <= arena.width_m && c.y + r <= arena.height_m
}

impl ScenarioSpec {
    /// Checks every rule and builds the validated [`Scenario`] (grid layouts, start rows and
    /// debris fields expanded). `origin` names the source in errors (e.g. the file path).
    ///
    /// Errors from this method carry the field path but no line/column (the spec has no
    /// source text); [`super::from_str`] and [`super::load`] add positions.
    ///
    /// # Errors
    /// [`ScenarioError::Invalid`] for the first rule broken; see `docs/scenario-format.md`.
    pub fn validate(&self, origin: &str) -> Result<Scenario, ScenarioError> {
        validate(self, &Ctx { origin, map: None })
    }
}

/// A place generated debris must keep away from.
struct Protected {
    center: PointM,
    radius_m: f64,
    what: String,
}

/// See the module docs.
pub(crate) fn validate(spec: &ScenarioSpec, ctx: &Ctx<'_>) -> R<Scenario> {
    if spec.name.trim().is_empty() {
        return Err(ctx.err("name", "expected a non-empty name"));
    }

    let arena = Arena {
        width_m: ctx.positive("arena.width_m", spec.arena.width_m)?,
        height_m: ctx.positive("arena.height_m", spec.arena.height_m)?,
        wall_thickness_m: ctx.positive("arena.wall_thickness_m", spec.arena.wall_thickness_m)?,
    };

    let kinds = validate_kinds(ctx, &spec.kinds)?;
    let min_ground_radius = kinds
        .iter()
        .filter(|k| k.locomotion == Locomotion::Ground)
        .map(|k| k.body_radius_m)
        .fold(f64::INFINITY, f64::min);
    // Reach: how close to debris a point may be for a ground robot to get to it.
    let reach = if min_ground_radius.is_finite() {
        min_ground_radius
    } else {
        0.0
    };

    // Listed debris.
    let mut debris = Vec::with_capacity(spec.debris.len());
    let mut debris_names = Vec::with_capacity(spec.debris.len());
    for (i, d) in spec.debris.iter().enumerate() {
        let path = format!("debris[{i}]");
        debris.push(validate_debris(ctx, &path, d, &arena)?);
        debris_names.push(path);
    }

    // Rest station and task geometry.
    let rest_station = ctx.circle_in_arena("rest_station", &spec.rest_station, &arena)?;
    let mut task_geo = Vec::with_capacity(2);
    for level in TaskLevel::ALL {
        let t: &TaskSpec = match level {
            TaskLevel::Easy => &spec.tasks.easy,
            TaskLevel::Hard => &spec.tasks.hard,
        };
        let base = format!("tasks.{}", level.name());
        let search_area =
            ctx.rect_in_arena(&format!("{base}.search_area"), &t.search_area, &arena)?;
        let goal = ctx.point_in_arena(&format!("{base}.goal_m"), &t.goal_m, &arena)?;
        let drop_off = ctx.circle_in_arena(&format!("{base}.drop_off"), &t.drop_off, &arena)?;
        task_geo.push((search_area, goal, drop_off));
    }
    let reachable =
        |field: String, p: &PointM, what: &str, debris: &[DebrisShape], names: &[String]| {
            for (d, name) in debris.iter().zip(names) {
                let dist = d.distance_to_point(p);
                if dist < reach || dist == 0.0 {
                    return Err(ctx.err(
                        field,
                        format!(
                            "{what} {} is {dist:.3} m from {name}; it must be at least {reach} m \
                         (the smallest ground body radius) away so ground robots can reach it",
                            fmt_pt(p)
                        ),
                    ));
                }
            }
            Ok(())
        };
    reachable(
        "rest_station.center_m".into(),
        &rest_station.center,
        "rest station centre",
        &debris,
        &debris_names,
    )?;
    for (level, (_, goal, drop_off)) in TaskLevel::ALL.iter().zip(&task_geo) {
        let base = format!("tasks.{}", level.name());
        reachable(
            format!("{base}.goal_m"),
            goal,
            "goal",
            &debris,
            &debris_names,
        )?;
        reachable(
            format!("{base}.drop_off.center_m"),
            &drop_off.center,
            "drop-off centre",
            &debris,
            &debris_names,
        )?;
    }

    // Start positions (expanded; checked against the arena now, against debris later).
    let mut robots = Vec::new();
    let mut robot_paths = Vec::new();
    for (k, (ks, kind)) in spec.kinds.iter().zip(&kinds).enumerate() {
        let base = format!("kinds[{k}].starts");
        // (field path, label for messages, position)
        let starts: Vec<(String, String, PointM)> = match &ks.starts {
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
                        ctx.point(&path, xy)
                            .map(|p| (path, format!("{} robot {i}", kind.name), p))
                    })
                    .collect::<R<_>>()?
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
                (0..kind.count)
                    .map(|i| {
                        (
                            base.clone(),
                            format!("{} robot {i}", kind.name),
                            first + step * i as f64,
                        )
                    })
                    .collect()
            }
        };
        for (path, label, p) in starts {
            if !disc_inside(&arena, &p, kind.body_radius_m) {
                return Err(ctx.err(
                    path,
                    format!(
                        "{label}: start {} with body radius {} m is not inside the arena {}",
                        fmt_pt(&p),
                        kind.body_radius_m,
                        fmt_arena(&arena)
                    ),
                ));
            }
            robots.push(RobotStart {
                kind: k,
                start_in_world: p,
            });
            robot_paths.push((path, label));
        }
    }

    // Generated debris.
    let mut protected: Vec<Protected> = robots
        .iter()
        .zip(&robot_paths)
        .map(|(r, (_, label))| Protected {
            center: r.start_in_world,
            radius_m: kinds[r.kind].body_radius_m,
            what: format!("the start of {label}"),
        })
        .collect();
    protected.push(Protected {
        center: rest_station.center,
        radius_m: rest_station.radius_m,
        what: "the rest station".into(),
    });
    for (level, (_, goal, drop_off)) in TaskLevel::ALL.iter().zip(&task_geo) {
        protected.push(Protected {
            center: drop_off.center,
            radius_m: drop_off.radius_m,
            what: format!("the {} drop-off", level.name()),
        });
        protected.push(Protected {
            center: *goal,
            radius_m: 0.0,
            what: format!("the {} goal", level.name()),
        });
    }
    for (j, field) in spec.debris_fields.iter().enumerate() {
        let generated =
            generate_debris_field(ctx, j, field, &arena, spec.sim.seed, &debris, &protected)?;
        for (n, d) in generated.into_iter().enumerate() {
            debris.push(d);
            debris_names.push(format!("debris_fields[{j}] shape {n}"));
        }
    }

    // Starts against debris and each other.
    for (r, (path, label)) in robots.iter().zip(&robot_paths) {
        let kind = &kinds[r.kind];
        if kind.locomotion != Locomotion::Ground {
            continue;
        }
        for (d, name) in debris.iter().zip(&debris_names) {
            let dist = d.distance_to_point(&r.start_in_world);
            if dist < kind.body_radius_m {
                return Err(ctx.err(
                    path.clone(),
                    format!(
                        "{label}: start {} of a ground robot overlaps {name}: its centre is \
                         {dist:.3} m from it, need at least the body radius {} m",
                        fmt_pt(&r.start_in_world),
                        kind.body_radius_m
                    ),
                ));
            }
        }
    }
    for (i, (a, (_, la))) in robots.iter().zip(&robot_paths).enumerate() {
        for (b, (pb, lb)) in robots.iter().zip(&robot_paths).skip(i + 1) {
            let (ka, kb) = (&kinds[a.kind], &kinds[b.kind]);
            if ka.locomotion != kb.locomotion {
                continue;
            }
            let need = ka.body_radius_m + kb.body_radius_m;
            let dist = (a.start_in_world - b.start_in_world).norm();
            if dist < need {
                return Err(ctx.err(
                    pb.clone(),
                    format!(
                        "{lb}: start {} overlaps {la} at {}: {dist:.3} m apart, need at least {need} m \
                         (sum of body radii)",
                        fmt_pt(&b.start_in_world),
                        fmt_pt(&a.start_in_world)
                    ),
                ));
            }
        }
    }

    // Tasks with rescuees.
    let mut tasks = Vec::with_capacity(2);
    for (level, (search_area, goal, drop_off)) in TaskLevel::ALL.into_iter().zip(task_geo) {
        let t = match level {
            TaskLevel::Easy => &spec.tasks.easy,
            TaskLevel::Hard => &spec.tasks.hard,
        };
        let path = format!("tasks.{}.rescuees", level.name());
        let rescuees = expand_rescuees(
            ctx,
            &path,
            &t.rescuees,
            &search_area,
            &debris,
            &debris_names,
            reach,
        )?;
        tasks.push(Task {
            level,
            search_area,
            goal,
            drop_off,
            rescuees,
        });
    }
    let Ok(tasks) = <[Task; 2]>::try_from(tasks) else {
        unreachable!("two task levels")
    };

    let mut radiation_zones = Vec::with_capacity(spec.radiation_zones.len());
    for (i, z) in spec.radiation_zones.iter().enumerate() {
        let path = format!("radiation_zones[{i}]");
        let area = ctx.circle_in_arena(
            &path,
            &CircleSpec {
                center_m: z.center_m,
                radius_m: z.radius_m,
            },
            &arena,
        )?;
        let dose_rate_factor =
            ctx.positive(&format!("{path}.dose_rate_factor"), z.dose_rate_factor)?;
        radiation_zones.push(RadiationZone {
            area,
            dose_rate_factor,
        });
    }

    let w = &spec.needs_weights;
    let named: [(&str, f64); NEEDS_LEN] = [
        ("hp", w.hp),
        ("v", w.v),
        ("sen", w.sen),
        ("eng", w.eng),
        ("res", w.res),
        ("cap", w.cap),
        ("obs", w.obs),
    ];
    let mut needs_weights = [0.0; NEEDS_LEN];
    for (slot, (name, v)) in needs_weights.iter_mut().zip(named) {
        *slot = ctx.positive(&format!("needs_weights.{name}"), v)?;
    }

    let m = &spec.mission;
    let mission = MissionParams {
        duration_s: ctx.positive("mission.duration_s", m.duration_s)?,
        energy_pct_per_moving_step: ctx.non_negative(
            "mission.energy_pct_per_moving_step",
            m.energy_pct_per_moving_step,
        )?,
        energy_pct_per_m: ctx.non_negative("mission.energy_pct_per_m", m.energy_pct_per_m)?,
        hp_pct_per_step_in_radiation: ctx.non_negative(
            "mission.hp_pct_per_step_in_radiation",
            m.hp_pct_per_step_in_radiation,
        )?,
        radiation_overlap: m.radiation_overlap,
        radiation_falloff: m.radiation_falloff,
        round_start: m.round_start,
        away_quotas: m.away_quotas,
        load_on_leave: m.load_on_leave,
        search_time_budget_s: m
            .search_time_budget_s
            .map(|b| ctx.positive("mission.search_time_budget_s", b))
            .transpose()?,
        refresh: m.refresh,
        sweep_spacing_m: m
            .sweep_spacing_m
            .map(|v| ctx.positive("mission.sweep_spacing_m", v))
            .transpose()?,
        min_hp_factor: ctx.in_range("mission.min_hp_factor", m.min_hp_factor, 0.0, 1.0)?,
        pickup_s: ctx.non_negative("mission.pickup_s", m.pickup_s)?,
        low_energy_pct: ctx.in_range("mission.low_energy_pct", m.low_energy_pct, 0.0, 100.0)?,
        low_hp_pct: ctx.in_range("mission.low_hp_pct", m.low_hp_pct, 0.0, 100.0)?,
        recharge_s: ctx.non_negative("mission.recharge_s", m.recharge_s)?,
        no_observer_speed_factor: {
            let f = m.no_observer_speed_factor;
            if f.is_finite() && f > 0.0 && f <= 1.0 {
                f
            } else {
                return Err(ctx.err(
                    "mission.no_observer_speed_factor",
                    format!("expected a number in (0, 1], found {f}"),
                ));
            }
        },
        initial_energy: clamped_normal(ctx, "mission.initial_energy", &m.initial_energy)?,
        initial_hp: clamped_normal(ctx, "mission.initial_hp", &m.initial_hp)?,
    };

    let n = &spec.navigation;
    let navigation = NavigationParams {
        grid_cell_m: ctx.positive("navigation.grid_cell_m", n.grid_cell_m)?,
        clearance_m: ctx.non_negative("navigation.clearance_m", n.clearance_m)?,
        waypoint_tolerance_m: ctx
            .positive("navigation.waypoint_tolerance_m", n.waypoint_tolerance_m)?,
    };

    let c = &spec.collision;
    let collision = CollisionParams {
        enabled: c.enabled,
        lookahead_s: ctx.positive("collision.lookahead_s", c.lookahead_s)?,
        safety_margin_m: ctx.non_negative("collision.safety_margin_m", c.safety_margin_m)?,
        deadlock_after_s: ctx.positive("collision.deadlock_after_s", c.deadlock_after_s)?,
    };

    let dt_s = ctx.positive("sim.dt_s", spec.sim.dt_s)?;
    if dt_s > mission.duration_s {
        return Err(ctx.err(
            "sim.dt_s",
            format!(
                "step {dt_s} s is longer than the trial (mission.duration_s = {} s)",
                mission.duration_s
            ),
        ));
    }

    Ok(Scenario {
        name: spec.name.clone(),
        description: spec.description.clone(),
        arena,
        kinds,
        robots,
        rest_station,
        tasks,
        debris: debris.iter().map(|d| *d.debris()).collect(),
        radiation_zones,
        needs_weights,
        mission,
        navigation,
        collision,
        sim: SimParams {
            dt_s,
            seed: spec.sim.seed,
        },
    })
}

fn validate_kinds(ctx: &Ctx<'_>, specs: &[KindSpec]) -> R<Vec<RobotKind>> {
    if specs.is_empty() {
        return Err(ctx.err("kinds", "expected at least one robot kind"));
    }
    let mut kinds: Vec<RobotKind> = Vec::with_capacity(specs.len());
    for (k, s) in specs.iter().enumerate() {
        let base = format!("kinds[{k}]");
        let f = |name: &str| format!("{base}.{name}");
        if s.name.trim().is_empty() {
            return Err(ctx.err(f("name"), "expected a non-empty kind name"));
        }
        if let Some(j) = kinds.iter().position(|o| o.name == s.name) {
            return Err(ctx.err(
                f("name"),
                format!("duplicate kind name {:?} (also kinds[{j}])", s.name),
            ));
        }
        if s.count == 0 {
            return Err(ctx.err(f("count"), "expected at least 1 robot, found 0"));
        }
        let total = s.quota.easy.checked_add(s.quota.hard);
        if total != Some(s.count) {
            return Err(ctx.err(
                f("quota"),
                format!(
                    "easy {} + hard {} = {} but count is {}",
                    s.quota.easy,
                    s.quota.hard,
                    total.map_or_else(|| "overflow".to_owned(), |t| t.to_string()),
                    s.count
                ),
            ));
        }
        kinds.push(RobotKind {
            name: s.name.clone(),
            role: s.role,
            locomotion: s.locomotion,
            count: s.count,
            quota: [s.quota.easy, s.quota.hard],
            body_radius_m: ctx.positive(&f("body_radius_m"), s.body_radius_m)?,
            max_speed_m_per_s: ctx.positive(&f("max_speed_m_per_s"), s.max_speed_m_per_s)?,
            sensing_range_m: ctx.positive(&f("sensing_range_m"), s.sensing_range_m)?,
            observing_range_m: ctx.positive(&f("observing_range_m"), s.observing_range_m)?,
            carrying_capacity: s.carrying_capacity,
            rescuing_resources: s.rescuing_resources,
            hp_needs_full: ctx.positive(&f("hp_needs_full"), s.hp_needs_full)?,
            energy_needs_full: ctx.positive(&f("energy_needs_full"), s.energy_needs_full)?,
        });
    }
    Ok(kinds)
}

fn validate_debris(ctx: &Ctx<'_>, path: &str, d: &DebrisSpec, arena: &Arena) -> R<DebrisShape> {
    let shape = match d {
        DebrisSpec::Rect {
            center_m,
            size_m,
            rotation_deg,
        } => {
            let center = ctx.point(&format!("{path}.center_m"), center_m)?;
            let size_path = format!("{path}.size_m");
            if !(size_m.iter().all(|v| v.is_finite() && *v > 0.0)) {
                return Err(ctx.err(
                    size_path,
                    format!(
                        "expected width and height finite and > 0, found ({}, {})",
                        size_m[0], size_m[1]
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
            radius_m: ctx.positive(&format!("{path}.radius_m"), *radius_m)?,
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

fn clamped_normal(ctx: &Ctx<'_>, path: &str, s: &ClampedNormalSpec) -> R<ClampedNormal> {
    let min_pct = ctx.in_range(&format!("{path}.min_pct"), s.min_pct, 0.0, 100.0)?;
    let max_pct = ctx.in_range(&format!("{path}.max_pct"), s.max_pct, min_pct, 100.0)?;
    Ok(ClampedNormal {
        mean_pct: ctx.finite(&format!("{path}.mean_pct"), s.mean_pct)?,
        std_dev_pct: ctx.non_negative(&format!("{path}.std_dev_pct"), s.std_dev_pct)?,
        min_pct,
        max_pct,
    })
}

fn size_range(ctx: &Ctx<'_>, path: &str, (lo, hi): (f64, f64)) -> R<(f64, f64)> {
    if lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi {
        Ok((lo, hi))
    } else {
        Err(ctx.err(
            path,
            format!("expected (min, max) with 0 < min <= max, both finite, found ({lo}, {hi})"),
        ))
    }
}

/// Expands debris field `j`; see [`DebrisFieldSpec`].
fn generate_debris_field(
    ctx: &Ctx<'_>,
    j: usize,
    f: &DebrisFieldSpec,
    arena: &Arena,
    sim_seed: u64,
    existing: &[DebrisShape],
    protected: &[Protected],
) -> R<Vec<DebrisShape>> {
    let base = format!("debris_fields[{j}]");
    let region = ctx.rect_in_arena(&format!("{base}.region"), &f.region, arena)?;
    if f.count == 0 {
        return Err(ctx.err(
            format!("{base}.count"),
            "expected at least 1 shape, found 0",
        ));
    }
    let gap = ctx.non_negative(&format!("{base}.min_gap_m"), f.min_gap_m)?;
    let (w, h) = (region.max.x - region.min.x, region.max.y - region.min.y);
    enum Draw {
        Circles(f64, f64),
        Rects(f64, f64, f64),
    }
    let draw = match &f.shape {
        DebrisShapeSpec::Circles { radius_m } => {
            let (lo, hi) = size_range(ctx, &format!("{base}.shape.radius_m"), *radius_m)?;
            if 2.0 * lo > w.min(h) {
                return Err(ctx.err(
                    format!("{base}.shape.radius_m"),
                    format!(
                        "the smallest disc (radius {lo} m) does not fit in the region ({w} x {h} m)"
                    ),
                ));
            }
            Draw::Circles(lo, hi)
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
                    format!("the smallest rectangle (side {lo} m) does not fit in the region ({w} x {h} m)"),
                ));
            }
            Draw::Rects(lo, hi, rot.to_radians())
        }
    };
    let seed = f.seed.unwrap_or(sim_seed.wrapping_add(j as u64));
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut placed: Vec<DebrisShape> = Vec::with_capacity(f.count);
    let max_attempts = ATTEMPTS_PER_SHAPE * f.count;
    let mut attempts = 0;
    while placed.len() < f.count && attempts < max_attempts {
        attempts += 1;
        let (mut shape, half) = match draw {
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
        };
        let (x_lo, x_hi) = (region.min.x + half.x, region.max.x - half.x);
        let (y_lo, y_hi) = (region.min.y + half.y, region.max.y - half.y);
        if x_lo > x_hi || y_lo > y_hi {
            continue;
        }
        let c = Point2::new(rng.random_range(x_lo..=x_hi), rng.random_range(y_lo..=y_hi));
        match &mut shape {
            Debris::Circle(circle) => circle.center = c,
            Debris::Rect { center, .. } => *center = c,
        }
        let shape = shape.shape();
        let clear_of_debris = existing
            .iter()
            .chain(&placed)
            .all(|d| shape.distance(d) >= gap);
        let clear_of_places = protected
            .iter()
            .all(|p| shape.distance_to_point(&p.center) >= p.radius_m + gap);
        if clear_of_debris && clear_of_places {
            placed.push(shape);
        }
    }
    if placed.len() < f.count {
        // Name the most likely culprit: a protected place inside the region.
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
        return Err(ctx.err(
            format!("{base}.count"),
            format!(
                "placed only {} of {} shapes in {attempts} attempts{hint}; enlarge the region \
                 or reduce count, sizes or min_gap_m",
                placed.len(),
                f.count
            ),
        ));
    }
    Ok(placed)
}

fn expand_rescuees(
    ctx: &Ctx<'_>,
    path: &str,
    layout: &RescueeLayoutSpec,
    area: &Rect,
    debris: &[DebrisShape],
    debris_names: &[String],
    reach: f64,
) -> R<Vec<PointM>> {
    let near_debris = |p: &PointM| {
        debris
            .iter()
            .zip(debris_names)
            .find(|(d, _)| {
                let dist = d.distance_to_point(p);
                dist == 0.0 || dist < reach
            })
            .map(|(_, n)| n)
    };
    let points = match layout {
        RescueeLayoutSpec::Grid {
            spacing_m,
            margin_m,
        } => {
            let s = ctx.positive(&format!("{path}.spacing_m"), *spacing_m)?;
            let m = ctx.non_negative(&format!("{path}.margin_m"), *margin_m)?;
            let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
            let (uw, uh) = (w - 2.0 * m, h - 2.0 * m);
            if uw < 0.0 || uh < 0.0 {
                return Err(ctx.err(
                    format!("{path}.margin_m"),
                    format!("margin {m} m leaves no room in a {w} x {h} m search area"),
                ));
            }
            let nx = (uw / s + 1e-9).floor() as usize + 1;
            let ny = (uh / s + 1e-9).floor() as usize + 1;
            if nx.saturating_mul(ny) > MAX_GRID_POINTS {
                return Err(ctx.err(
                    format!("{path}.spacing_m"),
                    format!(
                        "spacing {s} m gives {nx} x {ny} rescuees, more than {MAX_GRID_POINTS}"
                    ),
                ));
            }
            let x0 = area.min.x + (w - (nx - 1) as f64 * s) / 2.0;
            let y0 = area.min.y + (h - (ny - 1) as f64 * s) / 2.0;
            let pts: Vec<PointM> = (0..ny)
                .flat_map(|iy| {
                    (0..nx).map(move |ix| Point2::new(x0 + ix as f64 * s, y0 + iy as f64 * s))
                })
                .filter(|p| near_debris(p).is_none())
                .collect();
            if pts.is_empty() {
                return Err(ctx.err(
                    path,
                    "every grid point is covered by debris; expected at least one rescuee",
                ));
            }
            pts
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
            pts
        }
    };
    Ok(points)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{from_str, load};

    fn scenario_file(name: &str) -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name)
    }

    #[test]
    fn paper_debris_keeps_gaps_ground_robots_fit_through() {
        let s = load(scenario_file("paper.ron")).expect("paper.ron loads");
        // 8 + 3 listed, 8 + 5 generated.
        assert_eq!(s.debris.len(), 24);
        for (i, a) in s.debris.iter().enumerate() {
            for b in &s.debris[i + 1..] {
                let d = a.shape().distance(&b.shape());
                assert!(d >= 2.0, "gap {d} between {a:?} and {b:?}");
            }
        }
    }

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
        let pts = expand_rescuees(
            &ctx,
            "r",
            &RescueeLayoutSpec::Grid {
                spacing_m: 1.0,
                margin_m: 0.0,
            },
            &area,
            &[],
            &[],
            0.4,
        )
        .expect("grid");
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
        let d = [Debris::Circle(Circle {
            center: Point2::new(1.25, 0.0),
            radius_m: 0.1,
        })
        .shape()];
        let pts = expand_rescuees(
            &ctx,
            "r",
            &RescueeLayoutSpec::Grid {
                spacing_m: 1.0,
                margin_m: 0.0,
            },
            &area,
            &d,
            &["debris[0]".to_owned()],
            0.4,
        )
        .expect("grid");
        assert_eq!(pts.len(), 5);
    }

    #[test]
    fn rows_expand_in_order_and_kinds_order_robots() {
        let src = std::fs::read_to_string(scenario_file("paper.ron")).expect("paper.ron");
        let s = from_str(&src, "paper.ron").expect("loads");
        assert_eq!(s.robots.len(), 12);
        let kinds: Vec<usize> = s.robots.iter().map(|r| r.kind).collect();
        assert_eq!(kinds, [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2]);
        assert_eq!(s.robots[0].start_in_world, Point2::new(32.5, 3.0));
        assert_eq!(s.robots[5].start_in_world, Point2::new(47.5, 3.0));
    }

    #[test]
    fn zero_row_step_is_rejected() {
        let src = std::fs::read_to_string(scenario_file("corridor.ron")).expect("corridor.ron");
        let src = src.replacen("step_m: (-1.0, 0.0)", "step_m: (0.0, 0.0)", 1);
        let err = from_str(&src, "c.ron").expect_err("zero step");
        assert_eq!(err.field(), Some("kinds[0].starts.step_m"));
        assert!(err.line_col().is_some());
    }
}
