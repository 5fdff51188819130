//! A* over the cells of one grid with dense per-cell arrays: the search of the `pathfinding`
//! crate's `astar` (the same open-set order, the same tie-breaking, so the same path), with the
//! crate's hash map of visited nodes replaced by arrays indexed by cell, reused between
//! searches. Detours (robots planning around others standing in their way) run it thousands
//! of times in a 1,000-robot trial, and hashing was most of their cost.
//!
//! Why the path is the crate's: the open set is a `std` binary heap ordered by (estimated
//! cost, then larger cost first) exactly as the crate's `SmallestCostHolder`, which compares
//! nothing else, and nodes are pushed, updated and popped in the crate's order (a node's cost
//! and parent are replaced when a cheaper way is found; a popped entry whose cost is above
//! the node's current cost is skipped, after the goal test). So every heap operation sees the
//! same sequence of keys, and the heap gives the same entries back. Tested against
//! `pathfinding::directed::astar::astar` on random grids.
//!
//! Costs are `u32`: a move that would take a path's cost past `u32::MAX` is not taken (the
//! crate's sum would overflow), so a goal only that far away has no path, and an estimate
//! past it counts as `u32::MAX`. Grid paths cost [`super::grid_moves::STRAIGHT_COST`] per
//! straight move, so this is a path of over 4.29 million straight moves, beyond any open
//! arena of the largest grid ([`crate::scenario::limits::MAX_NAV_CELLS`]): only a maze could
//! need one.
//!
//! Reference: P. E. Hart, N. J. Nilsson and B. Raphael, "A formal basis for the heuristic
//! determination of minimum cost paths", IEEE Trans. SSC 4(2), 1968; the order of
//! operations is that of `pathfinding` 4.16 (`src/directed/astar.rs`).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// An open-set entry: the ordering of `pathfinding`'s `SmallestCostHolder` (smallest
/// estimated cost first, then the larger cost first; the cell is not compared).
#[derive(Debug, Clone, Copy)]
struct Open {
    estimated: u32,
    cost: u32,
    cell: u32,
}

impl PartialEq for Open {
    fn eq(&self, other: &Self) -> bool {
        self.estimated == other.estimated && self.cost == other.cost
    }
}

impl Eq for Open {}

impl PartialOrd for Open {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

impl Ord for Open {
    fn cmp(&self, other: &Self) -> Ordering {
        match other.estimated.cmp(&self.estimated) {
            Ordering::Equal => self.cost.cmp(&other.cost),
            s => s,
        }
    }
}

/// Parent of the start cell.
const NO_PARENT: u32 = u32::MAX;

/// Reusable A* state for a grid of `cells` cells: per cell the best cost found and the parent
/// on that way, valid where `seen[c] == generation` (so a new search clears nothing). Empty
/// until the first [`GridAstar::search`]; then 12 bytes per cell.
#[derive(Debug, Clone, Default)]
pub(super) struct GridAstar {
    seen: Vec<u32>,
    generation: u32,
    cost: Vec<u32>,
    parent: Vec<u32>,
    open: BinaryHeap<Open>,
}

impl GridAstar {
    /// The path from cell `start` to cell `goal` (both included, `start` first) of a grid of
    /// `cells` cells, or `None` when no path exists: A* with moves `successors(cell)` (cell,
    /// integer cost) and the heuristic `heuristic(cell)`, as `pathfinding`'s `astar` would
    /// return it (module docs). Cells must be below `cells`.
    pub fn search<I>(
        &mut self,
        cells: usize,
        start: u32,
        goal: u32,
        mut successors: impl FnMut(u32) -> I,
        mut heuristic: impl FnMut(u32) -> u32,
    ) -> Option<Vec<u32>>
    where
        I: IntoIterator<Item = (u32, u32)>,
    {
        self.begin(cells);
        self.visit(start, 0, NO_PARENT);
        self.open.push(Open {
            estimated: 0,
            cost: 0,
            cell: start,
        });
        while let Some(Open { cost, cell, .. }) = self.open.pop() {
            if cell == goal {
                return Some(self.path_to(goal));
            }
            if cost > self.cost[cell as usize] {
                continue;
            }
            for (next, move_cost) in successors(cell) {
                // A path costing more than `u32::MAX` is no path (module docs).
                let Some(new_cost) = cost.checked_add(move_cost) else {
                    continue;
                };
                let n = next as usize;
                if self.seen[n] == self.generation && self.cost[n] <= new_cost {
                    continue;
                }
                self.visit(next, new_cost, cell);
                self.open.push(Open {
                    estimated: new_cost.saturating_add(heuristic(next)),
                    cost: new_cost,
                    cell: next,
                });
            }
        }
        None
    }

    /// Starts a search over `cells` cells: a new generation (clearing the arrays only when
    /// the grid changed or the generation counter wraps) and an empty open set.
    fn begin(&mut self, cells: usize) {
        if self.seen.len() != cells || self.generation == u32::MAX {
            self.seen.clear();
            self.seen.resize(cells, 0);
            self.cost.resize(cells, 0);
            self.parent.resize(cells, NO_PARENT);
            self.generation = 0;
        }
        self.generation += 1;
        self.open.clear();
    }

    fn visit(&mut self, cell: u32, cost: u32, parent: u32) {
        let c = cell as usize;
        self.seen[c] = self.generation;
        self.cost[c] = cost;
        self.parent[c] = parent;
    }

