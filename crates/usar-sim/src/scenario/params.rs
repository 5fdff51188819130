//! The scenario's leaf parameter blocks (arena, mission, navigation, collision, sim, needs
//! weights): one type each, read from the file as they are and used by the simulator as they
//! are. Every number is a validated type ([`super::numbers`]), so a block is checked while it
//! is deserialised (an error names the field's line and column), and every default is written
//! once, here. Cross-field rules (e.g. `sim.dt_s <= mission.duration_s`) are checked by
//! validation. Field meanings and the paper's values: `docs/scenario-format.md`,
//! `docs/mission-model.md`.

use serde::{Deserialize, Serialize};

use super::choices::{
    AwayQuotas, CollisionPriority, EmptyOnLeave, HpEffect, IdleBeforeArea, LeaveWhenLow,
    LoadOnLeave, OutsideRange, PhysicsStepping, RadiationFalloff, RadiationOverlap, Refresh,
    RescuedAt, RestAt, RoundStart, SearchClock, SweepPattern,
};
use super::lifecycle_choices::{CostClock, CostsCount, ResourceStock, RestTiming, RoundClock};
use super::numbers::{Factor, Finite, Fraction, NonNegative, Percent, Positive, RangeError};

/// The paper's "step", seconds: Unity's fixed step of 1/50 s, the unit of the paper's per-step
/// costs (section VI.B). The per-step rates of [`MissionParams`] are quoted per such a step
/// and scaled by `sim.dt_s / PAPER_STEP_S` on a step of another length, so that the physics do
/// not depend on the step ([`MissionParams::per_paper_step`]).
pub const PAPER_STEP_S: f64 = 0.02;

/// The walled rectangular field `[0, width_m] x [0, height_m]` (world frame: origin at the
/// bottom-left inner corner, x right, y up).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Arena {
    /// Inner width, metres, > 0.
    pub width_m: Positive,
    /// Inner height, metres, > 0.
    pub height_m: Positive,
    /// Boundary wall thickness (outside the field), metres, > 0 and at most
    /// [`crate::scenario::limits::MAX_ARENA_SIDE_M`] (10,000); default 0.5.
    #[serde(default = "Arena::default_wall_thickness_m")]
    pub wall_thickness_m: Positive,
}

impl Arena {
    fn default_wall_thickness_m() -> Positive {
        Positive::known(0.5)
    }

    /// Width, metres.
    pub fn width(&self) -> f64 {
        self.width_m.get()
    }

    /// Height, metres.
    pub fn height(&self) -> f64 {
        self.height_m.get()
    }
}

/// A normal distribution `N(mean_pct, std_dev_pct)` kept inside `[min_pct, max_pct]` (clamped,
/// or drawn again: `outside_range`), for the initial energy and HP levels (validation also
/// checks `min_pct <= max_pct`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ClampedNormal {
    /// Mean, percent, finite.
    pub mean_pct: Finite,
    /// Standard deviation, percent, >= 0.
    pub std_dev_pct: NonNegative,
    /// Lowest value a draw is clamped to, percent, in `[0, 100]`; default 0.
    #[serde(default = "ClampedNormal::zero")]
    pub min_pct: Percent,
    /// Highest value a draw is clamped to, percent, in `[min_pct, 100]`; default 100.
    #[serde(default = "ClampedNormal::hundred")]
    pub max_pct: Percent,
    /// What happens to a draw outside `[min_pct, max_pct]`; default `Clamp`.
    #[serde(default)]
    pub outside_range: OutsideRange,
}

impl ClampedNormal {
    fn zero() -> Percent {
        Percent::known(0.0)
    }

    fn hundred() -> Percent {
        Percent::known(100.0)
    }

    /// A "distribution" that always draws `level_pct` (no spread), for fixed starting levels
    /// in tests and experiments.
    ///
    /// # Errors
    /// [`RangeError`] when `level_pct` is not in `[0, 100]`.
    pub fn fixed(level_pct: f64) -> Result<Self, RangeError> {
        Percent::new(level_pct)?;
        Ok(Self {
            mean_pct: Finite::new(level_pct)?,
            std_dev_pct: NonNegative::known(0.0),
            min_pct: Percent::known(0.0),
            max_pct: Percent::known(100.0),
            outside_range: OutsideRange::Clamp,
        })
    }

