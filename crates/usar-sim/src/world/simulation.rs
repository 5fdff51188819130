//! The USAR world: Rapier physics plus navigation and the priority-based collision resolver,
//! stepped at a fixed `dt` in a deterministic order (robots by id; no wall-clock time, no
//! threads, no hash-map iteration).

use nalgebra::Vector2;
use parry2d::math::Vector as Vec2;
use rapier2d::prelude::RigidBodyHandle;

use super::bodies::{PhysicsScene, StaticObstacle, to_point, to_vec2};
use super::error::{NavError, WorldError};
use super::navigation::{ClearanceGrid, PathPlanner};
use super::radiation::{self, DoseRule};
use super::resolver::{Resolver, ResolverInput, STEER_STATIC_GAP_M};
use super::robot::{Motion, RobotCounters, RobotState};
use crate::scenario::{
    CollisionParams, Locomotion, NavigationParams, PointM, RadiationZone, Scenario,
};

/// A step displacement above this counts as "moved" (energy accounting, `moved_this_step`),
/// metres.
pub const MOVED_TOLERANCE_M: f64 = 1e-4;
/// Ground robots re-check the line of sight to their current waypoint every this many steps
/// (staggered by id) and re-plan when it is blocked.
pub const PATH_CHECK_INTERVAL_STEPS: u64 = 10;
/// Longest stretch of the line of sight checked by the periodic path check, metres.
pub const PATH_CHECK_MAX_M: f32 = 4.0;
/// A ground robot within this distance of a path corner, beyond the line through the corner
/// perpendicular to the next leg and in sight of the next waypoint, counts the corner as
/// passed, metres.
pub const CORNER_PASS_M: f32 = 2.0;

/// World-level totals.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WorldStats {
    /// Steps taken.
    pub steps: u64,
    /// Deadlocks detected (one per list and rotation, not per member).
    pub deadlocks_detected: u64,
    /// Largest collision list seen (members).
    pub max_list_len: usize,
}

#[derive(Debug, Clone)]
struct Nav {
    body: RigidBodyHandle,
    radius: f32,
    max_speed: f32,
    sensing: f32,
    layer: Locomotion,
    /// The goal as requested (re-planning targets it).
    requested: Option<Vec2>,
    /// The effective goal.
    goal: Option<Vec2>,
    path: Vec<Vec2>,
    wp: usize,
    pos: Vec2,
    intent: Vec2,
}

impl Nav {
    /// Remaining path length: to the current waypoint, then along the rest of the path.
    fn remaining(&self) -> f32 {
        if self.goal.is_none() || self.wp >= self.path.len() {
            return 0.0;
        }
        let mut total = (self.path[self.wp] - self.pos).length();
        for k in self.wp + 1..self.path.len() {
            total += (self.path[k] - self.path[k - 1]).length();
        }
        total
    }
}

/// The physical world of one USAR trial (paper, sections IV-VI): walls, debris, radiation zones
/// and robots, stepped with Rapier 2D at `scenario.sim.dt_s`.
///
/// Robots start at rest at their start positions with no goal; ids are indices into
/// `scenario.robots`. The mission layer sets goals, speed factors and priority keys, calls
/// [`World::step`] and reads [`World::robots`].
pub struct World {
    scene: PhysicsScene,
    grid: ClearanceGrid,
    planner: PathPlanner,
    resolver: Resolver,
    nav: Vec<Nav>,
    robots: Vec<RobotState>,
    inputs: Vec<ResolverInput>,
    zones: Vec<RadiationZone>,
    dose_rule: DoseRule,
    arena: (f32, f32),
    dt: f64,
    collision: CollisionParams,
    navigation: NavigationParams,
    stats: WorldStats,
    scratch: Vec<Vec2>,
}

