//! The per-robot navigation state the world keeps beside the public [`super::RobotState`]:
//! body handle, kinematic limits, goal, path and current waypoint, intended velocity.

use parry2d::math::Vector as Vec2;
use rapier2d::prelude::RigidBodyHandle;

use super::neighbours::NeighbourIndex;
use super::resolver_input::ResolverInput;
use super::robot::RobotState;
use crate::scenario::{Locomotion, RobotKind};

/// Navigation state of one robot (physics precision, `f32`, world frame, metres).
#[derive(Debug, Clone)]
pub(super) struct Nav {
    /// The robot's Rapier body.
    pub(super) body: RigidBodyHandle,
    /// Body radius, metres.
    pub(super) radius: f32,
    /// Top speed at speed factor 1, metres per second.
    pub(super) max_speed: f32,
    /// Sensing range at sensing factor 1, metres.
    pub(super) sensing: f32,
    /// Ground or aerial.
    pub(super) layer: Locomotion,
    /// The goal as requested (re-planning targets it).
    pub(super) requested: Option<Vec2>,
    /// The effective goal.
    pub(super) goal: Option<Vec2>,
    /// Distance from the effective goal within which it counts as reached, metres:
    /// `navigation.waypoint_tolerance_m` unless the goal was set by
    /// [`super::World::set_goal_within`].
    pub(super) goal_tolerance_m: f32,
    /// Waypoints (start excluded, effective goal last); non-empty while `goal` is set.
    pub(super) path: Vec<Vec2>,
    /// Position after the last step.
    pub(super) pos: Vec2,
    /// The fields path following updates each control step (waypoint, no-progress clock,
    /// intended velocity).
    pub(super) following: Following,
    /// Velocity commanded at the last control step (the intent after the resolver), held
    /// until the next one, metres per second.
    pub(super) command: Vec2,
    /// The last deflected heading the resolver's rule 5 commanded (a velocity, metres per
    /// second), zero after a straight command, a new goal or a new path: the robot steers to
    /// its side first ([`Nav::steering_side`]).
    pub(super) deflection: Vec2,
    /// The speed of the robot's body as Rapier last left it or the world last set it before
    /// the contact gate reads it (the length of its linear velocity, metres per second; 0 at
    /// the start): written by the read-back of a body, by driving every body
    /// (`sim.physics` other than `NearBodies`) and by a teleport, so that the gate reads it
    /// here instead of looking the body up in Rapier's set. (A body the gate enables or drives
    /// is stepped and read back before the gate reads again.)
    pub(super) body_speed_m_per_s: f32,
}

/// The navigation fields path following updates on each control step (`follow.rs`), kept
/// together so that the parallel pass can compute them into a buffer and copy them back.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Following {
    /// Index of the current waypoint in the robot's path.
    pub(super) wp: usize,
    /// Shortest remaining path length since the no-progress clock last restarted, metres
    /// (infinite right after a goal is set); see `path_following.rs`.
    pub(super) best_remaining: f32,
    /// Step at which the no-progress clock last restarted.
    pub(super) progress_step: u64,
    /// Intended velocity (path following, before collision avoidance), metres per second.
    pub(super) intent: Vec2,
}

impl Nav {
    /// A robot of `kind` with body `body`, at rest at `pos` without a goal.
    pub(super) fn new(body: RigidBodyHandle, kind: &RobotKind, pos: Vec2) -> Self {
        Self {
            body,
            radius: kind.body_radius_m as f32,
            max_speed: kind.max_speed_m_per_s as f32,
            sensing: kind.sensing_range_m as f32,
            layer: kind.locomotion,
            requested: None,
            goal: None,
            goal_tolerance_m: 0.0,
            path: Vec::with_capacity(64),
            pos,
            following: Following {
                wp: 0,
                best_remaining: f32::INFINITY,
                progress_step: 0,
                intent: Vec2::ZERO,
            },
            command: Vec2::ZERO,
            deflection: Vec2::ZERO,
            body_speed_m_per_s: 0.0,
        }
    }

    /// Starts following a new path (already in `path`) from its first waypoint: the
    /// no-progress clock measures against the new path, and the steering side is forgotten.
    pub(super) fn restart_on_new_path(&mut self) {
        self.following.wp = 0;
        self.following.best_remaining = self.remaining();
        self.deflection = Vec2::ZERO;
    }