    /// `N(mean_pct, std_dev_pct)` clamped to `[0, 100]`.
    pub(crate) const fn known(mean_pct: f64, std_dev_pct: f64) -> Self {
        Self {
            mean_pct: Finite::known(mean_pct),
            std_dev_pct: NonNegative::known(std_dev_pct),
            min_pct: Percent::known(0.0),
            max_pct: Percent::known(100.0),
            outside_range: OutsideRange::Clamp,
        }
    }
}

/// Mission rules (paper, section VI.B). Every field has a default: the paper's value where it
/// gives one, otherwise the model as it was before calibration (`scenarios/paper-v0.ron`),
/// except where that model was a defect (`sweep_spacing_m`, `sweep_pattern`: paper-v0.ron
/// writes the old values out); `scenarios/paper.ron` writes every field out.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct MissionParams {
    /// Trial length, seconds, > 0; default 600 (paper).
    pub duration_s: Positive,
    /// Energy spent on each paper step ([`PAPER_STEP_S`], 1/50 s) in which the robot moves,
    /// percent, >= 0; default 0.0045 (paper). A simulation step of another length is charged
    /// `energy_pct_per_moving_step * sim.dt_s / PAPER_STEP_S`. The default is 0.225 % per
    /// second of moving, 13.5 % per minute: from 80 % to `low_energy_pct` (30 %) in about
    /// 3 min 40 s of moving.
    pub energy_pct_per_moving_step: NonNegative,
    /// Energy spent per metre moved, percent per metre, >= 0; default 0 (adds to
    /// `energy_pct_per_moving_step`; the authors' Unity code charges `energy -= distance * k`).
    pub energy_pct_per_m: NonNegative,
    /// HP lost per paper step ([`PAPER_STEP_S`], 1/50 s) inside a radiation zone of dose factor
    /// 1, percent, >= 0; default 0.0003 (paper: 0.015 % per second, 0.9 % per minute). A
    /// simulation step of another length is charged `hp_pct_per_step_in_radiation * sim.dt_s /
    /// PAPER_STEP_S`. A value `x` costs `3000 x` % HP per minute at dose 1: the default is
    /// nearly harmless (over an hour from 90 % to `low_hp_pct`, 30 %); paper.ron's 0.0055 is
    /// 16.5 % per minute (90 % to 30 % in about 3 min 40 s at dose 1).
    pub hp_pct_per_step_in_radiation: NonNegative,
    /// How overlapping zones combine; default `Sum`.
    pub radiation_overlap: RadiationOverlap,
    /// How a zone's dose varies inside it; default `Uniform`.
    pub radiation_falloff: RadiationFalloff,
    /// When a new round may start; default `Available`.
    pub round_start: RoundStart,
    /// What ends a round: every group back, or a timer; default `AllBack`.
    pub round_clock: RoundClock,
    /// Whether a rest is taken in its round's slack; default `OutOfRound`.
    pub rest_timing: RestTiming,
    /// Where a group's rescuing resources come from: refilled each round, at rests, or one team
    /// stock per round; default `PerRound`.
    pub resource_stock: ResourceStock,
    /// The clock of the per-step costs: the paper's 1/50 s step or rendered frames; default
    /// `PaperStep`.
    pub cost_clock: CostClock,
    /// Which costs count in the metrics; default `InGroup`.
    pub costs_count: CostsCount,
    /// Which quotas shrink when robots are away at a round's start; default `HardestFirst`.
    pub away_quotas: AwayQuotas,
    /// What becomes of a leaving robot's load; default `Abandon`.
    pub load_on_leave: LoadOnLeave,
    /// Longest time a group searches its area per round, seconds from the moment its first
    /// ground member entered it, > 0, written `Some(14.0)`; default `None` (no limit: the group
    /// leaves only when full, out of resources, or when nothing more is to be found).
    pub search_time_budget_s: Option<Positive>,
    /// When the search time budget starts to run; default `FirstArrival`.
    pub search_clock: SearchClock,
    /// What a ground member with nothing to claim does before it reaches its search area;
    /// default `Wait`.
    pub idle_before_area: IdleBeforeArea,
    /// Where a member carrying nothing goes when its group leaves the search area; default
    /// `ViaDropOff`.
    pub empty_on_leave: EmptyOnLeave,
    /// Where a robot below a threshold recharges; default `RestStation`.
    pub rest_at: RestAt,
    /// What a stay at the rest station restores; default `Both`.
    pub refresh: Refresh,
    /// Row spacing of a blind group's lawn-mower search, metres, > 0, written `Some(2.0)`;
    /// default `None`: the narrowest ground detection width `2 * (body_radius_m +
    /// observing_range_m)` (see `scenario::sweep_spacing_m`), so a sweep covers the area.
    pub sweep_spacing_m: Option<Positive>,
    /// The blind search's pattern; default `EdgeToEdge` (`CentreToCentre` is the defective
    /// pattern of the model before 2026-11-24).
    pub sweep_pattern: SweepPattern,
    /// How HP scales speed, sensing and observing range; default `Linear`.
    pub hp_effect: HpEffect,
    /// Smallest factor HP scales speed, sensing and observing range by under `hp_effect:
    /// Linear`, in `[0, 1]`; default 0 (the factor is `hp_pct / 100`, so a robot at 0 % HP
    /// stops; see `mission::hp_factor`).
    pub min_hp_factor: Fraction,
    /// Time a ground robot stands at a rescuee to rescue it (secure and load it), seconds,
    /// >= 0; default 0 (at once).
    pub pickup_s: NonNegative,
    /// Below this energy a robot leaves its task to recharge, percent; default 30 (paper).
    pub low_energy_pct: Percent,
    /// Below this HP a robot leaves its task to refresh, percent; default 30 (paper).
    pub low_hp_pct: Percent,
    /// When a robot below `low_energy_pct` or `low_hp_pct` leaves; default `AtOnce`.
    pub leave_when_low: LeaveWhenLow,
    /// When a rescuee counts as rescued; default `DropOff`.
    pub rescued_at: RescuedAt,
    /// Time spent at the rest station, seconds, >= 0; default 30 (paper).
    pub recharge_s: NonNegative,
    /// Speed factor of a group without an observer, in `(0, 1]`; default 0.7 (paper: "decrease
    /// by 30 %").
    pub no_observer_speed_factor: Factor,
    /// Initial energy levels; default `N(80, 20)` clamped to `[0, 100]` (paper).
    pub initial_energy: ClampedNormal,
    /// Initial HP levels; default `N(90, 10)` clamped to `[0, 100]` (paper).
    pub initial_hp: ClampedNormal,
}

