//! Rule 5's candidate headings and its look-ahead against walls and debris.
//!
//! The turns a moving robot's intent is deflected by, in the order they are tried, and how
//! far a deflected heading is checked against walls and debris (the turn itself is
//! `Resolver::steer`), and the nearby robots a heading is tested against ([`NearRobot`]).

use parry2d::math::Vector as Vec2;

use super::collision_course::about_to_collide;

/// Step between candidate steering headings, radians (15 degrees).
pub const STEER_ANGLE_STEP_RAD: f32 = std::f32::consts::PI / 12.0;
/// Number of candidate deflections per side (8 x 15 = 120 degrees).
pub const STEER_STEPS_PER_SIDE: u32 = 8;
/// How far ahead a deflected heading is checked against walls and debris, metres (at most).
pub const STEER_STATIC_LOOKAHEAD_M: f32 = 0.25;
/// Gap to walls and debris a deflected heading must keep (beyond the body radius), metres.
pub const STEER_STATIC_GAP_M: f32 = 0.05;

/// The candidate turns of rule 5 in the order they are tried, as `(sin, cos)` of
/// `sign * k * STEER_ANGLE_STEP_RAD` for `k` in `1..=STEER_STEPS_PER_SIDE` and `sign` in
/// `[-1, 1]` (right side first): computed once, the same `f32` values as computing them per
/// robot and step.
pub(super) fn steer_turns() -> &'static [(f32, f32)] {
    static TURNS: std::sync::OnceLock<Vec<(f32, f32)>> = std::sync::OnceLock::new();
    TURNS.get_or_init(|| {
        (1..=STEER_STEPS_PER_SIDE)
            .flat_map(|k| {
                [-1.0f32, 1.0].map(|sign| (sign * k as f32 * STEER_ANGLE_STEP_RAD).sin_cos())
            })
            .collect()
    })
}

/// A robot near the steering one as rule 5 (section V of the paper, the resolver's steering)
/// tests headings against it: an entry of [`Resolver::steer_with`]'s scratch list, filled by
/// it (fields private). Taken once per steering robot instead of once per heading tried: the
/// same values and the same operations on them, so the same answer, bit for bit.
///
/// [`Resolver::steer_with`]: super::resolver::Resolver::steer_with
#[derive(Debug, Clone, Copy)]
pub struct NearRobot {
    /// Its position relative to the steering robot's (world frame), metres.
    offset_m: Vec2,
    /// Whether it stands still (held, inactive or without intent): its velocity counts as 0.
    still: bool,
    /// Its intended velocity (world frame), metres per second; read only when it moves.
    intent: Vec2,
    /// The distance the two bodies must keep: both radii plus the safety margin, metres.
    clearance_m: f32,
}

impl NearRobot {
    /// A robot at `offset_m` from the steering one (metres, world frame), standing `still` or
    /// moving at `intent` (metres per second), to be kept `clearance_m` metres away.
    pub(super) fn new(offset_m: Vec2, still: bool, intent: Vec2, clearance_m: f32) -> Self {
        Self {
            offset_m,
            still,
            intent,
            clearance_m,
        }
    }

    /// Whether heading `w` (metres per second) of the steering robot is clear of this one
    /// within `horizon_s` seconds ([`about_to_collide`]): against its velocity 0 if it stands
    /// still, against its intent if it moves and `w` is `deflected` (under
    /// `collision.steering: KeepSide` a deflected heading may turn further than rule 1's pair
    /// test saw), and always clear if it moves and `w` is the steering robot's own intent.
    pub(super) fn clear_of(&self, w: Vec2, deflected: bool, horizon_s: f32) -> bool {
        let v = if self.still {
            Vec2::ZERO
        } else if deflected {
            self.intent
        } else {
            return true;
        };
        !about_to_collide(self.offset_m, v - w, self.clearance_m, horizon_s)
    }
}

/// How many more turn steps ([`STEER_ANGLE_STEP_RAD`]) a robot turns to the side it last
/// steered to than the other side would need, at most, before it changes side (3 x 15 = 45
/// degrees). Keeping to its side, a robot slides along an obstacle one way instead of turning
/// back and forth on every control step (which gained nothing and made its path depend on the
/// step length); bounding it keeps its turns near the smallest clear one, as the resolver's
/// pair test (rule 1, on intents) assumes. `docs/world-model.md`, "Steering side".
pub const STEER_SIDE_HYSTERESIS_STEPS: usize = 3;

