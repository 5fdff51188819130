//! Kinds and tasks written in code with plain numbers ([`KindDraft`], [`TaskDraft`]), for
//! [`super::ScenarioBuilder`]: nothing is checked until the builder's `build`, which names the
//! field of a bad or missing value.
//!
//! Each setter is named after the file's field (`docs/scenario-format.md`), so a kind or a task
//! reads as its RON. Points are `(x, y)` in metres, world frame.

use super::edit::{field_error, number_at};
use super::error::ScenarioError;
use super::model::{Locomotion, Role};
use super::spec::{
    CircleSpec, KindSpec, RectSpec, RescueeLayoutSpec, StartsSpec, TaskQuotas, TaskSpec, XyM,
};

/// A point `(x, y)` in metres, world frame, as the builder takes it.
pub type Xy = (f64, f64);

fn xy((x, y): Xy) -> XyM {
    [x, y]
}

/// One kind of robot, written in code (the file's [`KindSpec`]). Every field of the file
/// without a default must be set (`body_radius_m` ... `energy_needs_full`, and a start
/// layout); `count` may be left out: it is then the sum of the quotas the tasks give the kind
/// ([`TaskDraft::quota`]), or the number of listed starts when no task names it.
///
/// ```
/// # use usar_sim::scenario::{KindDraft, Role};
/// let carriers = KindDraft::ground("carrier", Role::Carrier)
///     .body_radius_m(0.4)
///     .max_speed_m_per_s(2.5)
///     .sensing_range_m(3.0)
///     .observing_range_m(0.05)
///     .carrying_capacity(6)
///     .rescuing_resources(1)
///     .hp_needs_full(2.0)
///     .energy_needs_full(1.5)
///     .starts_row((32.5, 3.0), (3.0, 0.0));
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct KindDraft {
    name: String,
    role: Role,
    locomotion: Locomotion,
    count: Option<usize>,
    body_radius_m: Option<f64>,
    max_speed_m_per_s: Option<f64>,
    sensing_range_m: Option<f64>,
    observing_range_m: Option<f64>,
    carrying_capacity: Option<u32>,
    rescuing_resources: Option<u32>,
    hp_needs_full: Option<f64>,
    energy_needs_full: Option<f64>,
    starts: Option<StartsSpec>,
}

impl KindDraft {
    /// A kind called `name` with `role` and `locomotion`, nothing else set yet.
    pub fn new(name: impl Into<String>, role: Role, locomotion: Locomotion) -> Self {
        Self {
            name: name.into(),
            role,
            locomotion,
            count: None,
            body_radius_m: None,
            max_speed_m_per_s: None,
            sensing_range_m: None,
            observing_range_m: None,
            carrying_capacity: None,
            rescuing_resources: None,
            hp_needs_full: None,
            energy_needs_full: None,
            starts: None,
        }
    }

    /// A ground kind ([`Locomotion::Ground`]): drives, collides, plans around debris.
    pub fn ground(name: impl Into<String>, role: Role) -> Self {
        Self::new(name, role, Locomotion::Ground)
    }

    /// An aerial kind ([`Locomotion::Aerial`]): flies straight over debris and ground robots.
    pub fn aerial(name: impl Into<String>, role: Role) -> Self {
        Self::new(name, role, Locomotion::Aerial)
    }

    /// Number of robots, >= 1; default: the sum of the tasks' quotas for this kind (or the
    /// number of listed starts when no task names it).
    pub fn count(mut self, count: usize) -> Self {
        self.count = Some(count);
        self
    }

    /// Body (disc) radius, metres, > 0.
    pub fn body_radius_m(mut self, v: f64) -> Self {
        self.body_radius_m = Some(v);
        self
    }

    /// Top speed at full HP, m/s, > 0 (needs entry `v`).
    pub fn max_speed_m_per_s(mut self, v: f64) -> Self {
        self.max_speed_m_per_s = Some(v);
        self
    }

    /// Range to sense robots and obstacles at full HP, metres, > 0 (needs entry `sen`).
    pub fn sensing_range_m(mut self, v: f64) -> Self {
        self.sensing_range_m = Some(v);
        self
    }

    /// Range to detect rescuees at full HP, metres, > 0 (needs entry `obs`).
    pub fn observing_range_m(mut self, v: f64) -> Self {
        self.observing_range_m = Some(v);
        self
    }

