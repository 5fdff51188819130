//! [`World`]: the physical world of one USAR trial and the API the mission layer drives
//! (goals, speed, sensing and priority settings, teleports, read-only state and queries).
//!
//! [`World::step`] runs the step's stages, each a function over explicit borrows in a file of
//! its own: driving the bodies and the commands in `step.rs`, a robot's plans in
//! `robot_planning.rs` ([`World::plan`] the thin call), path following in `path_following.rs`,
//! the per-robot phases in `parallel.rs`, the contact gate in `contact_gate.rs`.

use nalgebra::Vector2;
use parry2d::math::Vector as Vec2;

use super::bodies::{PhysicsScene, to_point, to_vec2};
use super::error::{NavError, WorldError};
use super::nav_state::{Nav, for_each_near, max_penetration_m};

use super::clearance_grid::ClearanceGrid;
use super::contact_gate::GateInputs;
use super::control_clock::ControlClock;
use super::follow::FollowCtx;
use super::parallel::{
    ReadBack, ReadFrom, follow_all, read_back_all, resolver_inputs_all, steer_all,
};
use super::path_following::PathFollowing;
use super::per_robot::on_a_pool_thread;
use super::pipelines::Pipelines;
use super::plan_into::PlanInto;
use super::radiation_field::RadiationField;
use super::read_back_so_far::{Covered, ReadBackSoFar, Rest};
use super::robot::RobotState;
use super::robot_planning::{PlanInputs, ground_query, plan_robot, shared_queries};
use super::step::{CommandInputs, command_all, drive_all, step_near_bodies};
use super::world_build::{
    clearance_grid, max_radius_m, pipelines, radiation_field, robots_at_start, shared_goals,
};
use crate::scenario::{
    CollisionParams, HoldRule, Locomotion, NavigationParams, PhysicsStepping, PointM, Scenario,
};
use crate::scenario::{in_field, in_span};

/// World-level totals.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct WorldStats {
    /// Steps taken.
    pub steps: u64,
    /// Steps Rapier took: every step, or with `sim.physics: NearContacts` or `NearBodies`
    /// those on which some robot was near a contact.
    pub physics_steps: u64,
    /// Deadlocks detected (one per list and rotation, not per member).
    pub deadlocks_detected: u64,
    /// Largest collision list seen (members).
    pub max_list_len: usize,
    /// Rebuilds of the resolver's neighbour lists (`neighbour_lists.rs`).
    pub list_rebuilds: u64,
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
    nav: Vec<Nav>,
    robots: Vec<RobotState>,
    /// Each robot's radiation factor at its current position
    /// ([`super::radiation::radiation_factor_at`]): computed where the position changes (when the
    /// bodies are read back after a physics step, and on a teleport).
    radiation_factor: Vec<f64>,
    /// The radiation zones and their dose rule.
    radiation: RadiationField,
    /// Arena width and height at physics precision, metres.
    arena: (f32, f32),
    dt: f64,
    /// When Rapier steps (`sim.physics`).
    physics: PhysicsStepping,
    collision: CollisionParams,
    navigation: NavigationParams,
    stats: WorldStats,
    /// Largest body radius of the ground and the aerial robots, metres (0 without robots).
    max_radius_m: [f64; 2],
    /// The goals many robots share, at physics precision: each task's goal point and drop-off
    /// centre, then the rest-station centre. Ground robots reach them by shared distance fields.
    /// Empty when `navigation.shared_goal_fields` is off (every goal by A*).
    shared_goals: Vec<Vec2>,
    /// The systems that update the fields above on a step (planning, path following, the
    /// resolver, the contact gate, the parallel phases), each with its own memory and scratch.
    pipelines: Pipelines,
}

/// The state of a [`World`] laid open for the stage tests of `world/` (test builds only): the
/// fields stay private to `world.rs`, and a test that must set a command or step Rapier by
/// hand borrows them here, one call at a time.
#[cfg(test)]
pub(super) struct WorldParts<'a> {
    pub scene: &'a mut PhysicsScene,
    pub nav: &'a mut Vec<Nav>,
    pub robots: &'a mut Vec<RobotState>,
    pub pipelines: &'a mut Pipelines,
    pub navigation: &'a NavigationParams,
}

