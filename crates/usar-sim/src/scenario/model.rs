//! The validated scenario: the only scenario type the simulator takes.
//!
//! A [`Scenario`] is produced from a RON file by [`crate::scenario::load`] (raw spec types are
//! deserialized, then validated once: "parse, don't validate"). Every value here has already been
//! checked: lengths are positive, shapes lie inside the arena, counts match quotas, and so on, so
//! the simulator never re-checks them.
//!
//! Frame and units: the world frame has its origin at the arena's bottom-left inner corner, x to
//! the right, y up; lengths in metres (`_m`), times in seconds (`_s`), speeds in metres per second
//! (`_m_per_s`), energy and health in percent of the robot's full level (`_pct`).

use nalgebra::{Point2, Vector2};
use serde::{Deserialize, Serialize};

/// A point in the world frame, metres.
pub type PointM = Point2<f64>;

/// Number of entries of the paper's needs vector (hp, v, sen, eng, res, cap, obs), Eqs. 19-21.
pub const NEEDS_LEN: usize = 7;

/// A fully validated USAR scenario (paper, sections IV-VI).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Scenario {
    /// Short name, used for output folders (e.g. `paper`).
    pub name: String,
    /// Free text shown by `usar check`.
    pub description: String,
    /// The walled field.
    pub arena: Arena,
    /// Robot kinds, in the merge order of the hierarchical grouping (paper: carrier, supplier,
    /// observer). A robot's `kind` indexes this list.
    pub kinds: Vec<RobotKind>,
    /// Every robot of the team, ordered by kind (in `kinds` order) and then as listed in the file.
    /// A robot's id is its index in this list.
    pub robots: Vec<RobotStart>,
    /// Where robots recharge energy and refresh HP (paper, section VI.B: "rest position").
    pub rest_station: Circle,
    /// The two tasks, indexed by [`TaskLevel::index`]: `[easy, hard]`.
    pub tasks: [Task; 2],
    /// Static obstacles (listed and generated ones, generation already expanded).
    pub debris: Vec<Debris>,
    /// Radiation zones: robots inside lose HP.
    pub radiation_zones: Vec<RadiationZone>,
    /// Weights of the 7-entry needs vector (hp, v, sen, eng, res, cap, obs), all > 0 (Eq. 8).
    pub needs_weights: [f64; NEEDS_LEN],
    /// Mission rules: energy and HP costs, thresholds, recharging, initial levels (section VI.B).
    pub mission: MissionParams,
    /// Path planning of ground robots.
    pub navigation: NavigationParams,
    /// Priority-based collision avoidance and deadlock solving (section V, Algorithm 5).
    pub collision: CollisionParams,
    /// Time stepping and seeds.
    pub sim: SimParams,
}

/// Easy or hard task (paper, section V).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum TaskLevel {
    /// The near task with few adversaries (paper: top right).
    Easy,
    /// The far task with more debris and radiation (paper: top left).
    Hard,
}

impl TaskLevel {
    /// Both levels, in index order `[Easy, Hard]`.
    pub const ALL: [TaskLevel; 2] = [TaskLevel::Easy, TaskLevel::Hard];

    /// Index into `[easy, hard]` arrays: 0 for easy, 1 for hard.
    pub fn index(self) -> usize {
        match self {
            TaskLevel::Easy => 0,
            TaskLevel::Hard => 1,
        }
    }

    /// Lower-case name, `"easy"` or `"hard"`.
    pub fn name(self) -> &'static str {
        match self {
            TaskLevel::Easy => "easy",
            TaskLevel::Hard => "hard",
        }
    }
}

/// The walled, rectangular field `[0, width_m] x [0, height_m]`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Arena {
    /// Inner width, metres, > 0.
    pub width_m: f64,
    /// Inner height, metres, > 0.
    pub height_m: f64,
    /// Thickness of the boundary walls (outside the field), metres, > 0.
    pub wall_thickness_m: f64,
}

impl Arena {
    /// Whether `p` lies inside the field (boundary included; NaN or infinite coordinates are
    /// outside).
    pub fn contains(&self, p: &PointM) -> bool {
        in_field(p.x, p.y, self.width_m, self.height_m)
    }
}

/// Whether `v` lies in `[0, max]` (boundary included), at any float precision. NaN and
/// infinite values are outside (for a finite `max`).
pub(crate) fn in_span<T: PartialOrd + Default>(v: T, max: T) -> bool {
    v >= T::default() && v <= max
}