impl Default for MissionParams {
    fn default() -> Self {
        Self {
            duration_s: Positive::known(600.0),
            energy_pct_per_moving_step: NonNegative::known(0.0045),
            energy_pct_per_m: NonNegative::known(0.0),
            hp_pct_per_step_in_radiation: NonNegative::known(0.0003),
            radiation_overlap: RadiationOverlap::default(),
            radiation_falloff: RadiationFalloff::default(),
            round_start: RoundStart::default(),
            round_clock: RoundClock::default(),
            rest_timing: RestTiming::default(),
            resource_stock: ResourceStock::default(),
            cost_clock: CostClock::default(),
            costs_count: CostsCount::default(),
            away_quotas: AwayQuotas::default(),
            load_on_leave: LoadOnLeave::default(),
            search_time_budget_s: None,
            search_clock: SearchClock::FirstArrival,
            idle_before_area: IdleBeforeArea::Wait,
            empty_on_leave: EmptyOnLeave::ViaDropOff,
            rest_at: RestAt::RestStation,
            refresh: Refresh::default(),
            sweep_spacing_m: None,
            sweep_pattern: SweepPattern::default(),
            hp_effect: HpEffect::Linear,
            min_hp_factor: Fraction::known(0.0),
            pickup_s: NonNegative::known(0.0),
            low_energy_pct: Percent::known(30.0),
            low_hp_pct: Percent::known(30.0),
            leave_when_low: LeaveWhenLow::AtOnce,
            rescued_at: RescuedAt::DropOff,
            recharge_s: NonNegative::known(30.0),
            no_observer_speed_factor: Factor::known(0.7),
            initial_energy: ClampedNormal::known(80.0, 20.0),
            initial_hp: ClampedNormal::known(90.0, 10.0),
        }
    }
}

