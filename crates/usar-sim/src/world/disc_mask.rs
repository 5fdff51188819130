//! The cells a detour's A* may not enter, marked once per search: every cell of the clearance
//! grid whose centre lies inside one of the robots standing in the way
//! ([`StandingDisc`]).
//!
//! A detour ([`super::path_planner::PathPlanner::plan_around`]) used to test each successor cell
//! against every standing disc, `O(expanded cells x 8 x discs)`; the mask makes that test one
//! array read, for `O(discs x cells per disc)` marking first. A cell is marked exactly when
//! `StandingDisc::contains` holds for its centre (the same `f32` test), so A* sees the same
//! successors in the same order and finds the same path.

use super::clearance_grid::ClearanceGrid;
use super::standing_disc::StandingDisc;

/// Marked cells of one grid, by generation stamp: `stamp[c] == current` marks cell `c`, so a
/// new marking costs the discs' cells, not a clear of the grid. Empty (no memory) until the
/// first [`DiscMask::mark`]; then one `u32` per grid cell.
#[derive(Debug, Clone, Default)]
pub(super) struct DiscMask {
    stamp: Vec<u32>,
    current: u32,
}

impl DiscMask {
    /// Forgets the previous marking and marks every cell of `grid` whose centre lies inside one
    /// of `discs` (see the module docs). Discs partly or wholly outside the grid mark the cells
    /// they cover inside it; a disc with a non-finite centre or radius marks nothing that the
    /// exact test would not (its box clamps to the grid, the test decides).
    pub fn mark(&mut self, grid: &ClearanceGrid, discs: &[StandingDisc]) {
        let (nx, ny) = grid.dims();
        let cells = nx as usize * ny as usize;
        if self.stamp.len() != cells || self.current == u32::MAX {
            self.stamp.clear();
            self.stamp.resize(cells, 0);
            self.current = 0;
        }
        self.current += 1;
        let cell = grid.cell_m();
        // Cell coordinate range of [lo, hi] metres, one cell wider each side than the cells
        // the interval meets (rounding), clamped to [0, n - 1]; NaN clamps to 0.
        let range = |lo: f32, hi: f32, n: u32| {
            let clamp = |q: f32| (q.max(0.0) as u32).min(n - 1);
            (clamp(lo / cell - 1.0), clamp(hi / cell + 1.0))
        };
        for d in discs {
            let r = d.radius_m.abs();
            let (x0, x1) = range(d.center.x - r, d.center.x + r, nx);
            let (y0, y1) = range(d.center.y - r, d.center.y + r, ny);
            for iy in y0..=y1 {
                for ix in x0..=x1 {
                    let c = iy * nx + ix;
                    if d.contains(grid.cell_center(c)) {
                        self.stamp[c as usize] = self.current;
                    }
                }
            }
        }
    }

    /// Whether cell `c` (an index of the grid last marked) is covered by a disc of the last
    /// [`DiscMask::mark`].
    pub fn is_marked(&self, c: u32) -> bool {
        self.stamp.get(c as usize) == Some(&self.current)
    }
}

#[cfg(test)]
mod tests {
    use parry2d::math::Vector as Vec2;
    use proptest::prelude::*;

    use super::*;
    use crate::scenario::{Arena, Positive};

    fn grid(w: f64, h: f64, cell: f64) -> ClearanceGrid {
        let arena = Arena {
            width_m: Positive::new(w).unwrap(),
            height_m: Positive::new(h).unwrap(),
            wall_thickness_m: Positive::new(0.5).unwrap(),
        };
        ClearanceGrid::build(&arena, &[], cell, 2.0)
    }

    fn disc() -> impl Strategy<Value = StandingDisc> {
        (-3.0f32..23.0, -3.0f32..18.0, 0.0f32..3.0).prop_map(|(x, y, r)| StandingDisc {
            center: Vec2::new(x, y),
            radius_m: r,
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// Marked cells are exactly those whose centre some disc contains, over several
        /// markings of one mask (stale marks never survive).
        #[test]
        fn marks_exactly_the_cells_a_disc_contains(
            markings in prop::collection::vec(prop::collection::vec(disc(), 0..6), 1..4),
            cell in prop_oneof![Just(0.5f64), 0.2f64..1.5],
        ) {
            let g = grid(20.0, 15.0, cell);
            let (nx, ny) = g.dims();
            let mut mask = DiscMask::default();
            for discs in &markings {
                mask.mark(&g, discs);
                for c in 0..nx * ny {
                    let expected = discs.iter().any(|d| d.contains(g.cell_center(c)));
                    prop_assert_eq!(mask.is_marked(c), expected, "cell {}", c);
                }
            }
        }
    }

    /// The generation counter wraps by clearing the stamps: a mark left by an early
    /// generation does not read as a mark of the generation numbers that come round again.
    #[test]
    fn stamps_wrap_without_stale_marks() {
        let g = grid(4.0, 4.0, 1.0);
        let mut mask = DiscMask::default();
        let at = |x, y| StandingDisc {
            center: Vec2::new(x, y),
            radius_m: 0.6,
        };
        mask.mark(&g, &[at(0.5, 0.5)]); // generation 1 marks cell 0
        mask.current = u32::MAX - 1;
        mask.mark(&g, &[at(3.5, 3.5)]); // generation u32::MAX marks cell 15 only
        assert!(mask.is_marked(15) && !mask.is_marked(0));
        mask.mark(&g, &[at(3.5, 0.5)]); // wraps to generation 1: cell 0's stamp must be gone
        assert_eq!(mask.current, 1);
        assert!(!mask.is_marked(0));
        assert!(mask.is_marked(3));
        assert_eq!((0..16).filter(|&c| mask.is_marked(c)).count(), 1);
    }
}
