//! A robot's 7-entry needs vector (hp, v, sen, eng, res, cap, obs) from its current state
//! (paper, Eqs. 19-21 and section VI.B).

use rne_core::NeedsVector;

use crate::scenario::{HpEffect, MissionParams, RobotKind};

/// Index of each entry of the needs vector, in the paper's order (Eqs. 19-21).
pub mod entry {
    /// Health points.
    pub const HP: usize = 0;
    /// Speed.
    pub const V: usize = 1;
    /// Sensing range.
    pub const SEN: usize = 2;
    /// Energy (battery).
    pub const ENG: usize = 3;
    /// Rescuing resources.
    pub const RES: usize = 4;
    /// Carrying capacity.
    pub const CAP: usize = 5;
    /// Observing range.
    pub const OBS: usize = 6;
}

/// How HP scales a robot's speed, sensing range and observing range (paper, section VI.B:
/// "the lower its HP, the smaller its velocity, sensing, and observing range"), in `[0, 1]`.
///
/// The paper gives no function; `mission.hp_effect` chooses one ([`HpEffect`]):
/// - `Linear` (default): `f(hp) = hp_pct / 100` clamped to `[min_hp_factor, 1]`: a robot at
///   90 % HP moves at 90 % of its kind's top speed, and none drops below
///   `mission.min_hp_factor` (0 lets a robot at 0 % HP stop dead);
/// - `Threshold { below_pct, factor }`: 1 while `hp_pct >= below_pct`, else `factor`;
/// - `NoEffect`: 1.
///
/// See `docs/mission-model.md`.
pub fn hp_factor(mission: &MissionParams, hp_pct: f64) -> f64 {
    match mission.hp_effect {
        HpEffect::Linear => (hp_pct / 100.0)
            .clamp(0.0, 1.0)
            .max(mission.min_hp_factor.get()),
        HpEffect::Threshold { below_pct, factor } => {
            if hp_pct >= below_pct.get() {
                1.0
            } else {
                factor.get()
            }
        }
        HpEffect::NoEffect => 1.0,
    }
}

/// The needs vector of a robot of `kind` at `hp_pct` and `energy_pct` (both in `[0, 100]`),
/// with `resources` rescuing resources and `capacity` free carrying capacity left, under the
/// mission's HP effect (see [`hp_factor`]).
///
/// Entries (paper, Eqs. 19-21, ratios of section VI.B through the kind's fields):
/// `hp = hp_needs_full * hp_pct/100`, `v = max_speed_m_per_s * f(hp)`,
/// `sen = sensing_range_m * f(hp)`, `eng = energy_needs_full * energy_pct/100`,
/// `res = resources`, `cap = capacity`, `obs = observing_range_m * f(hp)`, with `f` =
/// [`hp_factor`]. Units are mixed (that is the paper's model); the needs distribution
/// normalises them with the scenario's weights.
///
/// # Panics
/// If `hp_pct` or `energy_pct` is NaN (levels outside `[0, 100]` are clamped); the mission
/// keeps both finite. The kind must be validated (its fields finite and positive).
pub fn needs_vector(
    kind: &RobotKind,
    mission: &MissionParams,
    hp_pct: f64,
    energy_pct: f64,
    resources: u32,
    capacity: u32,
) -> NeedsVector {
    let f = hp_factor(mission, hp_pct);
    let values = vec![
        kind.hp_needs_full * hp_pct.clamp(0.0, 100.0) / 100.0,
        kind.max_speed_m_per_s * f,
        kind.sensing_range_m * f,
        kind.energy_needs_full * energy_pct.clamp(0.0, 100.0) / 100.0,
        f64::from(resources),
        f64::from(capacity),
        kind.observing_range_m * f,
    ];
    // Every entry is finite and non-negative: the kind was validated (positive, finite fields)
    // and the levels are clamped above.
    NeedsVector::new(values).expect("needs entries are finite and non-negative by construction")
}
