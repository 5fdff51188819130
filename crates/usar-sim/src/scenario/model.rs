//! The parts of a validated scenario: robot kinds and starts, tasks, shapes, debris and
//! radiation zones, as [`crate::scenario::Scenario`] holds them.
//!
//! These are produced by validation ([`crate::scenario::ScenarioSpec::validate`]; "parse,
//! don't validate") and read through the scenario's accessors. Every value here has already
//! been checked: lengths are positive, shapes lie inside the arena, counts match quotas, and so
//! on, so the simulator never re-checks them. Building one of these by hand gives no scenario:
//! only validation makes a [`crate::scenario::Scenario`].
//!
//! Frame and units: the world frame has its origin at the arena's bottom-left inner corner, x to
//! the right, y up; lengths in metres (`_m`), times in seconds (`_s`), speeds in metres per second
//! (`_m_per_s`), energy and health in percent of the robot's full level (`_pct`).

use nalgebra::{Point2, Vector2};
use serde::{Deserialize, Serialize};

use super::params::Arena;

/// A point in the world frame, metres.
pub type PointM = Point2<f64>;

/// Number of entries of the paper's needs vector (hp, v, sen, eng, res, cap, obs), Eqs. 19-21.
pub const NEEDS_LEN: usize = 7;

impl Arena {
    /// Whether `p` lies inside the field (boundary included; NaN or infinite coordinates are
    /// outside).
    pub fn contains(&self, p: &PointM) -> bool {
        in_field(p.x, p.y, self.width(), self.height())
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

/// A robot's role in the mission (paper, section IV). Only `Observer` changes behaviour: a
/// group with an observer in it sees (its ground members go for the rescuees the group has
/// found, at full speed), a group without one searches blind (lawn-mower pattern, speeds times
/// `mission.no_observer_speed_factor`). What a robot carries or brings is its kind's
/// `carrying_capacity` and `rescuing_resources`, whatever its role (`docs/scenario-format.md`,
/// "What `role` and `locomotion` change").
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Role {
    /// Carries rescuees (paper: large carrying capacity). A label: behaviour as `Supplier`.
    Carrier,
    /// Brings rescuing resources shared with the group (paper). A label: behaviour as
    /// `Carrier`.
    Supplier,
    /// Scout (paper: aerial, with a very long observing range). Its group is not blind.
    Observer,
}

/// How a robot moves.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Locomotion {
    /// Drives on the ground: collides with walls, debris and other ground robots, plans around
    /// debris, takes part in collision avoidance (Algorithm 5). Only ground robots pick up and
    /// carry rescuees.
    Ground,
    /// Flies: passes over debris and ground robots, flies straight, avoids other aerial robots.
    /// Finds rescuees for its group but never carries one.
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
    /// Number of robots of this kind, >= 1; equals the sum of `quota`.
    pub count: usize,
    /// How many robots of this kind each task's group takes, indexed by task id (paper: 3
    /// carriers, 2 suppliers, 1 observer per task).
    pub quota: Vec<usize>,
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
    /// Index into [`Scenario::kinds`](crate::scenario::Scenario::kinds).
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

    /// Euclidean distance from `p` to the rectangle, metres (0 inside or on its boundary):
    /// `dx.hypot(dy)` of the distances beyond its sides, or the one that is non-zero when the
    /// other is zero (inside, or beside a side rather than a corner), which is the same value
    /// (C99 Annex F.10.4.3: `hypot(x, ±0)` is `fabs(x)`) without the library call.
    pub fn distance_to(&self, p: &PointM) -> f64 {
        let dx = (self.min.x - p.x).max(p.x - self.max.x).max(0.0);
        let dy = (self.min.y - p.y).max(p.y - self.max.y).max(0.0);
        if dy == 0.0 {
            dx
        } else if dx == 0.0 {
            dy
        } else {
            dx.hypot(dy)
        }
    }
}

/// One task of the mission (paper, sections IV-V): a search area holding rescuees, a goal point
/// that distance-based grouping measures to, and a drop-off ("safety place").
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Task {
    /// Unique name (e.g. `hard`), used by quotas in the file and by the outputs.
    pub name: String,
    /// Difficulty rank, higher is harder (ties: the task listed first is the harder).
    pub difficulty: u32,
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
/// `mission.hp_pct_per_step_in_radiation` times the zone's dose factor percent HP per step (the
/// dose rule `mission.radiation_overlap` / `radiation_falloff` says how zones combine).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RadiationZone {
    /// Extent of the zone.
    pub area: Circle,
    /// Relative dose rate, dimensionless, > 0 (1 = the scenario's base rate).
    pub dose_rate_factor: f64,
}

/// Most steps one trial may take: 10 million, i.e. 200,000 s (about 55 hours) of simulated
/// time at the default 1/50 s step. A longer trial is an error (of validation for
/// `mission.duration_s`, of the trial builder for a requested length), not a run of days.
pub const MAX_TRIAL_STEPS: u64 = 10_000_000;

/// Steps of a trial of `duration_s` at step `dt_s`: `ceil(duration_s / dt_s)`, where a ratio
/// within 1e-9 (relative) of a whole number counts as that number (so float rounding of, say,
/// `30 / 0.02` cannot add a step), and at least 1.
///
/// # Errors
/// A one-line message unless `duration_s` is finite and `> 0` and the steps number at most
/// [`MAX_TRIAL_STEPS`].
pub fn trial_steps(duration_s: f64, dt_s: f64) -> Result<u64, String> {
    if !(duration_s.is_finite() && duration_s > 0.0) {
        return Err(format!(
            "trial length: expected a number of seconds > 0, found {}",
            number_text(duration_s)
        ));
    }
    let ratio = duration_s / dt_s;
    let nearest = ratio.round();
    let steps = if (ratio - nearest).abs() <= 1e-9 * nearest.max(1.0) {
        nearest
    } else {
        ratio.ceil()
    };
    if steps.is_nan() || steps > MAX_TRIAL_STEPS as f64 {
        return Err(format!(
            "trial length {} s is {} steps of {} s, more than the limit of {MAX_TRIAL_STEPS} \
             steps",
            number_text(duration_s),
            count_text(steps),
            number_text(dt_s)
        ));
    }
    Ok(steps.max(1.0) as u64)
}

pub use rne_core::{number_text, one_line_text, path_text, short_numbers};

/// A count computed in `f64` as messages write it: as [`number_text`], or `more than 1.8e308`
/// when it overflowed to infinity (a count is never negative); a count of 1e15 or more with
/// three significant digits (`4e302`, not `3.9999999999999995e302`: its last digits are float
/// rounding, not a count).
pub(crate) fn count_text(v: f64) -> String {
    if v.is_infinite() {
        "more than 1.8e308".to_string()
    } else if v.abs() >= 1e15 {
        let s = format!("{v:.2e}");
        // `4.00e302` -> `4e302`, `1.50e20` -> `1.5e20`.
        match s.split_once('e') {
            Some((mantissa, exp)) if mantissa.contains('.') => {
                let m = mantissa.trim_end_matches('0').trim_end_matches('.');
                format!("{m}e{exp}")
            }
            _ => s,
        }
    } else {
        number_text(v)
    }
}

/// `v` with three decimals (`2.500`), or as [`number_text`] writes it when it is 1e15 or more in
/// magnitude (or not finite), where three decimals would follow sixteen or more digits.
pub(crate) fn number_text_3dp(v: f64) -> String {
    if v.abs() < 1e15 {
        format!("{v:.3}")
    } else {
        number_text(v)
    }
}

#[cfg(test)]
mod count_text_tests {
    use super::count_text;