impl MissionParams {
    /// A per-paper-step rate (`energy_pct_per_moving_step`, `hp_pct_per_step_in_radiation`) as
    /// charged on one simulation step of `dt_s` seconds: `rate * dt_s / PAPER_STEP_S` (exactly
    /// `rate` at `dt_s = 0.02`).
    pub fn per_paper_step(rate: NonNegative, dt_s: f64) -> f64 {
        rate.get() * (dt_s / PAPER_STEP_S)
    }

    /// A per-step rate (`energy_pct_per_moving_step`, `hp_pct_per_step_in_radiation`) as
    /// charged on one simulation step of `dt_s` seconds on this mission's `cost_clock`: under
    /// `PaperStep` [`MissionParams::per_paper_step`]; under `Frames(steps_per_s)` `rate * dt_s
    /// * steps_per_s` (the frames the step spans).
    pub fn per_step_on_cost_clock(&self, rate: NonNegative, dt_s: f64) -> f64 {
        match self.cost_clock {
            CostClock::PaperStep => Self::per_paper_step(rate, dt_s),
            CostClock::Frames { steps_per_s } => rate.get() * (dt_s * steps_per_s.get()),
        }
    }
}

/// Default of `navigation.stall_replan_s`: a ground robot with a goal, outside every collision
/// list, whose remaining path length has not fallen [`STALL_PROGRESS_M`] below its best value
/// for this long re-plans around the robots standing within its sensing range (a detour),
/// seconds. (Robots in a list are left to the resolver's deadlock rotation.) Used by the
/// world's path following; re-exported as `world::STALL_REPLAN_S`.
pub const STALL_REPLAN_S: f64 = 3.0;
/// Progress that restarts a ground robot's no-progress clock (see [`STALL_REPLAN_S`]), metres.
/// Used by the world's path following; re-exported as `world::STALL_PROGRESS_M`.
pub const STALL_PROGRESS_M: f32 = 0.05;

/// Path planning of ground robots over an occupancy grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NavigationParams {
    /// Side of an occupancy-grid cell, metres, > 0 and at most the arena's shorter side;
    /// default 0.25.
    pub grid_cell_m: Positive,
    /// Clearance kept from debris and walls beyond the body radius, metres, >= 0; default 0.1.
    pub clearance_m: NonNegative,
    /// Distance at which a waypoint counts as reached, metres, at least
    /// [`crate::scenario::limits::min_waypoint_tolerance_m`] (1 mm, more in arenas over
    /// 525 m) and at most [`crate::scenario::limits::MAX_WAYPOINT_TOLERANCE_M`] (5); default
    /// 0.3.
    pub waypoint_tolerance_m: Positive,
    /// Whether ground robots reach the goals many of them share (task goal points, drop-off
    /// centres, the rest station) by descending one distance field per goal and clearance
    /// class, computed once and reused by every robot (`true`, the default: what large teams
    /// need), or each by its own A* search (`false`: the model `paper.ron` was calibrated
    /// with). Both give shortest paths on the grid; they differ only in how ties between
    /// equally short paths are broken. See `docs/world-model.md`.
    pub shared_goal_fields: bool,
    /// A ground robot outside every collision list whose remaining path has not shortened for
    /// this long re-plans around the robots standing near it (a detour), seconds, > 0;
    /// `None` switches detours off (the model `paper.ron` was calibrated with); default
    /// `Some(3.0)` ([`STALL_REPLAN_S`]).
    pub stall_replan_s: Option<Positive>,
}

