//! A robot's plans: [`World::plan`] and the inflation and grid query it plans with.
//!
//! One planning function for goals, goal checks and re-plans: the [`super::path_planner`] for
//! ground robots, a straight line for aerial ones.

use parry2d::math::Vector as Vec2;

use super::error::NavError;
use super::path_planner::GoalKind;
use super::plan_into::PlanInto;
use super::plan_query::{PlanQuery, plan_inflation_m};
use super::world::World;
use crate::scenario::{Locomotion, in_field};

impl World {
    /// Inflation robot `id` plans with: body radius + `navigation.clearance_m` + half a cell,
    /// metres (see [`super::path_planner`]).
    pub(super) fn plan_inflation(&self, id: usize) -> f32 {
        plan_inflation_m(self.nav[id].radius, &self.navigation)
    }

    /// The grid query robot `id` would plan `goal` with: `Some` for a ground robot, `None`
    /// for an aerial one (it flies straight).
    pub(super) fn ground_query(&self, id: usize, goal: Vec2) -> Option<PlanQuery> {
        let nav = &self.nav[id];
        (nav.layer == Locomotion::Ground).then(|| PlanQuery {
            from: nav.pos,
            to: goal,
            inflation_m: self.plan_inflation(id),
        })
    }

    /// Plans from robot `id`'s position to `goal` (world frame, metres) and returns the effective
    /// goal. Ground robots plan on the clearance grid ([`super::path_planner::PathPlanner::plan`],
    /// inflation [`World::plan_inflation`]): a goal that is one of the scenario's shared goal
    /// points (a task's goal point or drop-off centre, the rest-station centre, compared
    /// exactly at physics precision) by descent of its shared distance field, any other goal by
    /// A*. Aerial robots fly straight, so their plan is the goal itself. The waypoints go where
    /// `into` says.
    ///
    /// # Errors
    /// [`NavError::GoalOutsideArena`] for a goal that is not a finite point in the arena; for
    /// ground robots also the planner's other errors.
    pub(super) fn plan(&mut self, id: usize, goal: Vec2, into: PlanInto) -> Result<Vec2, NavError> {
        let infl = self.plan_inflation(id);
        let nav = &mut self.nav[id];
        let out = match into {
            PlanInto::Path => {
                nav.following.wp = 0;
                &mut nav.path
            }
            PlanInto::Scratch => &mut self.pipelines.scratch,
        };
        match nav.layer {
            Locomotion::Aerial => {
                let (w, h) = self.arena;
                if !in_field(goal.x, goal.y, w, h) {
                    return Err(NavError::GoalOutsideArena);
                }
                out.clear();
                out.push(goal);
                Ok(goal)
            }
            Locomotion::Ground => {
                let kind = if self.shared_goals.contains(&goal) {
                    GoalKind::Shared
                } else {
                    GoalKind::Own
                };
                let query = PlanQuery {
                    from: nav.pos,
                    to: goal,
                    inflation_m: infl,
                };
                self.pipelines
                    .planner
                    .plan(&self.grid, self.arena, query, kind, out)
            }
        }
    }
}
