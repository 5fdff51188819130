//! The physical world of the USAR mission (paper, sections IV-VI), stepped with Rapier 2D.
//!
//! One concept per file; this module only declares and re-exports:
//! - [`bodies`]: Rapier bodies, colliders and collision groups (walls, debris, robot discs).
//! - `commands`: [`drive_bodies`], the write rule of the velocities the last step commanded
//!   ([`World::commanded_velocities`]) for a bare scene (replaying a trial's motion).
//! - [`clearance_grid`]: the clearance grid (parry2d distance queries): free cells, grid
//!   moves, nearest free cell, line of sight.
//! - [`standing_disc`]: a robot standing in the way of a detour, as a keep-out disc.
//! - [`plan_query`]: one planning query and its endpoints snapped to free cells.
//! - `path_smoothing`: line-of-sight smoothing of raw grid paths (greedy and galloping).
//! - `grid_search`: one smoothed A* search between two cells (outside standing discs).
//! - [`path_planner`]: the path planner (plan cache, A* for own goals and detours, shared
//!   distance fields for shared goals).
//! - `plan_around`: a detour's search round the robots standing in the way, and a detour
//!   planned ahead on another thread.
//! - [`neighbours`]: the neighbour index (a uniform grid per layer) behind every robot-robot
//!   query.
//! - `neighbour_lists`: the resolver's neighbour lists, kept over several steps (Verlet
//!   lists).
//! - `disc_mask`: the grid cells a detour's A* may not enter (robots standing in the way).
//! - `grid_astar`: grid A* over dense per-cell arrays (the `pathfinding` crate's search order).
//! - `grid_moves`: a cell's grid moves and their costs, as a bit mask tabulated per
//!   inflation.
//! - `grid_regions`: the grid's regions per inflation (cells grid moves join), so a search
//!   between two regions fails without running.
//! - [`distance_field`]: shared distance fields (one per shared goal and clearance class).
//! - `shared_fields`: the planner's shared fields, the most recently used kept within a
//!   memory budget.
//! - `plan_cache`: the planner's plan cache, bounded in entries and bytes.
//! - `bucket_queue`: Dial's bucket queue, the distance fields' Dijkstra open set.
//! - `control_clock`: [`ControlClock`], when the robots' software runs (steps per control
//!   period, path checks), computed once from the scenario and passed to every step.
//! - `contact_gate`: `sim.physics: NearContacts` and `NearBodies`, whether a contact may begin
//!   within the next step (for the team or per robot), the straight move of every body on a
//!   step without one, and the bodies enabled in Rapier only near a contact; its pair test
//!   reads neighbour lists of its own (`neighbour_lists`).
//! - `static_buckets`: walls and debris (or radiation zones) by the buckets of a coarse grid,
//!   for the contact gate's static test and the dose factor.
//! - `conflicts`: the resolver's conflict graph (adjacency lists of the pairs about to
//!   collide), for the `Yield` hold rule.
//! - [`resolver`]: priority-based collision avoidance and deadlock solving (section V,
//!   Algorithm 5).
//! - `resolver_pairs`: rule 1's search for the pairs about to collide, robot by robot, in
//!   parallel for a large team.
//! - `resolver_reach`: how far a robot's rules can reach this step (the neighbour lists' radius).
//! - `resolver_input`: what the resolver knows about one robot this step.
//! - `collision_course`: the resolver's "about to collide" test of two moving discs.
//! - `union_find`: union-find over robot ids, the collision lists as its components.
//! - `steering`: rule 5's candidate headings and static look-ahead.
//! - [`radiation`]: radiation zones.
//! - `radiation_field`: the zones with their dose rule, read at a robot's bucket only.
//! - `read_back_so_far`: [`ReadBackSoFar`], the robots a step has read back at some point of
//!   it, for work beside Rapier's step ([`World::step_beside`]).
//! - `robot`: the per-robot state the mission layer reads ([`RobotState`]).
//! - `world`: [`World`], the API the mission layer drives, and [`WorldStats`].
//! - `world_build`: the parts [`World::new`] builds from a scenario (clearance grid, robots at
//!   their starts, radiation field, pipelines), each a function of it;
//!   [`CLEARANCE_CAP_MARGIN_M`].
//! - `nav_state`: the per-robot navigation state (path, current waypoint, intent).
//! - `plan_into`: where a robot's plan is written (its path, or the world's scratch buffer).
//! - `robot_planning`: a robot's plans (one planning function over the [`path_planner`] and
//!   explicit borrows of the world, `PlanInputs`: goals, goal checks, re-plans).
//! - `follow`: one robot's path following up to where it needs the planner (goal test,
//!   no-progress clock, the periodic line-of-sight check, corner passing, intended velocity),
//!   written to a buffer: a function of the robot's own state.
//! - `path_following`: a robot's intended velocity from its path: `follow`, then the planner's
//!   part (detours and re-plans), in robot order; a stage over explicit borrows of the world
//!   (`PathFollowing`).
//! - `detour`: a detour's geometry (the robots it goes round, where it rejoins the path).
//! - `detours_ahead`: the detours and re-plans of a large team's control step planned ahead,
//!   side by side, and taken only when asked for exactly.
//! - `step`: the step's serial stages over explicit borrows ([`World::step`] runs them): each
//!   body driven at its robot's command, and on a control step each robot's command, motion
//!   and list flags from the resolver's decisions and steering.
//! - `parallel`: the step's per-robot phases (path following, read-back, steering), functions
//!   over explicit borrows, on a rayon pool for a large team ([`PARALLEL_MIN_ROBOTS`]),
//!   bit-identical on any number of threads; [`MOVED_TOLERANCE_M`].
//! - `per_robot`: the per-robot outputs of those phases, and when they run in parallel.
//! - `pipelines`: the world's pipelines (planner, resolver, contact gate, parallel phases)
//!   with their memory and scratch, kept apart from the world's state.
//!
//! See `docs/world-model.md` for the model and its rules.

