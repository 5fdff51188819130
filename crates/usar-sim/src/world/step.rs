//! The step's stages over explicit borrows ([`World::step`](super::World::step) runs them, in
//! `world.rs`): each robot's body driven at its command,
//! `sim.physics: NearBodies`' Rapier step beside the read-back of the robots far from any
//! contact, and on a control step each robot's command, motion and list flags from the
//! resolver's decisions and rule 5's steering (per robot, in parallel for a large team). Robots
//! by id; no wall-clock time, no hash-map iteration (a large team's per-robot phases on several
//! threads give the same bits, `parallel.rs`, where a step displacement above
//! `MOVED_TOLERANCE_M` counts as moved).

use parry2d::math::Vector as Vec2;
use rayon::prelude::*;

use super::bodies::PhysicsScene;
use super::nav_state::Nav;
use super::parallel::{ReadBack, ReadFrom, read_back_all};
use super::per_robot::CHUNK_ROBOTS;
#[cfg(doc)]
use super::per_robot::PerRobot;
use super::read_back_so_far::{Covered, ReadBackSoFar};
use super::resolver::Resolver;
use super::resolver_input::ResolverInput;
use super::robot::{Motion, RobotState};
use crate::scenario::{CollisionParams, PhysicsStepping, Steering};

/// Unless `physics` is `NearBodies` (the contact gate drives its bodies), drives each robot's
/// body of `scene` at its command `nav[id].command` (m/s), in id order, and records that speed
/// in `nav[id].body_speed_m_per_s`. Writes only `scene`'s bodies and those speeds. (A held
/// robot's step is counted at its read-back, `parallel.rs`.)
pub(super) fn drive_all(physics: PhysicsStepping, nav: &mut [Nav], scene: &mut PhysicsScene) {
    if physics == PhysicsStepping::NearBodies {
        return;
    }
    for nav in nav {
        scene.drive_body(nav.body, nav.command);
        nav.body_speed_m_per_s = nav.command.length();
    }
}

/// The physics step and read-back of `sim.physics: NearBodies`, after the contact gate marked
/// the robots `near[id]` a contact and enabled just their bodies in `scene`
/// ([`PhysicsScene::gate_bodies`]): Rapier steps the near bodies (when `any` is near) while
/// the other robots are read back straight at their commands ([`ReadFrom::Free`]: they read
/// no body) and `beside` runs over them ([`ReadBackSoFar`], the far robots), side by side on
/// the calling rayon pool when `to.parallel`; then the near robots are read back from their
/// bodies. The same bits as a Rapier step followed by [`ReadFrom::Bodies`]: a robot's
/// read-back reads only its own state and, when near, its body after the step. Returns
/// whether Rapier stepped.
pub(super) fn step_near_bodies(
    scene: &mut PhysicsScene,
    near: &[bool],
    any: bool,
    to: &mut ReadBack,
    beside: impl FnOnce(ReadBackSoFar) + Send,
) -> bool {
    let far = |to: &mut ReadBack| {
        read_back_all(ReadFrom::Free(near), to);
        beside(to.so_far(Covered::Far(near)));
    };
    if any && to.parallel {
        rayon::join(|| scene.step(), || far(to));
    } else {
        if any {
            scene.step();
        }
        far(to);
    }
    if any {
        read_back_all(ReadFrom::Near(&scene.physics.bodies, near), to);
    }
    any
}

/// What a control step's commands read, borrowed from the world: the scenario's `collision`
/// parameters, the resolver after it ran (its decisions and the taken-goal test), its inputs
/// (one per robot, by id) and each robot's steered velocity of this control step (rule 5,
/// m/s, `None` when blocked; by id, read only with the resolver on).
pub(super) struct CommandInputs<'a> {
    pub(super) collision: &'a CollisionParams,
    pub(super) resolver: &'a Resolver,
    pub(super) inputs: &'a [ResolverInput],
    pub(super) steered: &'a [Option<Vec2>],
}

/// Sets every robot's command until the next control step (`nav[id].command`, m/s) from its
/// intent, or with the resolver on, what [`resolved_command`] makes of it; records its
/// motion, list flags and resolver counters in `robots[id]` (a held step is counted at the
/// read-back, every step). `nav` and `robots` are by id, of one length. Each robot writes
/// only its own slots, so on the calling rayon pool when `parallel` ([`PerRobot::parallel_for`]
/// of the team) it gives the same bits.
pub(super) fn command_all(
    w: &CommandInputs,
    parallel: bool,
    nav: &mut [Nav],
    robots: &mut [RobotState],
) {
    let each = |(id, (nav, state)): (usize, (&mut Nav, &mut RobotState))| {
        nav.command = command(w, id, nav, state);
    };
    if parallel {
        nav.par_iter_mut()
            .zip(robots.par_iter_mut())
            .enumerate()
            .with_min_len(CHUNK_ROBOTS)
            .with_max_len(CHUNK_ROBOTS)
            .for_each(each);
    } else {
        nav.iter_mut()
            .zip(robots.iter_mut())
            .enumerate()
            .for_each(each);
    }
}

/// The velocity robot `id` (navigation state `nav`, state `state`) commands until the next
/// control step; records its motion, list flags and resolver counters (see [`command_all`]).
fn command(w: &CommandInputs, id: usize, nav: &mut Nav, state: &mut RobotState) -> Vec2 {
    let input = w.inputs[id];
    let motion = if state.goal.is_none() {
        Motion::Idle
    } else if state.goal_reached {
        Motion::Arrived
    } else {
        Motion::Moving
    };
    let (command, motion) = if w.collision.enabled {
        let d = w.resolver.decisions()[id];
        state.in_collision_list = d.in_list;
        state.held = d.held;
        let c = &mut state.counters;
        c.lists_joined += u64::from(d.joined);
        c.deadlocks_detected += u64::from(d.deadlock_detected);
        c.deadlocks_resolved += u64::from(d.deadlock_resolved);
        resolved_command(w, id, nav, state, d.held, motion)
    } else {
        (input.intent, motion)
    };
    state.motion = motion;
    command
}

/// With the resolver on, robot `id`'s command and motion (`motion` as path following
/// left it): zero when `held`; zero and [`Motion::Arrived`] (goal reached) when deflected
/// or blocked at the rim of a goal a robot standing still has taken
/// (`world/goal_taken.rs`); zero and [`Motion::Blocked`] when no heading is clear; else
/// its intent steered around robots standing still (rule 5 of `world/resolver.rs`, to the
/// side of its last deflection first, which it remembers in `nav.deflection`:
/// [`Nav::steering_side`]). Under `collision.steering: Memoryless` neither the taken goal
/// nor the side. Writes only `nav.deflection` and `state.goal_reached`.
fn resolved_command(
    w: &CommandInputs,
    id: usize,
    nav: &mut Nav,
    state: &mut RobotState,
    held: bool,
    motion: Motion,
) -> (Vec2, Motion) {
    if held {
        return (Vec2::ZERO, Motion::Held);
    }
    let intent = w.inputs[id].intent;
    let steered = w.steered[id];
    if steered == Some(intent) {
        nav.deflection = Vec2::ZERO;
        return (intent, motion);
    }
    let keep_side = w.collision.steering == Steering::KeepSide;
    let taken = keep_side
        && motion == Motion::Moving
        && nav.goal.is_some_and(|goal| {
            w.resolver
                .goal_taken(w.inputs, id, goal, nav.goal_tolerance_m)
        });
    if taken {
        state.goal_reached = true;
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