impl World {
    /// Builds the world of a validated scenario: physics bodies, the clearance grid (cell
    /// `navigation.grid_cell_m`) and an idle robot at each start position.
    pub fn new(s: &Scenario) -> Self {
        let scene = PhysicsScene::new(s);
        let max_radius = s.kinds.iter().map(|k| k.body_radius_m).fold(0.0, f64::max);
        let cap =
            (max_radius + s.navigation.clearance_m + 2.0 * s.navigation.grid_cell_m + 1.0) as f32;
        let grid = ClearanceGrid::build(&s.arena, &scene.statics, s.navigation.grid_cell_m, cap);
        let mut nav = Vec::with_capacity(s.robots.len());
        let mut robots = Vec::with_capacity(s.robots.len());
        for (id, r) in s.robots.iter().enumerate() {
            let kind = &s.kinds[r.kind];
            let pos = to_vec2(&r.start_in_world);
            nav.push(Nav {
                body: scene.robot_bodies[id],
                radius: kind.body_radius_m as f32,
                max_speed: kind.max_speed_m_per_s as f32,
                sensing: kind.sensing_range_m as f32,
                layer: kind.locomotion,
                requested: None,
                goal: None,
                path: Vec::with_capacity(64),
                wp: 0,
                pos,
                intent: Vec2::ZERO,
            });
            robots.push(RobotState {
                id,
                kind: r.kind,
                locomotion: kind.locomotion,
                radius_m: f64::from(kind.body_radius_m as f32),
                position: to_point(pos),
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
            });
        }
        let resolver = Resolver::new(s.collision, nav.len());
        let inputs = nav
            .iter()
            .map(|n| ResolverInput {
                pos: n.pos,
                intent: Vec2::ZERO,
                radius: n.radius,
                sensing: n.sensing,
                layer: n.layer,
                active: false,
                key: 0.0,
                remaining: 0.0,
            })
            .collect();
        Self {
            scene,
            grid,
            planner: PathPlanner::new(),
            resolver,
            nav,
            robots,
            inputs,
            zones: s.radiation_zones.clone(),
            dose_rule: DoseRule {
                overlap: s.mission.radiation_overlap,
                falloff: s.mission.radiation_falloff,
            },
            arena: (s.arena.width_m as f32, s.arena.height_m as f32),
            dt: s.sim.dt_s,
            collision: s.collision,
            navigation: s.navigation,
            stats: WorldStats::default(),
            scratch: Vec::with_capacity(64),
        }
    }

    fn check_id(&self, id: usize) -> Result<(), WorldError> {
        if id < self.robots.len() {
            Ok(())
        } else {
            Err(WorldError::UnknownRobot(id))
        }
    }

    fn plan_inflation(&self, id: usize) -> f32 {
        self.nav[id].radius
            + self.navigation.clearance_m as f32
            + 0.5 * self.navigation.grid_cell_m as f32
    }

    fn check_inflation(&self, id: usize) -> f32 {
        self.nav[id].radius + 0.5 * self.navigation.clearance_m as f32
    }

    /// Sets (or with `None` clears) robot `id`'s goal, world frame, metres.
    ///
    /// Ground robots plan a path at once (grid A* plus line-of-sight smoothing, cached by
    /// (start cell, goal cell, inflation)); aerial robots fly straight. A goal inside the
    /// inflated obstacles is moved to the nearest free cell centre within `inflation + 2 cells`
    /// (see [`RobotState::goal`]). Resets `goal_reached`.
    ///
    /// # Errors
    /// [`WorldError::UnknownRobot`]; [`WorldError::Unreachable`] when planning fails (goal
    /// outside the arena, blocked, or no path): the robot's goal is then cleared (it stops).
    pub fn set_goal(&mut self, id: usize, goal: Option<PointM>) -> Result<(), WorldError> {
        self.check_id(id)?;
        let result = match goal {
            None => Ok(None),
            Some(g) => self.plan_into_nav(id, to_vec2(&g)).map(Some),
        };
        let nav = &mut self.nav[id];
        let state = &mut self.robots[id];
        state.goal_reached = false;
        match result {
            Ok(eff) => {
                nav.requested = goal.map(|g| to_vec2(&g));
                nav.goal = eff;
                state.goal = eff.map(to_point);
                Ok(())
            }
            Err(source) => {
                nav.requested = None;
                nav.goal = None;
                nav.path.clear();
                state.goal = None;
                Err(WorldError::Unreachable { id, source })
            }
        }
    }

