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