impl World {
    /// This world's fields for a stage test ([`WorldParts`]).
    #[cfg(test)]
    pub(super) fn parts(&mut self) -> WorldParts<'_> {
        WorldParts {
            scene: &mut self.scene,
            nav: &mut self.nav,
            robots: &mut self.robots,
            pipelines: &mut self.pipelines,
            navigation: &self.navigation,
        }
    }

    /// Builds the world of a validated scenario: physics bodies, the clearance grid (cell
    /// `navigation.grid_cell_m`) and an idle robot at each start position. `clock` is the
    /// scenario's control clock ([`ControlClock::of`]`(&s.sim)`), the one the caller passes to
    /// every [`World::step`]: the resolver sizes its neighbour lists for its period.
    pub fn new(s: &Scenario, clock: &ControlClock) -> Self {
        let scene = PhysicsScene::new(s);
        let grid = clearance_grid(s, &scene);
        let (nav, robots) = robots_at_start(s, &scene);
        let radiation = radiation_field(s);
        let radiation_factor = robots
            .iter()
            .map(|r| radiation.factor_at(&r.position))
            .collect();
        Self {
            pipelines: pipelines(s, clock, &nav, &robots),
            scene,
            grid,
            nav,
            robots,
            radiation_factor,
            radiation,
            arena: (s.arena.width_m.get() as f32, s.arena.height_m.get() as f32),
            dt: s.sim.dt_s.get(),
            physics: s.sim.physics,
            collision: s.collision,
            navigation: s.navigation,
            stats: WorldStats::default(),
            max_radius_m: max_radius_m(s),
            shared_goals: shared_goals(s),
        }
    }

    /// Path following's stage ([`PathFollowing`]) over this world for a control step of a
    /// period of `period_s` seconds: the grid, parameters, clock, shared goals and neighbour
    /// index read; the planner, the pipelines' scratch buffers and every robot's navigation
    /// state and state written.
    pub(super) fn path_following(&mut self, period_s: f64) -> PathFollowing<'_> {
        let p = &mut self.pipelines;
        PathFollowing {
            ctx: FollowCtx {
                grid: &self.grid,
                navigation: &self.navigation,
                crowd: self.collision.hold_rule == HoldRule::Yield,
                steps: self.stats.steps,
                dt: self.dt,
                period_s,
            },
            arena: self.arena,
            shared_goals: &self.shared_goals,
            max_radius_m: self.max_radius_m,
            neighbours: &p.neighbours,
            planner: &mut p.planner,
            scratch: &mut p.scratch,
            standing: &mut p.standing,
            near_ids: &mut p.near_ids,
            ahead: &mut p.detours_ahead,
            nav: &mut self.nav,
            robots: &mut self.robots,
        }
    }

    /// [`plan_robot`] for robot `id` over this world: from its position to `goal` (world
    /// frame, metres), with the pipelines' planner, into its path or the pipelines' scratch
    /// buffer as `into` says; returns the effective goal.
    ///
    /// # Errors
    /// As [`plan_robot`].
    pub(super) fn plan(&mut self, id: usize, goal: Vec2, into: PlanInto) -> Result<Vec2, NavError> {
        let w = PlanInputs {
            grid: &self.grid,
            arena: self.arena,
            navigation: &self.navigation,
            shared_goals: &self.shared_goals,
        };
        let p = &mut self.pipelines;
        plan_robot(
            &w,
            &mut p.planner,
            &mut self.nav[id],
            goal,
            into,
            &mut p.scratch,
        )
    }

    fn check_id(&self, id: usize) -> Result<(), WorldError> {
        if id < self.robots.len() {
            Ok(())
        } else {
            Err(WorldError::UnknownRobot(id))
        }
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
        let tolerance_m = self.navigation.waypoint_tolerance_m.get();
        self.set_goal_with_tolerance(id, goal, tolerance_m)
    }

    /// Sets the goal of each robot of `goals` (robot id, goal: world frame, metres) as
    /// [`World::set_goal`] does, one after the other in the order given, and returns each
    /// call's result in that order. The same paths, state and results as those calls; for a
    /// team large enough to step in parallel ([`World::per_robot_parallel`]) the ground
    /// robots' plans to shared goals (a task's goal point, a drop-off, a rest station) are
    /// made first, side by side (`shared_descents.rs`), as a round's start needs for a team
    /// of thousands.
    ///
    /// # Errors
    /// None of its own: each result is that robot's [`World::set_goal`] result
    /// ([`WorldError::UnknownRobot`], [`WorldError::Unreachable`]), and a failed goal leaves
    /// the robots after it their goals.
    pub fn set_goals(&mut self, goals: &[(usize, PointM)]) -> Vec<Result<(), WorldError>> {
        if self.per_robot_parallel() {
            let queries = shared_queries(goals, &self.nav, &self.shared_goals, &self.navigation);
            let planner = &mut self.pipelines.planner;
            planner.prepare_shared(&self.grid, self.arena, &queries, true);
        }
        let results = goals.iter().map(|&(id, g)| self.set_goal(id, Some(g)));
        let results = results.collect();
        self.pipelines.planner.clear_prepared();
        results
    }

    /// [`World::set_goal`] with the goal reached only within `tolerance_m` of it (metres)
    /// instead of `navigation.waypoint_tolerance_m`: for a point the robot must pass closely,
    /// such as a turn of a blind search's sweep (`mission::sweep_waypoints`). The robot slows
    /// on its last leg so that it does not overshoot the goal (at most the remaining distance
    /// per control period, `sim.control_period_s`, one step by default), so it can meet a
    /// tolerance smaller than a period's travel. A tolerance below
    /// the arena's floor [`min_waypoint_tolerance_m`](crate::scenario::limits::min_waypoint_tolerance_m)
    /// (`f32` positions cannot resolve less), or NaN, is raised to that floor.
    ///
    /// # Errors
    /// As [`World::set_goal`].
    pub fn set_goal_within(
        &mut self,
        id: usize,
        goal: PointM,
        tolerance_m: f64,
    ) -> Result<(), WorldError> {
        let (w, h) = self.arena;
        let floor_m = crate::scenario::limits::min_waypoint_tolerance_m(f64::from(w.max(h)));
        self.set_goal_with_tolerance(id, Some(goal), tolerance_m.max(floor_m))
    }

    /// [`World::set_goal`] with the goal's tolerance given (metres, used as is).
    fn set_goal_with_tolerance(
        &mut self,
        id: usize,
        goal: Option<PointM>,
        tolerance_m: f64,
    ) -> Result<(), WorldError> {
        self.check_id(id)?;
        let result = match goal {
            None => Ok(None),
            Some(g) => self.plan(id, to_vec2(&g), PlanInto::Path).map(Some),
        };
        let nav = &mut self.nav[id];
        nav.following.best_remaining = f32::INFINITY;
        nav.deflection = Vec2::ZERO;
        nav.following.progress_step = self.stats.steps;
        nav.goal_tolerance_m = tolerance_m as f32;
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
                Err(WorldError::Unreachable { id, error: source })
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
        self.plan(id, to_vec2(&goal), PlanInto::Scratch)
            .map(to_point)
    }

    /// Length of the path robot `id` would take from where it stands to `goal`, metres: from
    /// its position through the planned waypoints (the same plan as [`World::set_goal`]: a
    /// shared goal's distance field or A* for ground robots, a straight line for aerial
    /// ones), or `None` when no path exists. Does not change the robot (fills the plan cache).
    pub fn path_length_m(&mut self, id: usize, goal: PointM) -> Option<f64> {
        self.check_goal(id, goal).ok()?;
        let mut at = self.nav[id].pos;
        let mut length = 0.0;
        for &wp in &self.pipelines.scratch {
            length += f64::from((wp - at).length());
            at = wp;
        }
        Some(length)
    }

    /// Whether [`World::check_goal`] succeeds. A ground robot's goal is answered from the
    /// grid's regions, labelled once per inflation, not by a search: the same answer (a path
    /// exists exactly when start and goal share a region, for A* and a shared goal's distance
    /// field alike), without visiting a walled-in goal's surroundings for every robot, and
    /// without making a distance field per shared goal (80 MiB each on the largest grid).
    pub fn is_goal_reachable(&mut self, id: usize, goal: PointM) -> bool {
        if id >= self.robots.len() {
            return false;
        }
        match ground_query(&self.nav[id], to_vec2(&goal), &self.navigation) {
            Some(query) => self
                .pipelines
                .planner
                .connects(&self.grid, self.arena, query)
                .is_ok(),
            None => self.check_goal(id, goal).is_ok(),
        }
    }

    /// Sets the multiplier of robot `id`'s top speed (`kind.max_speed_m_per_s`), finite and
    /// `>= 0`, default 1 (e.g. HP level times `mission.no_observer_speed_factor`; section VI.B).
    ///
    /// # Errors
    /// Unknown id, or a NaN, infinite or negative factor.
    pub fn set_speed_factor(&mut self, id: usize, factor: f64) -> Result<(), WorldError> {
        self.check_id(id)?;
        WorldError::check_factor("speed factor", factor)?;
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
        WorldError::check_factor("sensing factor", factor)?;
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
        WorldError::check_not_nan("priority key", key)?;
        self.robots[id].priority_key = key;
        Ok(())
    }

    /// Lets (`true`, the default) or forbids (`false`) this world's per-robot phases to run on
    /// the threads of the calling rayon pool. Results are bit-identical either way; a sweep
    /// that runs one trial per thread forbids it so that trials do not compete for threads.
    pub fn set_parallel(&mut self, enabled: bool) {
        self.pipelines.per_robot.enabled = enabled;
    }

    /// Whether this world runs its per-robot phases on the threads of the calling rayon pool:
    /// [`World::set_parallel`] left it enabled, the team has at least
    /// [`PARALLEL_MIN_ROBOTS`](super::PARALLEL_MIN_ROBOTS) robots and the pool more than one
    /// thread. The mission layer's per-robot systems follow it (same bits either way).
    pub fn per_robot_parallel(&self) -> bool {
        self.pipelines.per_robot.parallel_for(self.robots.len())
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
        if !in_field(p.x, p.y, w, h) {
            let (what, value) = if in_span(p.x, w) {
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
        nav.body_speed_m_per_s = 0.0;
        nav.command = Vec2::ZERO;
        nav.following.intent = Vec2::ZERO;
        nav.pos = p;
        let state = &mut self.robots[id];
        state.position = to_point(p);
        self.radiation_factor[id] = self.radiation.factor_at(&state.position);
        state.velocity = Vector2::zeros();
        // At rest without a goal until the next control step decides again.
        state.held = false;
        state.in_collision_list = false;
        state.motion = super::robot::Motion::Idle;
        self.reindex();
        Ok(())
    }

    /// Advances the world by one fixed step `dt`, on the scenario's control clock `clock` (the
    /// one [`World::new`] was given):
    /// 1. on a control step ([`ControlClock::is_control_step`]; every step without
    ///    `sim.control_period_s`), every robot (by id) updates its intended velocity from its
    ///    goal and path; if `collision.enabled`, the resolver builds collision lists, holds all
    ///    but each list's head, rotates deadlocked lists, and the moving robots steer around
    ///    robots standing still (see [`crate::world::resolver`]); otherwise the intents are
    ///    commanded as they are. Between control steps each robot keeps its command, motion
    ///    and list flags;
    /// 2. the commanded velocities are set on the bodies and
    ///    Rapier steps once (with `sim.physics: NearContacts`, only when a contact may begin
    ///    or go on, see `world/contact_gate.rs`; otherwise every body moves straight; with
    ///    `NearBodies`, only the bodies of the robots near a contact, the others disabled and
    ///    moved straight by the read-back);
    /// 3. positions, velocities, flags and counters are read back (a held robot counting a
    ///    held step), and before a control step
    ///    the neighbour index is rebuilt (the resolver and the mission's queries use it).
    ///
    /// Never panics on a valid scenario; allocation-free except when a robot re-plans, or on a
    /// team that steps in parallel when two or more robots need the planner (their plans are
    /// made ahead, `detours_ahead.rs`).
    pub fn step(&mut self, clock: &ControlClock) {
        self.step_beside(clock, |_| {});
        self.pipelines.rest = Rest::All;
    }

    /// [`World::step`], handing the robots read back before the step ends to `beside`
    /// ([`ReadBackSoFar`]): under `sim.physics: NearBodies` the robots far from any contact
    /// (beside Rapier's step when the team steps in parallel, after it otherwise); under the
    /// other steppings every robot after the read-back. [`World::read_back_rest`] then gives
    /// the others. Work that reads only each
    /// robot's own state after the step gets the same bits over the two as over the team.
    ///
    /// A team whose per-robot phases run in parallel ([`World::per_robot_parallel`]), stepped
    /// from a thread outside every rayon pool, takes the whole step on a thread of the global
    /// pool (the calling thread waits): the same bits, without handing each parallel phase
    /// over on its own.
    pub fn step_beside(&mut self, clock: &ControlClock, beside: impl FnOnce(ReadBackSoFar) + Send) {
        on_a_pool_thread(self.per_robot_parallel(), || {
            self.step_beside_here(clock, beside);
        });
    }

    /// [`World::step_beside`] on the calling thread.
    fn step_beside_here(
        &mut self,
        clock: &ControlClock,
        beside: impl FnOnce(ReadBackSoFar) + Send,
    ) {
        let n = self.robots.len();
        // Taken by the step that reads back beside Rapier, else run after the read-back.
        let mut beside = Some(beside);
        if clock.is_control_step(self.stats.steps) {
            self.control(clock);
        }
        let physics = self.physics;
        drive_all(physics, &mut self.nav, &mut self.scene);
        match physics {
            PhysicsStepping::NearContacts if !self.near_contact() => {
                self.scene.move_free(self.dt as f32);
            }
            PhysicsStepping::NearBodies => {
                // The gate reads its own neighbour lists, rebuilt (with the neighbour index
                // when stale) only when robots have moved far enough.
                let mut near = std::mem::take(&mut self.pipelines.near_body);
                near.resize(n, false);
                let any = self.mark_near_bodies(&mut near);
                self.scene.gate_bodies(&self.nav, &near);
                let (mut to, scene) = self.read_back_parts();
                let far = beside.take();
                let far = |v: ReadBackSoFar| far.into_iter().for_each(|b| b(v));
                if step_near_bodies(scene, &near, any, &mut to, far) {
                    self.stats.physics_steps += 1;
                }
                self.pipelines.near_body = near;
                self.pipelines.rest = Rest::Near;
            }
            _ => {
                self.scene.step();
                self.stats.physics_steps += 1;
            }
        }
        self.stats.steps += 1;
        if let Some(beside) = beside {
            let (mut to, scene) = self.read_back_parts();
            read_back_all(ReadFrom::Bodies(&scene.physics.bodies), &mut to);
            beside(to.so_far(Covered::All));
            self.pipelines.rest = Rest::None;
        }
        if clock.is_control_step(self.stats.steps) {
            self.reindex();
        } else {
            self.pipelines.index_fresh = false;
        }
    }

    /// The control step's software (see [`World::step`]): intents (path following, in
    /// parallel up to the planner for a large team), the resolver over the control period,
    /// rule 5's steering, and each robot's command, motion and list flags
    /// ([`command_all`]).
    fn control(&mut self, clock: &ControlClock) {
        let n = self.robots.len();
        // `tick` counts the control steps taken before this one (see
        // `ControlClock::path_check_due`).
        let tick = clock.tick(self.stats.steps);
        let period_s = clock.period_s(self.dt);
        // A large team follows its paths in parallel up to the planner; the robots that need
        // it, and every robot of a serial trial, follow theirs here, in id order.
        let parallel = self.pipelines.per_robot.parallel_for(n);
        let out = std::mem::take(&mut self.pipelines.per_robot.followed);
        let mut stage = self.path_following(period_s);
        let followed = if parallel {
            let mut out = out;
            follow_all(&stage.ctx, stage.nav, stage.robots, tick, clock, &mut out);
            stage.plan_ahead(&out, tick, clock);
            stage.follow_team(&out, |id| clock.path_check_due(tick, id));
            out
        } else {
            stage.follow_team(&[], |id| clock.path_check_due(tick, id));
            out
        };
        self.pipelines.per_robot.followed = followed;
        let inputs = &mut self.pipelines.resolver_inputs;
        resolver_inputs_all(&self.nav, &self.robots, parallel, inputs);
        let p = &mut self.pipelines;
        if self.collision.enabled {
            p.resolver.set_parallel(parallel);
            p.resolver
                .resolve(&p.resolver_inputs, &p.neighbours, period_s);
            steer_all(
                &p.resolver,
                &p.resolver_inputs,
                &self.grid,
                &self.nav,
                &mut p.per_robot,
            );
        }
        let w = CommandInputs {
            collision: &self.collision,
            resolver: &p.resolver,
            inputs: &p.resolver_inputs,
            steered: &p.per_robot.steered,
        };
        command_all(&w, parallel, &mut self.nav, &mut self.robots);
        if self.collision.enabled {
            self.stats.deadlocks_detected += p.resolver.deadlocked_lists();
            self.stats.list_rebuilds += u64::from(p.resolver.rebuilt_lists());
            let largest = p.resolver.largest_list();
            self.stats.max_list_len = self.stats.max_list_len.max(largest);
        }
    }

    /// Rebuilds the neighbour index from the robots' current positions, `O(n + cells)` (the
    /// layers side by side for a team that steps in parallel).
    pub(super) fn reindex(&mut self) {
        let parallel = self.pipelines.per_robot.parallel_for(self.nav.len());
        self.pipelines
            .neighbours
            .rebuild(self.nav.iter().map(|n| (n.layer, n.pos)), parallel);
        self.pipelines.index_fresh = true;
    }

    /// The contact gate's state, borrowed from this world for one step, beside the pipelines
    /// (the gate's own state and the neighbour index).
    pub(super) fn gate_inputs(&mut self) -> (GateInputs<'_>, &mut Pipelines) {
        let inputs = GateInputs {
            nav: &self.nav,
            grid: &self.grid,
            scene: &self.scene,
            max_radius_m: self.max_radius_m,
            dt_s: self.dt,
        };
        (inputs, &mut self.pipelines)
    }

    /// [`ContactGate::near_contact`](super::contact_gate::ContactGate::near_contact) over
    /// this world (`sim.physics: NearContacts`).
    pub(super) fn near_contact(&mut self) -> bool {
        let (w, p) = self.gate_inputs();
        p.gate
            .near_contact(&w, &mut p.neighbours, &mut p.index_fresh)
    }

    /// [`ContactGate::mark_near_bodies`](super::contact_gate::ContactGate::mark_near_bodies)
    /// over this world (`sim.physics: NearBodies`), in parallel for a large team.
    pub(super) fn mark_near_bodies(&mut self, near: &mut [bool]) -> bool {
        let (w, p) = self.gate_inputs();
        let parallel = p.per_robot.parallel_for(near.len());
        p.gate
            .mark_near_bodies(&w, &mut p.neighbours, &mut p.index_fresh, parallel, near)
    }

    /// What a read-back writes ([`ReadBack`]: each robot's navigation state, state and dose
    /// factor, in parallel for a large team), beside the physics scene it reads.
    pub(super) fn read_back_parts(&mut self) -> (ReadBack<'_>, &mut PhysicsScene) {
        let to = ReadBack {
            radiation: &self.radiation,
            dt_s: self.dt,
            parallel: self.pipelines.per_robot.parallel_for(self.nav.len()),
            nav: &mut self.nav,
            robots: &mut self.robots,
            radiation_factor: &mut self.radiation_factor,
        };
        (to, &mut self.scene)
    }

    /// The robots the last step did not hand to [`World::step_beside`]'s `beside` (every
    /// robot after [`World::step`]), read back by the end of the step.
    pub fn read_back_rest(&self) -> ReadBackSoFar<'_> {
        let p = &self.pipelines;
        ReadBackSoFar {
            robots: &self.robots,
            radiation_factors: &self.radiation_factor,
            covered: Covered::rest(p.rest, &p.near_body),
            parallel: self.per_robot_parallel(),
        }
    }

    /// [`for_each_near`] over this world's robots and, while it is fresh, its neighbour index.
    pub(super) fn for_each_near(
        &self,
        layer: Locomotion,
        p: Vec2,
        radius_m: f32,
        f: impl FnMut(usize),
    ) {
        let index = self
            .pipelines
            .index_fresh
            .then_some(&self.pipelines.neighbours);
        for_each_near(&self.nav, index, layer, p, radius_m, f);
    }

    /// Whether the spot `p` is clear of ground robots: no ground robot other than `except` has
    /// its centre within its own body radius plus `gap_m` (metres, `>= 0`) of `p`, i.e. a robot
    /// of radius `gap_m` could stand there untouched (the mission's claim rule). Uses the
    /// neighbour index: `O(robots nearby)`.
    pub fn is_spot_clear(&self, p: &PointM, except: usize, gap_m: f64) -> bool {
        let radius = self.max_radius_m[0] + gap_m.max(0.0);
        let mut clear = true;
        self.for_each_near(Locomotion::Ground, to_vec2(p), radius as f32, |j| {
            let o = &self.robots[j];
            clear &= j == except || (o.position - p).norm() > o.radius_m + gap_m;
        });
        clear
    }

    /// Simulated time, seconds (`steps * dt`).
    pub fn time_s(&self) -> f64 {
        self.stats.steps as f64 * self.dt
    }

    /// The fixed step, seconds (`scenario.sim.dt_s`).
    pub fn dt_s(&self) -> f64 {
        self.dt
    }

    /// Steps taken so far (`stats().steps`): the next [`World::step`] is a control step when
    /// [`ControlClock::is_control_step`] of it holds.
    pub fn steps(&self) -> u64 {
        self.stats.steps
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

    /// The linear velocity, metres per second (world frame, physics precision `f32`), that
    /// [`World::step`] commanded for each robot's body before Rapier stepped, in robot id order
    /// (`len()` is the team size): the resolver's command of the last control step, held until
    /// the next one (zero when held or blocked, the intent without the resolver). Zero before the
    /// first step and after a [`World::teleport`]. Bodies are rotation-locked, so no angular
    /// velocity is ever commanded.
    ///
    /// Read it after each step; [`drive_bodies`](super::drive_bodies) (`commands.rs`) applies
    /// it to a bare [`PhysicsScene`] of the same scenario exactly as the step does, so stepping
    /// that scene after each call moves its bodies bit for bit as the world's (without
    /// teleports). `O(1)` to create, no allocation.
    pub fn commanded_velocities(&self) -> impl ExactSizeIterator<Item = Vec2> + '_ {
        self.nav.iter().map(|n| n.command)
    }

    /// Remaining waypoints of robot `id` (current one first, effective goal last); empty without
    /// a goal.
    ///
    /// # Panics
    /// If `id` is not a robot id.
    pub fn waypoints(&self, id: usize) -> impl Iterator<Item = PointM> + '_ {
        self.nav[id].waypoints_ahead().iter().map(|&v| to_point(v))
    }

    /// The radiation dose factor at `p` under the scenario's dose rule
    /// (`mission.radiation_overlap`, `mission.radiation_falloff`; see
    /// [`super::radiation::radiation_factor_at`]): 0 outside all zones, dimensionless.
    pub fn radiation_factor_at(&self, p: &PointM) -> f64 {
        self.radiation.factor_at(p)
    }

    /// [`World::radiation_factor_at`] robot `id`'s position.
    ///
    /// # Panics
    /// If `id` is not a robot id.
    pub fn radiation_factor(&self, id: usize) -> f64 {
        // Computed where the position changes (after each physics step, in parallel for a
        // large team, and on a teleport): the same value as computing it here.
        self.radiation_factor[id]
    }

    /// Every robot's [`World::radiation_factor`], by id (`len()` is the team size).
    pub fn radiation_factors(&self) -> &[f64] {
        &self.radiation_factor
    }

    /// Exact distance from `p` to the nearest wall or debris surface, metres (0 inside);
    /// parry2d point queries, not the grid.
    pub fn static_distance_at(&self, p: &PointM) -> f64 {
        f64::from(self.scene.static_distance(to_vec2(p), true))
    }

    /// Largest penetration at the current state, metres, `>= 0`: over same-layer robot pairs
    /// `r_i + r_j - distance`, over ground robots and walls/debris `r - distance`, over aerial
    /// robots and walls `r - distance`. For safety checks (not used by stepping).
    pub fn max_penetration_m(&self) -> f64 {
        let index = (self.pipelines.index_fresh).then_some(&self.pipelines.neighbours);
        let statics = |p, ground| self.scene.static_distance(p, ground);
        max_penetration_m(&self.nav, index, self.max_radius_m, statics)
    }
}
