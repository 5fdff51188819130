//! The navigation grid's regions at one inflation: the sets of free cells that grid moves
//! ([`ClearanceGrid::successors`]) join, labelled once by a flood fill: after the first A*
//! that finds no path, or for the first goal check
//! ([`super::path_planner::PathPlanner::connects`]). Two cells in different
//! regions have no path between them, so a search between them is known to fail without
//! running it; without the labels an A* to a walled-in goal visits every cell of the start's
//! region, which takes seconds on a grid near the 2^24-cell limit, for every robot sent there.
//!
//! The moves are symmetric, so a region is exactly the set of cells A* can reach from any of
//! its cells: the labels answer "does a path exist" as the search would, never otherwise.

use super::clearance_grid::ClearanceGrid;

/// Most inflations whose labels are kept at once (4 bytes a cell each: 64 MiB at the largest
/// grid); labelling a fifth drops the least recently used, labelled again if needed.
const MAX_LABELLED_INFLATIONS: usize = 4;

/// The label of a cell that is not free at the inflation.
const NOT_FREE: u32 = u32::MAX;

/// Region labels of the navigation grid, per inflation, made on demand.
#[derive(Debug, Clone, Default)]
pub(super) struct GridRegions {
    /// (inflation's bits, one label per cell), least recently used first.
    labelled: Vec<(u32, Vec<u32>)>,
    /// The flood fill's stack, reused.
    stack: Vec<u32>,
}

impl GridRegions {
    /// Whether cells `a` and `b` are known to lie in different regions at `inflation` metres:
    /// `true` only when that inflation has been labelled ([`GridRegions::label`]) and the
    /// labels differ (a cell that is not free is in no region).
    pub(super) fn known_apart(&self, inflation: f32, a: u32, b: u32) -> bool {
        self.labels(inflation)
            .is_some_and(|l| l[a as usize] != l[b as usize] || l[a as usize] == NOT_FREE)
    }

    /// Whether a path joins cells `a` and `b` at `inflation` metres: both free and in one
    /// region. Labels the inflation first if needed (one pass over the grid).
    pub(super) fn connected(
        &mut self,
        grid: &ClearanceGrid,
        inflation: f32,
        a: u32,
        b: u32,
    ) -> bool {
        let labels = self.label(grid, inflation);
        labels[a as usize] != NOT_FREE && labels[a as usize] == labels[b as usize]
    }

    /// The region labels at `inflation` metres (one per cell, [`NOT_FREE`] for a cell that
    /// is not free), made by a flood fill over the whole grid unless already made.
    pub(super) fn label(&mut self, grid: &ClearanceGrid, inflation: f32) -> &[u32] {
        let bits = inflation.to_bits();
        let k = match self.labelled.iter().position(|(b, _)| *b == bits) {
            // Least recently used goes first: the one used now moves to the end.
            Some(k) => {
                let used = self.labelled.remove(k);
                self.labelled.push(used);
                self.labelled.len() - 1
            }
            None => {
                if self.labelled.len() >= MAX_LABELLED_INFLATIONS {
                    self.labelled.remove(0);
                }
                let labels = flood(grid, inflation, &mut self.stack);
                self.labelled.push((bits, labels));
                self.labelled.len() - 1
            }
        };
        &self.labelled[k].1
    }

    fn labels(&self, inflation: f32) -> Option<&[u32]> {
        let bits = inflation.to_bits();
        self.labelled
            .iter()
            .find(|(b, _)| *b == bits)
            .map(|(_, l)| l.as_slice())
    }
}

/// One label per cell of `grid`: the regions at `inflation` numbered from 0 in the order of
/// their lowest cell, [`NOT_FREE`] for cells that are not free.
fn flood(grid: &ClearanceGrid, inflation: f32, stack: &mut Vec<u32>) -> Vec<u32> {
    let (nx, ny) = grid.dims();
    let cells = nx as usize * ny as usize;
    let mut labels = vec![NOT_FREE; cells];
    let mut next = 0;
    for seed in 0..cells as u32 {
        if labels[seed as usize] != NOT_FREE || !grid.is_free(seed, inflation) {
            continue;
        }
        labels[seed as usize] = next;
        stack.push(seed);
        while let Some(c) = stack.pop() {
            for (n, _) in grid.successors(c, inflation) {
                if labels[n as usize] == NOT_FREE {
                    labels[n as usize] = next;
                    stack.push(n);
                }
            }
        }
        next += 1;
    }
    labels
}

