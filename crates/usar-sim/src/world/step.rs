//! [`World::step`]: one fixed step `dt` of path following, collision resolution and physics,
//! in a deterministic order (robots by id; no wall-clock time, no hash-map iteration; a large
//! team's per-robot phases on several threads give the same bits, `parallel.rs`). A step
//! displacement above `MOVED_TOLERANCE_M` (`parallel.rs`) counts as moved.

use parry2d::math::Vector as Vec2;

use super::control_clock::ControlClock;
use super::parallel::{follow_all, steer_all};
use super::robot::Motion;
use super::world::World;
use crate::scenario::{PhysicsStepping, Steering};

impl World {
    /// Advances the world by one fixed step `dt`, on the scenario's control clock `clock` (the
    /// one [`World::new`] was given):
    /// 1. on a control step ([`ControlClock::is_control_step`]; every step without
    ///    `sim.control_period_s`), every robot (by id) updates its intended velocity from its
    ///    goal and path; if `collision.enabled`, the resolver builds collision lists, holds all
    ///    but each list's head, rotates deadlocked lists, and the moving robots steer around
    ///    robots standing still (see [`crate::world::resolver`]); otherwise the intents are
    ///    commanded as they are. Between control steps each robot keeps its command, motion
    ///    and list flags;
    /// 2. the commanded velocities are set on the bodies (held robots count a held step) and
    ///    Rapier steps once (with `sim.physics: NearContacts`, only when a contact may begin
    ///    or go on, see `world/contact_gate.rs`; otherwise every body moves straight; with
    ///    `NearBodies`, only the bodies of the robots near a contact, the others disabled and
    ///    moved straight by the read-back);
    /// 3. positions, velocities, flags and counters are read back, and before a control step
    ///    the neighbour index is rebuilt (the resolver and the mission's queries use it).
    ///
    /// Never panics on a valid scenario; allocation-free except when a robot re-plans.
    pub fn step(&mut self, clock: &ControlClock) {
        let n = self.robots.len();
        if clock.is_control_step(self.stats.steps) {
            self.control(clock);
        }
        let physics = self.physics;
        for id in 0..n {
            let state = &mut self.robots[id];
            if state.held {
                let c = &mut state.counters;
                c.steps_held += 1;
                c.time_held_s = c.steps_held as f64 * self.dt;
            }
            if physics != PhysicsStepping::NearBodies {
                self.scene
                    .drive_body(self.nav[id].body, self.nav[id].command);
            }
        }
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
                if any {
                    self.scene.step();
                    self.stats.physics_steps += 1;
                }
                self.pipelines.near_body = near;
            }
            _ => {
                self.scene.step();
                self.stats.physics_steps += 1;
            }
        }
        self.stats.steps += 1;
        self.read_back_all();
        if clock.is_control_step(self.stats.steps) {
            self.reindex();
        } else {
            self.pipelines.index_fresh = false;
        }
    }

    /// The control step's software: intents, the resolver over the control period, and each
    /// robot's command, motion and list flags (see [`World::step`]).
    fn control(&mut self, clock: &ControlClock) {
        let n = self.robots.len();
        // `tick` counts the control steps taken before this one (see
        // `ControlClock::path_check_due`).
        let tick = clock.tick(self.stats.steps);
        let period_s = clock.period_s(self.dt);
        // A large team follows its paths in parallel up to the planner; the robots that need
        // it, and every robot of a serial trial, follow theirs here, in id order.
        let parallel = self.pipelines.per_robot.parallel_for(n);
        if parallel {
            let mut out = std::mem::take(&mut self.pipelines.per_robot.followed);
            let stage = self.path_following(period_s);
            follow_all(&stage.ctx, stage.nav, stage.robots, tick, clock, &mut out);
            self.pipelines.per_robot.followed = out;
        }
        for id in 0..n {
            let followed = if parallel {
                self.pipelines.per_robot.followed[id]
            } else {
                None
            };
            match followed {
                Some(f) => f.apply(&mut self.nav[id], &mut self.robots[id]),
                None => self
                    .path_following(period_s)
                    .update_intent(id, clock.path_check_due(tick, id)),
            }
            self.pipelines.resolver_inputs[id] = self.nav[id].resolver_input(&self.robots[id]);
        }
        if self.collision.enabled {
            self.pipelines.resolver.set_parallel(parallel);
            self.pipelines.resolver.resolve(
                &self.pipelines.resolver_inputs,
                &self.pipelines.neighbours,
                period_s,
            );
            let p = &mut self.pipelines;
            steer_all(
                &p.resolver,
                &p.resolver_inputs,
                &self.grid,
                &self.nav,
                &mut p.per_robot,
            );
        }
        for id in 0..n {
            self.nav[id].command = self.command(id);
        }
        if self.collision.enabled {
            self.stats.deadlocks_detected += self.pipelines.resolver.deadlocked_lists();
            self.stats.list_rebuilds += u64::from(self.pipelines.resolver.rebuilt_lists());
            self.stats.max_list_len = self
                .stats
                .max_list_len
                .max(self.pipelines.resolver.largest_list());
        }
    }

    /// The velocity robot `id` commands until the next control step: its intent, or with the
    /// resolver on, what [`World::resolved_command`] makes of it. Records the robot's motion,
    /// list flags and resolver counters (a held step is counted by [`World::step`], every
    /// step).
    fn command(&mut self, id: usize) -> Vec2 {
        let input = self.pipelines.resolver_inputs[id];
        let state = &mut self.robots[id];
        let motion = if state.goal.is_none() {
            Motion::Idle
        } else if state.goal_reached {
            Motion::Arrived
        } else {
            Motion::Moving
        };
        let (command, motion) = if self.collision.enabled {
            let d = self.pipelines.resolver.decisions()[id];
            state.in_collision_list = d.in_list;
            state.held = d.held;
            let c = &mut state.counters;
            c.lists_joined += u64::from(d.joined);
            c.deadlocks_detected += u64::from(d.deadlock_detected);
            c.deadlocks_resolved += u64::from(d.deadlock_resolved);
            self.resolved_command(id, d.held, motion)
        } else {
            (input.intent, motion)
        };
        self.robots[id].motion = motion;
        command
    }

    /// With the resolver on, robot `id`'s command and motion (`motion` as path following
    /// left it): zero when `held`; zero and [`Motion::Arrived`] (goal reached) when deflected
    /// or blocked at the rim of a goal a robot standing still has taken
    /// (`world/goal_taken.rs`); zero and [`Motion::Blocked`] when no heading is clear; else
    /// its intent steered around robots standing still (rule 5 of `world/resolver.rs`, to the
    /// side of its last deflection first, which it remembers: [`Nav::steering_side`]). Under
    /// `collision.steering: Memoryless` neither the taken goal nor the side.
    fn resolved_command(&mut self, id: usize, held: bool, motion: Motion) -> (Vec2, Motion) {
        if held {
            return (Vec2::ZERO, Motion::Held);
        }
        let intent = self.pipelines.resolver_inputs[id].intent;
        let steered = self.pipelines.per_robot.steered[id];
        let nav = &mut self.nav[id];
        if steered == Some(intent) {
            nav.deflection = Vec2::ZERO;
            return (intent, motion);
        }
        let keep_side = self.collision.steering == Steering::KeepSide;
        let taken = keep_side
            && motion == Motion::Moving
            && nav.goal.is_some_and(|goal| {
                let inputs = &self.pipelines.resolver_inputs;
                let resolver = &self.pipelines.resolver;
                resolver.goal_taken(inputs, id, goal, nav.goal_tolerance_m)
            });
        if taken {
            self.robots[id].goal_reached = true;
            return (Vec2::ZERO, Motion::Arrived);
        }
        match steered {
            Some(v) => {
                if keep_side {
                    nav.deflection = v;
                }
                (v, motion)
            }
            None => (Vec2::ZERO, Motion::Blocked),
        }
    }
}
