//! Raw scenario spec: exactly what a RON scenario file holds, before validation.
//!
//! These types mirror the file format (documented field by field in `docs/scenario-format.md`).
//! Every struct rejects unknown fields. Values here are *not* checked: turn a spec into the
//! validated [`Scenario`](super::Scenario) with [`ScenarioSpec::validate`] (or load a file with
//! [`load`](super::load) / [`from_str`](super::from_str), which do both).
//!
//! Points and vectors are written as RON tuples `(x, y)` in metres, world frame (origin at the
//! arena's bottom-left inner corner, x right, y up). Fields marked *default* may be omitted.

use serde::{Deserialize, Serialize};

use super::model::{
    AwayQuotas, LoadOnLeave, Locomotion, RadiationFalloff, RadiationOverlap, Refresh, Role,
    RoundStart,
};

/// A point or vector `(x, y)` in metres, world frame.
pub type XyM = [f64; 2];

/// A closed range `(min, max)`, in the unit the field name gives.
pub type RangeSpec = (f64, f64);

/// The whole scenario file. In RON: `Scenario( name: ..., ... )` (the struct name is optional).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename = "Scenario", deny_unknown_fields)]
pub struct ScenarioSpec {
    /// Short name, non-empty, used for output folders (e.g. `"paper"`).
    pub name: String,
    /// Free text; default empty.
    #[serde(default)]
    pub description: String,
    /// The walled field.
    pub arena: ArenaSpec,
    /// Robot kinds in grouping merge order (paper: carrier, supplier, observer); at least one.
    pub kinds: Vec<KindSpec>,
    /// Rest (recharge) station.
    pub rest_station: CircleSpec,
    /// The easy and the hard task.
    pub tasks: TasksSpec,
    /// Listed static obstacles; default none.
    #[serde(default)]
    pub debris: Vec<DebrisSpec>,
    /// Seeded, generated static obstacles (expanded at validation); default none.
    #[serde(default)]
    pub debris_fields: Vec<DebrisFieldSpec>,
    /// Radiation zones; default none.
    #[serde(default)]
    pub radiation_zones: Vec<RadiationZoneSpec>,
    /// Weights of the needs vector; default all 1.
    #[serde(default)]
    pub needs_weights: NeedsWeightsSpec,
    /// Mission rules; default the paper's values.
    #[serde(default)]
    pub mission: MissionSpec,
    /// Path planning; default `grid_cell_m: 0.25, clearance_m: 0.1, waypoint_tolerance_m: 0.3`.
    #[serde(default)]
    pub navigation: NavigationSpec,
    /// Collision avoidance; default `enabled: true, lookahead_s: 1.0, safety_margin_m: 0.2,
    /// deadlock_after_s: 2.0`.
    #[serde(default)]
    pub collision: CollisionSpec,
    /// Time step and seed; default `dt_s: 0.02, seed: 0`.
    #[serde(default)]
    pub sim: SimSpec,
}

/// The walled rectangular field `[0, width_m] x [0, height_m]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArenaSpec {
    /// Inner width, metres, finite, > 0.
    pub width_m: f64,
    /// Inner height, metres, finite, > 0.
    pub height_m: f64,
    /// Boundary wall thickness (outside the field), metres, finite, > 0; default 0.5.
    #[serde(default = "default_wall_thickness_m")]
    pub wall_thickness_m: f64,
}

fn default_wall_thickness_m() -> f64 {
    0.5
}

/// A circle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleSpec {
    /// Centre, metres.
    pub center_m: XyM,
    /// Radius, metres, finite, > 0.
    pub radius_m: f64,
}

/// An axis-aligned rectangle given by two corners.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RectSpec {
    /// Bottom-left corner, metres.
    pub min_m: XyM,
    /// Top-right corner, metres; both coordinates strictly greater than `min_m`'s.
    pub max_m: XyM,
}

/// Robots of one kind per task, `(easy: n, hard: m)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct QuotaSpec {
    /// Robots of this kind in the easy task's group, >= 0.
    pub easy: usize,
    /// Robots of this kind in the hard task's group, >= 0.
    pub hard: usize,
}

