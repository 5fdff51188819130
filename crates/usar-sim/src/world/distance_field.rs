//! Shared navigation: a distance field (the grid cost to one goal cell of every free cell) that
//! every ground robot of one clearance class heading to that goal takes its path from.
//!
//! The field is Dijkstra's algorithm run backwards from the goal over the same 8-connected,
//! no-corner-cutting moves and integer costs as the planner's A* ([`super::path_planner`]), so a
//! cell's field cost equals A*'s optimal cost from that cell to the goal. It is computed lazily:
//! a query expands the search only until the queried cell is settled, and later queries resume
//! it, so a field costs at most one full Dijkstra over the free cells, however many robots use
//! it. A path is read off by descent: from the start, step to the first neighbour through which
//! the cost falls by exactly the move's cost, until the goal. Ties are broken by a fixed
//! neighbour order, diagonals first: north-east, north-west, south-east, south-west, then
//! east, west, north, south. (With straight moves first, the smoothed paths of
//! `scenarios/paper.ron` hug other sides of the debris and three of the nine calibration
//! statistics, the HP ratios, leave their bands; diagonals first keeps all nine inside.) Settled costs are final and every
//! such neighbour is settled before the cell itself, so a path does not depend on the order of
//! earlier queries: deterministic. A cell whose cost would pass `u32::MAX` (a path of over
//! 4.29 million straight moves) stays unreached, as A* finds no path to it.
//!
//! Source: E. W. Dijkstra, "A note on two problems in connexion with graphs", Numerische
//! Mathematik 1 (1959); the shared-field idea is that of flow-field crowd navigation
//! (Treuille, Cooper and Popovic, "Continuum crowds", SIGGRAPH 2006).

use super::bucket_queue::BucketQueue;
use super::clearance_grid::ClearanceGrid;
use super::grid_moves::{DIAGONAL_COST, STRAIGHT_COST};

/// The largest move cost, the bucket queue's window.
const MAX_MOVE_COST: u32 = if DIAGONAL_COST > STRAIGHT_COST {
    DIAGONAL_COST
} else {
    STRAIGHT_COST
};

/// Cost of a cell the search has not reached (yet, or at all).
const UNREACHED: u32 = u32::MAX;

/// The grid cost to one goal cell for one planning inflation (a clearance class), computed
/// lazily (see the module docs). Costs are in the planner's units: 1000 per straight move,
/// 1414 per diagonal move of one cell.
#[derive(Debug, Clone)]
pub struct DistanceField {
    goal: u32,
    inflation_bits: u32,
    /// Tentative cost per cell, final once `settled`; [`UNREACHED`] if not reached.
    cost: Vec<u32>,
    settled: Vec<bool>,
    /// Dijkstra's open set: cells by cost, smallest first (Dial's bucket queue; equal costs
    /// in any order, which changes no settled cost and so no path).
    open: BucketQueue,
}

impl DistanceField {
    /// A field towards cell `goal` of `grid` for planning inflation `inflation` metres (the
    /// goal cell must be free for it; the planner snaps goals before it asks). Nothing is
    /// expanded yet.
    pub fn new(grid: &ClearanceGrid, goal: u32, inflation: f32) -> Self {
        let (nx, ny) = grid.dims();
        let cells = (nx * ny) as usize;
        let mut cost = vec![UNREACHED; cells];
        cost[goal as usize] = 0;
        let mut open = BucketQueue::new(MAX_MOVE_COST);
        open.push(0, goal);
        Self {
            goal,
            inflation_bits: inflation.to_bits(),
            cost,
            settled: vec![false; cells],
            open,
        }
    }

    /// Turns this field into the field [`DistanceField::new`] makes towards cell `goal` of
    /// `grid` for planning inflation `inflation` metres (nothing expanded yet), in the memory
    /// of its cells: every cell's cost and settled flag written afresh, the open set made
    /// anew (so the field holds the bytes a new one holds, [`DistanceField::heap_bytes`], and
    /// a store keeps as many). For a store that drops one field to make room for another: on
    /// a grid of millions of cells, a new field's pages cost more to fault in than to
    /// overwrite (`shared_fields.rs`). The same costs and descents as a new field. `goal`
    /// must be a cell of `grid` (below `nx * ny`, as for `new`, which panics likewise
    /// otherwise) and free for `inflation`.
    pub fn renew(&mut self, grid: &ClearanceGrid, goal: u32, inflation: f32) {
        let (nx, ny) = grid.dims();
        let cells = (nx * ny) as usize;
        self.cost.clear();
        self.cost.resize(cells, UNREACHED);
        self.cost[goal as usize] = 0;
        self.settled.clear();
        self.settled.resize(cells, false);
        self.open = BucketQueue::new(MAX_MOVE_COST);
        self.open.push(0, goal);
        self.goal = goal;
        self.inflation_bits = inflation.to_bits();
    }

