//! Raw scenario spec: exactly what a RON scenario file holds, before expansion and validation.
//!
//! These types mirror the file format (documented field by field in `docs/scenario-format.md`).
//! Every struct rejects unknown fields. The leaf parameter blocks are the simulator's own types
//! ([`super::params`]) and check their numbers while they are read; the types here are the
//! parts whose shape changes on the way to the [`Scenario`](super::Scenario) (start rows, task
//! quotas by name, rescuee layouts, generated debris) and are expanded and checked by
//! [`ScenarioSpec::validate`] (or by [`load`](super::load) / [`from_str`](super::from_str), which
//! do both).
//!
//! Points and vectors are written as RON tuples `(x, y)` in metres, world frame (origin at the
//! arena's bottom-left inner corner, x right, y up). Fields marked *default* may be omitted.

use std::collections::BTreeMap;

use serde::{Deserialize, Deserializer, Serialize};

use super::model::{Locomotion, Role};
use super::numbers::Positive;
use super::params::{
    Arena, CollisionParams, MissionParams, NavigationParams, NeedsWeights, SimParams,
};

/// A point or vector `(x, y)` in metres, world frame.
pub type XyM = [f64; 2];

/// A closed range `(min, max)`, in the unit the field name gives.
pub type RangeSpec = (f64, f64);

/// The whole scenario file. In RON: `Scenario( name: ..., ... )` (the struct name is optional).
///
/// The leaf blocks (`arena`, `mission`, `navigation`, `collision`, `sim`, `needs_weights`) are
/// the simulator's own parameter types, checked while they are read ([`super::params`]); the
/// rest is expanded and checked by [`ScenarioSpec::validate`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename = "Scenario", deny_unknown_fields)]
pub struct ScenarioSpec {
    /// Short name, non-empty, used for output folders (e.g. `"paper"`).
    pub name: String,
    /// Free text; default empty.
    #[serde(default)]
    pub description: String,
    /// The walled field.
    pub arena: Arena,
    /// Robot kinds in grouping merge order (paper: carrier, supplier, observer); at least one.
    pub kinds: Vec<KindSpec>,
    /// Rest (recharge) stations: one circle, or a list of at least one (a robot leaving to
    /// recharge goes to the one with the shortest path; see [`RestStationsSpec`]).
    pub rest_station: RestStationsSpec,
    /// The tasks, at least one, in the order the outputs list them (columns, figures); their
    /// `difficulty` orders them for grouping.
    pub tasks: Vec<TaskSpec>,
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
    pub needs_weights: NeedsWeights,
    /// Mission rules; defaults in [`MissionParams`].
    #[serde(default)]
    pub mission: MissionParams,
    /// Path planning; defaults in [`NavigationParams`].
    #[serde(default)]
    pub navigation: NavigationParams,
    /// Collision avoidance; defaults in [`CollisionParams`].
    #[serde(default)]
    pub collision: CollisionParams,
    /// Time step and seed; defaults in [`SimParams`].
    #[serde(default)]
    pub sim: SimParams,
    /// What a sweep's report compares the scenario with (data only; the simulator does not
    /// read it); default no targets and no claims ([`ReportSpec`]).
    #[serde(default)]
    pub report: ReportSpec,
}

/// The `report` section: `report: (targets: "paper-targets.ron", claims: "paper-claims.ron")`.
/// Data for the
/// reports of a sweep (the `experiments` crate); the simulator does not read it. Both fields
/// may be omitted, and unknown fields are rejected.
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct ReportSpec {
    /// Calibration targets to compare the results with: a path to a targets file (such as
    /// `scenarios/paper-targets.ron`), relative to the scenario file's folder; default none
    /// (no calibration bands). Written as a plain string, `targets: "paper-targets.ron"`
    /// (`Some("...")` and `None` are read too).
    #[serde(
        serialize_with = "ser_path_or_none",
        deserialize_with = "de_path_or_none"
    )]
    pub targets: Option<String>,
    /// Claims to check the results against: a path to a claims file (such as
    /// `scenarios/paper-claims.ron`, the paper's claims of section VI), relative to the scenario
    /// file's folder; default none (no claims section). Written as a plain string, `claims:
    /// "paper-claims.ron"` (`Some("...")` and `None` are read too). The former boolean still
    /// reads: `claims: true` (which checked the paper's claims) as `"paper-claims.ron"`, the
    /// file that now holds them, and `false` as none.
    #[serde(
        serialize_with = "ser_path_or_none",
        deserialize_with = "de_claims_path"
    )]
    pub claims: Option<String>,
}