    /// Rescuees carried at once (needs entry `cap`; only ground robots pick rescuees up).
    pub fn carrying_capacity(mut self, n: u32) -> Self {
        self.carrying_capacity = Some(n);
        self
    }

    /// Rescuing resources brought per round (needs entry `res`).
    pub fn rescuing_resources(mut self, n: u32) -> Self {
        self.rescuing_resources = Some(n);
        self
    }

    /// Health needs level at 100 % HP, > 0 (needs entry `hp`).
    pub fn hp_needs_full(mut self, v: f64) -> Self {
        self.hp_needs_full = Some(v);
        self
    }

    /// Energy needs level at 100 % energy, > 0 (needs entry `eng`).
    pub fn energy_needs_full(mut self, v: f64) -> Self {
        self.energy_needs_full = Some(v);
        self
    }

    /// Starts in a line: robot `i` at `first + i * step` (the file's `Row`).
    pub fn starts_row(mut self, first: Xy, step: Xy) -> Self {
        self.starts = Some(StartsSpec::Row {
            first_m: xy(first),
            step_m: xy(step),
        });
        self
    }

    /// Starts on a grid of `columns` columns filled row by row (the file's `Grid`).
    pub fn starts_grid(mut self, first: Xy, columns: u32, spacing: Xy) -> Self {
        self.starts = Some(StartsSpec::Grid {
            first_m: xy(first),
            columns,
            spacing_m: xy(spacing),
        });
        self
    }

    /// Starts at these points, one per robot (the file's `List`).
    pub fn starts_at(mut self, points: &[Xy]) -> Self {
        self.starts = Some(StartsSpec::List(points.iter().copied().map(xy).collect()));
        self
    }

    /// The kind's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// The spec of kind `k` with `quota` (by task name): numbers checked, the count
    /// defaulted (see [`KindDraft`]).
    ///
    /// # Errors
    /// [`ScenarioError::Invalid`] at `kinds[k].<field>` for a number out of range or a
    /// required field not set; no origin (the builder sets it).
    pub(crate) fn to_spec(&self, k: usize, quota: TaskQuotas) -> Result<KindSpec, ScenarioError> {
        let at = |field: &str| format!("kinds[{k}].{field}");
        let num = |field: &str, v: Option<f64>| match v {
            Some(v) => number_at(&at(field), v),
            None => Err(missing(&at(field))),
        };
        let int = |field: &str, v: Option<u32>| v.ok_or_else(|| missing(&at(field)));
        let starts = self.starts.clone().ok_or_else(|| missing(&at("starts")))?;
        let count = match (self.count, &starts) {
            (Some(n), _) => n,
            (None, StartsSpec::List(points)) if quota.0.is_empty() => points.len(),
            (None, _) => quota.0.values().sum(),
        };
        Ok(KindSpec {
            name: self.name.clone(),
            role: self.role,
            locomotion: self.locomotion,
            count,
            quota,
            body_radius_m: num("body_radius_m", self.body_radius_m)?,
            max_speed_m_per_s: num("max_speed_m_per_s", self.max_speed_m_per_s)?,
            sensing_range_m: num("sensing_range_m", self.sensing_range_m)?,
            observing_range_m: num("observing_range_m", self.observing_range_m)?,
            carrying_capacity: int("carrying_capacity", self.carrying_capacity)?,
            rescuing_resources: int("rescuing_resources", self.rescuing_resources)?,
            hp_needs_full: num("hp_needs_full", self.hp_needs_full)?,
            energy_needs_full: num("energy_needs_full", self.energy_needs_full)?,
            starts,
        })
    }
}

/// One task, written in code (the file's [`TaskSpec`]), with the robots of each kind its
/// group takes ([`TaskDraft::quota`]; the file writes these per kind). A search area, a goal,
/// a drop-off and a rescuee layout must be set.
///
/// ```
/// # use usar_sim::scenario::TaskDraft;
/// let hard = TaskDraft::new("hard", 1)
///     .search_area((6.0, 47.0), (26.0, 59.0))
///     .goal_m((16.0, 53.0))
///     .drop_off((16.0, 12.0), 3.0)
///     .rescuee_grid(1.0, 0.5)
///     .quota("carrier", 3)
///     .quota("observer", 1);
/// ```
#[derive(Debug, Clone, PartialEq)]
pub struct TaskDraft {
    name: String,
    difficulty: u32,
    search_area: Option<(Xy, Xy)>,
    goal_m: Option<Xy>,
    drop_off: Option<(Xy, f64)>,
    rescuees: Option<RescueeDraft>,
    quotas: Vec<(String, usize)>,
}