    /// Plans from robot `id`'s position to `goal` into its path; returns the effective goal.
    fn plan_into_nav(&mut self, id: usize, goal: Vec2) -> Result<Vec2, NavError> {
        let infl = self.plan_inflation(id);
        let nav = &mut self.nav[id];
        nav.wp = 0;
        match nav.layer {
            Locomotion::Aerial => {
                let (w, h) = self.arena;
                if !(goal.is_finite()
                    && goal.x >= 0.0
                    && goal.y >= 0.0
                    && goal.x <= w
                    && goal.y <= h)
                {
                    return Err(NavError::GoalOutsideArena);
                }
                nav.path.clear();
                nav.path.push(goal);
                Ok(goal)
            }
            Locomotion::Ground => {
                self.planner
                    .plan(&self.grid, self.arena, nav.pos, goal, infl, &mut nav.path)
            }
        }
    }

    /// Whether robot `id` could reach `goal` from where it stands now: `Ok(effective goal)` or
    /// the planning error. Does not change the robot (fills the plan cache).
    ///
    /// # Errors
    /// [`NavError`] as in [`World::set_goal`]; an unknown id is reported as
    /// [`NavError::StartBlocked`].
    pub fn check_goal(&mut self, id: usize, goal: PointM) -> Result<PointM, NavError> {
        if id >= self.robots.len() {
            return Err(NavError::StartBlocked);
        }
        let infl = self.plan_inflation(id);
        let g = to_vec2(&goal);
        let mut scratch = Vec::new();
        match self.nav[id].layer {
            Locomotion::Aerial => {
                let (w, h) = self.arena;
                if g.is_finite() && g.x >= 0.0 && g.y >= 0.0 && g.x <= w && g.y <= h {
                    Ok(to_point(g))
                } else {
                    Err(NavError::GoalOutsideArena)
                }
            }
            Locomotion::Ground => self
                .planner
                .plan(
                    &self.grid,
                    self.arena,
                    self.nav[id].pos,
                    g,
                    infl,
                    &mut scratch,
                )
                .map(to_point),
        }
    }

    /// Whether [`World::check_goal`] succeeds.
    pub fn is_goal_reachable(&mut self, id: usize, goal: PointM) -> bool {
        self.check_goal(id, goal).is_ok()
    }

    fn check_factor(what: &'static str, value: f64) -> Result<(), WorldError> {
        if value.is_finite() && value >= 0.0 {
            Ok(())
        } else {
            Err(WorldError::InvalidValue { what, value })
        }
    }

    /// Sets the multiplier of robot `id`'s top speed (`kind.max_speed_m_per_s`), finite and
    /// `>= 0`, default 1 (e.g. HP level times `mission.no_observer_speed_factor`; section VI.B).
    ///
    /// # Errors
    /// Unknown id, or a NaN, infinite or negative factor.
    pub fn set_speed_factor(&mut self, id: usize, factor: f64) -> Result<(), WorldError> {
        self.check_id(id)?;
        Self::check_factor("speed factor", factor)?;
        self.robots[id].speed_factor = factor;
        Ok(())
    }

    /// Sets the multiplier of robot `id`'s sensing range (`kind.sensing_range_m`), finite and
    /// `>= 0`, default 1 (the paper lowers sensing with HP, section VI.B).
    ///
    /// # Errors
    /// Unknown id, or a NaN, infinite or negative factor.
    pub fn set_sensing_factor(&mut self, id: usize, factor: f64) -> Result<(), WorldError> {
        self.check_id(id)?;
        Self::check_factor("sensing factor", factor)?;
        self.robots[id].sensing_factor = factor;
        Ok(())
    }