/// [`de_path_or_none`], and the former boolean: `false` is none, `true` the file that now
/// holds the paper's claims it meant, `paper-claims.ron` (next to `paper.ron`). Anything else
/// is refused naming what the field takes.
fn de_claims_path<'de, D: Deserializer<'de>>(d: D) -> Result<Option<String>, D::Error> {
    d.deserialize_any(PathOrNone {
        what: "a claims file's path such as \"paper-claims.ron\", or None",
        true_means: Some("paper-claims.ron"),
    })
}

fn ser_path_or_none<S: serde::Serializer>(v: &Option<String>, s: S) -> Result<S::Ok, S::Error> {
    match v {
        Some(path) => s.serialize_str(path),
        None => s.serialize_none(),
    }
}

/// A string, `Some("...")`, `None` (or a JSON `null`).
fn de_path_or_none<'de, D: Deserializer<'de>>(d: D) -> Result<Option<String>, D::Error> {
    d.deserialize_any(PathOrNone {
        what: "a path such as \"paper-targets.ron\", or None",
        true_means: None,
    })
}

/// Reads a file path that may be absent (a string, `Some("...")`, `None`, `()` or a JSON
/// `null`); with `true_means`, a former boolean too (`false` is none, `true` that path). Its
/// errors say `what` the field takes (an untagged enum's would name only the enum).
struct PathOrNone {
    /// What the field takes, for errors.
    what: &'static str,
    /// The path a former `true` stands for, if the field was once a boolean.
    true_means: Option<&'static str>,
}

impl<'de> serde::de::Visitor<'de> for PathOrNone {
    type Value = Option<String>;
    fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.what)
    }
    fn visit_bool<E: serde::de::Error>(self, v: bool) -> Result<Self::Value, E> {
        match self.true_means {
            Some(path) => Ok(v.then(|| path.to_owned())),
            None => Err(E::invalid_type(serde::de::Unexpected::Bool(v), &self)),
        }
    }
    fn visit_str<E: serde::de::Error>(self, v: &str) -> Result<Self::Value, E> {
        Ok(Some(v.to_owned()))
    }
    fn visit_none<E: serde::de::Error>(self) -> Result<Self::Value, E> {
        Ok(None)
    }
    fn visit_unit<E: serde::de::Error>(self) -> Result<Self::Value, E> {
        Ok(None)
    }
    fn visit_some<D2: Deserializer<'de>>(self, d: D2) -> Result<Self::Value, D2::Error> {
        String::deserialize(d).map(Some)
    }
}

/// The `rest_station` field: one circle `(center_m: (x, y), radius_m: r)` (the paper's single
/// "rest position", section VI.B) or a list of circles `[(...), (...)]` for large teams, at
/// least one and at most [`MAX_REST_STATIONS`](super::limits::MAX_REST_STATIONS). Written back
/// in the form it was read (one circle stays one circle).
#[derive(Debug, Clone, PartialEq)]
pub enum RestStationsSpec {
    /// One station, written as a circle.
    One(CircleSpec),
    /// Several stations, written as a list of circles (may be empty here; validation refuses
    /// an empty list).
    Many(Vec<CircleSpec>),
}

impl RestStationsSpec {
    /// The stations, in the file's order (a station's index in this slice is its index in
    /// [`Scenario::rest_stations`](super::Scenario::rest_stations)).
    pub fn circles(&self) -> &[CircleSpec] {
        match self {
            Self::One(c) => std::slice::from_ref(c),
            Self::Many(list) => list,
        }
    }
}

impl Serialize for RestStationsSpec {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Self::One(c) => c.serialize(s),
            Self::Many(list) => list.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for RestStationsSpec {
    /// A map or struct is one circle, a sequence a list; inner errors (unknown fields, a
    /// negative radius) are the circle's own, at their own position.
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
        struct Stations;
        impl<'de> serde::de::Visitor<'de> for Stations {
            type Value = RestStationsSpec;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a circle (center_m: (x, y), radius_m: r) or a list of circles")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                map: A,
            ) -> Result<Self::Value, A::Error> {
                CircleSpec::deserialize(MapAccessDeserializer::new(map)).map(RestStationsSpec::One)
            }
            fn visit_seq<A: serde::de::SeqAccess<'de>>(
                self,
                seq: A,
            ) -> Result<Self::Value, A::Error> {
                Vec::deserialize(SeqAccessDeserializer::new(seq)).map(RestStationsSpec::Many)
            }
        }
        d.deserialize_any(Stations)
    }
}