/// A rescuee layout with its spacing not yet checked.
#[derive(Debug, Clone, PartialEq)]
enum RescueeDraft {
    Grid { spacing_m: f64, margin_m: f64 },
    List(Vec<XyM>),
}

impl TaskDraft {
    /// A task called `name` of rank `difficulty` (higher is harder; the file's default is 0).
    pub fn new(name: impl Into<String>, difficulty: u32) -> Self {
        Self {
            name: name.into(),
            difficulty,
            search_area: None,
            goal_m: None,
            drop_off: None,
            rescuees: None,
            quotas: Vec::new(),
        }
    }

    /// Where rescuees lie: the rectangle from `min` (bottom-left) to `max` (top-right).
    pub fn search_area(mut self, min: Xy, max: Xy) -> Self {
        self.search_area = Some((min, max));
        self
    }

    /// The goal point distance-based grouping measures to.
    pub fn goal_m(mut self, goal: Xy) -> Self {
        self.goal_m = Some(goal);
        self
    }

    /// The drop-off ("safety place"): a disc of `radius_m` (> 0) about `center`.
    pub fn drop_off(mut self, center: Xy, radius_m: f64) -> Self {
        self.drop_off = Some((center, radius_m));
        self
    }

    /// Rescuees on a square grid of `spacing_m` (> 0), at least `margin_m` (>= 0) from the
    /// search area's edges (the file's `Grid`).
    pub fn rescuee_grid(mut self, spacing_m: f64, margin_m: f64) -> Self {
        self.rescuees = Some(RescueeDraft::Grid {
            spacing_m,
            margin_m,
        });
        self
    }

    /// Rescuees at these points, each inside the search area (the file's `List`).
    pub fn rescuees_at(mut self, points: &[Xy]) -> Self {
        self.rescuees = Some(RescueeDraft::List(points.iter().copied().map(xy).collect()));
        self
    }

    /// `robots` of the kind called `kind` join this task's group (the file's `quota` of that
    /// kind; a kind a task does not name gives it 0).
    pub fn quota(mut self, kind: impl Into<String>, robots: usize) -> Self {
        self.quotas.push((kind.into(), robots));
        self
    }

    /// The task's name.
    pub fn name(&self) -> &str {
        &self.name
    }

    /// `(kind name, robots)` in the order given.
    pub(crate) fn quotas(&self) -> &[(String, usize)] {
        &self.quotas
    }

    /// The spec of task `t`.
    ///
    /// # Errors
    /// As [`KindDraft::to_spec`], at `tasks[t].<field>`.
    pub(crate) fn to_spec(&self, t: usize) -> Result<TaskSpec, ScenarioError> {
        let at = |field: &str| format!("tasks[{t}].{field}");
        let (min, max) = self
            .search_area
            .ok_or_else(|| missing(&at("search_area")))?;
        let goal = self.goal_m.ok_or_else(|| missing(&at("goal_m")))?;
        let (center, radius_m) = self.drop_off.ok_or_else(|| missing(&at("drop_off")))?;
        let rescuees = match self.rescuees.clone() {
            Some(RescueeDraft::Grid {
                spacing_m,
                margin_m,
            }) => RescueeLayoutSpec::Grid {
                spacing_m: number_at(&at("rescuees.spacing_m"), spacing_m)?,
                margin_m,
            },
            Some(RescueeDraft::List(points)) => RescueeLayoutSpec::List(points),
            None => return Err(missing(&at("rescuees"))),
        };
        Ok(TaskSpec {
            name: self.name.clone(),
            difficulty: self.difficulty,
            search_area: RectSpec {
                min_m: xy(min),
                max_m: xy(max),
            },
            goal_m: xy(goal),
            drop_off: circle(&at("drop_off.radius_m"), center, radius_m)?,
            rescuees,
        })
    }
}

/// A circle spec, its radius checked at `field`.
pub(crate) fn circle(field: &str, center: Xy, radius_m: f64) -> Result<CircleSpec, ScenarioError> {
    Ok(CircleSpec {
        center_m: xy(center),
        radius_m: number_at(field, radius_m)?,
    })
}

/// The error for a required field left unset: `field: missing ...`, no origin.
pub(crate) fn missing(field: &str) -> ScenarioError {
    field_error(
        field,
        "missing: this field has no default and was not set".into(),
    )
}
