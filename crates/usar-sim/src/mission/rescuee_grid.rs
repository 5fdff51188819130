//! A static bucket grid over one task's rescuee positions, so that detecting the rescuees
//! within a robot's observing range costs the rescuees near it, not the task's whole list
//! (a uniform grid, as in the world's neighbour index; rescuees never move while waiting).

use crate::scenario::{PointM, Rect};

/// Rescuees per cell aimed at when the grid is sized (about 4).
const RESCUEES_PER_CELL: f64 = 4.0;
/// At most this many cells per side.
const MAX_CELLS_PER_SIDE: usize = 1024;

/// Rescuee indices bucketed by cell: cell `c` holds `items[starts[c]..starts[c + 1]]`, in
/// ascending index order. Cells are squares of `cell_m` from the search area's `min` corner;
/// positions outside the area fall into the nearest edge cell.
#[derive(Debug, Clone)]
pub(super) struct RescueeGrid {
    min: PointM,
    cell_m: f64,
    nx: usize,
    ny: usize,
    starts: Vec<u32>,
    items: Vec<u32>,
}

impl RescueeGrid {
    /// Buckets `positions` (world frame, metres) over `area`, with cells sized for about
    /// [`RESCUEES_PER_CELL`] rescuees each (at most [`MAX_CELLS_PER_SIDE`] a side; one cell for
    /// an empty list or a degenerate area).
    pub(super) fn new(positions: &[PointM], area: &Rect) -> Self {
        let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
        let per = (w * h * RESCUEES_PER_CELL / positions.len().max(1) as f64).sqrt();
        let limit = MAX_CELLS_PER_SIDE as f64;
        let cell_m = per.max(w / limit).max(h / limit);
        let ok = cell_m.is_finite() && cell_m > 0.0;
        let cell_m = if ok { cell_m } else { f64::INFINITY };
        let side = |len: f64| {
            let n = (len / cell_m).ceil();
            if n.is_finite() && n >= 1.0 {
                (n as usize).min(MAX_CELLS_PER_SIDE)
            } else {
                1
            }
        };
        let mut grid = Self {
            min: area.min,
            cell_m,
            nx: side(w),
            ny: side(h),
            starts: Vec::new(),
            items: Vec::new(),
        };
        let cells: Vec<usize> = positions.iter().map(|p| grid.cell_of(p)).collect();
        let mut starts = vec![0u32; grid.nx * grid.ny + 1];
        for &c in &cells {
            starts[c + 1] += 1;
        }
        for c in 1..starts.len() {
            starts[c] += starts[c - 1];
        }
        let mut next = starts.clone();
        let mut items = vec![0u32; positions.len()];
        for (i, &c) in cells.iter().enumerate() {
            items[next[c] as usize] = i as u32;
            next[c] += 1;
        }
        grid.starts = starts;
        grid.items = items;
        grid
    }

    /// Cell coordinate of `v` metres from the grid's origin along an axis of `n` cells,
    /// clamped to `0..n` (NaN to 0): monotone in `v`.
    fn coord(&self, v: f64, n: usize) -> usize {
        let c = v / self.cell_m;
        if c >= n as f64 {
            n - 1
        } else if c >= 0.0 {
            c as usize // truncation is the floor for c >= 0
        } else {
            0
        }
    }

    fn cell_of(&self, p: &PointM) -> usize {
        self.coord(p.y - self.min.y, self.ny) * self.nx + self.coord(p.x - self.min.x, self.nx)
    }

    /// Calls `f` with every rescuee index whose position may lie within `range_m` of
    /// `center` (a superset: every cell the disc's bounding box, widened by a relative 1e-9
    /// against rounding, touches), cell by cell.
    pub(super) fn for_each_candidate(
        &self,
        center: &PointM,
        range_m: f64,
        mut f: impl FnMut(usize),
    ) {
        let r = range_m.max(0.0) * (1.0 + 1e-9) + 1e-9;
        let (x, y) = (center.x - self.min.x, center.y - self.min.y);
        let (x0, x1) = (self.coord(x - r, self.nx), self.coord(x + r, self.nx));
        let (y0, y1) = (self.coord(y - r, self.ny), self.coord(y + r, self.ny));
        for cy in y0..=y1 {
            let row = cy * self.nx;
            let (a, b) = (
                self.starts[row + x0] as usize,
                self.starts[row + x1 + 1] as usize,
            );
            for &i in &self.items[a..b] {
                f(i as usize);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Point2;
    use proptest::prelude::*;

    use super::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// The candidates hold every rescuee within range (positions inside and outside the
        /// area, ranges from 0 to past the area), each once.
        #[test]
        fn candidates_cover_the_disc(
            points in prop::collection::vec((-5.0f64..35.0, -5.0f64..25.0), 0..200),
            queries in prop::collection::vec((-10.0f64..40.0, -10.0f64..30.0, 0.0f64..40.0), 1..20),
            size in (0.5f64..30.0, 0.5f64..20.0),
        ) {
            let area = Rect { min: Point2::new(0.0, 0.0), max: Point2::new(size.0, size.1) };
            let positions: Vec<PointM> = points.iter().map(|&(x, y)| Point2::new(x, y)).collect();
            let grid = RescueeGrid::new(&positions, &area);
            for &(x, y, r) in &queries {
                let c = Point2::new(x, y);
                let mut seen = vec![0u32; positions.len()];
                grid.for_each_candidate(&c, r, |i| seen[i] += 1);
                for (i, p) in positions.iter().enumerate() {
                    prop_assert!(seen[i] <= 1, "rescuee {} seen {} times", i, seen[i]);
                    if (p - c).norm_squared() <= r * r {
                        prop_assert_eq!(seen[i], 1, "rescuee {} at {:?} missed from {:?} r {}", i, p, c, r);
                    }
                }
            }
        }
    }

    #[test]
    fn degenerate_inputs_give_one_cell() {
        let area = Rect {
            min: Point2::new(0.0, 0.0),
            max: Point2::new(10.0, 10.0),
        };
        let empty = RescueeGrid::new(&[], &area);
        empty.for_each_candidate(&Point2::new(1.0, 1.0), 5.0, |_| panic!("no rescuees"));
        let flat = Rect {
            min: Point2::new(0.0, 0.0),
            max: Point2::new(0.0, 0.0),
        };
        let one = RescueeGrid::new(&[Point2::new(0.0, 0.0)], &flat);
        let mut n = 0;
        one.for_each_candidate(&Point2::new(0.0, 0.0), 1.0, |_| n += 1);
        assert_eq!(n, 1);
    }
}
