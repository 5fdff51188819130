//! A bounded flood from a goal cell: proves "no path" before A* would flood the whole grid to
//! find it out.
//!
//! A* returns no path only after expanding every cell it can reach from the start. When the
//! goal is shut in (robots standing round a drop-off, a detour's goal behind a crowd) and the
//! start is not, that is the whole arena: in a 1,000-robot trial a handful of such searches
//! took two thirds of all A* expansions. The cells that can reach the goal form a small
//! region then, and a flood of it (no heap, a few cells) settles the question.
//!
//! Why it is exact: every cell on a path after the start is a move's target, so it is free
//! for the inflation and not excluded by the caller's filter (a detour's standing robots).
//! Moves between two such cells go both ways (the grid's successors are symmetric between
//! free cells, and the filter only looks at the target). So the cells that can reach the
//! goal are the goal's connected component of those cells, and a path exists if and only if
//! the start is the goal or one of the start's moves enters that component. When the flood
//! of the component ends within its budget and neither holds, A* would return no path too;
//! in every other case the search runs as it would have.

/// Cells flooded from the goal before the check gives up and A* runs anyway. A shut-in goal's
/// region is a few cells to a few hundred (a disc of robots round it); an open goal costs the
/// search this many cheap steps first.
pub(super) const GOAL_REGION_BUDGET_CELLS: usize = 1024;

/// The region of cells flooded from a goal, by generation stamp (a new flood clears
/// nothing), and the flood's queue. Empty (no memory) until the first flood; then one `u32`
/// per grid cell.
#[derive(Debug, Clone, Default)]
pub(super) struct GoalRegion {
    stamp: Vec<u32>,
    current: u32,
    queue: Vec<u32>,
}

impl GoalRegion {
    /// Whether no path can lead from cell `start` to cell `goal` (module docs), in a grid of
    /// `cells` cells whose moves are `moves(cell)` (cell, cost) (symmetric between cells that
    /// are some move's target), and `goal_enterable` says whether `goal` is a move's target.
    /// `false` means "maybe a path" (the region is larger than `budget` cells, or it holds a
    /// move of the start): run the search.
    pub fn proves_no_path<I>(
        &mut self,
        cells: usize,
        (start, goal): (u32, u32),
        goal_enterable: bool,
        budget: usize,
        mut moves: impl FnMut(u32) -> I,
    ) -> bool
    where
        I: IntoIterator<Item = (u32, u32)>,
    {
        if start == goal {
            return false;
        }
        if !goal_enterable {
            return true;
        }
        if !self.flood(cells, goal, budget, &mut moves) {
            return false;
        }
        !moves(start).into_iter().any(|(c, _)| self.contains(c))
    }

    /// Floods the component of `goal` breadth first; `true` when it ended within `budget`
    /// cells (then [`GoalRegion::contains`] answers for it).
    fn flood<I>(
        &mut self,
        cells: usize,
        goal: u32,
        budget: usize,
        moves: &mut impl FnMut(u32) -> I,
    ) -> bool
    where
        I: IntoIterator<Item = (u32, u32)>,
    {
        if self.stamp.len() != cells || self.current == u32::MAX {
            self.stamp.clear();
            self.stamp.resize(cells, 0);
            self.current = 0;
        }
        self.current += 1;
        self.queue.clear();
        self.queue.push(goal);
        self.stamp[goal as usize] = self.current;
        let mut head = 0;
        while let Some(&cell) = self.queue.get(head) {
            head += 1;
            for (next, _) in moves(cell) {
                if self.stamp[next as usize] != self.current {
                    if self.queue.len() == budget {
                        return false;
                    }
                    self.stamp[next as usize] = self.current;
                    self.queue.push(next);
                }
            }
        }
        true
    }

    /// Whether cell `c` is in the region of the last complete flood.
    fn contains(&self, c: u32) -> bool {
        self.stamp.get(c as usize) == Some(&self.current)
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::world::grid_astar::GridAstar;
    use crate::world::grid_astar::tests::{Maze, maze};

    /// Cells of the goal's component in `m` (plain depth-first search, the test's oracle).
    fn component(m: &Maze, goal: u32) -> usize {
        let mut seen = vec![false; m.blocked.len()];
        let mut todo = vec![goal];
        seen[goal as usize] = true;
        let mut n = 0;
        while let Some(c) = todo.pop() {
            n += 1;
            for (next, _) in m.successors(c) {
                if !std::mem::replace(&mut seen[next as usize], true) {
                    todo.push(next);
                }
            }
        }
        n
    }

    proptest! {
        /// Never "no path" where A* finds one; and "no path" whenever A* finds none and the
        /// goal's region fits the budget (or the goal cannot be entered).
        #[test]
        fn proves_no_path_exactly_when_a_star_finds_none(
            m in maze(),
            (s, g) in (any::<u32>(), any::<u32>()),
            budget in 1usize..60,
        ) {
            let cells = (m.w * m.h) as usize;
            let (start, goal) = (s % (m.w * m.h), g % (m.w * m.h));
            let found = GridAstar::default()
                .search(cells, start, goal, |c| m.successors(c), |_| 0)
                .is_some();
            let enterable = !m.blocked[goal as usize];
            let proved = GoalRegion::default().proves_no_path(
                cells,
                (start, goal),
                enterable,
                budget,
                |c| m.successors(c),
            );
            prop_assert!(!(proved && found), "proved no path, but A* found one");
            let small = !enterable || component(&m, goal) <= budget;
            prop_assert!(found || !small || proved, "missed a shut-in goal");
        }
    }

    #[test]
    fn a_shut_in_goal_is_proved_with_one_flood_reused() {
        // 9 x 9, a ring of blocked cells round the centre; the start outside.
        let (w, h) = (9u32, 9u32);
        let mut blocked = vec![false; 81];
        for y in 2..=6u32 {
            for x in 2..=6u32 {
                if x == 2 || x == 6 || y == 2 || y == 6 {
                    blocked[(y * w + x) as usize] = true;
                }
            }
        }
        let m = Maze {
            w,
            h,
            blocked,
            straight: vec![1; 81],
            diagonal: vec![1; 81],
        };
        let mut region = GoalRegion::default();
        let centre = 4 * w + 4;
        // The generation counter wraps: the region is cleared, no stale cell counts.
        assert!(!region.proves_no_path(81, (0, 80), true, 81, |c| m.successors(c)));
        region.current = u32::MAX - 1;
        for _ in 0..3 {
            assert!(region.proves_no_path(81, (0, centre), true, 9, |c| m.successors(c)));
            // The ring's inside is 9 cells: a budget of 8 gives up ("maybe a path").
            assert!(!region.proves_no_path(81, (0, centre), true, 8, |c| m.successors(c)));
            // Reachable: never proved.
            assert!(!region.proves_no_path(81, (0, 80), true, 81, |c| m.successors(c)));
        }
    }
}