    /// Heap memory a field of `grid` holds when made ([`DistanceField::new`]), bytes: a cost
    /// (4 bytes) and a settled flag (1 byte) per cell, and the open set's bucket list (1,415
    /// empty buckets). 80 MiB on a grid at the 2^24-cell limit
    /// ([`crate::scenario::limits::MAX_NAV_CELLS`]).
    pub fn new_heap_bytes(grid: &ClearanceGrid) -> usize {
        let (nx, ny) = grid.dims();
        let cells = nx as usize * ny as usize;
        cells * (size_of::<u32>() + size_of::<bool>())
            + (MAX_MOVE_COST as usize + 1) * size_of::<Vec<u32>>()
    }

    /// Heap memory the field holds now, bytes: [`DistanceField::new_heap_bytes`] plus what
    /// its open set has grown to (at most a few bytes per cell of the search's frontier).
    pub fn heap_bytes(&self) -> usize {
        self.cost.capacity() * size_of::<u32>()
            + self.settled.capacity() * size_of::<bool>()
            + self.open.heap_bytes()
    }

    /// Where the field's costs are held (tests check that a renewed field keeps its memory).
    #[cfg(test)]
    pub(super) fn cost_memory(&self) -> *const u32 {
        self.cost.as_ptr()
    }

    /// Whether this is the field towards cell `goal` for inflation `inflation` metres.
    pub fn is_for(&self, goal: u32, inflation: f32) -> bool {
        self.goal == goal && self.inflation_bits == inflation.to_bits()
    }

    /// The goal cell.
    pub fn goal(&self) -> u32 {
        self.goal
    }

    /// The optimal grid cost from cell `from` to the goal (the A* cost), or `None` when no
    /// path exists (then the whole field has been expanded). Expands the search as far as
    /// needed.
    pub fn cost_from(&mut self, grid: &ClearanceGrid, from: u32) -> Option<u32> {
        let inflation = f32::from_bits(self.inflation_bits);
        while !self.settled[from as usize] {
            let (c, u) = self.open.pop()?;
            if self.settled[u as usize] {
                continue;
            }
            self.settled[u as usize] = true;
            for (v, w) in grid.successors(u, inflation) {
                // A cost past `u32::MAX` leaves the cell unreached (module docs).
                let Some(reached) = c.checked_add(w) else {
                    continue;
                };
                let slot = &mut self.cost[v as usize];
                if !self.settled[v as usize] && reached < *slot {
                    *slot = reached;
                    self.open.push(reached, v);
                }
            }
        }
        Some(self.cost[from as usize])
    }

    /// The grid path from cell `from` (free for the field's inflation) to the goal by descent
    /// (module docs), both ends included, written into `out`; `false` (and `out` empty) when
    /// no path exists.
    pub fn descend(&mut self, grid: &ClearanceGrid, from: u32, out: &mut Vec<u32>) -> bool {
        out.clear();
        self.cost_from(grid, from).is_some() && self.descend_settled(grid, from, out)
    }

    /// [`DistanceField::descend`] from a cell `from` the field has already settled
    /// ([`DistanceField::cost_from`] returned `Some` for it): the same path, reading the field
    /// only, so descents from many cells may run side by side. `false` (and `out` empty) when
    /// `from` is not settled.
    pub fn descend_settled(&self, grid: &ClearanceGrid, from: u32, out: &mut Vec<u32>) -> bool {
        out.clear();
        if !self.settled[from as usize] {
            return false;
        }
        let inflation = f32::from_bits(self.inflation_bits);
        let mut cell = from;
        out.push(cell);
        while cell != self.goal {
            let here = self.cost[cell as usize];
            // A settled predecessor on a shortest path exists for every settled cell but the
            // goal; unsettled neighbours cost at least `here` and never qualify.
            let on_shortest = |&(n, w): &(u32, u32)| {
                self.settled[n as usize] && self.cost[n as usize].checked_add(w) == Some(here)
            };
            let mut moves = grid.successors(cell, inflation);
            let next = moves
                .clone()
                .filter(|&(_, w)| w == DIAGONAL_COST)
                .find(on_shortest)
                .or_else(|| moves.find(on_shortest));
            let Some((n, _)) = next else {
                // Unreachable for a settled cell (see above); stop rather than loop.
                out.clear();
                return false;
            };
            cell = n;
            out.push(cell);
        }
        true
    }
}

