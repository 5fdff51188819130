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

    /// A `w x h` maze: 8-connected moves into unblocked cells, a diagonal only with both
    /// cells beside it unblocked (symmetric between unblocked cells, as the grid's moves).
    #[derive(Debug)]
    struct Maze {
        w: u32,
        h: u32,
        blocked: Vec<bool>,
    }

    impl Maze {
        fn open(&self, x: i64, y: i64) -> bool {
            x >= 0
                && y >= 0
                && x < i64::from(self.w)
                && y < i64::from(self.h)
                && !self.blocked[(y as u32 * self.w + x as u32) as usize]
        }

        fn moves(&self, c: u32) -> Vec<(u32, u32)> {
            let (x, y) = (i64::from(c % self.w), i64::from(c / self.w));
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
                let diagonal = dx != 0 && dy != 0;
                if self.open(x + dx, y + dy)
                    && (!diagonal || (self.open(x + dx, y) && self.open(x, y + dy)))
                {
                    let cost = if diagonal { 14 } else { 10 };
                    out.push((((y + dy) as u32) * self.w + (x + dx) as u32, cost));
                }
            }
            out
        }

        /// Cells of the goal's component (plain breadth-first search, the test's oracle).
        fn component(&self, goal: u32) -> usize {
            let mut seen = vec![false; self.blocked.len()];
            let mut todo = vec![goal];
            seen[goal as usize] = true;
            let mut n = 0;
            while let Some(c) = todo.pop() {
                n += 1;
                for (m, _) in self.moves(c) {
                    if !std::mem::replace(&mut seen[m as usize], true) {
                        todo.push(m);
                    }
                }
            }
            n
        }
    }

    fn maze() -> impl Strategy<Value = (Maze, u32, u32)> {
        (2u32..14, 2u32..14).prop_flat_map(|(w, h)| {
            let cells = (w * h) as usize;
            (
                prop::collection::vec(prop::bool::weighted(0.35), cells),
                0..w * h,
                0..w * h,
            )
                .prop_map(move |(blocked, s, g)| (Maze { w, h, blocked }, s, g))
        })
    }

    proptest! {
        /// Never "no path" where A* finds one; and "no path" whenever A* finds none and the
        /// goal's region fits the budget (or the goal cannot be entered).
        #[test]
        fn proves_no_path_exactly_when_a_star_finds_none(
            (m, start, goal) in maze(),
            budget in 1usize..60,
        ) {
            let cells = (m.w * m.h) as usize;
            let found = GridAstar::default()
                .search(cells, start, goal, |c| m.moves(c), |_| 0)
                .is_some();
            let enterable = !m.blocked[goal as usize];
            let proved = GoalRegion::default().proves_no_path(
                cells,
                (start, goal),
                enterable,
                budget,
                |c| m.moves(c),
            );
            prop_assert!(!(proved && found), "proved no path, but A* found one");
            let small = !enterable || m.component(goal) <= budget;
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
        let m = Maze { w, h, blocked };
        let mut region = GoalRegion::default();
        let centre = 4 * w + 4;
        // The generation counter wraps: the region is cleared, no stale cell counts.
        assert!(!region.proves_no_path(81, (0, 80), true, 81, |c| m.moves(c)));
        region.current = u32::MAX - 1;
        for _ in 0..3 {
            assert!(region.proves_no_path(81, (0, centre), true, 9, |c| m.moves(c)));
            // The ring's inside is 9 cells: a budget of 8 gives up ("maybe a path").
            assert!(!region.proves_no_path(81, (0, centre), true, 8, |c| m.moves(c)));
            // Reachable: never proved.
            assert!(!region.proves_no_path(81, (0, 80), true, 81, |c| m.moves(c)));
        }
    }
}