/// A circle.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CircleSpec {
    /// Centre, metres.
    pub center_m: XyM,
    /// Radius, metres, > 0.
    pub radius_m: Positive,
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

/// Robots of one kind per task, by task name: `quota: (hard: 3, easy: 3)` (struct syntax) or
/// `quota: {"hard": 3, "easy": 3}` (map syntax). Every task of the scenario is named exactly
/// once (validation checks the names and that the counts add up to the kind's `count`).
#[derive(Debug, Clone, Default, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct TaskQuotas(pub BTreeMap<String, usize>);

impl<'de> Deserialize<'de> for TaskQuotas {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Quotas;
        impl<'de> serde::de::Visitor<'de> for Quotas {
            type Value = TaskQuotas;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str("robots per task by task name, e.g. (hard: 3, easy: 3)")
            }
            fn visit_map<A: serde::de::MapAccess<'de>>(
                self,
                mut map: A,
            ) -> Result<TaskQuotas, A::Error> {
                let mut out = BTreeMap::new();
                while let Some((task, n)) = map.next_entry::<String, usize>()? {
                    if out.contains_key(&task) {
                        return Err(serde::de::Error::custom(format!(
                            "task {} is given twice",
                            super::plain_words::shorten(&format!("{task:?}"))
                        )));
                    }
                    out.insert(task, n);
                }
                Ok(TaskQuotas(out))
            }
        }
        // `deserialize_any` lets ron read `(hard: 3)` as a map, as well as `{"hard": 3}`.
        d.deserialize_any(Quotas)
    }
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
    /// Number of robots, >= 1; must equal the sum of `quota`.
    pub count: usize,
    /// Robots of this kind in each task's group, by task name.
    pub quota: TaskQuotas,
    /// Body (disc) radius, metres, > 0.
    pub body_radius_m: Positive,
    /// Top speed at full HP, m/s, > 0.
    pub max_speed_m_per_s: Positive,
    /// Range to sense robots and obstacles, metres, > 0.
    pub sensing_range_m: Positive,
    /// Range to detect rescuees, metres, > 0.
    pub observing_range_m: Positive,
    /// Rescuees carried at once, >= 0.
    pub carrying_capacity: u32,
    /// Rescuing resources brought per round, >= 0.
    pub rescuing_resources: u32,
    /// Health needs level at 100 % HP, > 0.
    pub hp_needs_full: Positive,
    /// Energy needs level at 100 % energy, > 0.
    pub energy_needs_full: Positive,
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
    /// `count` positions on a grid of `columns` columns, filled row by row: robot `i` starts
    /// at `first_m + (i mod columns) * spacing_m.x` across and `(i div columns) *
    /// spacing_m.y` up (negative spacings go left or down). `Grid(first_m: (x, y), columns:
    /// 20, spacing_m: (dx, dy))`. For large teams: changing `count` needs no other edit.
    Grid {
        /// Position of the kind's first robot, metres.
        first_m: XyM,
        /// Robots per row, >= 1.
        columns: u32,
        /// Distance between neighbouring columns (x) and rows (y), metres; `x` non-zero when
        /// a row holds more than one robot, `y` non-zero when there is more than one row.
        spacing_m: XyM,
    },
}

/// One task: a name, a difficulty, a search area with rescuees, a goal point and a drop-off
/// (paper, sections IV-V: an easy and a hard task; any number here).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TaskSpec {
    /// Unique, non-empty name (e.g. `"hard"`); kinds' quotas and the outputs name the task by
    /// it (claims and targets files name a task's metrics by it: `rescued_hard`).
    pub name: String,
    /// Difficulty rank, >= 0, higher is harder; default 0. Grouping methods fill tasks from the
    /// hardest down (paper: the hard task); on equal ranks the task listed first counts as the
    /// harder.
    #[serde(default)]
    pub difficulty: u32,
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
        /// Distance between neighbours, metres, > 0.
        spacing_m: Positive,
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
        /// Radius, metres, > 0.
        radius_m: Positive,
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
    /// Radius, metres, > 0; the disc lies inside the arena.
    pub radius_m: Positive,
    /// Relative dose rate, > 0; default 1.
    #[serde(default = "one")]
    pub dose_rate_factor: Positive,
}

fn one() -> Positive {
    Positive::known(1.0)
}