impl Default for NavigationParams {
    fn default() -> Self {
        Self {
            grid_cell_m: Positive::known(0.25),
            clearance_m: NonNegative::known(0.1),
            waypoint_tolerance_m: Positive::known(0.3),
            shared_goal_fields: true,
            stall_replan_s: Some(Positive::known(STALL_REPLAN_S)),
        }
    }
}

/// Who in a collision list is held (see `crate::world::resolver` and `docs/world-model.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum HoldRule {
    /// Paper, Algorithm 5: the list's head moves, every other member is held (default). In a
    /// dense crowd the lists grow to hundreds of robots and one robot per list moves.
    #[default]
    ListHead,
    /// For crowds (not from the paper): the members are taken in the list's priority order
    /// (rotated as under `ListHead`); a member moves unless it is about to collide with a
    /// member before it that moves. In a list whose members are all about to collide with
    /// each other this holds the same members as `ListHead`; in a long list every robot with
    /// no conflict ahead of it moves. List members that make no progress also take detours
    /// (`navigation.stall_replan_s`), which they never do under `ListHead`. Rule 3 (followers
    /// join held robots' lists) is skipped: a robot that would hit a held one steers around it
    /// (rule 5).
    /// Reference: greedy conflict resolution in priority order, as in prioritised planning
    /// (Erdmann and Lozano-Perez, "On multiple moving objects", Algorithmica 2, 1987).
    Yield,
}

/// How a moving robot steers around robots standing still (the resolver's rule 5, see
/// `crate::world::resolver` and `docs/world-model.md`, "Steering"). Not from the paper.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Steering {
    /// The default: a robot tries the turns of the side it last steered to first (every
    /// turn of that side, smallest first, then the other side's), forgetting the side when
    /// it drives straight or gets a new path; and a robot deflected or blocked at the rim of
    /// a goal a robot standing still has taken (the goal inside that robot's keep-out,
    /// `r_i + r_j + safety_margin_m`) has reached it when within its goal tolerance of the rim
    /// point nearest the goal. Without both, a robot could slide back and forth along a
    /// keep-out's rim on every control step, and its path depended on `sim.dt_s` (issue 70).
    #[default]
    KeepSide,
    /// Before issue 70 (kept for `paper-v0.ron` and `paper-v1.ron`, which reproduce older
    /// commits): on each control step the first clear turn, right side first at each angle,
    /// with no memory; a goal is reached only within its tolerance.
    Memoryless,
}

/// Priority-based collision avoidance and deadlock solving (paper, section V, Algorithm 5).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct CollisionParams {
    /// Whether the resolver runs (switch off to show what it solves); default `true`.
    pub enabled: bool,
    /// Look-ahead: robots that would come closer than `safety_margin_m` within this time are
    /// "about to collide", seconds, > 0; default 1.0.
    pub lookahead_s: Positive,
    /// Gap kept between bodies, metres, >= 0; default 0.2.
    pub safety_margin_m: NonNegative,
    /// A collision list none of whose members has made progress along its path (remaining path
    /// length down by more than 0.05 m) for this long is a deadlock, seconds, > 0; default 2.0.
    pub deadlock_after_s: Positive,
    /// Who in a collision list is held; default [`HoldRule::ListHead`] (the paper's).
    pub hold_rule: HoldRule,
    /// The order of a collision list: which need ranks a robot; default
    /// [`CollisionPriority::LowestEnergy`].
    pub priority: CollisionPriority,
    /// How a moving robot steers around robots standing still; default
    /// [`Steering::KeepSide`].
    pub steering: Steering,
}

impl Default for CollisionParams {
    fn default() -> Self {
        Self {
            enabled: true,
            lookahead_s: Positive::known(1.0),
            safety_margin_m: NonNegative::known(0.2),
            deadlock_after_s: Positive::known(2.0),
            hold_rule: HoldRule::ListHead,
            priority: CollisionPriority::LowestEnergy,
            steering: Steering::KeepSide,
        }
    }
}

