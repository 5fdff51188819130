//! Per-robot parallelism inside one trial: the step's per-robot work that reads shared state
//! and writes only its own robot's output (path following up to the planner, the read-back
//! after the physics step with each robot's radiation factor, and the resolver's steering),
//! computed with rayon into buffers kept between steps, then applied in robot id order. The
//! contact gate of `sim.physics: NearBodies` (`contact_gate.rs`), the resolver's search
//! for pairs about to collide (`resolver_pairs.rs`), the rebuild of its neighbour lists
//! (`neighbour_lists.rs`) and each robot's command (`step.rs`) run the same way; under
//! `NearBodies` the robots far from any contact are read back while Rapier steps the near
//! ones (`step.rs`, `step_near_bodies`). Each phase here is a function over explicit
//! borrows (`&` what it reads, `&mut` the slices or buffers it writes), called by the step.
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
use super::clearance_grid::ClearanceGrid;
use super::control_clock::ControlClock;
use super::follow::{Follow, FollowCtx, Followed, Stage, follow};
use super::nav_state::Nav;
use super::per_robot::{CHUNK_ROBOTS, PerRobot};
use super::radiation_field::RadiationField;
use super::read_back_so_far::{Covered, ReadBackSoFar};
use super::resolver::Resolver;
use super::resolver_input::ResolverInput;
use super::robot::RobotState;
use super::steering::{NearRobot, STEER_STATIC_GAP_M};
use crate::scenario::Locomotion;

/// A step displacement above this counts as "moved" (energy accounting, `moved_this_step`),
/// metres.
pub const MOVED_TOLERANCE_M: f64 = 1e-4;

/// Path following of every robot from the start of this control step ([`follow`]) into
/// `out` (resized to one entry per robot, by id), in parallel: `Some` where it is done, `None`
/// where the robot needs the planner (the world then runs that robot's path following
/// serially, in id order). Reads `ctx` (grid, parameters, clock), each robot's own navigation
/// state `nav[id]` and state `robots[id]` (`nav` and `robots` of one length, by id) and
/// `clock`'s path checks; `tick` counts the control steps before this one. Writes only `out`.
pub(super) fn follow_all(
    ctx: &FollowCtx,
    nav: &[Nav],
    robots: &[RobotState],
    tick: u64,
    clock: &ControlClock,
    out: &mut Vec<Option<Followed>>,
) {
    out.resize(nav.len(), None);
    out.par_iter_mut()
        .enumerate()
        .with_min_len(CHUNK_ROBOTS)
        .with_max_len(CHUNK_ROBOTS)
        .for_each(|(id, o)| {
            let (me, state) = (&nav[id], &robots[id]);
            let mut f = Followed::of(me, state);
            let due = clock.path_check_due(tick, id);
            let done = follow(ctx, me, state, due, &mut f, Stage::Start) == Follow::Done;
            *o = done.then_some(f);
        });
}

/// Where a read-back finds a robot after the physics step (see [`read_back_all`]).
#[derive(Clone, Copy)]
pub(super) enum ReadFrom<'a> {
    /// Every robot from its body in `bodies` (disabled bodies straight at their commands).
    Bodies(&'a RigidBodySet),
    /// Only the robots not `near[id]` a contact (`sim.physics: NearBodies`, their bodies
    /// disabled): straight at their commands, reading no body, so Rapier may step the near
    /// bodies meanwhile.
    Free(&'a [bool]),
    /// Only the robots `near[id]` a contact, from their (enabled) bodies in `bodies`.
    Near(&'a RigidBodySet, &'a [bool]),
}

/// What a read-back writes, borrowed from the world: each robot's navigation state `nav[id]`,
/// state `robots[id]` and dose factor `radiation_factor[id]` under `radiation` (the three
/// slices of one length, by id), after a physics step of `dt_s` seconds; on the calling rayon
/// pool when `parallel` ([`PerRobot::parallel_for`] of the team).
pub(super) struct ReadBack<'a> {
    pub(super) radiation: &'a RadiationField,
    pub(super) dt_s: f64,
    pub(super) parallel: bool,
    pub(super) nav: &'a mut [Nav],
    pub(super) robots: &'a mut [RobotState],
    pub(super) radiation_factor: &'a mut [f64],
}

impl ReadBack<'_> {
    /// The robots `covered` as this read-back has left them ([`ReadBackSoFar`]).
    pub(super) fn so_far<'b>(&'b self, covered: Covered<'b>) -> ReadBackSoFar<'b> {
        ReadBackSoFar {
            robots: self.robots,
            radiation_factors: self.radiation_factor,
            covered,
            parallel: self.parallel,
        }
    }
}

