//! What the collision resolver knows about one robot this step ([`ResolverInput`]).
//!
//! Also the slot of a robot's layer in the resolver's per-layer arrays.

use parry2d::math::Vector as Vec2;

use crate::scenario::Locomotion;

/// What the resolver needs to know about one robot this step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ResolverInput {
    /// Position, metres.
    pub pos: Vec2,
    /// Intended velocity (path following, before avoidance), metres per second.
    pub intent: Vec2,
    /// Body radius, metres.
    pub radius: f32,
    /// Effective sensing range, metres.
    pub sensing: f32,
    /// Collision layer.
    pub layer: Locomotion,
    /// Goal set and not reached.
    pub active: bool,
    /// Priority key: lower goes first, ties by id.
    pub key: f64,
    /// Remaining path length to the goal (distance to the current waypoint plus the rest of
    /// the path), metres; progress for deadlock detection is its decrease. Read only for
    /// robots in a collision list, which are all `active`: the world passes 0 for the others.
    pub remaining: f32,
}

/// Index of a layer in per-layer arrays: ground 0, aerial 1.
pub(super) fn layer_slot(layer: Locomotion) -> usize {
    match layer {
        Locomotion::Ground => 0,
        Locomotion::Aerial => 1,
    }
}
