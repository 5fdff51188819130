//! What a replay records per robot ([`Channel`]) and per rescuee ([`RescueeCode`]), and how
//! each value is quantised to an integer.

use usar_sim::mission::{MissionRobot, Phase, RescueeStatus};
use usar_sim::world::{Motion, RobotState};

/// One recorded quantity of every robot at every sample, as an integer: the value divided by
/// [`Channel::quantum`], rounded to nearest. The order of [`Channel::ALL`] is the order of the
/// encoded stream and of the page's arrays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Channel {
    /// Position x, world frame, centimetres.
    XCm,
    /// Position y, world frame, centimetres.
    YCm,
    /// Energy, hundredths of a percent (0..=10 000).
    EnergyCentiPct,
    /// HP, hundredths of a percent (0..=10 000).
    HpCentiPct,
    /// The mission phase, [`phase_code`].
    Phase,
    /// The task (id) of the robot's group plus one; 0 when in no group (between rounds, resting).
    Group,
    /// Rescuees carried.
    Load,
    /// [`StateFlags`] bits.
    Flags,
    /// Needs vector entry `i` (hp, v, sen, eng, res, cap, obs; paper Eqs. 19-21), thousandths.
    Needs(usize),
}

/// Entries of the needs vector (paper, Eqs. 19-21).
pub const NEEDS_ENTRIES: usize = 7;

impl Channel {
    /// Every channel, in stream order.
    pub const ALL: [Channel; 8 + NEEDS_ENTRIES] = [
        Channel::XCm,
        Channel::YCm,
        Channel::EnergyCentiPct,
        Channel::HpCentiPct,
        Channel::Phase,
        Channel::Group,
        Channel::Load,
        Channel::Flags,
        Channel::Needs(0),
        Channel::Needs(1),
        Channel::Needs(2),
        Channel::Needs(3),
        Channel::Needs(4),
        Channel::Needs(5),
        Channel::Needs(6),
    ];

    /// The channel's name in the page's data (`x_cm`, `needs_3`, ...).
    pub fn name(self) -> String {
        match self {
            Channel::XCm => "x_cm".into(),
            Channel::YCm => "y_cm".into(),
            Channel::EnergyCentiPct => "energy_centi_pct".into(),
            Channel::HpCentiPct => "hp_centi_pct".into(),
            Channel::Phase => "phase".into(),
            Channel::Group => "group".into(),
            Channel::Load => "load".into(),
            Channel::Flags => "flags".into(),
            Channel::Needs(i) => format!("needs_{i}"),
        }
    }

    /// The value of one integer step of the channel, in its quantity's unit (metres, percent,
    /// needs units; 1 for codes).
    pub fn quantum(self) -> f64 {
        match self {
            Channel::XCm | Channel::YCm | Channel::EnergyCentiPct | Channel::HpCentiPct => 0.01,
            Channel::Needs(_) => 0.001,
            _ => 1.0,
        }
    }

    /// Index of the channel in [`Channel::ALL`].
    pub fn index(self) -> usize {
        match self {
            Channel::Needs(i) => 8 + i.min(NEEDS_ENTRIES - 1),
            c => Channel::ALL.iter().position(|&x| x == c).unwrap_or(0),
        }
    }
}

/// `value / quantum` rounded to nearest and saturated to `i32`.
pub fn quantise(value: f64, quantum: f64) -> i32 {
    let q = (value / quantum).round();
    if q.is_nan() {
        0
    } else {
        q.clamp(f64::from(i32::MIN), f64::from(i32::MAX)) as i32
    }
}

/// Names of the phase codes, by code (the page shows them; see [`phase_code`]).
pub const PHASE_NAMES: [&str; 9] = [
    "AtStart",
    "ToSearchArea",
    "Searching",
    "Waiting",
    "ToDropOff",
    "ToStart",
    "ToRest",
    "Recharging",
    "RestToStart",
];