/// One kind of robot (paper, section VI.B).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct KindSpec {
    /// Unique, non-empty name (e.g. `"carrier"`).
    pub name: String,
    /// `Carrier`, `Supplier` or `Observer`.
    pub role: Role,
    /// `Ground` or `Aerial`.
    pub locomotion: Locomotion,
    /// Number of robots, >= 1; must equal `quota.easy + quota.hard`.
    pub count: usize,
    /// Robots per task group.
    pub quota: QuotaSpec,
    /// Body (disc) radius, metres, finite, > 0.
    pub body_radius_m: f64,
    /// Top speed at full HP, m/s, finite, > 0.
    pub max_speed_m_per_s: f64,
    /// Range to sense robots and obstacles, metres, finite, > 0.
    pub sensing_range_m: f64,
    /// Range to detect rescuees, metres, finite, > 0.
    pub observing_range_m: f64,
    /// Rescuees carried at once, >= 0.
    pub carrying_capacity: u32,
    /// Rescuing resources brought per round, >= 0.
    pub rescuing_resources: u32,
    /// Health needs level at 100 % HP, finite, > 0.
    pub hp_needs_full: f64,
    /// Energy needs level at 100 % energy, finite, > 0.
    pub energy_needs_full: f64,
    /// Start positions of the `count` robots.
    pub starts: StartsSpec,
}

/// Start positions of one kind's robots.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum StartsSpec {
    /// Explicit positions, metres, exactly `count` of them: `List([(x, y), ...])`.
    List(Vec<XyM>),
    /// `count` positions in a line: robot `i` starts at `first_m + i * step_m`.
    /// `Row(first_m: (x, y), step_m: (dx, dy))`. Changing `count` needs no other edit.
    Row {
        /// Position of the kind's first robot, metres.
        first_m: XyM,
        /// Offset between consecutive robots, metres (non-zero when `count > 1`).
        step_m: XyM,
    },
}

/// The two tasks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TasksSpec {
    /// The easy task (paper: near, few adversaries).
    pub easy: TaskSpec,
    /// The hard task (paper: far, more debris and radiation).
    pub hard: TaskSpec,
}

/// One task: search area with rescuees, goal point and drop-off.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskSpec {
    /// Where rescuees lie; inside the arena.
    pub search_area: RectSpec,
    /// Goal point (distance-based grouping measures to it), metres; inside the arena, not
    /// inside debris.
    pub goal_m: XyM,
    /// Drop-off ("safety place"); inside the arena, centre not inside debris.
    pub drop_off: CircleSpec,
    /// Rescuee layout.
    pub rescuees: RescueeLayoutSpec,
}

/// How rescuees are laid out in a search area.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum RescueeLayoutSpec {
    /// A square grid filling the search area, centred in it, at least `margin_m` from its
    /// edges; points covered by debris (closer to debris than the smallest ground body radius)
    /// are left out. Row by row from the bottom-left.
    /// `Grid(spacing_m: 1.0, margin_m: 0.5)`.
    Grid {
        /// Distance between neighbours, metres, finite, > 0.
        spacing_m: f64,
        /// Minimum distance from the search area's edges, metres, finite, >= 0; default 0.
        #[serde(default)]
        margin_m: f64,
    },
    /// Explicit positions, metres, each inside the search area and not inside debris:
    /// `List([(x, y), ...])`; at least one.
    List(Vec<XyM>),
}

/// A listed static obstacle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum DebrisSpec {
    /// A rectangle: `Rect(center_m: (x, y), size_m: (w, h), rotation_deg: 30.0)`.
    Rect {
        /// Centre, metres.
        center_m: XyM,
        /// Full width and height before rotation, metres, both finite, > 0.
        size_m: XyM,
        /// Counter-clockwise rotation about the centre, degrees, finite; default 0.
        #[serde(default)]
        rotation_deg: f64,
    },
    /// A disc: `Circle(center_m: (x, y), radius_m: r)`.
    Circle {
        /// Centre, metres.
        center_m: XyM,
        /// Radius, metres, finite, > 0.
        radius_m: f64,
    },
}

/// Shapes drawn by a [`DebrisFieldSpec`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub enum DebrisShapeSpec {
    /// Discs with radius uniform in `radius_m = (min, max)`, metres, `0 < min <= max`.
    Circles {
        /// Radius range, metres.
        radius_m: RangeSpec,
    },
    /// Rectangles, each side uniform in `side_m = (min, max)` metres (`0 < min <= max`),
    /// rotated uniformly in `[-max_rotation_deg, max_rotation_deg]` (default 0, range
    /// `[0, 180]`).
    Rects {
        /// Side length range, metres.
        side_m: RangeSpec,
        /// Largest rotation either way, degrees; default 0.
        #[serde(default)]
        max_rotation_deg: f64,
    },
}

