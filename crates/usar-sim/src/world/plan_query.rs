//! One planning query of a ground robot and its endpoints snapped to free cells.
//!
//! Also the inflation a robot of a given radius plans with, and the waypoints a plan between
//! the snapped endpoints writes.

use parry2d::math::Vector as Vec2;

use super::clearance_grid::ClearanceGrid;
use super::error::NavError;
use crate::scenario::{NavigationParams, in_field};

/// One planning query of a ground robot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanQuery {
    /// Where the robot stands, world frame, metres.
    pub from: Vec2,
    /// The requested goal, world frame, metres (inside the arena, or the plan fails).
    pub to: Vec2,
    /// Planning inflation: a cell is free when its clearance is at least this, metres (> 0;
    /// the world uses body radius + `navigation.clearance_m` + half a cell).
    pub inflation_m: f32,
}

/// Inflation a robot of body radius `radius_m` plans with: `radius_m +
/// navigation.clearance_m + navigation.grid_cell_m / 2`, metres, in `f32` (see
/// [`super::clearance_grid`]).
pub(super) fn plan_inflation_m(radius_m: f32, navigation: &NavigationParams) -> f32 {
    radius_m + navigation.clearance_m.get() as f32 + 0.5 * navigation.grid_cell_m.get() as f32
}

/// Start and goal of a plan after snapping (see
/// [`super::path_planner::PathPlanner::plan`]).
pub(super) struct Endpoints {
    /// The cell the query's start lies in.
    pub(super) start_raw: u32,
    /// The start cell: `start_raw`, or the nearest free cell when it is blocked.
    pub(super) start: u32,
    /// The goal cell: the goal's own, or the nearest free cell when it is blocked.
    pub(super) goal: u32,
    /// The effective goal: the requested goal, or the snapped goal cell's centre.
    pub(super) goal_point: Vec2,
}

impl Endpoints {
    /// Snaps the query's start and goal to free cells for its inflation.
    pub(super) fn snap(
        grid: &ClearanceGrid,
        arena: (f32, f32),
        query: PlanQuery,
    ) -> Result<Self, NavError> {
        let PlanQuery {
            from,
            to,
            inflation_m: inflation,
        } = query;
        if !in_field(to.x, to.y, arena.0, arena.1) {
            return Err(NavError::GoalOutsideArena);
        }
        let snap_radius = inflation + 2.0 * grid.cell_m();
        let start_raw = grid.cell_index(from);
        let start = if grid.is_free(start_raw, inflation) {
            start_raw
        } else {
            grid.nearest_free(from, inflation, snap_radius)
                .ok_or(NavError::StartBlocked)?
        };
        let goal_raw = grid.cell_index(to);
        let (goal, goal_point) = if grid.is_free(goal_raw, inflation) {
            (goal_raw, to)
        } else {
            let g = grid
                .nearest_free(to, inflation, snap_radius)
                .ok_or(NavError::GoalBlocked)?;
            (g, grid.cell_center(g))
        };
        Ok(Self {
            start_raw,
            start,
            goal,
            goal_point,
        })
    }

    /// Writes the waypoints of the smoothed `cells` (start to goal) into `out`: the snapped
    /// start's centre if the start moved, the interior cells' centres, the effective goal.
    pub(super) fn write(&self, grid: &ClearanceGrid, cells: &[u32], out: &mut Vec<Vec2>) -> Vec2 {
        out.clear();
        if self.start != self.start_raw {
            out.push(grid.cell_center(self.start));
        }
        if cells.len() > 2 {
            out.extend(
                cells[1..cells.len() - 1]
                    .iter()
                    .map(|&c| grid.cell_center(c)),
            );
        }
        out.push(self.goal_point);
        self.goal_point
    }
}
