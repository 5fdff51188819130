//! Validation: [`ScenarioSpec`] -> [`Scenario`], once ("parse, don't validate").
//!
//! The leaf parameter blocks are already checked (their numbers are validated types); this
//! step checks what spans fields and expands the compact forms ([`super::generate`]). In order
//! (the first failure is reported, with its field path): name; tasks (names, search areas,
//! goals, drop-offs inside the arena); kinds (names, counts, quotas by task name); listed
//! debris (inside the arena); rest station; goals, drop-off centres and the rest station clear
//! of debris; start positions (count, inside the arena with the body); generated debris; start
//! positions against debris (ground robots) and against each other (same locomotion);
//! rescuees; radiation zones; cross-field parameter rules.

use nalgebra::Vector2;

use super::context::{Ctx, R, disc_inside, fmt_arena, fmt_pt};
use super::error::ScenarioError;
use super::generate::{
    Protected, Start, debris_index, expand_rescuees, generate_debris_field, start_positions,
};
use super::limits::{
    MAX_DEBRIS, MAX_RESCUEES, MAX_REST_STATIONS, check_derived, check_kind, check_lists,
    check_sweeps,
};
use super::model::{
    Circle, Debris, Locomotion, PointM, RadiationZone, Rect, RobotKind, RobotStart, Scenario, Task,
    number_text, number_text_3dp,
};
use super::params::{Arena, ClampedNormal};
use super::shape::DebrisShape;
use super::spec::{CircleSpec, DebrisSpec, KindSpec, RestStationsSpec, ScenarioSpec, TaskSpec};

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

/// A task's checked geometry, before its rescuees are laid out.
struct TaskGeometry {
    search_area: Rect,
    goal: PointM,
    drop_off: Circle,
}

/// Debris with the names messages give them (`debris[3]`, `debris_fields[0] shape 2`).
type NamedDebris = Vec<(DebrisShape, String)>;

/// The name no task may have: the tables name the sum over all tasks `total`
/// (`rescued_total`, `energy_total_pct`, the `total` rows of `summary.csv`), so a task of
/// that name would give two columns of one name.
pub const RESERVED_TASK_NAME: &str = "total";

/// Whose energy per rescuee the tables' columns of a task named `name` would stand for: the
/// columns `energy_<task>_pct` and `hp_<task>_pct` of a task `per_rescuee` are those of all
/// tasks' cost per rescuee (`energy_per_rescuee_pct`), and of a task `per_<other>_rescuee`
/// those of task `other` (`energy_per_<other>_rescuee_pct`). `None` when there is no clash.
fn per_rescuee_clash(name: &str, tasks: &[TaskSpec]) -> Option<String> {
    let inner = name.strip_prefix("per_")?.strip_suffix("rescuee")?;
    if inner.is_empty() {
        return Some("all tasks".into());
    }
    let other = inner.strip_suffix('_')?;
    tasks
        .iter()
        .any(|o| o.name == other)
        .then(|| format!("task {other:?}"))
}

/// Checks `name`, the `what` at `field`: not blank, and one line of text without control
/// characters or the Unicode line and paragraph separators (a line break or tab would break
/// the reports' tables, the CSV headers that carry task names, and the console's lines).
fn check_name(ctx: &Ctx<'_>, field: String, what: &str, name: &str) -> R<()> {
    if name.trim().is_empty() {
        return Err(ctx.err(field, format!("expected a non-empty {what}")));
    }
    let breaks_lines = |c: char| c.is_control() || matches!(c, '\u{2028}' | '\u{2029}');
    if let Some(c) = name.chars().find(|&c| breaks_lines(c)) {
        // At most 60 characters of the name are quoted, so the message stays short.
        let quoted: String = name.chars().take(60).collect();
        let more = if quoted.len() < name.len() { "..." } else { "" };
        let kind = if c.is_control() {
            "the control character"
        } else {
            "the line-breaking character"
        };
        return Err(ctx.err(
            field,
            format!("{what} {quoted:?}{more} holds {kind} {c:?}; a name is one line of text"),
        ));
    }
    Ok(())
}