/// Whether `(x, y)` lies in the field `[0, w] x [0, h]` (boundary included), at any float
/// precision: the scenario checks `f64` points against the `f64` arena ([`Arena::contains`]),
/// the world its `f32` points against the arena rounded to `f32`. NaN or infinite coordinates
/// are outside (for a finite `w`, `h`).
pub(crate) fn in_field<T: PartialOrd + Default>(x: T, y: T, w: T, h: T) -> bool {
    in_span(x, w) && in_span(y, h)
}

/// A robot's role in the mission (paper, section IV).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Role {
    /// Carries rescuees (large carrying capacity).
    Carrier,
    /// Brings rescuing resources shared with the group.
    Supplier,
    /// Aerial scout with a very long observing range; finds rescuees for its group.
    Observer,
}

/// How a robot moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Locomotion {
    /// Drives on the ground: collides with walls, debris and other ground robots, plans around
    /// debris.
    Ground,
    /// Flies: passes over debris and ground robots, flies straight, avoids other aerial robots.
    Aerial,
}

/// One kind of robot: its role, body and base needs (paper, section VI.B).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RobotKind {
    /// Name, e.g. `carrier`; unique within the scenario.
    pub name: String,
    /// Role in the mission.
    pub role: Role,
    /// Ground or aerial.
    pub locomotion: Locomotion,
    /// Number of robots of this kind, >= 1; equals `quota[0] + quota[1]`.
    pub count: usize,
    /// How many robots of this kind each task's group takes, `[easy, hard]` (paper: 3 carriers,
    /// 2 suppliers, 1 observer per task).
    pub quota: [usize; 2],
    /// Body (disc) radius, metres, > 0.
    pub body_radius_m: f64,
    /// Top speed at full HP, metres per second, > 0 (needs entry `v`).
    pub max_speed_m_per_s: f64,
    /// Range within which the robot senses other robots and obstacles at full HP, metres, > 0
    /// (needs entry `sen`).
    pub sensing_range_m: f64,
    /// Range within which the robot detects rescuees at full HP, metres, > 0 (needs entry `obs`).
    pub observing_range_m: f64,
    /// Rescuees it can carry at once, >= 0 (needs entry `cap`).
    pub carrying_capacity: u32,
    /// Rescuing resources it brings per round, >= 0 (needs entry `res`).
    pub rescuing_resources: u32,
    /// Health needs level at 100 % HP, > 0 (needs entry `hp`; paper: hp_c = hp_s = 2 hp_o).
    pub hp_needs_full: f64,
    /// Energy needs level at 100 % energy, > 0 (needs entry `eng`; paper: eng_c = eng_s =
    /// 1.5 eng_o).
    pub energy_needs_full: f64,
}

/// One robot's kind and start (initial) position.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RobotStart {
    /// Index into [`Scenario::kinds`].
    pub kind: usize,
    /// Start position, world frame, metres; inside the arena, and for ground robots clear of
    /// debris by at least the body radius.
    pub start_in_world: PointM,
}

/// A circle in the world frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Circle {
    /// Centre, world frame, metres.
    pub center: PointM,
    /// Radius, metres, > 0.
    pub radius_m: f64,
}

impl Circle {
    /// Whether `p` lies inside the circle (boundary included).
    pub fn contains(&self, p: &PointM) -> bool {
        (p - self.center).norm_squared() <= self.radius_m * self.radius_m
    }
}

/// An axis-aligned rectangle in the world frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Rect {
    /// Bottom-left corner, world frame, metres.
    pub min: PointM,
    /// Top-right corner, world frame, metres; `max.x > min.x`, `max.y > min.y`.
    pub max: PointM,
}

impl Rect {
    /// Whether `p` lies inside the rectangle (boundary included).
    pub fn contains(&self, p: &PointM) -> bool {
        p.x >= self.min.x && p.y >= self.min.y && p.x <= self.max.x && p.y <= self.max.y
    }

    /// Centre point.
    pub fn center(&self) -> PointM {
        nalgebra::center(&self.min, &self.max)
    }
}

/// One task of the mission (paper, sections IV-V): a search area holding rescuees, a goal point
/// that distance-based grouping measures to, and a drop-off ("safety place").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Task {
    /// Easy or hard.
    pub level: TaskLevel,
    /// Where rescuees lie; inside the arena.
    pub search_area: Rect,
    /// The task's goal point (paper, DIS: "the goal points of two tasks"); inside the arena.
    pub goal: PointM,
    /// Where rescuees are delivered; inside the arena.
    pub drop_off: Circle,
    /// Rescuee positions (a file's grid layout already expanded), all inside `search_area`,
    /// in a fixed order (row by row from the bottom-left).
    pub rescuees: Vec<PointM>,
}