    #[test]
    fn large_counts_have_three_significant_digits() {
        assert_eq!(count_text(3.9999999999999995e302), "4e302");
        assert_eq!(count_text(1.5e20), "1.5e20");
        assert_eq!(count_text(1.2345e16), "1.23e16");
        assert_eq!(count_text(30_000.0), "30000");
        assert_eq!(count_text(f64::INFINITY), "more than 1.8e308");
    }
}

#[cfg(test)]
mod rect_tests {
    use super::{PointM, Rect};

    #[test]
    fn distance_to_a_rectangle_is_zero_inside_and_euclidean_outside() {
        let r = Rect {
            min: PointM::new(0.0, 0.0),
            max: PointM::new(4.0, 2.0),
        };
        let d = |x, y| r.distance_to(&PointM::new(x, y));
        assert_eq!(d(1.0, 1.0), 0.0);
        assert_eq!(d(4.0, 2.0), 0.0);
        assert!((d(5.0, 1.0) - 1.0).abs() < 1e-12);
        assert!((d(1.0, -0.5) - 0.5).abs() < 1e-12);
        assert!((d(7.0, 6.0) - 5.0).abs() < 1e-12);
    }

    proptest::proptest! {
        /// The shortcut beside a side gives the bits of `hypot`, at every point round a
        /// rectangle (inside, beside a side, beyond a corner, and far out).
        #[test]
        fn distance_to_a_rectangle_has_the_bits_of_hypot(
            x in -1e3f64..1e3,
            y in -1e3f64..1e3,
            w in 0.0f64..50.0,
            h in 0.0f64..50.0,
        ) {
            let r = Rect {
                min: PointM::new(-w, -h),
                max: PointM::new(w, 2.0 * h),
            };
            let p = PointM::new(x, y);
            let dx = (r.min.x - p.x).max(p.x - r.max.x).max(0.0);
            let dy = (r.min.y - p.y).max(p.y - r.max.y).max(0.0);
            proptest::prop_assert_eq!(r.distance_to(&p).to_bits(), dx.hypot(dy).to_bits());
            // Beside a side: one component zero, the other the distance itself.
            let beside = PointM::new(x.clamp(-w, w), y);
            let dy = (r.min.y - y).max(y - r.max.y).max(0.0);
            proptest::prop_assert_eq!(r.distance_to(&beside).to_bits(), dy.hypot(0.0).to_bits());
        }
    }
}