    /// The cells from the start to `goal` by parents.
    fn path_to(&self, goal: u32) -> Vec<u32> {
        let mut path = vec![goal];
        let mut c = goal;
        while self.parent[c as usize] != NO_PARENT {
            c = self.parent[c as usize];
            path.push(c);
        }
        path.reverse();
        path
    }
}

#[cfg(test)]
mod tests {
    use pathfinding::prelude::astar;
    use proptest::prelude::*;

    use super::*;

    /// A `w x h` grid with `blocked` cells, 8-connected moves (straight cost `straight[c]`,
    /// diagonal `diagonal[c]` of the cell moved to, small so that ties are many).
    #[derive(Debug)]
    struct Maze {
        w: u32,
        h: u32,
        blocked: Vec<bool>,
        straight: Vec<u32>,
        diagonal: Vec<u32>,
    }

    impl Maze {
        fn successors(&self, c: u32) -> Vec<(u32, u32)> {
            let (x, y) = ((c % self.w) as i64, (c / self.w) as i64);
            let mut out = Vec::new();
            for (dx, dy) in [
                (1, 0),
                (-1, 0),
                (0, 1),
                (0, -1),
                (1, 1),
                (-1, 1),
                (1, -1),
                (-1, -1),
            ] {
                let (nx, ny) = (x + dx, y + dy);
                if nx < 0 || ny < 0 || nx >= i64::from(self.w) || ny >= i64::from(self.h) {
                    continue;
                }
                let n = (ny as u32) * self.w + nx as u32;
                if self.blocked[n as usize] {
                    continue;
                }
                let cost = if dx != 0 && dy != 0 {
                    self.diagonal[n as usize]
                } else {
                    self.straight[n as usize]
                };
                out.push((n, cost));
            }
            out
        }
    }

    fn maze() -> impl Strategy<Value = Maze> {
        (2u32..16, 2u32..16).prop_flat_map(|(w, h)| {
            let n = (w * h) as usize;
            (
                prop::collection::vec(prop::bool::weighted(0.3), n),
                prop::collection::vec(1u32..4, n),
                prop::collection::vec(1u32..6, n),
            )
                .prop_map(move |(blocked, straight, diagonal)| Maze {
                    w,
                    h,
                    blocked,
                    straight,
                    diagonal,
                })
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(512))]

        /// The same path as `pathfinding`'s `astar` (or none with it), with an admissible
        /// heuristic or an arbitrary one (stale open entries and many ties), over several
        /// searches of one reused state.
        #[test]
        fn finds_the_path_of_pathfinding_astar(
            m in maze(),
            queries in prop::collection::vec((any::<u32>(), any::<u32>(), any::<bool>()), 1..6),
            arbitrary in prop::collection::vec(0u32..12, 256),
        ) {
            let cells = (m.w * m.h) as usize;
            let mut ours = GridAstar::default();
            for &(s, g, admissible) in &queries {
                let (start, goal) = (s % (m.w * m.h), g % (m.w * m.h));
                let heuristic = |c: u32| {
                    if admissible {
                        let (dx, dy) = ((c % m.w).abs_diff(goal % m.w), (c / m.w).abs_diff(goal / m.w));
                        dx.max(dy)
                    } else {
                        arbitrary[c as usize % arbitrary.len()]
                    }
                };
                let reference = astar(&start, |&c| m.successors(c), |&c| heuristic(c), |&c| c == goal)
                    .map(|(path, _)| path);
                let found = ours.search(cells, start, goal, |c| m.successors(c), heuristic);
                prop_assert_eq!(found, reference, "start {} goal {}", start, goal);
            }
        }
    }

    /// The generation counter wraps by clearing the arrays: a cell seen by an early
    /// generation does not count as seen (with its old cost) when that generation number
    /// comes round again.
    #[test]
    fn generations_wrap_without_stale_cells() {
        let line = |c: u32| {
            [c.checked_sub(1), (c < 3).then_some(c + 1)]
                .into_iter()
                .flatten()
                .map(|n| (n, 1))
        };
        let mut a = GridAstar::default();
        // Generation 1 sees every cell, cell 1 at cost 1.
        assert_eq!(a.search(4, 0, 3, line, |_| 0), Some(vec![0, 1, 2, 3]));
        a.generation = u32::MAX - 1;
        // Generation u32::MAX sees cell 3 only.
        assert_eq!(a.search(4, 3, 3, line, |_| 0), Some(vec![3]));
        // Generation 1 again: a stale cell 1 (cost 1 <= 1) would be skipped and no path found.
        assert_eq!(a.search(4, 0, 3, line, |_| 0), Some(vec![0, 1, 2, 3]));
        assert_eq!(a.generation, 1);
        // An unreachable goal: no path.
        assert_eq!(a.search(4, 0, 3, |_| std::iter::empty(), |_| 0), None);
    }

    /// A goal whose path would cost more than `u32::MAX` has no path, and the search neither
    /// wraps nor panics (a debug build panicked on the overflowing sum); a heuristic past
    /// `u32::MAX` with the cost counts as `u32::MAX`.
    #[test]
    fn a_path_cost_past_u32_max_is_no_path() {
        let half = u32::MAX / 2;
        let line = move |c: u32| (c < 3).then_some((c + 1, half)).into_iter();
        let mut a = GridAstar::default();
        // Cell 2 costs 2 * half = u32::MAX - 1: still found.
        assert_eq!(a.search(4, 0, 2, line, |_| 0), Some(vec![0, 1, 2]));
        // Cell 3 would cost 3 * half: beyond u32, no path.
        assert_eq!(a.search(4, 0, 3, line, |_| 0), None);
        assert_eq!(a.search(4, 0, 2, line, |_| u32::MAX), Some(vec![0, 1, 2]));
    }
}
