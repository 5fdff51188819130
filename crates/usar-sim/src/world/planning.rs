//! Planning glue between a robot and the [`super::navigation`] planner: the inflations a robot
//! plans and checks with, and planning from where it stands (into its path, or to check a goal).

use parry2d::math::Vector as Vec2;

use super::error::NavError;
use super::world::World;
use crate::scenario::Locomotion;

impl World {
    /// Inflation robot `id` plans with: body radius + `navigation.clearance_m` + half a cell,
    /// metres (see [`super::navigation`]).
    pub(super) fn plan_inflation(&self, id: usize) -> f32 {
        self.nav[id].radius
            + self.navigation.clearance_m as f32
            + 0.5 * self.navigation.grid_cell_m as f32
    }

    /// Plans from robot `id`'s position to `goal` into its path; returns the effective goal.
    pub(super) fn plan_into_nav(&mut self, id: usize, goal: Vec2) -> Result<Vec2, NavError> {
        let infl = self.plan_inflation(id);
        let nav = &mut self.nav[id];
        nav.wp = 0;
        match nav.layer {
            Locomotion::Aerial => {
                let (w, h) = self.arena;
                if !(goal.is_finite()
                    && goal.x >= 0.0
                    && goal.y >= 0.0
                    && goal.x <= w
                    && goal.y <= h)
                {
                    return Err(NavError::GoalOutsideArena);
                }
                nav.path.clear();
                nav.path.push(goal);
                Ok(goal)
            }
            Locomotion::Ground => {
                self.planner
                    .plan(&self.grid, self.arena, nav.pos, goal, infl, &mut nav.path)
            }
        }
    }

    /// Plans from robot `id`'s position to `goal` without changing the robot; returns the
    /// effective goal.
    pub(super) fn plan_check(&mut self, id: usize, g: Vec2) -> Result<Vec2, NavError> {
        let infl = self.plan_inflation(id);
        let mut scratch = Vec::new();
        match self.nav[id].layer {
            Locomotion::Aerial => {
                let (w, h) = self.arena;
                if g.is_finite() && g.x >= 0.0 && g.y >= 0.0 && g.x <= w && g.y <= h {
                    Ok(g)
                } else {
                    Err(NavError::GoalOutsideArena)
                }
            }
            Locomotion::Ground => self.planner.plan(
                &self.grid,
                self.arena,
                self.nav[id].pos,
                g,
                infl,
                &mut scratch,
            ),
        }
    }
}