    /// Sets robot `id`'s priority key for the collision resolver (lower goes first, ties by
    /// id; default 0). Any non-NaN value (section V: the needs-based priority, e.g. energy).
    ///
    /// # Errors
    /// Unknown id or NaN.
    pub fn set_priority_key(&mut self, id: usize, key: f64) -> Result<(), WorldError> {
        self.check_id(id)?;
        if key.is_nan() {
            return Err(WorldError::InvalidValue {
                what: "priority key",
                value: key,
            });
        }
        self.robots[id].priority_key = key;
        Ok(())
    }

    /// Moves robot `id` to `position` at rest and clears its goal (e.g. to park a robot at the
    /// rest station). The caller keeps positions valid (inside the arena, free of obstacles).
    ///
    /// # Errors
    /// Unknown id, or a position that is not finite or outside the arena.
    pub fn teleport(&mut self, id: usize, position: PointM) -> Result<(), WorldError> {
        self.check_id(id)?;
        let p = to_vec2(&position);
        let (w, h) = self.arena;
        if !(p.is_finite() && p.x >= 0.0 && p.y >= 0.0 && p.x <= w && p.y <= h) {
            let (what, value) = if p.x.is_finite() && p.x >= 0.0 && p.x <= w {
                ("teleport y", position.y)
            } else {
                ("teleport x", position.x)
            };
            return Err(WorldError::InvalidValue { what, value });
        }
        self.set_goal(id, None)?;
        let nav = &mut self.nav[id];
        let body = &mut self.scene.physics.bodies[nav.body];
        body.set_translation(p, true);
        body.set_linvel(Vec2::ZERO, true);
        nav.pos = p;
        let state = &mut self.robots[id];
        state.position = to_point(p);
        state.velocity = Vector2::zeros();
        Ok(())
    }

    /// Simulated time, seconds (`steps * dt`).
    pub fn time_s(&self) -> f64 {
        self.stats.steps as f64 * self.dt
    }

    /// The fixed step, seconds (`scenario.sim.dt_s`).
    pub fn dt_s(&self) -> f64 {
        self.dt
    }

    /// World-level totals.
    pub fn stats(&self) -> &WorldStats {
        &self.stats
    }

    /// State of robot `id`.
    ///
    /// # Panics
    /// If `id` is not a robot id.
    pub fn robot(&self, id: usize) -> &RobotState {
        &self.robots[id]
    }

    /// All robots, indexed by id.
    pub fn robots(&self) -> &[RobotState] {
        &self.robots
    }