    /// The side robot steers to first when its intent `intent` (metres per second) is not
    /// clear (`Resolver::steer_with`'s `side`): `1.0` when its last deflection
    /// ([`Nav::deflection`]) turned left of `intent`, `-1.0` right, `0.0` without one.
    pub(super) fn steering_side(&self, intent: Vec2) -> f32 {
        let cross = intent.x * self.deflection.y - intent.y * self.deflection.x;
        if cross > 0.0 {
            1.0
        } else if cross < 0.0 {
            -1.0
        } else {
            0.0
        }
    }

    /// Waypoint `wp` of the path (the last one if `wp` runs past the end).
    ///
    /// # Panics
    /// If the path is empty (no goal).
    pub(super) fn waypoint_at(&self, wp: usize) -> Vec2 {
        self.path[wp.min(self.path.len() - 1)]
    }

    /// The waypoints still ahead (the current one first, the effective goal last), metres in
    /// the world frame; empty without a goal.
    pub(super) fn waypoints_ahead(&self) -> &[Vec2] {
        match self.goal {
            Some(_) => &self.path[self.following.wp.min(self.path.len())..],
            None => &[],
        }
    }

    /// Remaining path length: to the current waypoint, then along the rest of the path.
    pub(super) fn remaining(&self) -> f32 {
        let wp = self.following.wp;
        if self.goal.is_none() || wp >= self.path.len() {
            return 0.0;
        }
        let mut total = (self.path[wp] - self.pos).length();
        for k in wp + 1..self.path.len() {
            total += (self.path[k] - self.path[k - 1]).length();
        }
        total
    }

    /// What the collision resolver needs to know about this robot, whose public state is
    /// `state`: its sensing range scaled by the sensing factor, active while it has a goal it has
    /// not reached, its priority key, and (active robots only, else 0) its remaining path
    /// length. The resolver reads `remaining` of list members only, and only active robots
    /// join lists; skipping the path of a parked robot saves a cache miss per robot and
    /// control step in a large team.
    #[inline]
    pub(super) fn resolver_input(&self, state: &RobotState) -> ResolverInput {
        let active = state.is_active();
        ResolverInput {
            pos: self.pos,
            intent: self.following.intent,
            radius: self.radius,
            sensing: self.sensing * state.sensing_factor as f32,
            layer: self.layer,
            active,
            key: state.priority_key,
            remaining: if active { self.remaining() } else { 0.0 },
        }
    }
}

/// Calls `f(j)` for every robot `j` of `layer` whose centre may lie within `radius_m` of `p`
/// (and perhaps others): the candidates of `index` (the neighbour index while it holds the
/// robots' positions), else every robot of the layer in `nav` (between control steps the
/// index is not rebuilt). Callers test the distance themselves, so both give the same answers.
pub(super) fn for_each_near(
    nav: &[Nav],
    index: Option<&NeighbourIndex>,
    layer: Locomotion,
    p: Vec2,
    radius_m: f32,
    mut f: impl FnMut(usize),
) {
    match index {
        Some(index) => index
            .grid(layer)
            .for_each_candidate(p, radius_m, |j, _| f(j)),
        None => (0..nav.len())
            .filter(|&j| nav[j].layer == layer)
            .for_each(f),
    }
}

/// Largest penetration among the robots of `nav`, metres, `>= 0` (see
/// [`super::World::max_penetration_m`]): over same-layer pairs `r_i + r_j - distance` (pairs
/// found through [`for_each_near`] with `index`, within a robot's radius plus the largest
/// radius of its layer, `max_radius_m` by layer: ground, aerial), and over robots and the
/// statics `r - static_distance(position, ground)` (metres; walls and debris for ground
/// robots, walls for aerial ones).
pub(super) fn max_penetration_m(
    nav: &[Nav],
    index: Option<&NeighbourIndex>,
    max_radius_m: [f64; 2],
    static_distance: impl Fn(Vec2, bool) -> f32,
) -> f64 {
    let mut worst = 0.0f64;
    for (i, a) in nav.iter().enumerate() {
        let ground = a.layer == Locomotion::Ground;
        let d = f64::from(static_distance(a.pos, ground));
        worst = worst.max(f64::from(a.radius) - d);
        let reach = a.radius + max_radius_m[usize::from(!ground)] as f32;
        for_each_near(nav, index, a.layer, a.pos, reach, |j| {
            if j > i {
                let d = (nav[j].pos - a.pos).length();
                worst = worst.max(f64::from(a.radius + nav[j].radius - d));
            }
        });
    }
    worst
}
