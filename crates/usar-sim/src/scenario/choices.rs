//! The rules the paper leaves open, one switch each: every enum here is a reading of the
//! paper's words that a scenario chooses (`mission.*`, `collision.priority`,
//! `mission.initial_*.outside_range`). Each documents the paper's words, its alternatives and
//! its default; `docs/mission-model.md` says what each does, and `docs/multiverse.md` how the
//! paper's claims move with them. Defaults are the model before calibration
//! (`scenarios/paper-v0.ron`), so a scenario that names none of them runs as it always did.

use serde::{Deserialize, Serialize};

use super::numbers::{Fraction, Percent};

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

/// Which tasks' quotas shrink when robots of a kind are away at a round's start (paper silent;
/// see `docs/mission-model.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum AwayQuotas {
    /// The tasks are filled from the hardest down; the easiest take what is left (default).
    #[default]
    HardestFirst,
    /// The tasks are filled from the easiest up; the hardest take what is left.
    EasiestFirst,
    /// The shortfall is shared: one robot at a time is taken from the task whose quota is
    /// currently largest (ties: from the easiest of them).
    Even,
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

/// The lawn-mower pattern of a blind group's search (paper silent; see `mission::sweep_waypoints`
/// and "Searching" in `docs/mission-model.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SweepPattern {
    /// Each row runs from the search area's left edge to its right edge, and a robot turns at
    /// a row's end itself, not within `navigation.waypoint_tolerance_m` of it: the robot
    /// passes within `sweep_spacing_m / 2` of every point of the area (default).
    #[default]
    EdgeToEdge,
    /// The pattern before 2026-11-24, kept so that `scenarios/paper-v0.ron` reproduces its
    /// commit: a row ends at the centre of its outer columns, a robot turns within the
    /// waypoint tolerance of it, and the pattern's last waypoint is assigned but not driven
    /// to. It misses rescuees in a strip up to `sweep_spacing_m / 2 + waypoint_tolerance_m`
    /// wide along the area's left and right edges.
    CentreToCentre,
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

/// How HP scales a robot's speed, sensing range and observing range (paper, section VI.B:
/// "the lower its HP, the smaller its velocity, sensing, and observing range"; it gives no
/// function). See `mission::hp_factor`.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub enum HpEffect {
    /// `f(hp) = max(hp_pct / 100, mission.min_hp_factor)`: proportional to HP (default).
    #[default]
    Linear,
    /// Full capability while HP is at least `below_pct`; `factor` below it (a robot that is
    /// "damaged" works at a reduced rate). Written `Threshold(below_pct: 50.0, factor: 0.5)`.
    Threshold {
        /// HP below which the robot is slowed, percent, in `[0, 100]`.
        below_pct: Percent,
        /// Its speed, sensing and observing factor below `below_pct`, in `[0, 1]`.
        factor: Fraction,
    },
    /// HP changes none of the three (`f = 1`): HP matters only through the low-HP rule.
    NoEffect,
}

/// When a robot whose energy or HP fell below its threshold (`mission.low_energy_pct`,
/// `low_hp_pct`) leaves for the rest station (paper, section VI.B: "if the individual battery
/// (energy) or HP level is below 30%, it needs to go to the pre-defined rest position for
/// recharging energy (or for refreshing its health HP) 30 seconds, then back to the initial
/// position waiting for the next round to start").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum LeaveWhenLow {
    /// At once, wherever it is: a robot mid-trip leaves its group (and its load, by
    /// `mission.load_on_leave`) (default).
    #[default]
    AtOnce,
    /// When it is back at its start position: a robot finishes its round's trip with its group,
    /// then goes to the rest station instead of waiting for the next round. A robot below a
    /// threshold at the trial's start leaves at once (it is at its start).
    AfterTrip,
}

/// When a rescuee counts as rescued, for its task and its round (paper, section VI.A: "the
/// total number of resources the robot groups have rescued in both the tasks").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RescuedAt {
    /// When it is delivered at its task's drop-off (default): a load abandoned by a leaving
    /// robot, or still carried when the trial ends, does not count.
    #[default]
    DropOff,
    /// When a robot picks it up (secures it): every rescue counts, whatever becomes of the
    /// load afterwards.
    PickUp,
}

/// Which robot of a collision list moves first (paper, Algorithm 5: the list is "sorted based
/// on agent's needs", without naming the need). Ties are broken by robot id.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum CollisionPriority {
    /// The robot with the least energy first (default: energy is the basic need the paper
    /// names first).
    #[default]
    LowestEnergy,
    /// The robot with the least HP first (HP is the first of the safety needs).
    LowestHp,
    /// A fixed order, by robot id: the needs play no part.
    RobotId,
}

/// What happens to an initial-level draw outside `[min_pct, max_pct]` (paper, section VI.B:
/// levels "sampled from two Gaussian distributions with means of 80% and 90%, and standard
/// deviations of 20% and 10%"; a percent level must lie in `[0, 100]`, and the paper does not
/// say how).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum OutsideRange {
    /// Clamped to the nearest bound (default): N(80, 20) puts 16 % of the energy draws at
    /// exactly 100 %.
    #[default]
    Clamp,
    /// Drawn again until it lies inside (a truncated normal); after
    /// [`MAX_REDRAWS`] draws outside, the last one is clamped.
    Redraw,
}