#[cfg(test)]
mod tests {
    use parry2d::math::Pose;
    use parry2d::math::Vector as Vec2;
    use parry2d::shape::Cuboid;
    use pathfinding::prelude::astar;
    use proptest::prelude::*;

    use super::*;
    use crate::scenario::{Arena, Positive};
    use crate::world::bodies::{StaticObstacle, StaticShape};

    const INFL: f32 = 0.6;

    fn block(cx: f32, cy: f32, hx: f32, hy: f32) -> StaticObstacle {
        StaticObstacle {
            shape: StaticShape::Cuboid(Cuboid::new(Vec2::new(hx, hy))),
            pose: Pose::translation(cx, cy),
            is_wall: false,
        }
    }

    /// A 6 m x 6 m grid of 0.25 m cells (24 x 24) with a wall across it from x = 0 to 4.5 at
    /// y = 3 and a block at (4.5, 1.2).
    fn small_grid() -> ClearanceGrid {
        let arena = Arena {
            width_m: Positive::new(6.0).unwrap(),
            height_m: Positive::new(6.0).unwrap(),
            wall_thickness_m: Positive::new(0.5).unwrap(),
        };
        let statics = [block(2.25, 3.0, 2.25, 0.2), block(4.5, 1.2, 0.3, 0.3)];
        ClearanceGrid::build(&arena, &statics, 0.25, 2.0)
    }

    fn a_star_cost(g: &ClearanceGrid, from: u32, goal: u32) -> Option<u32> {
        astar(
            &from,
            |&n| g.successors(n, INFL),
            |&n| g.octile(n, goal),
            |&n| n == goal,
        )
        .map(|(_, c)| c)
    }

    #[test]
    fn the_field_equals_a_stars_cost_on_a_small_grid() {
        let g = small_grid();
        let goal = g.cell_index(Vec2::new(1.0, 5.0));
        assert!(g.is_free(goal, INFL));
        let mut field = DistanceField::new(&g, goal, INFL);
        let (nx, ny) = g.dims();
        let mut reachable = 0;
        for from in 0..nx * ny {
            if !g.is_free(from, INFL) {
                continue;
            }
            let expected = a_star_cost(&g, from, goal);
            assert_eq!(field.cost_from(&g, from), expected, "cell {from}");
            reachable += usize::from(expected.is_some());
        }
        assert!(reachable > 300, "{reachable} reachable cells");
    }

    #[test]
    fn descent_is_a_shortest_connected_path_to_the_goal() {
        let g = small_grid();
        let goal = g.cell_index(Vec2::new(1.0, 5.0));
        let from = g.cell_index(Vec2::new(1.0, 1.0));
        let mut field = DistanceField::new(&g, goal, INFL);
        let mut path = Vec::new();
        assert!(field.descend(&g, from, &mut path));
        assert_eq!((path[0], *path.last().unwrap()), (from, goal));
        let mut total = 0;
        for step in path.windows(2) {
            let w = g
                .successors(step[0], INFL)
                .find(|&(n, _)| n == step[1])
                .map(|(_, w)| w);
            total += w.expect("consecutive cells are grid neighbours");
        }
        assert_eq!(Some(total), a_star_cost(&g, from, goal));
        // The path goes round the wall's east end (x > 4.5 m).
        assert!(path.iter().any(|&c| g.cell_center(c).x > 4.5));
    }

    #[test]
    fn a_walled_off_cell_has_no_path() {
        let arena = Arena {
            width_m: Positive::new(6.0).unwrap(),
            height_m: Positive::new(6.0).unwrap(),
            wall_thickness_m: Positive::new(0.5).unwrap(),
        };
        let g = ClearanceGrid::build(&arena, &[block(3.0, 3.0, 3.5, 0.2)], 0.25, 2.0);
        let goal = g.cell_index(Vec2::new(1.0, 5.0));
        let mut field = DistanceField::new(&g, goal, INFL);
        let mut path = vec![7];
        let from = g.cell_index(Vec2::new(1.0, 1.0));
        assert_eq!(field.cost_from(&g, from), None);
        assert!(!field.descend(&g, from, &mut path));
        assert!(path.is_empty());
        assert!(field.descend(&g, g.cell_index(Vec2::new(5.0, 5.0)), &mut path));
    }

