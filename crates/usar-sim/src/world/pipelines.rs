//! [`Pipelines`]: the systems that update the world's state on a step, each with the scratch
//! it owns, held apart from that state (as rapier keeps its pipelines apart from its body and
//! collider sets).

use parry2d::math::Vector as Vec2;

use super::contact_gate::ContactGate;
use super::detours_ahead::DetoursAhead;
use super::neighbours::NeighbourIndex;
use super::path_planner::PathPlanner;
use super::per_robot::PerRobot;
use super::read_back_so_far::Rest;
use super::resolver::Resolver;
use super::resolver_input::ResolverInput;
use super::standing_disc::StandingDisc;

/// The world's pipelines and what each owns: the memory it keeps between steps (the
/// resolver's per-robot memory, the planner's caches, the parallel phases' outputs) and its
/// scratch buffers, each cleared or overwritten before it is read. The world's state (bodies,
/// robots, navigation state, radiation zones, counters) stays in [`super::World`]'s own
/// fields.
#[derive(Debug)]
pub(super) struct Pipelines {
    /// Path planning: the plan cache, A* and the shared distance fields
    /// ([`super::path_planner`]).
    pub(super) planner: PathPlanner,
    /// Plans that may be discarded (goal checks, re-plans, detours) are written here (planning
    /// and path following).
    pub(super) scratch: Vec<Vec2>,
    /// Robots standing in the way of a detour (path following).
    pub(super) standing: Vec<StandingDisc>,
    /// Robot ids from the neighbour index (path following).
    pub(super) near_ids: Vec<usize>,
    /// Detours planned ahead for a control step of a large team (path following).
    pub(super) detours_ahead: DetoursAhead,
    /// Collision avoidance and deadlock solving, with its neighbour lists
    /// ([`super::resolver`]).
    pub(super) resolver: Resolver,
    /// `sim.physics: NearBodies`: whether robot `id` is near a contact this step (the
    /// contact gate).
    pub(super) near_body: Vec<bool>,
    /// The contact gate's lists, readings and scratch (`contact_gate.rs`).
    pub(super) gate: ContactGate,
    /// What the resolver reads of each robot on a control step, taken from its navigation
    /// state and robot state before the resolver runs (indexed by id).
    pub(super) resolver_inputs: Vec<ResolverInput>,
    /// The per-robot outputs of the parallel phases (`parallel.rs`) and whether they run in
    /// parallel.
    pub(super) per_robot: PerRobot,
    /// Robot centres by layer (`nav[..].pos`), derived from the navigation state: rebuilt
    /// before every control step and after a teleport, and every robot-robot query goes
    /// through it (between control steps the public queries scan the robots instead, see
    /// `index_fresh`).
    pub(super) neighbours: NeighbourIndex,
    /// The robots the last step left for [`super::World::read_back_rest`].
    pub(super) rest: Rest,
    /// Whether [`Pipelines::neighbours`] holds the robots' current positions: it is rebuilt
    /// before every control step and after a teleport, not after the steps in between.
    pub(super) index_fresh: bool,
}
