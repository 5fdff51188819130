//! The parts [`World::new`](super::World::new) builds from a validated scenario, each a
//! function of the scenario (and the physics scene or robots built before it): the clearance
//! grid, the robots at their starts, the radiation field, the pipelines, the largest radii
//! and the shared goals.

use parry2d::math::Vector as Vec2;

use super::bodies::{PhysicsScene, to_point, to_vec2};
use super::clearance_grid::ClearanceGrid;
use super::contact_gate::ContactGate;
use super::control_clock::ControlClock;
use super::detours_ahead::DetoursAhead;
use super::nav_state::Nav;
use super::neighbours::NeighbourIndex;
use super::path_planner::PathPlanner;
use super::per_robot::PerRobot;
use super::pipelines::Pipelines;
use super::plan_query::plan_inflation_m;
use super::radiation::DoseRule;
use super::radiation_field::RadiationField;
use super::read_back_so_far::Rest;
use super::resolver::Resolver;
use super::robot::RobotState;
use crate::scenario::{Locomotion, Scenario};

/// What the clearance grid holds beyond the largest planning inflation, metres: a cell's
/// clearance is the distance to the nearest wall or debris capped at the largest body radius +
/// `navigation.clearance_m` + 2 cells + this. Every test of the grid compares a clearance with
/// an inflation below the cap, so the cap changes no answer; line of sight skips the samples
/// within a cell's clearance, so a larger cap skips more in open ground (4 m instead of 1 m:
/// 3 % fewer instructions in a 60 s `swarm-1000.ron` run, same results) and costs a larger
/// band of cells around each obstacle when the grid is built.
pub const CLEARANCE_CAP_MARGIN_M: f64 = 4.0;

/// The clearance grid of `s` over the statics of `scene` (cell `navigation.grid_cell_m`,
/// clearances capped [`CLEARANCE_CAP_MARGIN_M`] beyond the largest planning inflation), with
/// the grid moves tabulated for each ground kind's planning inflation.
pub(super) fn clearance_grid(s: &Scenario, scene: &PhysicsScene) -> ClearanceGrid {
    let max_radius = s.kinds.iter().map(|k| k.body_radius_m).fold(0.0, f64::max);
    let cap = (max_radius
        + s.navigation.clearance_m.get()
        + 2.0 * s.navigation.grid_cell_m.get()
        + CLEARANCE_CAP_MARGIN_M) as f32;
    let mut grid = ClearanceGrid::build(
        &s.arena,
        &scene.statics,
        s.navigation.grid_cell_m.get(),
        cap,
    );
    for k in s
        .kinds
        .iter()
        .filter(|k| k.locomotion == Locomotion::Ground)
    {
        grid.tabulate_moves(plan_inflation_m(k.body_radius_m as f32, &s.navigation));
    }
    grid
}

/// Each robot of `s` idle at its start, by id: its navigation state (on its body of `scene`)
/// and its state.
pub(super) fn robots_at_start(s: &Scenario, scene: &PhysicsScene) -> (Vec<Nav>, Vec<RobotState>) {
    let mut nav = Vec::with_capacity(s.robots.len());
    let mut robots = Vec::with_capacity(s.robots.len());
    for (id, r) in s.robots.iter().enumerate() {
        let kind = &s.kinds[r.kind];
        let pos = to_vec2(&r.start_in_world);
        nav.push(Nav::new(scene.robot_bodies[id], kind, pos));
        robots.push(RobotState::idle(id, r.kind, kind, to_point(pos)));
    }
    (nav, robots)
}

/// The radiation zones of `s` with its dose rule (`mission.radiation_overlap`,
/// `mission.radiation_falloff`) over its arena.
pub(super) fn radiation_field(s: &Scenario) -> RadiationField {
    let dose_rule = DoseRule {
        overlap: s.mission.radiation_overlap,
        falloff: s.mission.radiation_falloff,
    };
    RadiationField::new(
        s.radiation_zones.clone(),
        dose_rule,
        s.arena.width_m.get() as f32,
        s.arena.height_m.get() as f32,
    )
}

/// The pipelines of a world of `s` on control clock `clock` with the robots `nav` and
/// `robots` (by id, one length): the resolver sized for the team and the control period, its
/// inputs read from the robots, the neighbour index built at their positions, empty caches.
pub(super) fn pipelines(
    s: &Scenario,
    clock: &ControlClock,
    nav: &[Nav],
    robots: &[RobotState],
) -> Pipelines {
    let resolver_inputs = nav
        .iter()
        .zip(robots)
        .map(|(n, r)| n.resolver_input(r))
        .collect();
    let mut neighbours = NeighbourIndex::new(s);
    neighbours.rebuild(nav.iter().map(|n: &Nav| (n.layer, n.pos)), false);
    Pipelines {
        planner: PathPlanner::new(),
        scratch: Vec::with_capacity(64),
        standing: Vec::new(),
        near_ids: Vec::new(),
        detours_ahead: DetoursAhead::default(),
        rest: Rest::All,
        resolver: Resolver::new(s.collision, nav.len()).for_control_steps(clock.period_steps()),
        near_body: Vec::new(),
        gate: ContactGate::default(),
        resolver_inputs,
        per_robot: PerRobot::new(nav.len()),
        neighbours,
        index_fresh: true,
    }
}

/// The largest body radius of the ground and of the aerial kinds of `s`, at physics
/// precision, metres (0 for a layer without kinds).
pub(super) fn max_radius_m(s: &Scenario) -> [f64; 2] {
    [Locomotion::Ground, Locomotion::Aerial].map(|layer| {
        s.kinds
            .iter()
            .filter(|k| k.locomotion == layer)
            .map(|k| f64::from(k.body_radius_m as f32))
            .fold(0.0, f64::max)
    })
}

/// The goals many robots of `s` share, at physics precision: each task's goal point and
/// drop-off centre (in task order), then every rest-station centre; empty when
/// `navigation.shared_goal_fields` is off (every goal by A*).
pub(super) fn shared_goals(s: &Scenario) -> Vec<Vec2> {
    if !s.navigation.shared_goal_fields {
        return Vec::new();
    }
    s.tasks
        .iter()
        .flat_map(|t| [to_vec2(&t.goal), to_vec2(&t.drop_off.center)])
        .chain(s.rest_stations.iter().map(|c| to_vec2(&c.center)))
        .collect()
}
