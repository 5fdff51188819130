//! Rule 5's candidate headings and its look-ahead against walls and debris.
//!
//! The turns a moving robot's intent is deflected by, in the order they are tried, and how
//! far a deflected heading is checked against walls and debris (the turn itself is
//! `Resolver::steer`).

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

/// The candidate turns of rule 5 in the order a robot with steering side `side` tries them:
/// [`steer_turns`]'s order (right, left, at each angle in turn) for `side == 0`; for a robot
/// that last turned right (`side < 0`) every right turn from the smallest first, then every
/// left turn; for one that last turned left (`side > 0`) the reverse. Keeping to the side it
/// turned to, a robot slides along an obstacle one way instead of turning back and forth
/// between both sides on every control step, which gained nothing and made its path depend
/// on the step length (`docs/world-model.md`, "Steering side").
pub(super) fn steer_turns_for(side: f32) -> &'static [(f32, f32)] {
    static BY_SIDE: std::sync::OnceLock<[Vec<(f32, f32)>; 2]> = std::sync::OnceLock::new();
    if side == 0.0 {
        return steer_turns();
    }
    let [right_first, left_first] = BY_SIDE.get_or_init(|| {
        let turns = steer_turns();
        let side_of = |parity: usize| turns.iter().skip(parity).step_by(2).copied();
        [
            side_of(0).chain(side_of(1)).collect(),
            side_of(1).chain(side_of(0)).collect(),
        ]
    });
    if side < 0.0 { right_first } else { left_first }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_side_orders_its_own_turns_first_from_the_smallest() {
        let angle = |(s, c): (f32, f32)| s.atan2(c).to_degrees().round() as i32;
        let none: Vec<i32> = steer_turns_for(0.0).iter().copied().map(angle).collect();
        assert_eq!(&none[..4], [-15, 15, -30, 30]);
        let right: Vec<i32> = steer_turns_for(-1.0).iter().copied().map(angle).collect();
        assert_eq!(&right[..3], [-15, -30, -45]);
        assert_eq!(right[8], 15);
        let left: Vec<i32> = steer_turns_for(1.0).iter().copied().map(angle).collect();
        assert_eq!(&left[..3], [15, 30, 45]);
        assert_eq!(left[8], -15);
        for order in [none, right, left] {
            assert_eq!(order.len(), 16);
            let mut sorted = order.clone();
            sorted.sort_unstable();
            sorted.dedup();
            assert_eq!(sorted.len(), 16, "each turn once: {order:?}");
        }
    }
}