    /// A descent from a settled cell reads the same path off the field as a descent that
    /// expands it, from every cell the field settled on its way to one far start; a cell it
    /// has not settled yet gives no path.
    #[test]
    fn a_settled_descent_reads_the_descents_path() {
        let g = small_grid();
        let goal = g.cell_index(Vec2::new(1.0, 5.0));
        let mut field = DistanceField::new(&g, goal, INFL);
        let far = g.cell_index(Vec2::new(1.0, 1.0));
        assert!(field.cost_from(&g, far).is_some());
        let (nx, ny) = g.dims();
        let (mut settled, mut a, mut b) = (0, vec![7], Vec::new());
        for from in 0..nx * ny {
            if !field.settled[from as usize] {
                assert!(!field.descend_settled(&g, from, &mut a) && a.is_empty());
                continue;
            }
            settled += 1;
            let found = field.descend_settled(&g, from, &mut a);
            let fresh = DistanceField::new(&g, goal, INFL).descend(&g, from, &mut b);
            assert_eq!((found, &a), (fresh, &b), "cell {from}");
        }
        assert!(settled > 100, "{settled} settled cells");
    }

    /// A field renewed for another goal after a full expansion towards its own holds the
    /// state of a new field towards that goal (every cost, every settled flag) and answers
    /// every cell's cost and descent as a new field does, in the memory it held.
    #[test]
    fn a_renewed_field_is_a_new_field() {
        let g = small_grid();
        let (first, goal) = (Vec2::new(5.0, 1.0), Vec2::new(1.0, 5.0));
        let mut field = DistanceField::new(&g, g.cell_index(first), INFL);
        let blocked = g.cell_index(Vec2::new(4.5, 1.2));
        assert_eq!(field.cost_from(&g, blocked), None, "expanded in full");
        let memory = field.cost_memory();
        let goal = g.cell_index(goal);
        field.renew(&g, goal, INFL);
        let mut fresh = DistanceField::new(&g, goal, INFL);
        assert_eq!(field.cost_memory(), memory, "the same memory");
        assert_eq!(field.heap_bytes(), fresh.heap_bytes());
        assert!(field.is_for(goal, INFL) && !field.is_for(g.cell_index(first), INFL));
        assert_eq!((&field.cost, &field.settled), (&fresh.cost, &fresh.settled));
        let (nx, ny) = g.dims();
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for from in 0..nx * ny {
            assert_eq!(
                field.cost_from(&g, from),
                fresh.cost_from(&g, from),
                "cell {from}"
            );
            let found = field.descend(&g, from, &mut a);
            assert_eq!(
                (found, &a),
                (fresh.descend(&g, from, &mut b), &b),
                "cell {from}"
            );
        }
    }

    /// A new field holds what `new_heap_bytes` says (plus the one bucket its goal went
    /// into); a fully expanded one holds more only by its open set's buckets.
    #[test]
    fn heap_bytes_count_the_cells_and_the_open_set() {
        let g = small_grid();
        let goal = g.cell_index(Vec2::new(1.0, 5.0));
        let mut field = DistanceField::new(&g, goal, INFL);
        let made = DistanceField::new_heap_bytes(&g);
        assert_eq!(made, 24 * 24 * 5 + 1415 * size_of::<Vec<u32>>());
        let first = field.heap_bytes();
        assert!((made..=made + 64).contains(&first), "{first} of {made}");
        // A cell inside the block: never reached, after a full expansion.
        let blocked = g.cell_index(Vec2::new(4.5, 1.2));
        assert_eq!(field.cost_from(&g, blocked), None);
        let full = field.heap_bytes();
        assert!((first..=made + 24 * 24 * 4 * 8).contains(&full), "{full}");
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// Paths do not depend on the order of earlier queries.
        #[test]
        fn paths_do_not_depend_on_query_order(
            starts in prop::collection::vec((0.1f32..5.9, 0.1f32..5.9), 1..6)
        ) {
            let g = small_grid();
            let goal = g.cell_index(Vec2::new(1.0, 5.0));
            let mut shared = DistanceField::new(&g, goal, INFL);
            for &(x, y) in &starts {
                let from = g.cell_index(Vec2::new(x, y));
                if !g.is_free(from, INFL) {
                    continue;
                }
                let (mut a, mut b) = (Vec::new(), Vec::new());
                let found = shared.descend(&g, from, &mut a);
                let fresh = DistanceField::new(&g, goal, INFL).descend(&g, from, &mut b);
                prop_assert_eq!(found, fresh);
                prop_assert_eq!(a, b);
            }
        }
    }
}
