//! A goal taken by a robot standing still: when a moving robot counts its goal as reached at
//! the rim of another robot's keep-out (see [`goal_taken`]).
//!
//! Not in the paper (its robots are Unity agents whose arrival rule it does not give); this
//! simulator's choice, documented in `docs/world-model.md`, "A goal taken by a robot standing
//! still".

use parry2d::math::Vector as Vec2;

use super::resolver_input::ResolverInput;

/// Whether robot `i`'s goal `goal` (world frame, metres) is taken by a robot standing still
/// and robot `i` stands at its rim: some robot `j` of `candidates` (ids, any order; `i` itself
/// and others are skipped) on the same layer, active or not but with no intended motion
/// (`intent == 0`: idle, arrived, or without a goal), and sensed by `i` (within the larger of
/// the two sensing ranges), holds the goal inside its keep-out disc (radius
/// `r_i + r_j + safety_margin_m`, the resolver's clearance), and robot `i` lies within
/// `tolerance_m` (its goal tolerance, metres, > 0) of the point of that disc's rim nearest the
/// goal.
///
/// Such a goal can never be reached within its tolerance: the resolver's rule 5 keeps robot
/// `i` outside the disc, so without this rule the robot slides along the rim back and forth on
/// every control step and arrives, if ever, only when a step happens to land in the sliver of
/// the rim inside its tolerance (which made a robot's path depend on the step length: at
/// `sim.dt_s` 0.01 a corridor robot slid on for 20 s where at 0.02 it arrived at once).
/// A held robot (it has an intent) does not take a goal: it will move on.
///
/// `O(len(candidates))`; allocates nothing.
pub(super) fn goal_taken(
    inputs: &[ResolverInput],
    i: usize,
    candidates: &[usize],
    safety_margin_m: f32,
    goal: Vec2,
    tolerance_m: f32,
) -> bool {
    let a = &inputs[i];
    candidates.iter().any(|&j| {
        let b = &inputs[j];
        if j == i || b.layer != a.layer || b.intent != Vec2::ZERO {
            return false;
        }
        let range = a.sensing.max(b.sensing);
        if (b.pos - a.pos).length_squared() > range * range {
            return false;
        }
        let keep_out = a.radius + b.radius + safety_margin_m;
        let from_b = goal - b.pos;
        let d = from_b.length();
        if d >= keep_out {
            return false;
        }
        // The rim point nearest the goal (straight out from `b` through the goal; any rim
        // point when the goal is `b`'s centre: the one towards robot `i`).
        let dir = if d > f32::EPSILON {
            from_b / d
        } else {
            let to_a = a.pos - b.pos;
            let l = to_a.length();
            if l <= f32::EPSILON {
                return false;
            }
            to_a / l
        };
        let rim = b.pos + dir * keep_out;
        (a.pos - rim).length() <= tolerance_m
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Locomotion;

    fn robot(x: f32, y: f32, intent: Vec2) -> ResolverInput {
        ResolverInput {
            pos: Vec2::new(x, y),
            intent,
            radius: 0.4,
            sensing: 2.0,
            layer: Locomotion::Ground,
            active: intent != Vec2::ZERO,
            key: 0.0,
            remaining: 0.0,
        }
    }

    /// The corridor's case: robot 0 drives back to its start (6.5, 1.7); robot 1 stands 0.297 m
    /// east of its own start (5.5, 1.7), so robot 0's goal lies 0.703 m from it, inside its
    /// 1.0 m keep-out (0.4 + 0.4 + 0.2).
    fn corridor(a_x: f32, a_y: f32) -> Vec<ResolverInput> {
        vec![
            robot(a_x, a_y, Vec2::new(-0.9, 0.0)),
            robot(5.797, 1.7, Vec2::ZERO),
        ]
    }

    const GOAL: Vec2 = Vec2::new(6.5, 1.7);

    #[test]
    fn a_robot_at_the_rim_of_a_taken_goal_has_arrived() {
        // 0.304 m from the goal (outside its 0.3 m tolerance), 0.047 m from the rim point.
        let inputs = corridor(6.804, 1.747);
        assert!(goal_taken(&inputs, 0, &[0, 1], 0.2, GOAL, 0.3));
    }

    #[test]
    fn far_from_the_rim_point_or_with_a_free_goal_it_has_not() {
        // On the far side of robot 1: within its sensing, not near the rim point.
        let inputs = corridor(4.797, 1.7);
        assert!(!goal_taken(&inputs, 0, &[0, 1], 0.2, GOAL, 0.3));
        // A goal 1.2 m from robot 1 lies outside its keep-out: not taken.
        let inputs = corridor(7.0, 1.7);
        assert!(!goal_taken(&inputs, 0, &[1], 0.2, Vec2::new(7.0, 1.7), 0.3));
        // Not among the candidates: not taken.
        let inputs = corridor(6.804, 1.747);
        assert!(!goal_taken(&inputs, 0, &[0], 0.2, GOAL, 0.3));
    }

    #[test]
    fn a_robot_with_an_intent_or_on_another_layer_or_unsensed_takes_no_goal() {
        let mut inputs = corridor(6.804, 1.747);
        inputs[1].intent = Vec2::new(0.0, 0.5);
        assert!(!goal_taken(&inputs, 0, &[1], 0.2, GOAL, 0.3), "moving on");
        let mut inputs = corridor(6.804, 1.747);
        inputs[1].layer = Locomotion::Aerial;
        assert!(!goal_taken(&inputs, 0, &[1], 0.2, GOAL, 0.3), "other layer");
        let mut inputs = corridor(6.804, 1.747);
        inputs[0].sensing = 0.5;
        inputs[1].sensing = 0.5;
        assert!(!goal_taken(&inputs, 0, &[1], 0.2, GOAL, 0.3), "not sensed");
    }

    #[test]
    fn a_goal_at_the_standing_robots_centre_is_taken_on_the_near_side() {
        let inputs = corridor(6.85, 1.7);
        assert!(goal_taken(
            &inputs,
            0,
            &[1],
            0.2,
            Vec2::new(5.797, 1.7),
            0.3
        ));
        let inputs = corridor(5.797, 1.7);
        assert!(
            !goal_taken(&inputs, 0, &[1], 0.2, Vec2::new(5.797, 1.7), 0.3),
            "same spot"
        );
    }
}