/// Generated debris: `count` shapes placed uniformly at random (wholly) inside `region`,
/// deterministically from a seed (rand_chacha `ChaCha8Rng`).
///
/// Placement rejects a shape closer than `min_gap_m` to any other debris (so ground robots fit
/// between), or that would come within `min_gap_m` of a robot's body at its start, of the rest
/// station, of a drop-off or of a goal point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct DebrisFieldSpec {
    /// Where shapes go; inside the arena.
    pub region: RectSpec,
    /// Number of shapes, >= 1.
    pub count: usize,
    /// Shape family and sizes.
    pub shape: DebrisShapeSpec,
    /// Smallest gap kept to other debris and to the protected places, metres, finite, >= 0;
    /// default 2.0.
    #[serde(default = "default_min_gap_m")]
    pub min_gap_m: f64,
    /// Seed of this field's generator; default `None`: `sim.seed + index of the field`
    /// (wrapping). Written `seed: Some(42)`.
    #[serde(default)]
    pub seed: Option<u64>,
}

fn default_min_gap_m() -> f64 {
    2.0
}

/// A circular radiation zone.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RadiationZoneSpec {
    /// Centre, metres.
    pub center_m: XyM,
    /// Radius, metres, finite, > 0; the disc lies inside the arena.
    pub radius_m: f64,
    /// Relative dose rate, finite, > 0; default 1.
    #[serde(default = "one")]
    pub dose_rate_factor: f64,
}

fn one() -> f64 {
    1.0
}

/// Weights of the needs vector `(hp, v, sen, eng, res, cap, obs)`, each finite and > 0,
/// default 1.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NeedsWeightsSpec {
    /// Health points.
    pub hp: f64,
    /// Speed.
    pub v: f64,
    /// Sensing range.
    pub sen: f64,
    /// Energy.
    pub eng: f64,
    /// Rescuing resources.
    pub res: f64,
    /// Carrying capacity.
    pub cap: f64,
    /// Observing range.
    pub obs: f64,
}

impl Default for NeedsWeightsSpec {
    fn default() -> Self {
        Self {
            hp: 1.0,
            v: 1.0,
            sen: 1.0,
            eng: 1.0,
            res: 1.0,
            cap: 1.0,
            obs: 1.0,
        }
    }
}

/// A normal distribution `N(mean_pct, std_dev_pct)` clamped to `[min_pct, max_pct]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClampedNormalSpec {
    /// Mean, percent, finite.
    pub mean_pct: f64,
    /// Standard deviation, percent, finite, >= 0.
    pub std_dev_pct: f64,
    /// Lower clamp, percent, in `[0, 100]`; default 0.
    #[serde(default)]
    pub min_pct: f64,
    /// Upper clamp, percent, in `[min_pct, 100]`; default 100.
    #[serde(default = "hundred")]
    pub max_pct: f64,
}

fn hundred() -> f64 {
    100.0
}

/// Mission rules (paper, section VI.B). Every field defaults to the paper's value.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MissionSpec {
    /// Trial length, seconds, finite, > 0; default 600.
    pub duration_s: f64,
    /// Energy spent per moving step, percent, finite, >= 0; default 0.0045.
    pub energy_pct_per_moving_step: f64,
    /// Energy spent per metre moved, percent per metre, finite, >= 0; default 0 (adds to
    /// `energy_pct_per_moving_step`).
    pub energy_pct_per_m: f64,
    /// HP lost per step in a radiation zone of factor 1, percent, finite, >= 0; default 0.0003.
    pub hp_pct_per_step_in_radiation: f64,
    /// How overlapping radiation zones combine: `Sum` (default) or `Max`.
    pub radiation_overlap: RadiationOverlap,
    /// How a zone's dose varies inside it: `Uniform` (default) or `Linear`.
    pub radiation_falloff: RadiationFalloff,
    /// When a new round may start: `Available` (default; robots away sit it out) or `AllBack`
    /// (the whole team must be back at its start positions).
    pub round_start: RoundStart,
    /// Which quota shrinks first when robots are away at a round's start: `HardestFirst`
    /// (default), `EasiestFirst` or `Even`.
    pub away_quotas: AwayQuotas,
    /// What becomes of a leaving robot's load: `Abandon` (default), `ReturnToArea` or
    /// `DeliverFirst`.
    pub load_on_leave: LoadOnLeave,
    /// Longest search per group and round, seconds, finite, > 0, written `Some(40.0)`; default
    /// `None` (no limit).
    pub search_time_budget_s: Option<f64>,
    /// What a stay at the rest station restores: `Both` (default) or `LowOnly`.
    pub refresh: Refresh,
    /// Row spacing of a blind group's lawn-mower search, metres, finite, > 0, written
    /// `Some(2.0)`; default `None`: the narrowest ground detection width
    /// `2 * (body_radius_m + observing_range_m)`, so a sweep covers the whole area.
    pub sweep_spacing_m: Option<f64>,
    /// Smallest factor HP scales speed, sensing and observing range by, in `[0, 1]`; default 0
    /// (the factor is `hp_pct / 100`, so a robot at 0 % HP stops).
    pub min_hp_factor: f64,
    /// Time a ground robot stands at a rescuee to rescue it (secure and load it), seconds,
    /// finite, >= 0; default 0 (at once).
    pub pickup_s: f64,
    /// Recharge threshold, percent, in `[0, 100]`; default 30.
    pub low_energy_pct: f64,
    /// Refresh threshold, percent, in `[0, 100]`; default 30.
    pub low_hp_pct: f64,
    /// Time at the rest station, seconds, finite, >= 0; default 30.
    pub recharge_s: f64,
    /// Speed factor of a group without an observer, in `(0, 1]`; default 0.7.
    pub no_observer_speed_factor: f64,
    /// Initial energy; default `N(80, 20)` clamped to `[0, 100]`.
    pub initial_energy: ClampedNormalSpec,
    /// Initial HP; default `N(90, 10)` clamped to `[0, 100]`.
    pub initial_hp: ClampedNormalSpec,
}