    /// Remaining waypoints of robot `id` (current one first, effective goal last); empty without
    /// a goal.
    ///
    /// # Panics
    /// If `id` is not a robot id.
    pub fn waypoints(&self, id: usize) -> impl Iterator<Item = PointM> + '_ {
        let nav = &self.nav[id];
        let rest = if nav.goal.is_some() {
            &nav.path[nav.wp.min(nav.path.len())..]
        } else {
            &[]
        };
        rest.iter().map(|&v| to_point(v))
    }

    /// The radiation dose factor at `p` under the scenario's dose rule
    /// (`mission.radiation_overlap`, `mission.radiation_falloff`; see
    /// [`radiation::radiation_factor_at`]): 0 outside all zones, dimensionless.
    pub fn radiation_factor_at(&self, p: &PointM) -> f64 {
        radiation::radiation_factor_at(&self.zones, p, self.dose_rule)
    }

    /// [`World::radiation_factor_at`] robot `id`'s position.
    ///
    /// # Panics
    /// If `id` is not a robot id.
    pub fn radiation_factor(&self, id: usize) -> f64 {
        self.radiation_factor_at(&self.robots[id].position)
    }

    /// Exact distance from `p` to the nearest wall or debris surface, metres (0 inside);
    /// parry2d point queries, not the grid.
    pub fn static_distance_at(&self, p: &PointM) -> f64 {
        nearest(&self.scene.statics, to_vec2(p), true)
    }

    /// Largest penetration at the current state, metres, `>= 0`: over same-layer robot pairs
    /// `r_i + r_j - distance`, over ground robots and walls/debris `r - distance`, over aerial
    /// robots and walls `r - distance`. For safety checks (not used by stepping).
    pub fn max_penetration_m(&self) -> f64 {
        let mut worst = 0.0f64;
        for (i, a) in self.nav.iter().enumerate() {
            let ground = a.layer == Locomotion::Ground;
            let d = nearest(&self.scene.statics, a.pos, ground);
            worst = worst.max(f64::from(a.radius) - d);
            for b in &self.nav[i + 1..] {
                if a.layer == b.layer {
                    let d = (b.pos - a.pos).length();
                    worst = worst.max(f64::from(a.radius + b.radius - d));
                }
            }
        }
        worst
    }

    /// Intended velocity of robot `id` from its goal and path (rule: follow waypoints at top
    /// speed times the speed factor, slowing only to stop on the goal).
    fn update_intent(&mut self, id: usize) {
        let tol = self.navigation.waypoint_tolerance_m as f32;
        let check_infl = self.check_inflation(id);
        let infl = self.plan_inflation(id);
        let steps = self.stats.steps;
        let dt = self.dt as f32;
        let state = &mut self.robots[id];
        let nav = &mut self.nav[id];
        nav.intent = Vec2::ZERO;
        let Some(goal) = nav.goal else {
            return;
        };
        if state.goal_reached {
            return;
        }
        let p = nav.pos;
        if (goal - p).length() <= tol {
            state.goal_reached = true;
            return;
        }
        if nav.layer == Locomotion::Ground
            && (steps + id as u64).is_multiple_of(PATH_CHECK_INTERVAL_STEPS)
        {
            while nav.wp + 1 < nav.path.len()
                && (nav.path[nav.wp + 1] - p).length() < PATH_CHECK_MAX_M
                && self
                    .grid
                    .line_of_sight(p, nav.path[nav.wp + 1], check_infl, f32::INFINITY)
            {
                nav.wp += 1;
            }
            let target = nav.path[nav.wp.min(nav.path.len() - 1)];
            if !self
                .grid
                .line_of_sight(p, target, check_infl, PATH_CHECK_MAX_M)
                && let Some(requested) = nav.requested
                // On failure the old path is kept; physics keeps the robot out of obstacles.
                && let Ok(eff) = self.planner.plan(
                    &self.grid,
                    self.arena,
                    p,
                    requested,
                    infl,
                    &mut self.scratch,
                )
            {
                std::mem::swap(&mut nav.path, &mut self.scratch);
                nav.goal = Some(eff);
                state.goal = Some(to_point(eff));
                nav.wp = 0;
                state.counters.replans += 1;
            }
        }
        let last = nav.path.len() - 1;
        while nav.wp < last {
            let corner = nav.path[nav.wp];
            let next = nav.path[nav.wp + 1];
            let d = (corner - p).length();
            // A corner is passed when reached, or when the robot is near it, already beyond
            // the line through it perpendicular to the next leg, and sees the next waypoint.
            // Without the second rule robots queueing at a corner all aim at the same point,
            // which their own bodies cover: a jam no priority order resolves.
            let passed = d <= tol
                || (d <= CORNER_PASS_M
                    && (p - corner).dot(next - corner) > 0.0
                    && self.grid.line_of_sight(p, next, check_infl, f32::INFINITY));
            if !passed {
                break;
            }
            nav.wp += 1;
        }
        let target = nav.path[nav.wp.min(last)];
        let to_target = target - p;
        let dist = to_target.length();
        if dist <= f32::EPSILON {
            return;
        }
        let mut speed = nav.max_speed * state.speed_factor as f32;
        if nav.wp >= last {
            speed = speed.min(dist / dt);
        }
        nav.intent = to_target * (speed / dist);
    }

    /// Advances the world by one fixed step `dt`:
    /// 1. every robot (by id) updates its intended velocity from its goal and path;
    /// 2. if `collision.enabled`, the resolver builds collision lists, holds all but each
    ///    list's head, rotates deadlocked lists, and the moving robots steer around robots
    ///    standing still (see [`crate::world::resolver`]); otherwise the intents are commanded
    ///    as they are;
    /// 3. the commanded velocities are set on the bodies and Rapier steps once;
    /// 4. positions, velocities, flags and counters are read back.
    ///
    /// Never panics on a valid scenario; allocation-free except when a robot re-plans.
    pub fn step(&mut self) {
        let n = self.robots.len();
        for id in 0..n {
            self.update_intent(id);
            let nav = &self.nav[id];
            let st = &self.robots[id];
            self.inputs[id] = ResolverInput {
                pos: nav.pos,
                intent: nav.intent,
                radius: nav.radius,
                sensing: nav.sensing * st.sensing_factor as f32,
                layer: nav.layer,
                active: st.is_active(),
                key: st.priority_key,
                remaining: nav.remaining(),
            };
        }
        if self.collision.enabled {
            self.resolver.resolve(&self.inputs, self.dt);
        }
        for id in 0..n {
            let input = self.inputs[id];
            let state = &mut self.robots[id];
            let mut motion = if state.goal.is_none() {
                Motion::Idle
            } else if state.goal_reached {
                Motion::Arrived
            } else {
                Motion::Moving
            };
            let command = if self.collision.enabled {
                let d = self.resolver.decisions()[id];
                state.in_collision_list = d.in_list;
                state.held = d.held;
                let c = &mut state.counters;
                c.lists_joined += u64::from(d.joined);
                c.deadlocks_detected += u64::from(d.deadlock_detected);
                c.deadlocks_resolved += u64::from(d.deadlock_resolved);
                if d.held {
                    c.steps_held += 1;
                    c.time_held_s = c.steps_held as f64 * self.dt;
                    motion = Motion::Held;
                    Vec2::ZERO
                } else {
                    let infl = (input.layer == Locomotion::Ground)
                        .then_some(input.radius + STEER_STATIC_GAP_M);
                    match self.resolver.steer(&self.inputs, id, &self.grid, infl) {
                        Some(v) => v,
                        None => {
                            motion = Motion::Blocked;
                            Vec2::ZERO
                        }
                    }
                }
            } else {
                input.intent
            };
            state.motion = motion;
            self.scene.physics.bodies[self.nav[id].body].set_linvel(command, true);
        }
        if self.collision.enabled {
            self.stats.deadlocks_detected += self.resolver.deadlocked_lists();
            self.stats.max_list_len = self.stats.max_list_len.max(self.resolver.largest_list());
        }
        self.scene.step();
        self.stats.steps += 1;
        for id in 0..n {
            let nav = &mut self.nav[id];
            let body = &self.scene.physics.bodies[nav.body];
            let p = body.translation();
            let v = body.linvel();
            let disp = f64::from((p - nav.pos).length());
            nav.pos = p;
            let state = &mut self.robots[id];
            state.position = to_point(p);
            state.velocity = Vector2::new(f64::from(v.x), f64::from(v.y));
            state.moved_this_step = disp > MOVED_TOLERANCE_M;
            state.step_distance_m = if state.moved_this_step { disp } else { 0.0 };
            state.distance_travelled_m += state.step_distance_m;
        }
    }
}

/// Distance from `p` to the nearest static obstacle (walls and, if `with_debris`, debris).
fn nearest(statics: &[StaticObstacle], p: Vec2, with_debris: bool) -> f64 {
    statics
        .iter()
        .filter(|o| with_debris || o.is_wall)
        .map(|o| f64::from(o.distance_to_point(p)))
        .fold(f64::INFINITY, f64::min)
}