#[cfg(test)]
mod tests {
    use parry2d::math::{Pose, Vector as Vec2};
    use parry2d::shape::Cuboid;

    use super::*;
    use crate::scenario::{Arena, Positive};
    use crate::world::bodies::{StaticObstacle, StaticShape};
    use crate::world::path_planner::{GoalKind, PathPlanner};
    use crate::world::plan_query::PlanQuery;

    /// A 10 x 10 m grid of 0.25 m cells, clearance capped at 2 m, with (when `boxed`) a
    /// closed square of walls 0.5 m thick, 3 m across, around (7.5, 7.5).
    fn grid(boxed: bool) -> ClearanceGrid {
        let wall = |cx: f32, cy: f32, hx: f32, hy: f32| StaticObstacle {
            shape: StaticShape::Cuboid(Cuboid::new(Vec2::new(hx, hy))),
            pose: Pose::translation(cx, cy),
            is_wall: false,
        };
        let statics = if boxed {
            vec![
                wall(7.5, 6.0, 1.75, 0.25),
                wall(7.5, 9.0, 1.75, 0.25),
                wall(6.0, 7.5, 0.25, 1.75),
                wall(9.0, 7.5, 0.25, 1.75),
            ]
        } else {
            Vec::new()
        };
        let arena = Arena {
            width_m: Positive::new(10.0).unwrap(),
            height_m: Positive::new(10.0).unwrap(),
            wall_thickness_m: Positive::new(0.5).unwrap(),
        };
        ClearanceGrid::build(&arena, &statics, 0.25, 2.0)
    }

    #[test]
    fn a_walled_in_cell_is_apart_and_labels_agree_with_a_star() {
        let g = grid(true);
        let infl = 0.3;
        let mut regions = GridRegions::default();
        let outside = g.cell_index(Vec2::new(2.0, 2.0));
        let inside = g.cell_index(Vec2::new(7.5, 7.5));
        let elsewhere = g.cell_index(Vec2::new(2.0, 8.0));
        assert!(
            !regions.known_apart(infl, outside, inside),
            "not labelled yet"
        );
        assert!(!regions.connected(&g, infl, outside, inside));
        assert!(regions.connected(&g, infl, outside, elsewhere));
        assert!(regions.known_apart(infl, outside, inside));
        // Every free cell: connected to `outside` exactly when A* finds a path. A fresh
        // planner per cell, so that the answer is the search's, not the planner's own labels.
        let (nx, ny) = g.dims();
        let mut walled_in = 0;
        for c in (0..nx * ny)
            .step_by(7)
            .filter(|&c| g.is_free(c, infl) && c != outside)
        {
            let query = PlanQuery {
                from: g.cell_center(outside),
                to: g.cell_center(c),
                inflation_m: infl,
            };
            let mut planner = PathPlanner::new();
            let planned = planner.plan(&g, (10.0, 10.0), query, GoalKind::Own, &mut Vec::new());
            assert_eq!(planner.astar_searches(), 1, "cell {c}: A* ran");
            let connected = regions.connected(&g, infl, outside, c);
            assert_eq!(planned.is_ok(), connected, "cell {c}");
            walled_in += usize::from(!connected);
        }
        assert!(walled_in > 0, "some sampled cells lie inside the box");
    }

    #[test]
    fn robots_sent_to_a_walled_in_goal_search_once_between_them() {
        let g = grid(true);
        let mut planner = PathPlanner::new();
        let mut out = Vec::new();
        for i in 0..10 {
            let query = PlanQuery {
                from: Vec2::new(1.0 + 0.5 * i as f32, 1.5),
                to: Vec2::new(7.5, 7.5),
                inflation_m: 0.3,
            };
            let planned = planner.plan(&g, (10.0, 10.0), query, GoalKind::Own, &mut out);
            assert_eq!(planned, Err(crate::world::NavError::NoPath));
        }
        // The first search finds no path and labels the regions; the other nine starts lie
        // in the same region and fail from the labels (each searched the region before).
        assert_eq!(planner.astar_searches(), 1);
    }

    #[test]
    fn at_most_four_inflations_are_kept() {
        let g = grid(false);
        let mut regions = GridRegions::default();
        for infl in [0.1, 0.2, 0.3, 0.4, 0.5] {
            regions.label(&g, infl);
        }
        assert_eq!(regions.labelled.len(), MAX_LABELLED_INFLATIONS);
        assert!(regions.labels(0.1).is_none() && regions.labels(0.5).is_some());
    }
}