/// Time stepping and seeds.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct SimParams {
    /// Fixed step, seconds, > 0 and at most `mission.duration_s`; default 1/50 s (Unity's fixed
    /// step, against which the paper quotes its per-step costs).
    pub dt_s: Positive,
    /// Base seed of trials (trial `k` uses a seed derived from it and `k`) and default seed of
    /// debris fields; default 0.
    pub seed: u64,
    /// How often the robots' software runs, seconds: a whole number of steps `dt_s`, at least
    /// one step and at most `mission.duration_s`. Every control period the mission's decisions
    /// (rounds, claims, leaving, detection, phases), path following and the collision resolver
    /// run once and each robot's commanded velocity is held until the next; physics and the
    /// per-step costs (energy, HP in radiation) run every step. `None` (default): every step,
    /// the model `paper.ron` was calibrated with. Not from the paper (its Unity scripts ran at
    /// the engine's rate); large teams use a robot controller's rate, e.g. `Some(0.1)` (10 Hz, the
    /// default control step of the ARGoS swarm simulator). Turned into steps once, by
    /// `world::ControlClock::of`. See `docs/world-model.md`, "Control period".
    pub control_period_s: Option<Positive>,
    /// When Rapier steps the bodies; default `EveryStep` ([`PhysicsStepping`]).
    pub physics: PhysicsStepping,
}

impl Default for SimParams {
    fn default() -> Self {
        Self {
            dt_s: Positive::known(1.0 / 50.0),
            seed: 0,
            control_period_s: None,
            physics: PhysicsStepping::EveryStep,
        }
    }
}

/// Weights of the 7-entry needs vector `(hp, v, sen, eng, res, cap, obs)` (paper, Eqs. 19-21,
/// Alg. 4: `V = N x W`), each > 0, each defaulting to 1.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct NeedsWeights {
    /// Health points.
    pub hp: Positive,
    /// Speed.
    pub v: Positive,
    /// Sensing range.
    pub sen: Positive,
    /// Energy.
    pub eng: Positive,
    /// Rescuing resources.
    pub res: Positive,
    /// Carrying capacity.
    pub cap: Positive,
    /// Observing range.
    pub obs: Positive,
}

impl Default for NeedsWeights {
    fn default() -> Self {
        let one = Positive::known(1.0);
        Self {
            hp: one,
            v: one,
            sen: one,
            eng: one,
            res: one,
            cap: one,
            obs: one,
        }
    }
}

impl NeedsWeights {
    /// The weights in the needs vector's order `[hp, v, sen, eng, res, cap, obs]`.
    pub fn to_array(&self) -> [f64; 7] {
        [
            self.hp, self.v, self.sen, self.eng, self.res, self.cap, self.obs,
        ]
        .map(Positive::get)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Percent per minute charged by a per-paper-step `rate` on 0.02 s and 0.1 s steps alike.
    fn pct_per_minute(rate: NonNegative) -> [f64; 2] {
        [0.02, 0.1].map(|dt_s| MissionParams::per_paper_step(rate, dt_s) * 60.0 / dt_s)
    }

    /// The effects the docs state for the defaults (`docs/scenario-format.md`, Mission).
    #[test]
    fn default_costs_are_those_the_docs_state_per_minute() {
        let m = MissionParams::default();
        for got in pct_per_minute(m.energy_pct_per_moving_step) {
            assert!((got - 13.5).abs() < 1e-9, "energy {got} % per minute");
        }
        for got in pct_per_minute(m.hp_pct_per_step_in_radiation) {
            assert!((got - 0.9).abs() < 1e-9, "HP {got} % per minute");
        }
        // paper.ron's HP rate, 16.5 % per minute: 3000 x.
        for got in pct_per_minute(NonNegative::known(0.0055)) {
            assert!((got - 16.5).abs() < 1e-9, "paper HP {got} % per minute");
        }
    }
}
