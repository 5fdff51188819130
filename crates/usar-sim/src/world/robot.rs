//! The public, read-only state of one robot as the mission layer sees it.

use nalgebra::Vector2;

use crate::scenario::{Locomotion, PointM, RobotKind};

/// Per-robot counters of the priority-based collision avoidance (paper, section V, Algorithm 5).
///
/// All counters start at zero and only grow; they are never reset by the world.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct RobotCounters {
    /// How many times the robot joined a collision list (it was in no list at the previous step
    /// and is in one now).
    pub lists_joined: u64,
    /// Steps during which the resolver held the robot (commanded zero velocity).
    pub steps_held: u64,
    /// Simulated time held, seconds (`steps_held * dt`).
    pub time_held_s: f64,
    /// Deadlocks detected in a list the robot was a member of (each one rotated the list's
    /// priority order once: Algorithm 5's `Swap`).
    pub deadlocks_detected: u64,
    /// Deadlocks resolved: the robot left a list whose priority order had been rotated at least
    /// once (i.e. the deadlock it was part of has cleared for it).
    pub deadlocks_resolved: u64,
    /// Path re-plans triggered because the robot was pushed or side-stepped off its path.
    pub replans: u64,
}

/// Why a robot is not moving towards its goal, if it is not.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motion {
    /// No goal set (or the goal was cleared): the robot stands still and is a static obstacle to
    /// the others.
    Idle,
    /// Driving (or flying) towards its goal.
    Moving,
    /// Held by the collision resolver: a member of a collision list that is not its head.
    Held,
    /// Free to move, but every candidate heading would collide within the look-ahead (e.g. the
    /// goal is occupied by another robot); it stands still this step.
    Blocked,
    /// The goal has been reached (within its tolerance: `navigation.waypoint_tolerance_m`, or
    /// the one given to [`World::set_goal_within`](crate::world::World::set_goal_within)); the
    /// robot stands
    /// still until a new goal is set.
    Arrived,
}

/// State of one robot after the last [`crate::world::World::step`].
///
/// Positions and velocities are in the world frame (metres, metres per second); they come from
/// the `f32` physics state converted exactly to `f64`.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotState {
    /// Robot id: its index in [`crate::scenario::Scenario::robots`].
    pub id: usize,
    /// Index into [`crate::scenario::Scenario::kinds`].
    pub kind: usize,
    /// Ground or aerial (the robot's collision layer).
    pub locomotion: Locomotion,
    /// Body (disc) radius, metres.
    pub radius_m: f64,
    /// Centre of the body, world frame, metres.
    pub position: PointM,
    /// Linear velocity after the last step, metres per second.
    pub velocity: Vector2<f64>,
    /// The goal being driven to, if any. For ground robots this is the *effective* goal: the
    /// requested one, or the nearest free grid-cell centre when the requested point lies inside
    /// the inflated obstacles (see [`crate::world::NavError`]).
    pub goal: Option<PointM>,
    /// Whether the robot has come within its goal's tolerance of `goal`
    /// (`navigation.waypoint_tolerance_m`, or the one given to
    /// [`World::set_goal_within`](crate::world::World::set_goal_within)). Sticky: stays `true`
    /// until a new goal is set.
    pub goal_reached: bool,
    /// What the robot did in the last step.
    pub motion: Motion,
    /// Whether the robot's displacement in the last step exceeded
    /// [`crate::world::MOVED_TOLERANCE_M`] (for energy accounting: the paper charges energy
    /// per *moving* step, section VI.B).
    pub moved_this_step: bool,
    /// Displacement over the last step, metres: its length when the robot moved
    /// (`moved_this_step`), 0 otherwise (for energy charged per metre, `mission.energy_pct_per_m`).
    pub step_distance_m: f64,
    /// Total path length travelled, metres (sum of `step_distance_m` over all steps).
    pub distance_travelled_m: f64,
    /// Whether the robot is a member of a collision list at the last step.
    pub in_collision_list: bool,
    /// Whether the resolver held the robot at the last step.
    pub held: bool,
    /// Multiplier of the kind's top speed, `>= 0` (default 1).
    pub speed_factor: f64,
    /// Multiplier of the kind's sensing range, `>= 0` (default 1).
    pub sensing_factor: f64,
    /// Priority key for the collision resolver: lower goes first, ties by id (default 0).
    pub priority_key: f64,
    /// Collision-avoidance counters.
    pub counters: RobotCounters,
}

impl RobotState {
    /// Robot `id` of kind `kind` (index `kind_index`) idle at `position` (already rounded to
    /// physics precision): no goal, all factors 1, priority key 0, counters 0.
    pub(super) fn idle(id: usize, kind_index: usize, kind: &RobotKind, position: PointM) -> Self {
        Self {
            id,
            kind: kind_index,
            locomotion: kind.locomotion,
            radius_m: f64::from(kind.body_radius_m as f32),
            position,
            velocity: Vector2::zeros(),
            goal: None,
            goal_reached: false,
            motion: Motion::Idle,
            moved_this_step: false,
            step_distance_m: 0.0,
            distance_travelled_m: 0.0,
            in_collision_list: false,
            held: false,
            speed_factor: 1.0,
            sensing_factor: 1.0,
            priority_key: 0.0,
            counters: RobotCounters::default(),
        }
    }

    /// Whether the robot has a goal it has not reached yet (it takes part in collision lists).
    pub fn is_active(&self) -> bool {
        self.goal.is_some() && !self.goal_reached
    }
}