/// See the module docs.
pub(crate) fn validate(spec: &ScenarioSpec, ctx: &Ctx<'_>) -> R<Scenario> {
    check_name(ctx, "name".into(), "name", &spec.name)?;
    let arena = spec.arena;
    check_lists(ctx, &spec.kinds, spec.tasks.len())?;
    let geometry = task_geometry(ctx, &spec.tasks, &arena)?;
    let kinds = validate_kinds(ctx, &spec.kinds, &spec.tasks)?;
    // Reach: how close to debris a point may be for a ground robot to get to it.
    let reach = kinds
        .iter()
        .filter(|k| k.locomotion == Locomotion::Ground)
        .map(|k| k.body_radius_m)
        .reduce(f64::min)
        .unwrap_or(0.0);
    let mut debris = listed_debris(ctx, &spec.debris, &arena)?;
    let rest_stations = rest_stations(ctx, &spec.rest_station, &arena)?;
    check_reachable(ctx, &rest_stations, &spec.tasks, &geometry, &debris, reach)?;
    let starts = expand_starts(ctx, spec, &kinds, &arena)?;
    let protected = protected_places(&starts, &kinds, &rest_stations, &spec.tasks, &geometry);
    for (j, field) in spec.debris_fields.iter().enumerate() {
        let existing: Vec<DebrisShape> = debris.iter().map(|(d, _)| *d).collect();
        let generated =
            generate_debris_field(ctx, j, field, &arena, spec.sim.seed, &existing, &protected)?;
        debris.extend(
            generated
                .into_iter()
                .enumerate()
                .map(|(n, d)| (d, format!("debris_fields[{j}] shape {n}"))),
        );
    }
    check_starts(ctx, &starts, &kinds, &debris)?;
    let tasks = expand_tasks(ctx, &spec.tasks, geometry, &debris, reach)?;
    let radiation_zones = radiation_zones(ctx, spec, &arena)?;
    check_params(ctx, spec)?;
    check_derived(
        ctx,
        &arena,
        &spec.navigation,
        &spec.collision,
        &spec.needs_weights,
        &kinds,
        &spec.sim,
    )?;
    let scenario = Scenario {
        name: spec.name.clone(),
        description: spec.description.clone(),
        arena,
        kinds,
        robots: starts.iter().map(|(_, r)| *r).collect(),
        rest_stations: rest_stations.into_iter().map(|(_, c)| c).collect(),
        tasks,
        debris: debris.iter().map(|(d, _)| *d.debris()).collect(),
        radiation_zones,
        needs_weights: spec.needs_weights,
        mission: spec.mission.clone(),
        navigation: spec.navigation,
        collision: spec.collision,
        sim: spec.sim,
    };
    check_sweeps(ctx, &scenario)?;
    Ok(scenario)
}