impl Default for MissionSpec {
    fn default() -> Self {
        Self {
            duration_s: 600.0,
            energy_pct_per_moving_step: 0.0045,
            energy_pct_per_m: 0.0,
            hp_pct_per_step_in_radiation: 0.0003,
            radiation_overlap: RadiationOverlap::default(),
            radiation_falloff: RadiationFalloff::default(),
            round_start: RoundStart::default(),
            away_quotas: AwayQuotas::default(),
            load_on_leave: LoadOnLeave::default(),
            search_time_budget_s: None,
            refresh: Refresh::default(),
            sweep_spacing_m: None,
            min_hp_factor: 0.0,
            pickup_s: 0.0,
            low_energy_pct: 30.0,
            low_hp_pct: 30.0,
            recharge_s: 30.0,
            no_observer_speed_factor: 0.7,
            initial_energy: ClampedNormalSpec {
                mean_pct: 80.0,
                std_dev_pct: 20.0,
                min_pct: 0.0,
                max_pct: 100.0,
            },
            initial_hp: ClampedNormalSpec {
                mean_pct: 90.0,
                std_dev_pct: 10.0,
                min_pct: 0.0,
                max_pct: 100.0,
            },
        }
    }
}

/// Path planning of ground robots.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NavigationSpec {
    /// Occupancy-grid cell side, metres, finite, > 0; default 0.25.
    pub grid_cell_m: f64,
    /// Clearance beyond the body radius, metres, finite, >= 0; default 0.1.
    pub clearance_m: f64,
    /// Waypoint reached distance, metres, finite, > 0; default 0.3.
    pub waypoint_tolerance_m: f64,
}

impl Default for NavigationSpec {
    fn default() -> Self {
        Self {
            grid_cell_m: 0.25,
            clearance_m: 0.1,
            waypoint_tolerance_m: 0.3,
        }
    }
}

/// Priority-based collision avoidance (paper, section V, Algorithm 5).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CollisionSpec {
    /// Whether the resolver runs; default `true`.
    pub enabled: bool,
    /// Look-ahead, seconds, finite, > 0; default 1.0.
    pub lookahead_s: f64,
    /// Gap kept between bodies, metres, finite, >= 0; default 0.2.
    pub safety_margin_m: f64,
    /// Time without progress along their paths (see `docs/world-model.md`) that makes a
    /// collision list a deadlock, seconds, finite, > 0; default 2.0.
    pub deadlock_after_s: f64,
}

impl Default for CollisionSpec {
    fn default() -> Self {
        Self {
            enabled: true,
            lookahead_s: 1.0,
            safety_margin_m: 0.2,
            deadlock_after_s: 2.0,
        }
    }
}

/// Time stepping and seed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimSpec {
    /// Fixed step, seconds, finite, in `(0, mission.duration_s]`; default 0.02 (1/50 s).
    pub dt_s: f64,
    /// Base seed of trials and default seed of debris fields; default 0.
    pub seed: u64,
}

impl Default for SimSpec {
    fn default() -> Self {
        Self {
            dt_s: 1.0 / 50.0,
            seed: 0,
        }
    }
}
