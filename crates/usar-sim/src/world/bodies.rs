//! Rapier bodies and colliders of the USAR world: boundary walls, debris, robot discs, and their
//! collision groups.
//!
//! Physics runs in `f32` (Rapier's default); the scenario is `f64`. Conversions happen here and
//! in [`crate::world::World`] only.

use parry2d::bounding_volume::Aabb;
use parry2d::math::{Pose, Vector as Vec2};
use parry2d::query::PointQuery;
use parry2d::shape::{Ball, Cuboid, Shape};
use rapier2d::geometry::{BroadPhaseBvh, BvhOptimizationStrategy};
use rapier2d::prelude::{
    ColliderBuilder, Group, InteractionGroups, InteractionTestMode, PhysicsWorld, RigidBodyBuilder,
    RigidBodyHandle,
};

use super::static_buckets::StaticBuckets;
use crate::scenario::{DebrisPrimitive, DebrisShape, Locomotion, PointM, Scenario};

/// Collision group of the four boundary walls.
pub const WALLS: Group = Group::GROUP_1;
/// Collision group of debris (static obstacles inside the arena).
pub const DEBRIS: Group = Group::GROUP_2;
/// Collision group of ground robots (carriers, suppliers).
pub const GROUND: Group = Group::GROUP_3;
/// Collision group of aerial robots (observers).
pub const AERIAL: Group = Group::GROUP_4;

/// Collision groups of a body on `layer`: ground robots collide with walls, debris and ground
/// robots; aerial robots collide with walls and aerial robots only (they fly over debris and
/// ground robots).
pub fn robot_groups(layer: Locomotion) -> InteractionGroups {
    match layer {
        Locomotion::Ground => {
            InteractionGroups::new(GROUND, WALLS | DEBRIS | GROUND, InteractionTestMode::And)
        }
        Locomotion::Aerial => {
            InteractionGroups::new(AERIAL, WALLS | AERIAL, InteractionTestMode::And)
        }
    }
}

/// Converts a scenario point (metres, `f64`) to a physics vector (`f32`).
pub fn to_vec2(p: &PointM) -> Vec2 {
    Vec2::new(p.x as f32, p.y as f32)
}

/// Converts a physics vector (`f32`) to a scenario point (exact).
pub fn to_point(v: Vec2) -> PointM {
    PointM::new(f64::from(v.x), f64::from(v.y))
}

/// The shape of a static obstacle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StaticShape {
    /// A disc.
    Ball(Ball),
    /// A (possibly rotated, see the pose) rectangle.
    Cuboid(Cuboid),
}

/// A static obstacle (wall or debris) for exact parry2d queries, in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StaticObstacle {
    /// The shape, in its local frame.
    pub shape: StaticShape,
    /// Position and rotation of the shape in the world frame.
    pub pose: Pose,
    /// `true` for the boundary walls (which aerial robots collide with too), `false` for debris.
    pub is_wall: bool,
}

impl StaticObstacle {
    fn as_shape(&self) -> &dyn Shape {
        match &self.shape {
            StaticShape::Ball(b) => b,
            StaticShape::Cuboid(c) => c,
        }
    }

    /// Distance from `p` to the obstacle's surface, metres; 0 inside (parry2d point query).
    pub fn distance_to_point(&self, p: Vec2) -> f32 {
        match &self.shape {
            StaticShape::Ball(b) => b.distance_to_point(&self.pose, p, true),
            StaticShape::Cuboid(c) => c.distance_to_point(&self.pose, p, true),
        }
    }

    /// World-frame bounding box.
    pub fn aabb(&self) -> Aabb {
        self.as_shape().compute_aabb(&self.pose)
    }

    /// Debris at physics precision: the `f32` twin of the parry2d-f64 shape `d` (see
    /// [`crate::scenario::Debris::shape`]), its radius or half extents and its centre rounded to
    /// `f32`, its pose rebuilt from the scenario's rotation angle rounded to `f32` (not from the
    /// `f64` sine and cosine, so the collider is what `f32` parry makes of the scenario's
    /// angle).
    fn debris(d: &DebrisShape) -> Self {
        let center = to_vec2(&d.center());
        let (shape, pose) = match d.primitive() {
            DebrisPrimitive::Cuboid(c) => (
                StaticShape::Cuboid(Cuboid::new(Vec2::new(
                    c.half_extents.x as f32,
                    c.half_extents.y as f32,
                ))),
                Pose::new(center, d.rotation_rad() as f32),
            ),
            DebrisPrimitive::Ball(b) => (
                StaticShape::Ball(Ball::new(b.radius as f32)),
                Pose::from_translation(center),
            ),
        };
        Self {
            shape,
            pose,
            is_wall: false,
        }
    }

    fn collider(&self) -> ColliderBuilder {
        let b = match &self.shape {
            StaticShape::Ball(b) => ColliderBuilder::ball(b.radius),
            StaticShape::Cuboid(c) => ColliderBuilder::cuboid(c.half_extents.x, c.half_extents.y),
        };
        let groups = if self.is_wall {
            InteractionGroups::new(WALLS, GROUND | AERIAL, InteractionTestMode::And)
        } else {
            InteractionGroups::new(DEBRIS, GROUND, InteractionTestMode::And)
        };
        b.position(self.pose)
            .friction(0.0)
            .restitution(0.0)
            .collision_groups(groups)
    }
}