pub mod bodies;
mod bucket_queue;
pub mod clearance_grid;
mod collision_course;
mod commands;
mod conflicts;
mod contact_gate;
mod control_clock;
mod detour;
mod detours_ahead;
mod disc_mask;
pub mod distance_field;
mod error;
mod follow;
mod goal_taken;
mod grid_astar;
mod grid_moves;
mod grid_regions;
mod grid_search;
mod nav_state;
mod neighbour_lists;
pub mod neighbours;
mod parallel;
mod path_following;
mod path_following_params;
pub mod path_planner;
mod path_smoothing;
mod per_robot;
mod pipelines;
mod plan_around;
mod plan_cache;
mod plan_into;
pub mod plan_query;
pub mod radiation;
mod radiation_field;
mod read_back_so_far;
pub mod resolver;
mod resolver_input;
mod resolver_pairs;
mod resolver_reach;
mod robot;
mod robot_planning;
mod shared_descents;
mod shared_fields;
pub mod standing_disc;
mod static_buckets;
mod steering;
mod step;
#[cfg(test)]
mod test_grids;
mod union_find;
#[expect(
    clippy::module_inception,
    reason = "the World type's own file, as in rapier; private, so no world::world path"
)]
mod world;
mod world_build;

pub use commands::drive_bodies;
pub use contact_gate::NEAR_CONTACT_MARGIN_M;
pub use control_clock::ControlClock;
pub use error::{NavError, WorldError};
pub use parallel::MOVED_TOLERANCE_M;
pub use path_following_params::{
    CORNER_PASS_M, DETOUR_REJOIN_BEYOND_M, PATH_CHECK_INTERVAL_STEPS, PATH_CHECK_MAX_M,
    STALL_PROGRESS_M, STALL_REPLAN_S,
};
pub use per_robot::PARALLEL_MIN_ROBOTS;
pub(crate) use per_robot::{CHUNK_ROBOTS, on_a_pool_thread};
pub use read_back_so_far::ReadBackSoFar;
pub use robot::{Motion, RobotCounters, RobotState};
pub use shared_fields::SHARED_FIELDS_BUDGET_BYTES;
pub use world::{World, WorldStats};
pub use world_build::CLEARANCE_CAP_MARGIN_M;
