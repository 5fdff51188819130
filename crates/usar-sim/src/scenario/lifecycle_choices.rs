//! The round and rest lifecycle's switches (`mission.round_clock`, `mission.rest_timing`,
//! `mission.resource_stock`) and the cost clock's (`mission.cost_clock`,
//! `mission.costs_count`): readings of the paper's rounds and costs that the authors' results
//! sheet points to (issue 71, docs/calibration.md, "The authors' clock" and "A rule that
//! couples the tasks"). Defaults keep the model before them, so a scenario that names none
//! runs as it always did. The systems that apply them: `mission::round_clock`,
//! `mission::rest` and `mission::account` (and for `resource_stock` also `mission::decide`'s
//! pools and `mission::grouping`'s snapshot).

use serde::{Deserialize, Serialize};

use super::numbers::Positive;

/// What ends a round (paper, section VI.B: "After each round, when all agents are back to the
/// initial position, the whole group members will regroup"; how long a round may last is not
/// said). The authors' sheet has 6 rounds in 33 of its 40 trials of 600 s: a round timer.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub enum RoundClock {
    /// A round lasts until every robot still in a group is back at its start (default; the
    /// model before this switch).
    #[default]
    AllBack,
    /// A round lasts at most `length_s` plus the recall trip. `length_s` after its start the
    /// groups still out are recalled: each leaves its search area as when its search ends
    /// (`LeaveCause::RoundTimer`): a member with a load carries it to the task's drop-off,
    /// where it counts, then drives home; an empty member goes home by
    /// `mission.empty_on_leave`. A robot away for its needs (going to rest, resting, or back
    /// from it) goes on as it was. The round closes early when every group is back (as
    /// `AllBack`). Written `Timer(length_s: 100.0)`.
    Timer {
        /// Seconds from a round's start to the recall of its groups, > 0.
        length_s: Positive,
    },
}

/// When a robot below a threshold rests, relative to its round (paper, section VI.B: "it needs
/// to go to the pre-defined rest position for recharging energy (or for refreshing its health
/// HP) 30 seconds, then back to the initial position waiting for the next round to start").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum RestTiming {
    /// A robot that leaves for a rest leaves its round: its round closes without waiting for
    /// its rest, and `mission.leave_when_low` says when it leaves (default; the model before
    /// this switch).
    #[default]
    OutOfRound,
    /// The rest is taken in its round's slack: a robot below a threshold finishes its trip
    /// with its group (as `leave_when_low: AfterTrip`, whatever that field says), then rests
    /// (`mission.rest_at`, `mission.recharge_s`) and comes back to its start while its round
    /// is still open: the round closes early only once its rests are over too. Under
    /// `round_clock: Timer` the timer bounds the wait: a round whose time is up closes when its
    /// groups are back, and a robot whose rest is not over then waits for the round after.
    InSlack,
}

/// The clock the per-step costs run on (`mission.energy_pct_per_moving_step`,
/// `mission.hp_pct_per_step_in_radiation`; paper, section VI.B: "each agent costs 0.0045%
/// energy (battery point) for every moving step ... its HP will cost 0.0003% per step"). The
/// per-metre cost (`mission.energy_pct_per_m`) is charged on either clock.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize)]
pub enum CostClock {
    /// A step is the paper's fixed step of 1/50 s (`PAPER_STEP_S`): a simulation step of
    /// `dt_s` is charged `rate * dt_s / 0.02` (default; the model before this switch).
    #[default]
    PaperStep,
    /// A step is a rendered frame at `steps_per_s` frames per second (the authors' Unity code
    /// charges in its per-frame update): a simulation step of `dt_s` is charged
    /// `rate * dt_s * steps_per_s`. The sheet's 356 energy points per robot and trial come out
    /// of 0.0045 % per step only at about 130 frames per second or more
    /// (docs/calibration.md). Written `Frames(steps_per_s: 130.0)`.
    Frames {
        /// Frames per simulated second, > 0.
        steps_per_s: Positive,
    },
}

/// Which of a robot's costs count in the trial's metrics (`energy_*_pct`, `hp_*_pct`; every
/// cost is charged to the robot's levels whichever is chosen). The sheet does not say.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum CostsCount {
    /// Only while the robot is in a group (from its round's start until it leaves the group
    /// or the round closes), for that group's task (default; the model before this switch).
    #[default]
    InGroup,
    /// Every cost, the trips to and from the rest place and the rest included, for the task
    /// of the robot's latest group; a robot that has not been in a group yet counts for none.
    Every,
}

/// Where a group's rescuing resources come from (paper, section IV: "saving one rescued object
/// will cost one space (capacity) and one rescuing resource ... group members can share their
/// resources in the specific task"; when a robot's resources are refilled is not said). The
/// authors' sheet has the hard and easy yields of a trial trade off (r = -0.48) with totals
/// under-dispersed (variance / mean 0.15): the two tasks share something bounded
/// (docs/calibration.md, "A rule that couples the tasks").
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum ResourceStock {
    /// Every member of a round's group starts it with its kind's `rescuing_resources`, and a
    /// group draws on its members' (default; the model before this switch).
    #[default]
    PerRound,
    /// A robot's resources are refilled only when its rest ends (and held at its kind's
    /// `rescuing_resources` at the trial's start); a group draws on what its members hold, so
    /// a group of suppliers that rescued much in the last rounds and have not rested since
    /// rescues less.
    AtRest,
    /// One stock of `units` resources for the whole team per round, drawn by both groups' pick-
    /// ups, first come first served; the members' own resources are not used. A group leaves
    /// its area when the stock is spent (`LeaveCause::ResourcesUsed`). Written
    /// `TeamPerRound(units: 25)`; `units` >= 0.
    TeamPerRound {
        /// Resources the team holds at each round's start.
        units: u32,
    },
}