/// A static obstacle (debris), world frame.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Debris {
    /// A rectangle rotated by `rotation_rad` about its centre.
    Rect {
        /// Centre, metres.
        center: PointM,
        /// Half width and half height, metres, both > 0.
        half_extents_m: Vector2<f64>,
        /// Counter-clockwise rotation, radians.
        rotation_rad: f64,
    },
    /// A disc.
    Circle(Circle),
}

/// A circular radiation zone (paper, section VI.B). A robot inside loses
/// `mission.hp_pct_per_step_in_radiation * dose_rate_factor` percent HP per step; where zones
/// overlap the factors add.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RadiationZone {
    /// Extent of the zone.
    pub area: Circle,
    /// Relative dose rate, dimensionless, > 0 (1 = the scenario's base rate).
    pub dose_rate_factor: f64,
}

/// A normal distribution clamped to `[min, max]`, for initial energy and HP levels.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ClampedNormal {
    /// Mean, percent.
    pub mean_pct: f64,
    /// Standard deviation, percent, >= 0.
    pub std_dev_pct: f64,
    /// Lowest value a draw is clamped to, percent, in `[0, 100]`.
    pub min_pct: f64,
    /// Highest value a draw is clamped to, percent, in `[min_pct, 100]`.
    pub max_pct: f64,
}

/// How the doses of overlapping radiation zones combine at a point (paper silent; see
/// `docs/mission-model.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RadiationOverlap {
    /// The doses of all zones containing the point add (default: the authors' Unity scene
    /// applies damage once per overlapping radiation trigger per physics step).
    #[default]
    Sum,
    /// Only the strongest zone counts.
    Max,
}

/// How a radiation zone's dose varies with the distance `d` from its centre, inside its radius
/// `r` (paper silent; see `docs/mission-model.md`). Outside the disc the dose is 0.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RadiationFalloff {
    /// The full `dose_rate_factor` everywhere inside the disc (default).
    #[default]
    Uniform,
    /// `dose_rate_factor * (1 - d / r)`: the full factor at the source, 0 at the rim (a third
    /// of the uniform dose on average over the disc).
    Linear,
}

/// Which task's quota shrinks first when robots of a kind are away recharging at a round's
/// start (paper silent; see `docs/mission-model.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum AwayQuotas {
    /// The hard task is filled first; the easy task takes what is left (default).
    #[default]
    HardestFirst,
    /// The easy task is filled first; the hard task takes what is left.
    EasiestFirst,
    /// The shortfall is shared: one robot at a time is taken from the task whose quota is
    /// currently larger (ties: from the easy task).
    Even,
}

/// When a new round may start (paper, section VI.B: "After each round, when all agents are
/// back to the initial position, the whole group members will regroup").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RoundStart {
    /// As soon as the previous round's groups are back; robots away at the rest station (or on
    /// their way back from it) sit the round out and quotas shrink by `away_quotas` (default).
    #[default]
    Available,
    /// Only when every robot of the team is back at its start position: every round groups the
    /// whole team with the full quotas (`away_quotas` never applies).
    AllBack,
}

/// What becomes of the rescuees a robot carries when it leaves its task for the rest station
/// (paper silent; see `docs/mission-model.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum LoadOnLeave {
    /// They are dropped and lost for the trial (default).
    #[default]
    Abandon,
    /// They are put back where they were found and wait again (known to nobody).
    ReturnToArea,
    /// The robot first drives to its task's drop-off and delivers them (they count for the
    /// task), then goes to the rest station.
    DeliverFirst,
}

/// What a stay at the rest station restores (paper: "recharging its energy (or for refreshing
/// its health HP)"; see `docs/mission-model.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Refresh {
    /// Energy and HP both to 100 % (default).
    #[default]
    Both,
    /// Only the level(s) below their threshold (`low_energy_pct`, `low_hp_pct`) when the robot
    /// arrived, to 100 %.
    LowOnly,
}