/// The four boundary walls (outside the field, `arena.wall_thickness_m` thick, overlapping at
/// the corners) followed by the debris, in scenario order (each the `f32` twin of
/// [`crate::scenario::Debris::shape`]).
pub fn static_obstacles(s: &Scenario) -> Vec<StaticObstacle> {
    let w = s.arena.width_m.get() as f32;
    let h = s.arena.height_m.get() as f32;
    let t = s.arena.wall_thickness_m.get() as f32;
    let wall = |cx: f32, cy: f32, hx: f32, hy: f32| StaticObstacle {
        shape: StaticShape::Cuboid(Cuboid::new(Vec2::new(hx, hy))),
        pose: Pose::translation(cx, cy),
        is_wall: true,
    };
    let mut out = vec![
        wall(-t / 2.0, h / 2.0, t / 2.0, h / 2.0 + t),
        wall(w + t / 2.0, h / 2.0, t / 2.0, h / 2.0 + t),
        wall(w / 2.0, -t / 2.0, w / 2.0 + t, t / 2.0),
        wall(w / 2.0, h + t / 2.0, w / 2.0 + t, t / 2.0),
    ];
    out.extend(s.debris.iter().map(|d| StaticObstacle::debris(&d.shape())));
    out
}

/// Teams of at most this many robots (64) step Rapier's broad phase without its BVH
/// optimizer. With a dozen moving discs among a few dozen static colliders, a large share of
/// the leaves leaves its fattened box every step, so the optimizer (re)builds most of the tree
/// every step (`Bvh::rebuild_range_binned`, 12 % of a `paper.ron` trial): without it the tree
/// keeps its first shape, which a tree this small can afford. The same pairs are found, in the
/// same order: the paper, three-tasks and swarm-1000 sweeps are byte-identical. A large team
/// needs the optimizer (`swarm-1000.ron` without it: 5x slower). `docs/scaling.md`.
pub const SMALL_TEAM_ROBOTS: usize = 64;

/// The Rapier world of a scenario without any mission logic: zero gravity, fixed step
/// `sim.dt_s`, static colliders for walls and debris, one dynamic, rotation-locked,
/// frictionless disc per robot (never sleeping).
pub struct PhysicsScene {
    /// All Rapier state.
    pub physics: PhysicsWorld,
    /// Body of robot `id`, indexed by id.
    pub robot_bodies: Vec<RigidBodyHandle>,
    /// Walls then debris, for exact distance queries (same shapes as the colliders).
    pub statics: Vec<StaticObstacle>,
    /// The world-frame bounding box of each of `statics`, in the same order.
    pub static_boxes: Vec<Aabb>,
    /// `statics` by the buckets of a coarse grid over the arena (the contact gate's static
    /// test looks only at those near a robot).
    pub(super) static_buckets: StaticBuckets,
    /// Whether the contact gate (`sim.physics: NearBodies`) left each robot's body enabled, by
    /// robot id: empty until its first gating, when it is read from Rapier. Only the gate
    /// enables or disables bodies, so it answers without looking the body up.
    pub(super) gated_enabled: Vec<bool>,
}

impl PhysicsScene {
    /// Builds the scene of `s` with robots at their start positions, at rest.
    pub fn new(s: &Scenario) -> Self {
        let mut physics = PhysicsWorld::new();
        physics.gravity = Vec2::ZERO;
        physics.integration_parameters.dt = s.sim.dt_s.get() as f32;
        // No body enables CCD: Rapier's CCD pass would only look for some each step.
        physics.integration_parameters.max_ccd_substeps = 0;
        if s.robots.len() <= SMALL_TEAM_ROBOTS {
            physics.broad_phase =
                BroadPhaseBvh::with_optimization_strategy(BvhOptimizationStrategy::None);
        }
        let statics = static_obstacles(s);
        for o in &statics {
            physics.insert_collider(o.collider(), None);
        }
        let robot_bodies = s
            .robots
            .iter()
            .map(|r| {
                let kind = &s.kinds[r.kind];
                let body = RigidBodyBuilder::dynamic()
                    .translation(to_vec2(&r.start_in_world))
                    .lock_rotations()
                    .can_sleep(false);
                let collider = ColliderBuilder::ball(kind.body_radius_m as f32)
                    .friction(0.0)
                    .restitution(0.0)
                    .density(1.0)
                    .collision_groups(robot_groups(kind.locomotion));
                physics.insert(body, collider).0
            })
            .collect();
        let static_boxes: Vec<Aabb> = statics.iter().map(StaticObstacle::aabb).collect();
        let (w, h) = (s.arena.width_m.get() as f32, s.arena.height_m.get() as f32);
        Self {
            physics,
            robot_bodies,
            static_buckets: StaticBuckets::new(&static_boxes, w, h),
            static_boxes,
            statics,
            gated_enabled: Vec::new(),
        }
    }

    /// Drives `body` at `command` (m/s, world frame) for the next step: the velocity is
    /// written only where it differs from the body's (writing through `bodies[..]` as `&mut`
    /// queues the body for Rapier's pass over user-modified bodies; an unchanged velocity needs
    /// no write, same physics). The one write rule of [`crate::world::World::step`] and of
    /// [`crate::world::drive_bodies`], so a replay of the commands moves bodies bit for bit.
    pub fn drive_body(&mut self, body: RigidBodyHandle, command: Vec2) {
        if self.physics.bodies[body].linvel() != command {
            self.physics.bodies[body].set_linvel(command, true);
        }
    }

    /// Advances the physics by one fixed step.
    pub fn step(&mut self) {
        self.physics.step();
    }
}