/// Reads the robots `from` covers back after the physics step ([`read_back`]) into `to`, each
/// with its dose factor at its new position and, when the resolver holds it, a step counted
/// held. Each robot writes only its own slots, and a robot
/// read back from [`ReadFrom::Free`] gets the same bits as from [`ReadFrom::Bodies`].
pub(super) fn read_back_all(from: ReadFrom, to: &mut ReadBack) {
    let ReadBack {
        radiation,
        dt_s,
        parallel,
        ref mut nav,
        ref mut robots,
        ref mut radiation_factor,
    } = *to;
    let dt = dt_s as f32;
    let each = |(id, ((nav, state), rad)): (usize, ((&mut Nav, &mut RobotState), &mut f64))| {
        let bodies = match from {
            ReadFrom::Bodies(bodies) => Some(bodies),
            ReadFrom::Free(near) if !near[id] => None,
            ReadFrom::Near(bodies, near) if near[id] => Some(bodies),
            ReadFrom::Free(_) | ReadFrom::Near(..) => return,
        };
        let before = state.position;
        read_back(bodies, nav, state, dt);
        count_held_step(state, dt_s);
        // The dose factor is a function of the position alone, kept up to date since the
        // world was built: a robot at the very same spot (bit for bit) keeps its factor.
        if !same_bits(&before, &state.position) {
            *rad = radiation.factor_at(&state.position);
        }
    };
    if parallel {
        nav.par_iter_mut()
            .zip(robots.par_iter_mut())
            .zip(radiation_factor.par_iter_mut())
            .enumerate()
            .with_min_len(CHUNK_ROBOTS)
            .with_max_len(CHUNK_ROBOTS)
            .for_each(each);
    } else {
        nav.iter_mut()
            .zip(robots.iter_mut())
            .zip(radiation_factor.iter_mut())
            .enumerate()
            .for_each(each);
    }
}

/// Each robot's resolver input ([`Nav::resolver_input`]) after its path following, into
/// `out` (one per robot, by id; `nav` and `robots` of the same length), on the calling rayon
/// pool when `parallel` ([`PerRobot::parallel_for`] of the team). Each reads only its own
/// robot, so the order does not matter.
pub(super) fn resolver_inputs_all(
    nav: &[Nav],
    robots: &[RobotState],
    parallel: bool,
    out: &mut [ResolverInput],
) {
    let each = |(id, o): (usize, &mut ResolverInput)| *o = nav[id].resolver_input(&robots[id]);
    if parallel {
        out.par_iter_mut()
            .enumerate()
            .with_min_len(CHUNK_ROBOTS)
            .with_max_len(CHUNK_ROBOTS)
            .for_each(each);
    } else {
        out.iter_mut().enumerate().for_each(each);
    }
}

/// Rule 5 for every robot `resolver` did not hold, into `per.steered` (one entry per robot,
/// by id; ground robots keep [`STEER_STATIC_GAP_M`] beyond their radius from walls and debris
/// of `grid`), in parallel for a large team ([`PerRobot::parallel_for`]), each task of
/// [`CHUNK_ROBOTS`] robots with its own scratch list of `per.scratch`. Call after `resolver`
/// ran on `inputs` (one per robot, by id); `nav` (by id) gives each robot's steering side.
/// Writes only `per`.
pub(super) fn steer_all(
    resolver: &Resolver,
    inputs: &[ResolverInput],
    grid: &ClearanceGrid,
    nav: &[Nav],
    per: &mut PerRobot,
) {
    let n = inputs.len();
    let parallel = per.parallel_for(n);
    per.steered.resize(n, None);
    let chunks = n.div_ceil(CHUNK_ROBOTS).max(1);
    if per.scratch.len() < chunks {
        per.scratch.resize_with(chunks, Vec::new);
    }
    let decisions = resolver.decisions();
    let steer_chunk = |(c, (out, near)): (usize, (&mut [Option<Vec2>], &mut Vec<NearRobot>))| {
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
            .with_max_len(1)
            .for_each(steer_chunk);
    } else {
        per.steered
            .chunks_mut(CHUNK_ROBOTS)
            .zip(scratch)
            .enumerate()
            .for_each(steer_chunk);
    }
}

/// Whether two positions are the same bits (so `-0.0` differs from `0.0`, and a NaN equals
/// itself).
fn same_bits(a: &crate::scenario::PointM, b: &crate::scenario::PointM) -> bool {
    a.x.to_bits() == b.x.to_bits() && a.y.to_bits() == b.y.to_bits()
}

/// Counts a step of `dt_s` seconds held for a robot the resolver holds (`steps_held`,
/// `time_held_s`): one per step, as each robot is read back once per step.
fn count_held_step(state: &mut RobotState, dt_s: f64) {
    if state.held {
        let c = &mut state.counters;
        c.steps_held += 1;
        c.time_held_s = c.steps_held as f64 * dt_s;
    }
}

/// Reads one robot's body back after the physics step: position, velocity, whether it moved
/// (more than [`MOVED_TOLERANCE_M`]) and how far. A robot whose body is disabled
/// (`sim.physics: NearBodies`, far from any contact), or whose body is not read (`bodies`
/// `None`: the caller knows it is disabled), moves straight at its command for the step, `dt`
/// seconds, as Rapier moves a body with nothing in reach. Writes only `nav` and `state`.
fn read_back(bodies: Option<&RigidBodySet>, nav: &mut Nav, state: &mut RobotState, dt: f32) {
    let body = bodies.map(|b| &b[nav.body]).filter(|b| b.is_enabled());
    let (p, v) = match body {
        Some(body) => {
            nav.body_speed_m_per_s = body.linvel().length();
            (body.translation(), body.linvel())
        }
        None => (nav.pos + nav.command * dt, nav.command),
    };
    let disp = f64::from((p - nav.pos).length());
    nav.pos = p;
    state.position = to_point(p);
    state.velocity = Vector2::new(f64::from(v.x), f64::from(v.y));
    state.moved_this_step = disp > MOVED_TOLERANCE_M;
    state.step_distance_m = if state.moved_this_step { disp } else { 0.0 };
    state.distance_travelled_m += state.step_distance_m;
}