/// Task names (non-empty, unique, at least one task) and each task's search area, goal and
/// drop-off inside the arena.
fn task_geometry(ctx: &Ctx<'_>, tasks: &[TaskSpec], arena: &Arena) -> R<Vec<TaskGeometry>> {
    if tasks.is_empty() {
        return Err(ctx.err("tasks", "expected at least one task"));
    }
    let mut out = Vec::with_capacity(tasks.len());
    for (i, t) in tasks.iter().enumerate() {
        let base = format!("tasks[{i}]");
        check_name(ctx, format!("{base}.name"), "task name", &t.name)?;
        if t.name == RESERVED_TASK_NAME {
            return Err(ctx.err(
                format!("{base}.name"),
                format!(
                    "the task name {RESERVED_TASK_NAME:?} is reserved: the tables' columns of \
                     all tasks together use it (rescued_total, energy_total_pct)"
                ),
            ));
        }
        if let Some(j) = tasks[..i].iter().position(|o| o.name == t.name) {
            return Err(ctx.err(
                format!("{base}.name"),
                format!("duplicate task name {:?} (also tasks[{j}])", t.name),
            ));
        }
        if let Some(whose) = per_rescuee_clash(&t.name, tasks) {
            return Err(ctx.err(
                format!("{base}.name"),
                format!(
                    "the task name {:?} would give the column energy_{}_pct, the energy per \
                     rescuee of {whose}",
                    t.name, t.name
                ),
            ));
        }
        let named = |e: ScenarioError| match e {
            ScenarioError::Invalid {
                location,
                field,
                message,
            } => ScenarioError::Invalid {
                location,
                field,
                message: format!("task {:?}: {message}", t.name),
            },
            other => other,
        };
        out.push(TaskGeometry {
            search_area: ctx
                .rect_in_arena(&format!("{base}.search_area"), &t.search_area, arena)
                .map_err(named)?,
            goal: ctx
                .point_in_arena(&format!("{base}.goal_m"), &t.goal_m, arena)
                .map_err(named)?,
            drop_off: ctx
                .circle_in_arena(&format!("{base}.drop_off"), &t.drop_off, arena)
                .map_err(named)?,
        });
    }
    Ok(out)
}

/// Kinds: names unique and non-empty, at least one robot each, quotas naming known tasks and
/// adding up to the count (a task a kind's quota does not name gets none of it).
fn validate_kinds(ctx: &Ctx<'_>, specs: &[KindSpec], tasks: &[TaskSpec]) -> R<Vec<RobotKind>> {
    if specs.is_empty() {
        return Err(ctx.err("kinds", "expected at least one robot kind"));
    }
    let mut kinds: Vec<RobotKind> = Vec::with_capacity(specs.len());
    for (k, s) in specs.iter().enumerate() {
        let f = |name: &str| format!("kinds[{k}].{name}");
        check_name(ctx, f("name"), "kind name", &s.name)?;
        if let Some(j) = kinds.iter().position(|o| o.name == s.name) {
            return Err(ctx.err(
                f("name"),
                format!("duplicate kind name {:?} (also kinds[{j}])", s.name),
            ));
        }
        if s.count == 0 {
            return Err(ctx.err(f("count"), "expected at least 1 robot, found 0"));
        }
        let quota = quotas_by_task(ctx, &f("quota"), s, tasks)?;
        let kind = RobotKind {
            name: s.name.clone(),
            role: s.role,
            locomotion: s.locomotion,
            count: s.count,
            quota,
            body_radius_m: s.body_radius_m.get(),
            max_speed_m_per_s: s.max_speed_m_per_s.get(),
            sensing_range_m: s.sensing_range_m.get(),
            observing_range_m: s.observing_range_m.get(),
            carrying_capacity: s.carrying_capacity,
            rescuing_resources: s.rescuing_resources,
            hp_needs_full: s.hp_needs_full.get(),
            energy_needs_full: s.energy_needs_full.get(),
        };
        check_kind(ctx, k, &kind)?;
        kinds.push(kind);
    }
    Ok(kinds)
}

