//! Line-of-sight smoothing of a raw grid path.
//!
//! Greedy (from each anchor, the farthest visible cell) for A* plans; galloping (`O(log L)`
//! sight checks per leg) for descents of shared distance fields.

use parry2d::math::Vector as Vec2;

use super::clearance_grid::ClearanceGrid;
use super::standing_disc::StandingDisc;

/// Greedy line-of-sight smoothing: from each anchor, jump to the farthest following cell still
/// visible (checked on cell centres, against the grid and the `discs`).
pub(super) fn smooth(
    grid: &ClearanceGrid,
    raw: &[u32],
    inflation: f32,
    discs: &[StandingDisc],
) -> Vec<u32> {
    let visible = |a: Vec2, b: Vec2| {
        grid.line_of_sight(a, b, inflation, f32::INFINITY) && !discs.iter().any(|d| d.crosses(a, b))
    };
    let mut out = vec![raw[0]];
    let mut anchor = 0;
    while anchor < raw.len() - 1 {
        let a = grid.cell_center(raw[anchor]);
        let mut next = anchor + 1;
        while next + 1 < raw.len() && visible(a, grid.cell_center(raw[next + 1])) {
            next += 1;
        }
        out.push(raw[next]);
        anchor = next;
    }
    out
}

/// Line-of-sight smoothing with a galloping search: from each anchor, probe the raw cells at
/// offsets 2, 4, 8, ... while they are visible, then bisect between the last visible and the
/// first hidden probe; the leg goes to the visible cell found. Every leg is checked like
/// [`smooth`]'s (cell centres against the grid), so paths stay as clear of debris, but the
/// search costs `O(log L)` sight checks per leg instead of `O(L)`; where visibility is not
/// monotone along the raw path it may keep other corners than [`smooth`]. Used for descents
/// of shared distance fields, which 1,000 robots request at one round start.
pub(super) fn smooth_galloping(grid: &ClearanceGrid, raw: &[u32], inflation: f32) -> Vec<u32> {
    let last = raw.len() - 1;
    let mut out = vec![raw[0]];
    let mut anchor = 0;
    while anchor < last {
        let a = grid.cell_center(raw[anchor]);
        let visible =
            |k: usize| grid.line_of_sight(a, grid.cell_center(raw[k]), inflation, f32::INFINITY);
        // `lo` is visible (a neighbouring cell always is), `hi` is hidden or past the end.
        let (mut lo, mut hi, mut jump) = (anchor + 1, last + 1, 1);
        while lo < last {
            let probe = (lo + jump).min(last);
            if visible(probe) {
                lo = probe;
                jump *= 2;
            } else {
                hi = probe;
                break;
            }
        }
        while hi - lo > 1 {
            let mid = lo + (hi - lo) / 2;
            if visible(mid) {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        out.push(raw[lo]);
        anchor = lo;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::test_grids::*;

    #[test]
    fn both_smoothings_keep_corners_that_inflated_obstacles_hide() {
        // A block in the middle; the raw path runs along its south side, then up its east side.
        let statics = [block(5.0, 5.0, 2.0, 2.0)];
        let g = grid(&statics);
        let open = grid(&[]);
        let row = |iy: u32, xs: std::ops::RangeInclusive<u32>| xs.map(move |ix| iy * 40 + ix);
        let col = |ix: u32, ys: std::ops::RangeInclusive<u32>| ys.map(move |iy| iy * 40 + ix);
        // South of the block at y = 2.125, east of it at x = 7.875.
        let raw: Vec<u32> = row(8, 8..=31).chain(col(31, 9..=31)).collect();
        let (first, last) = (g.cell_center(raw[0]), g.cell_center(*raw.last().unwrap()));
        assert!(!g.line_of_sight(first, last, INFL, f32::INFINITY));
        type Smoother<'a> = &'a dyn Fn(&ClearanceGrid, &[u32]) -> Vec<u32>;
        let smoothers: [(&str, Smoother); 2] = [
            ("greedy", &|g, raw| smooth(g, raw, INFL, &[])),
            ("galloping", &|g, raw| smooth_galloping(g, raw, INFL)),
        ];
        for (name, smoother) in smoothers {
            let smoothed = smoother(&g, &raw);
            assert_eq!(smoothed.first(), raw.first(), "{name}");
            assert_eq!(smoothed.last(), raw.last(), "{name}");
            assert!(
                smoothed.len() >= 3,
                "{name}: the corner is kept: {smoothed:?}"
            );
            let points: Vec<Vec2> = smoothed.iter().map(|&c| g.cell_center(c)).collect();
            for leg in points.windows(2) {
                assert!(
                    g.line_of_sight(leg[0], leg[1], INFL, f32::INFINITY),
                    "{name}: {leg:?}"
                );
            }
            legs_clear(&statics, &points, INFL - CELL as f32 * 0.5f32.sqrt());
            // With nothing in the way the same raw path smooths to one straight leg.
            assert_eq!(
                smoother(&open, &raw),
                [raw[0], *raw.last().unwrap()],
                "{name}"
            );
            // Two cells: one leg.
            assert_eq!(smoother(&g, &raw[..2]), raw[..2], "{name}");
        }
    }
}
