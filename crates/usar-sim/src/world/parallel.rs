//! Per-robot parallelism inside one trial: the step's per-robot work that reads shared state
//! and writes only its own robot's output (path following up to the planner, the read-back
//! after the physics step with each robot's radiation factor, and the resolver's steering),
//! computed with rayon into buffers kept between steps, then applied in robot id order. The
//! contact gate of `sim.physics: NearBodies` (`contact_gate.rs`), the resolver's search
//! for pairs about to collide (`resolver_pairs.rs`) and the rebuild of its neighbour lists
//! (`neighbour_lists.rs`) run the same way.
//!
//! Not in the paper. Each robot's output is computed by the same code, with the same
//! floating-point operations in the same order, on whichever thread runs it, and nothing it
//! reads is written during the phase; anything that mutates shared state (Rapier, the
//! planner's caches, the resolver's lists, the mission's tallies) stays serial. So a trial
//! gives bit-identical results on any number of threads (`tests/tests/integration/parallel_trial.rs`).
//! Rapier itself steps serially: with its `parallel` feature a trial gave the same results, but
//! a Rapier step on a thread of a busy rayon pool waits for a task queued behind the trial that
//! thread runs, so a sweep with one trial per thread deadlocks (`docs/scaling.md`, "Rapier's
//! `parallel` feature", and `scripts/rapier-parallel.sh`).

use nalgebra::Vector2;
use parry2d::math::Vector as Vec2;
use rapier2d::dynamics::RigidBodySet;
use rayon::prelude::*;

use super::bodies::to_point;
use super::control_clock::ControlClock;
use super::follow::{Follow, Followed, Stage, follow};
use super::nav_state::Nav;
use super::per_robot::CHUNK_ROBOTS;
use super::robot::RobotState;
use super::steering::STEER_STATIC_GAP_M;
use super::step::MOVED_TOLERANCE_M;
use super::world::World;
use crate::scenario::Locomotion;

impl World {
    /// Lets (`true`, the default) or forbids (`false`) this world's per-robot phases to run on
    /// the threads of the calling rayon pool. Results are bit-identical either way; a sweep
    /// that runs one trial per thread forbids it so that trials do not compete for threads.
    pub fn set_parallel(&mut self, enabled: bool) {
        self.pipelines.per_robot.enabled = enabled;
    }

    /// Path following of every robot from the start of this control step ([`follow`]) into
    /// `per_robot.followed`, in parallel: `Some` where it is done, `None` where the robot needs
    /// the planner (the world then runs that robot's path following serially, in id order:
    /// [`World::update_intent`]). `tick` counts the control steps before this one. Reads only
    /// each robot's own state, the grid and the clock, and writes only the buffer.
    pub(super) fn follow_all(&mut self, tick: u64, clock: &ControlClock) {
        let mut out = std::mem::take(&mut self.pipelines.per_robot.followed);
        out.resize(self.nav.len(), None);
        let ctx = self.follow_ctx(clock.period_s(self.dt));
        let (nav, robots) = (&self.nav[..], &self.robots[..]);
        out.par_iter_mut()
            .enumerate()
            .with_min_len(CHUNK_ROBOTS)
            .for_each(|(id, o)| {
                let (me, state) = (&nav[id], &robots[id]);
                let mut f = Followed::of(me, state);
                let due = clock.path_check_due(tick, id);
                let done = follow(&ctx, me, state, due, &mut f, Stage::Start) == Follow::Done;
                *o = done.then_some(f);
            });
        self.pipelines.per_robot.followed = out;
    }

    /// Reads every robot's body back after the physics step (see [`read_back`]) and its
    /// radiation factor at its new position, in parallel for a large team.
    pub(super) fn read_back_all(&mut self) {
        let bodies = &self.scene.physics.bodies;
        let radiation = &self.radiation;
        let parallel = self.pipelines.per_robot.parallel_for(self.nav.len());
        let dt = self.dt as f32;
        let each = |((nav, state), rad): ((&mut Nav, &mut RobotState), &mut f64)| {
            read_back(bodies, nav, state, dt);
            *rad = radiation.factor_at(&state.position);
        };
        if parallel {
            self.nav
                .par_iter_mut()
                .zip(&mut self.robots)
                .zip(&mut self.radiation_factor)
                .with_min_len(CHUNK_ROBOTS)
                .for_each(each);
        } else {
            self.nav
                .iter_mut()
                .zip(&mut self.robots)
                .zip(&mut self.radiation_factor)
                .for_each(each);
        }
    }

    /// Rule 5 for every robot the resolver did not hold, into `per_robot.steered` (ground
    /// robots keep [`STEER_STATIC_GAP_M`] beyond their radius from walls and debris), in
    /// parallel for a large team. Call after the resolver ran on
    /// `pipelines.resolver_inputs`.
    pub(super) fn steer_all(&mut self) {
        let p = &mut self.pipelines;
        let n = p.resolver_inputs.len();
        let (resolver, inputs, grid) = (&p.resolver, &p.resolver_inputs[..], &self.grid);
        let nav = &self.nav[..];
        let per = &mut p.per_robot;
        let parallel = per.parallel_for(n);
        per.steered.resize(n, None);
        let chunks = n.div_ceil(CHUNK_ROBOTS).max(1);
        if per.scratch.len() < chunks {
            per.scratch.resize_with(chunks, Vec::new);
        }
        let decisions = resolver.decisions();
        let steer_chunk = |(c, (out, near)): (usize, (&mut [Option<Vec2>], &mut Vec<usize>))| {
            for (k, o) in out.iter_mut().enumerate() {
                let id = c * CHUNK_ROBOTS + k;
                if decisions[id].held {
                    continue;
                }
                let a = &inputs[id];
                let infl = (a.layer == Locomotion::Ground).then_some(a.radius + STEER_STATIC_GAP_M);
                *o = resolver.steer_with(
                    inputs,
                    id,
                    grid,
                    infl,
                    nav[id].steering_side(a.intent),
                    near,
                );
            }
        };
        let scratch = &mut per.scratch[..chunks];
        if parallel {
            per.steered
                .par_chunks_mut(CHUNK_ROBOTS)
                .zip(scratch)
                .enumerate()
                .for_each(steer_chunk);
        } else {
            per.steered
                .chunks_mut(CHUNK_ROBOTS)
                .zip(scratch)
                .enumerate()
                .for_each(steer_chunk);
        }
    }
}

/// Reads one robot's body back after the physics step: position, velocity, whether it moved
/// (more than [`MOVED_TOLERANCE_M`]) and how far. A robot whose body is disabled
/// (`sim.physics: NearBodies`, far from any contact) moves straight at its command for the
/// step, `dt` seconds, as Rapier moves a body with nothing in reach. Writes only `nav` and
/// `state`.
fn read_back(bodies: &RigidBodySet, nav: &mut Nav, state: &mut RobotState, dt: f32) {
    let body = &bodies[nav.body];
    let (p, v) = if body.is_enabled() {
        (body.translation(), body.linvel())
    } else {
        (nav.pos + nav.command * dt, nav.command)
    };
    let disp = f64::from((p - nav.pos).length());
    nav.pos = p;
    state.position = to_point(p);
    state.velocity = Vector2::new(f64::from(v.x), f64::from(v.y));
    state.moved_this_step = disp > MOVED_TOLERANCE_M;
    state.step_distance_m = if state.moved_this_step { disp } else { 0.0 };
    state.distance_travelled_m += state.step_distance_m;
}