/// A kind's quota per task id, from its quota by task name.
fn quotas_by_task(ctx: &Ctx<'_>, path: &str, s: &KindSpec, tasks: &[TaskSpec]) -> R<Vec<usize>> {
    let names = || {
        tasks
            .iter()
            .map(|t| format!("{:?}", t.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    if let Some(unknown) = s
        .quota
        .0
        .keys()
        .find(|n| !tasks.iter().any(|t| &t.name == *n))
    {
        return Err(ctx.err(
            path,
            format!("no task is called {unknown:?} (tasks: {})", names()),
        ));
    }
    let quota: Vec<usize> = tasks
        .iter()
        .map(|t| s.quota.0.get(&t.name).copied().unwrap_or(0))
        .collect();
    let total = quota.iter().try_fold(0usize, |a, q| a.checked_add(*q));
    if total != Some(s.count) {
        let terms: Vec<String> = tasks
            .iter()
            .zip(&quota)
            .map(|(t, q)| format!("{} {q}", t.name))
            .collect();
        return Err(ctx.err(
            path,
            format!(
                "{} = {} but count is {}",
                terms.join(" + "),
                total.map_or_else(|| "overflow".to_owned(), |t| t.to_string()),
                s.count
            ),
        ));
    }
    Ok(quota)
}

/// The listed debris, each inside the arena, named `debris[i]`.
fn listed_debris(ctx: &Ctx<'_>, specs: &[DebrisSpec], arena: &Arena) -> R<NamedDebris> {
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

/// The rest stations with their field paths (`rest_station` for one circle,
/// `rest_station[i]` in a list): at least one, at most [`MAX_REST_STATIONS`], each inside the
/// arena.
fn rest_stations(
    ctx: &Ctx<'_>,
    spec: &RestStationsSpec,
    arena: &Arena,
) -> R<Vec<(String, Circle)>> {
    let circles = spec.circles();
    if circles.is_empty() {
        return Err(ctx.err(
            "rest_station",
            "an empty list: give at least one rest station".to_owned(),
        ));
    }
    if circles.len() > MAX_REST_STATIONS {
        return Err(ctx.err(
            "rest_station",
            format!(
                "{} rest stations, more than the limit of {MAX_REST_STATIONS}",
                circles.len()
            ),
        ));
    }
    circles
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let field = match spec {
                RestStationsSpec::One(_) => "rest_station".to_owned(),
                RestStationsSpec::Many(_) => format!("rest_station[{i}]"),
            };
            let circle = ctx.circle_in_arena(&field, c, arena)?;
            Ok((field, circle))
        })
        .collect()
}

/// Every rest station's centre, every goal and every drop-off centre at least `reach` (the
/// smallest ground body radius) from the listed debris, so ground robots can get there.
fn check_reachable(
    ctx: &Ctx<'_>,
    rest_stations: &[(String, Circle)],
    tasks: &[TaskSpec],
    geometry: &[TaskGeometry],
    debris: &NamedDebris,
    reach: f64,
) -> R<()> {
    let mut places: Vec<(String, PointM, String)> = rest_stations
        .iter()
        .map(|(field, c)| {
            (
                format!("{field}.center_m"),
                c.center,
                "rest station centre".to_owned(),
            )
        })
        .collect();
    for (i, (t, g)) in tasks.iter().zip(geometry).enumerate() {
        places.push((
            format!("tasks[{i}].goal_m"),
            g.goal,
            format!("task {:?}: goal", t.name),
        ));
        places.push((
            format!("tasks[{i}].drop_off.center_m"),
            g.drop_off.center,
            format!("task {:?}: drop-off centre", t.name),
        ));
    }
    for (field, p, what) in places {
        for (d, name) in debris {
            let dist = d.distance_to_point(&p);
            if dist < reach || dist == 0.0 {
                return Err(ctx.err(
                    field,
                    format!(
                        "{what} {} is {} m from {name}; it must be at least {} m (the \
                         smallest ground body radius) away so ground robots can reach it",
                        fmt_pt(&p),
                        number_text_3dp(dist),
                        number_text(reach)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// Every robot's start (with its path and label), in kind order, each inside the arena with
/// its body.
fn expand_starts(
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

/// The places generated debris keeps away from: every start disc, every rest station, every
/// drop-off and every goal point.
fn protected_places(
    starts: &[(Start, RobotStart)],
    kinds: &[RobotKind],
    rest_stations: &[(String, Circle)],
    tasks: &[TaskSpec],
    geometry: &[TaskGeometry],
) -> Vec<Protected> {
    let mut out: Vec<Protected> = starts
        .iter()
        .map(|(s, r)| Protected {
            center: r.start_in_world,
            radius_m: kinds[r.kind].body_radius_m,
            what: format!("the start of {}", s.label),
        })
        .collect();
    out.extend(rest_stations.iter().map(|(field, c)| Protected {
        center: c.center,
        radius_m: c.radius_m,
        what: if rest_stations.len() == 1 {
            "the rest station".to_owned()
        } else {
            format!("the rest station {field}")
        },
    }));
    for (t, g) in tasks.iter().zip(geometry) {
        out.push(Protected {
            center: g.drop_off.center,
            radius_m: g.drop_off.radius_m,
            what: format!("the drop-off of task {:?}", t.name),
        });
        out.push(Protected {
            center: g.goal,
            radius_m: 0.0,
            what: format!("the goal of task {:?}", t.name),
        });
    }
    out
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
fn check_starts(
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

/// The tasks with their rescuees laid out.
fn expand_tasks(
    ctx: &Ctx<'_>,
    specs: &[TaskSpec],
    geometry: Vec<TaskGeometry>,
    debris: &NamedDebris,
    reach: f64,
) -> R<Vec<Task>> {
    let mut total = 0usize;
    specs
        .iter()
        .zip(geometry)
        .enumerate()
        .map(|(i, (t, g))| {
            let path = format!("tasks[{i}].rescuees");
            let rescuees = expand_rescuees(ctx, &path, &t.rescuees, &g.search_area, debris, reach)?;
            total += rescuees.len();
            if total > MAX_RESCUEES {
                return Err(ctx.err(
                    path,
                    format!(
                        "{} rescuees bring the tasks to {total}, more than the limit of \
                         {MAX_RESCUEES}",
                        rescuees.len()
                    ),
                ));
            }
            Ok(Task {
                name: t.name.clone(),
                difficulty: t.difficulty,
                search_area: g.search_area,
                goal: g.goal,
                drop_off: g.drop_off,
                rescuees,
            })
        })
        .collect()
}

fn radiation_zones(ctx: &Ctx<'_>, spec: &ScenarioSpec, arena: &Arena) -> R<Vec<RadiationZone>> {
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

/// The parameter rules that span fields: the clamp ranges of the initial levels, and a step no
/// longer than the trial.
fn check_params(ctx: &Ctx<'_>, spec: &ScenarioSpec) -> R<()> {
    let m = &spec.mission;
    for (path, d) in [
        ("mission.initial_energy", &m.initial_energy),
        ("mission.initial_hp", &m.initial_hp),
    ] {
        check_clamp(ctx, path, d)?;
    }
    let dt_s = spec.sim.dt_s.get();
    if let Err(e) = super::model::trial_steps(m.duration_s.get(), dt_s) {
        // Blame the length where the file writes it, else the step (the default length of
        // 600 s is too many steps only of a step the file sets).
        let written = |f: &str| ctx.map.is_some_and(|map| map.contains(f));
        let field = if !written("mission.duration_s") && written("sim.dt_s") {
            "sim.dt_s"
        } else {
            "mission.duration_s"
        };
        return Err(ctx.err(field, e));
    }
    if dt_s > m.duration_s.get() {
        return Err(ctx.err(
            "sim.dt_s",
            format!(
                "step {} s is longer than the trial (mission.duration_s = {} s)",
                number_text(dt_s),
                number_text(m.duration_s.get())
            ),
        ));
    }
    check_control_period(ctx, spec)
}

/// `sim.control_period_s`: a whole number of steps (relative tolerance 1e-9), from one step
/// to the whole trial.
fn check_control_period(ctx: &Ctx<'_>, spec: &ScenarioSpec) -> R<()> {
    let Some(period) = spec.sim.control_period_s else {
        return Ok(());
    };
    let (period_s, dt_s) = (period.get(), spec.sim.dt_s.get());
    let duration_s = spec.mission.duration_s.get();
    let steps = (period_s / dt_s).round();
    let problem = if period_s < dt_s * (1.0 - 1e-9) {
        Some(format!(
            "shorter than one step (sim.dt_s = {} s)",
            number_text(dt_s)
        ))
    } else if period_s > duration_s {
        Some(format!(
            "longer than the trial (mission.duration_s = {} s)",
            number_text(duration_s)
        ))
    } else if (steps * dt_s - period_s).abs() > 1e-9 * period_s {
        Some(format!(
            "not a whole number of steps of {} s (sim.dt_s): {} steps",
            number_text(dt_s),
            number_text(period_s / dt_s)
        ))
    } else {
        None
    };
    match problem {
        Some(why) => Err(ctx.err(
            "sim.control_period_s",
            format!("control period {} s is {why}", number_text(period_s)),
        )),
        None => Ok(()),
    }
}

fn check_clamp(ctx: &Ctx<'_>, path: &str, d: &ClampedNormal) -> R<()> {
    if d.max_pct < d.min_pct {
        return Err(ctx.err(
            format!("{path}.max_pct"),
            format!(
                "expected a number in [{}, 100] (at least min_pct), found {}",
                number_text(d.min_pct.get()),
                number_text(d.max_pct.get())
            ),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use crate::scenario::{from_str, load};
    use nalgebra::Point2;

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

    /// paper.ron with its carriers' row replaced by `grid`.
    fn paper_with_carrier_starts(grid: &str) -> String {
        let src = std::fs::read_to_string(scenario_file("paper.ron")).expect("paper.ron");
        let row = "Row(first_m: (32.5, 3.0), step_m: (3.0, 0.0))";
        assert!(src.contains(row));
        src.replacen(row, grid, 1)
    }

    #[test]
    fn grids_fill_row_by_row() {
        let src = paper_with_carrier_starts(
            "Grid(first_m: (32.5, 3.0), columns: 4, spacing_m: (3.0, -1.5))",
        );
        let s = from_str(&src, "p.ron").expect("loads");
        let starts: Vec<(f64, f64)> = s.robots[..6]
            .iter()
            .map(|r| (r.start_in_world.x, r.start_in_world.y))
            .collect();
        let want = [
            (32.5, 3.0),
            (35.5, 3.0),
            (38.5, 3.0),
            (41.5, 3.0),
            (32.5, 1.5),
            (35.5, 1.5),
        ];
        for (got, want) in starts.iter().zip(want) {
            assert!((got.0 - want.0).abs() < 1e-12 && (got.1 - want.1).abs() < 1e-12);
        }
    }

    #[test]
    fn degenerate_grids_are_rejected_with_their_field() {
        for (grid, field) in [
            (
                "Grid(first_m: (32.5, 3.0), columns: 0, spacing_m: (3.0, 1.5))",
                "kinds[0].starts.columns",
            ),
            (
                "Grid(first_m: (32.5, 3.0), columns: 3, spacing_m: (0.0, 1.5))",
                "kinds[0].starts.spacing_m",
            ),
            (
                "Grid(first_m: (32.5, 3.0), columns: 3, spacing_m: (3.0, 0.0))",
                "kinds[0].starts.spacing_m",
            ),
        ] {
            let err = from_str(&paper_with_carrier_starts(grid), "p.ron").expect_err(grid);
            assert_eq!(err.field(), Some(field), "{grid}: {err}");
            assert!(err.line_col().is_some(), "{grid}: {err}");
        }
        // One row needs no y spacing, one column no x spacing.
        for ok in [
            "Grid(first_m: (32.5, 3.0), columns: 6, spacing_m: (3.0, 0.0))",
            "Grid(first_m: (20.0, 3.0), columns: 1, spacing_m: (0.0, 0.9))",
        ] {
            from_str(&paper_with_carrier_starts(ok), "p.ron").expect(ok);
        }
    }
}