/// Most draws [`OutsideRange::Redraw`] takes for one level before it clamps (a range far in
/// the tail of the normal would otherwise take very long).
pub const MAX_REDRAWS: u32 = 1000;

/// When a group's search time budget (`mission.search_time_budget_s`) starts to run (the paper
/// does not say what ends a trip; a budget is our reading of its per-round yields, see
/// `docs/calibration.md`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum SearchClock {
    /// When the group's first ground member enters the search area (default): every group
    /// searches for the budget, however long its way out.
    #[default]
    FirstArrival,
    /// When every member of the group still in it (its observer included) has entered the
    /// search area: the group searches together for the budget once it is assembled, and
    /// members held up on the way (debris, other robots, a slow observer) do not shorten the
    /// others' search.
    LastArrival,
    /// When the round starts: the budget boxes the way out and the search together, so a group
    /// that is slower or farther away searches for less time.
    RoundStart,
}

/// Where a robot whose energy or HP fell below its threshold recharges (paper, section VI.B:
/// "it needs to go to the pre-defined rest position for recharging energy (or for refreshing
/// its health HP) 30 seconds, then back to the initial position").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RestAt {
    /// At a rest station (`rest_station`), the one nearest by path, in the first station disc
    /// it enters (default; the paper's model).
    #[default]
    RestStation,
    /// At its own start position, as a robot docking at its own charger: it drives home and
    /// recharges there for `mission.recharge_s`. No crowd forms at a station: in a team of
    /// 10,000, hundreds of robots converging on a few stations stood in the way of the robots
    /// going home, and rounds never completed (`scenarios/swarm-10000.ron`,
    /// `docs/scaling.md`).
    OwnStart,
}

/// Where a member carrying nothing goes when its group leaves the search area
/// (`docs/mission-model.md`, "Leaving the search area"). Not in the paper, which sends the
/// group to the drop-off and back and does not say whether an empty member makes the detour.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EmptyOnLeave {
    /// With its group, to the task's drop-off, and from there to its start (default; the model
    /// of the paper's scenarios).
    #[default]
    ViaDropOff,
    /// Straight back to its start. Members that carry rescuees still go to the drop-off. In a
    /// group of a thousand members drawn from a wide start area, empty members sent to the
    /// drop-off crossed the arena and met the loaded ones head-on (`scenarios/swarm-10000.ron`,
    /// `docs/scaling.md`).
    StraightToStart,
}

/// What a ground member with nothing to claim does before it has come within reach of its
/// task's search area (`MissionRobot::reached_area`). A member may claim a known rescuee on
/// its way and finish or lose the claim there (a claim is released when the member makes no
/// progress to it), and then has nothing to do. Not in the paper, which does not say.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum IdleBeforeArea {
    /// It stops and waits where it stands until its group leaves (default; the model of the
    /// paper's scenarios).
    #[default]
    Wait,
    /// It drives on to its task's goal and waits only once within reach of the search area.
    /// In a group of a thousand members, members standing on the way to the area block the
    /// others (`scenarios/swarm-10000.ron`, `docs/scaling.md`).
    GoToArea,
}

/// When Rapier steps the bodies (`sim.physics`). Robots are frictionless discs driven at a
/// commanded velocity; Rapier's part is the contacts that keep them out of walls, debris and
/// each other. Not in the paper (its Unity engine stepped its physics every frame).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum PhysicsStepping {
    /// Every step (default; the model of every scenario before this option).
    #[default]
    EveryStep,
    /// Only on a step where a contact may begin or go on: some robot within the distance both
    /// bodies can close in one step, plus Rapier's contact prediction distance and
    /// [`crate::world::NEAR_CONTACT_MARGIN_M`], of a wall, debris (ground robots) or another
    /// robot of its layer. On the other steps every robot moves straight at its commanded
    /// velocity, as Rapier moves a body with no contact in reach (up to the rounding of
    /// Rapier's four substeps), and Rapier's bodies are set to the new positions. In
    /// `paper.ron` 0.35 % of the steps are near a contact: a trial costs less than half
    /// (`docs/scaling.md`, "Physics only near contacts", with the effect on the calibration
    /// statistics).
    NearContacts,
    /// Per body: Rapier steps only the robots near a contact (as in `NearContacts`, both robots
    /// of a pair within reach of each other, or a robot within reach of a wall or debris); every
    /// other robot moves straight at its commanded velocity and its body is disabled in Rapier
    /// (out of the solver and the broad phase) until it comes near a contact again. Rapier
    /// steps only when some robot is near a contact. For large teams, where some robot is
    /// almost always near a contact but most are not (`scenarios/swarm-1000.ron`,
    /// `docs/scaling.md`, "Physics only near contacts").
    NearBodies,
}
