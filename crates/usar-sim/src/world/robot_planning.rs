//! A robot's plans: [`plan_robot`] over [`PlanInputs`], and the grid query it plans with.
//!
//! One planning function for goals, goal checks and re-plans: the [`super::path_planner`] for
//! ground robots, a straight line for aerial ones.

use parry2d::math::Vector as Vec2;

use super::bodies::to_vec2;
use super::clearance_grid::ClearanceGrid;
use super::error::NavError;
use super::nav_state::Nav;
use super::path_planner::{GoalKind, PathPlanner};
use super::plan_into::PlanInto;
use super::plan_query::{PlanQuery, plan_inflation_m};
use crate::scenario::{Locomotion, NavigationParams, PointM, in_field};

/// What a robot's plan reads besides the robot, borrowed from the world: the clearance grid,
/// the arena's width and height at physics precision (metres), the scenario's `navigation`
/// (the planning inflation, [`plan_inflation_m`]) and the goals many robots share (each
/// task's goal point and drop-off centre, then the rest-station centres, at physics
/// precision; empty when `navigation.shared_goal_fields` is off).
pub(super) struct PlanInputs<'a> {
    pub(super) grid: &'a ClearanceGrid,
    pub(super) arena: (f32, f32),
    pub(super) navigation: &'a NavigationParams,
    pub(super) shared_goals: &'a [Vec2],
}

/// The grid query the robot of navigation state `nav` would plan `goal` (world frame,
/// metres) with under `navigation`: `Some` for a ground robot (from its position, its
/// planning inflation), `None` for an aerial one (it flies straight).
pub(super) fn ground_query(
    nav: &Nav,
    goal: Vec2,
    navigation: &NavigationParams,
) -> Option<PlanQuery> {
    (nav.layer == Locomotion::Ground).then(|| PlanQuery {
        from: nav.pos,
        to: goal,
        inflation_m: plan_inflation_m(nav.radius, navigation),
    })
}

/// The grid queries of the ground robots of `goals` (robot id, goal: world frame, metres)
/// whose goal is one of `shared_goals` (compared exactly at physics precision), in the order
/// of `goals`, from their navigation states `nav` (by id; an unknown id is left out) under
/// `navigation` ([`ground_query`]).
pub(super) fn shared_queries(
    goals: &[(usize, PointM)],
    nav: &[Nav],
    shared_goals: &[Vec2],
    navigation: &NavigationParams,
) -> Vec<PlanQuery> {
    let shared = |&(id, goal): &(usize, PointM)| {
        let goal = to_vec2(&goal);
        let nav = nav.get(id).filter(|_| shared_goals.contains(&goal))?;
        ground_query(nav, goal, navigation)
    };
    goals.iter().filter_map(shared).collect()
}

/// Plans from the position of the robot of navigation state `nav` to `goal` (world frame,
/// metres) and returns the effective goal. Ground robots plan on `w.grid` with `planner`
/// ([`PathPlanner::plan`], inflation [`plan_inflation_m`]): a goal that is one of
/// `w.shared_goals` (compared exactly at physics precision) by descent of its shared distance
/// field, any other goal by A*. Aerial robots fly straight, so their plan is the goal itself.
/// The waypoints go where `into` says: `nav.path` (its current waypoint reset to the first)
/// or `scratch`. Writes only `planner`'s caches, `nav`'s path and `scratch`.
///
/// # Errors
/// [`NavError::GoalOutsideArena`] for a goal that is not a finite point in the arena; for
/// ground robots also the planner's other errors.
pub(super) fn plan_robot(
    w: &PlanInputs,
    planner: &mut PathPlanner,
    nav: &mut Nav,
    goal: Vec2,
    into: PlanInto,
    scratch: &mut Vec<Vec2>,
) -> Result<Vec2, NavError> {
    let infl = plan_inflation_m(nav.radius, w.navigation);
    let out = match into {
        PlanInto::Path => {
            nav.following.wp = 0;
            &mut nav.path
        }
        PlanInto::Scratch => scratch,
    };
    match nav.layer {
        Locomotion::Aerial => {
            let (width, height) = w.arena;
            if !in_field(goal.x, goal.y, width, height) {
                return Err(NavError::GoalOutsideArena);
            }
            out.clear();
            out.push(goal);
            Ok(goal)
        }
        Locomotion::Ground => {
            let kind = if w.shared_goals.contains(&goal) {
                GoalKind::Shared
            } else {
                GoalKind::Own
            };
            let query = PlanQuery {
                from: nav.pos,
                to: goal,
                inflation_m: infl,
            };
            planner.plan(w.grid, w.arena, query, kind, out)
        }
    }
}