/// The code of a mission phase: its index in [`PHASE_NAMES`].
pub fn phase_code(p: Phase) -> i32 {
    match p {
        Phase::AtStart => 0,
        Phase::ToSearchArea => 1,
        Phase::Searching => 2,
        Phase::Waiting => 3,
        Phase::ToDropOff => 4,
        Phase::ToStart => 5,
        Phase::ToRest => 6,
        Phase::Recharging { .. } => 7,
        Phase::RestToStart => 8,
    }
}

/// Bits of the [`Channel::Flags`] channel: what a robot's phase alone does not say.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StateFlags;

impl StateFlags {
    /// Delivering its load first on its way to the rest station (`MissionRobot::leaving`).
    pub const LEAVING: i32 = 1;
    /// Standing by its claimed rescuee, rescuing it (`mission.pickup_s`).
    pub const PICKING: i32 = 2;
    /// Driving to a claimed rescuee.
    pub const CLAIM: i32 = 4;
    /// Held by the collision resolver (paper, Algorithm 5).
    pub const HELD: i32 = 8;
    /// Every heading would collide within the look-ahead: standing still.
    pub const BLOCKED: i32 = 16;
    /// A member of a collision list.
    pub const IN_LIST: i32 = 32;

    /// The flags of a robot from its mission and world state.
    pub fn of(m: &MissionRobot, w: &RobotState) -> i32 {
        let mut f = 0;
        if m.leaving {
            f |= Self::LEAVING;
        }
        if m.picking_until_s.is_some() {
            f |= Self::PICKING;
        }
        if m.claim.is_some() {
            f |= Self::CLAIM;
        }
        if w.motion == Motion::Held {
            f |= Self::HELD;
        }
        if w.motion == Motion::Blocked {
            f |= Self::BLOCKED;
        }
        if w.in_collision_list {
            f |= Self::IN_LIST;
        }
        f
    }
}

/// What has become of a rescuee, as the page draws it: lying in its area (waiting, claimed,
/// skipped, unreachable) or gone (carried, delivered, abandoned).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RescueeCode {
    /// Lying in its area, free to be claimed.
    Waiting = 0,
    /// Claimed by a robot driving to it.
    Claimed = 1,
    /// Carried by a robot (not drawn).
    Carried = 2,
    /// Delivered (not drawn).
    Delivered = 3,
    /// Abandoned by a robot that left to recharge (not drawn).
    Abandoned = 4,
    /// Out of reach (inside inflated debris).
    Unreachable = 5,
    /// A claim on it expired; waits again from the next round on.
    Skipped = 6,
}

impl RescueeCode {
    /// The code of a rescuee with `status`.
    pub fn of(status: RescueeStatus) -> Self {
        match status {
            RescueeStatus::Waiting => Self::Waiting,
            RescueeStatus::Claimed(_) => Self::Claimed,
            RescueeStatus::Carried(_) => Self::Carried,
            RescueeStatus::Delivered => Self::Delivered,
            RescueeStatus::Abandoned => Self::Abandoned,
            RescueeStatus::Unreachable => Self::Unreachable,
            RescueeStatus::Skipped => Self::Skipped,
        }
    }

    /// Names of the codes, by code (for the page).
    pub const NAMES: [&'static str; 7] = [
        "waiting",
        "claimed",
        "carried",
        "delivered",
        "abandoned",
        "unreachable",
        "skipped",
    ];
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn channels_are_indexed_in_stream_order() {
        for (i, c) in Channel::ALL.iter().enumerate() {
            assert_eq!(c.index(), i, "{}", c.name());
        }
    }

    #[test]
    fn quantising_rounds_to_nearest_and_saturates() {
        assert_eq!(quantise(1.234, 0.01), 123);
        assert_eq!(quantise(-1.235_1, 0.01), -124);
        assert_eq!(quantise(1e300, 0.01), i32::MAX);
        assert_eq!(quantise(f64::NAN, 0.01), 0);
    }
}