/// Rule 5's turn for a robot with steering side `side` (`0`: none, `< 0`: it last turned
/// right, `> 0`: left), as `(sin, cos)` of the turn, given `clear`, which says whether a turn
/// is clear (called at most once per turn, in order of size): without a side, the smallest
/// clear turn, right side first at each angle ([`steer_turns`]'s order); with one, the
/// smallest clear turn of that side unless the other side has a clear turn more than
/// [`STEER_SIDE_HYSTERESIS_STEPS`] steps smaller, which is then taken. `None` when no turn is
/// clear.
pub(super) fn pick_turn(
    side: f32,
    mut clear: impl FnMut((f32, f32)) -> bool,
) -> Option<(f32, f32)> {
    let turns = steer_turns();
    if side == 0.0 {
        return turns.iter().copied().find(|&t| clear(t));
    }
    let own = usize::from(side > 0.0);
    let other_side = 1 - own;
    let mut other: Option<usize> = None;
    for k in 0..STEER_STEPS_PER_SIDE as usize {
        if other.is_some_and(|o| k > o + STEER_SIDE_HYSTERESIS_STEPS) {
            break;
        }
        if clear(turns[2 * k + own]) {
            return Some(turns[2 * k + own]);
        }
        if other.is_none() && clear(turns[2 * k + other_side]) {
            other = Some(k);
        }
    }
    other.map(|o| turns[2 * o + other_side])
}

/// Whether `clear(k)` holds for every `k` in `0..len`, testing first the index `hint` holds
/// (the one that failed the last time), then the others in order; a failing index is kept in
/// `hint`. The answer is that of testing `0..len` in order (a conjunction of calls without side
/// effects), only found sooner when failures repeat: rule 5's headings 15 degrees apart are
/// mostly blocked by the same robot.
pub(super) fn all_clear_hinted(
    len: usize,
    hint: &std::cell::Cell<Option<usize>>,
    clear: impl Fn(usize) -> bool,
) -> bool {
    let first = hint.get().filter(|&k| k < len);
    if first.is_some_and(|k| !clear(k)) {
        return false;
    }
    let blocker = (0..len).find(|&k| Some(k) != first && !clear(k));
    if blocker.is_some() {
        hint.set(blocker);
    }
    blocker.is_none()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The turn `pick_turn` takes for `side` when exactly the turns of `clear_deg` (degrees,
    /// right negative) are clear, in degrees.
    fn pick(side: f32, clear_deg: &[i32]) -> Option<i32> {
        let deg = |(s, c): (f32, f32)| s.atan2(c).to_degrees().round() as i32;
        let mut asked = Vec::new();
        let turn = pick_turn(side, |t| {
            asked.push(deg(t));
            clear_deg.contains(&deg(t))
        });
        let mut unique = asked.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), asked.len(), "each turn asked once: {asked:?}");
        turn.map(deg)
    }

    /// The hinted conjunction answers as the plain one for every set of failing indices and
    /// hint, and remembers a failing index.
    #[test]
    fn a_hinted_conjunction_answers_as_the_plain_one() {
        for mask in 0u32..64 {
            let clear = |k: usize| mask & (1 << k) == 0;
            for start in [None, Some(0), Some(3), Some(5), Some(9)] {
                let hint = std::cell::Cell::new(start);
                let plain = (0..6).all(clear);
                assert_eq!(all_clear_hinted(6, &hint, clear), plain, "mask {mask:b}");
                if !plain {
                    assert!(hint.get().is_some_and(|k| !clear(k)), "mask {mask:b}");
                }
            }
        }
    }

    #[test]
    fn without_a_side_the_smallest_clear_turn_right_first() {
        assert_eq!(pick(0.0, &[30, -30, 90]), Some(-30));
        assert_eq!(pick(0.0, &[45, -60]), Some(45));
        assert_eq!(pick(0.0, &[]), None);
    }

    #[test]
    fn a_side_is_kept_unless_the_other_is_more_than_the_hysteresis_nearer() {
        // Left side kept against a right turn up to 45 degrees smaller.
        assert_eq!(pick(1.0, &[-30, 75]), Some(75));
        assert_eq!(pick(1.0, &[-15, 60]), Some(60));
        // More than 45 degrees smaller: the right turn.
        assert_eq!(pick(1.0, &[-15, 75]), Some(-15));
        // Right side kept likewise.
        assert_eq!(pick(-1.0, &[15, -45]), Some(-45));
        assert_eq!(pick(-1.0, &[15, -90]), Some(15));
        // Nothing on its side: the other side's smallest.
        assert_eq!(pick(-1.0, &[30, 120]), Some(30));
        assert_eq!(pick(1.0, &[]), None);
    }
}