/// Mission rules (paper, section VI.B). Defaults are the paper's values.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MissionParams {
    /// Trial length, seconds (paper: 600).
    pub duration_s: f64,
    /// Energy spent per simulation step while moving, percent (paper: 0.0045).
    pub energy_pct_per_moving_step: f64,
    /// Energy spent per metre moved, percent per metre, `>= 0` (the authors' Unity code charges
    /// `energy -= distance * k`); adds to `energy_pct_per_moving_step`.
    pub energy_pct_per_m: f64,
    /// HP lost per simulation step inside a radiation zone of factor 1, percent (paper: 0.0003).
    pub hp_pct_per_step_in_radiation: f64,
    /// How overlapping zones combine.
    pub radiation_overlap: RadiationOverlap,
    /// How a zone's dose varies with the distance from its centre.
    pub radiation_falloff: RadiationFalloff,
    /// When a new round may start.
    pub round_start: RoundStart,
    /// Which quota shrinks first when robots are away at a round's start.
    pub away_quotas: AwayQuotas,
    /// What becomes of a leaving robot's load.
    pub load_on_leave: LoadOnLeave,
    /// Longest time a group searches its area, seconds from the moment its first ground member
    /// enters it, `> 0`; `None`: no limit (the group leaves only when full, out of resources,
    /// or when nothing more is to be found).
    pub search_time_budget_s: Option<f64>,
    /// What a stay at the rest station restores.
    pub refresh: Refresh,
    /// Row spacing of a blind group's lawn-mower search, metres, `> 0`; `None`: the narrowest
    /// ground detection width (see `mission::sweep_spacing_m`).
    pub sweep_spacing_m: Option<f64>,
    /// Smallest factor HP scales speed, sensing and observing range by, in `[0, 1]` (see
    /// `mission::hp_factor`).
    pub min_hp_factor: f64,
    /// Time a ground robot stands at a rescuee to rescue it, seconds, `>= 0` (0: at once).
    pub pickup_s: f64,
    /// Below this energy a robot leaves its task to recharge, percent (paper: 30).
    pub low_energy_pct: f64,
    /// Below this HP a robot leaves its task to refresh, percent (paper: 30).
    pub low_hp_pct: f64,
    /// Time spent at the rest station, seconds (paper: 30).
    pub recharge_s: f64,
    /// Speed factor of a group without an observer (paper: 0.7, "decrease by 30 %").
    pub no_observer_speed_factor: f64,
    /// Initial energy levels (paper: N(80 %, 20 %)).
    pub initial_energy: ClampedNormal,
    /// Initial HP levels (paper: N(90 %, 10 %)).
    pub initial_hp: ClampedNormal,
}

/// Path planning of ground robots over an occupancy grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NavigationParams {
    /// Side of an occupancy-grid cell, metres, > 0 (default 0.25).
    pub grid_cell_m: f64,
    /// Extra clearance kept from debris and walls beyond the body radius, metres, >= 0
    /// (default 0.1).
    pub clearance_m: f64,
    /// Distance at which a waypoint counts as reached, metres, > 0 (default 0.3).
    pub waypoint_tolerance_m: f64,
}

/// Priority-based collision avoidance and deadlock solving (section V, Algorithm 5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CollisionParams {
    /// Whether the resolver runs (switch off to show what it solves), default `true`.
    pub enabled: bool,
    /// Look-ahead: robots that would come closer than `safety_margin_m` within this time are
    /// "about to collide", seconds, > 0 (default 1.0).
    pub lookahead_s: f64,
    /// Gap kept between bodies, metres, >= 0 (default 0.2).
    pub safety_margin_m: f64,
    /// A collision list none of whose members has made progress along its path (remaining
    /// path length down by more than 0.05 m) for this long is a deadlock, seconds, > 0
    /// (default 2.0).
    pub deadlock_after_s: f64,
}

/// Time stepping and seeds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SimParams {
    /// Fixed step, seconds, > 0 (default 1/50 s, Unity's fixed step).
    pub dt_s: f64,
    /// Base seed of trials: trial `k` uses a seed derived from `seed` and `k`.
    pub seed: u64,
}

impl Scenario {
    /// The kind of robot `id`.
    ///
    /// # Panics
    /// If `id >= self.robots.len()`.
    pub fn kind_of(&self, id: usize) -> &RobotKind {
        &self.kinds[self.robots[id].kind]
    }

    /// The task at `level`.
    pub fn task(&self, level: TaskLevel) -> &Task {
        &self.tasks[level.index()]
    }

    /// Number of simulation steps in a trial: `ceil(duration_s / dt_s)`.
    pub fn steps_per_trial(&self) -> u64 {
        (self.mission.duration_s / self.sim.dt_s).ceil() as u64
    }
}
