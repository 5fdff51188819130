//! The clearance grid: each cell's capped distance to the nearest wall or debris.
//!
//! Built with parry2d point-distance queries from the cell centres. A cell is *free* for
//! inflation `i` when that distance is `>= i`; the world plans with `i = body radius +
//! navigation.clearance_m + cell / 2` (the half cell covers points of a free cell away from
//! its centre). The grid answers the planner's cell queries: free cells, grid moves
//! (tabulated per inflation, `grid_moves`), the nearest free cell, octile distances and line
//! of sight.

use parry2d::math::Vector as Vec2;

use super::bodies::StaticObstacle;
use super::grid_moves::{DIAGONAL_COST, MOVES, MoveTable, Moves, STRAIGHT_COST};
use crate::scenario::Arena;

/// Most move tables a [`ClearanceGrid`] keeps ([`ClearanceGrid::tabulate_moves`]; one byte
/// per cell each): the world tabulates each ground kind's planning inflation, the first four.
pub const MAX_MOVE_TABLES: usize = 4;
/// Absolute margin for `f32` rounding in [`ClearanceGrid::line_of_sight`]'s skipping (of the
/// stored distances, at most a few ulp of their cap), metres: far above those errors, far
/// below a cell.
pub const LOS_SKIP_MARGIN_M: f32 = 1e-3;
/// Relative margin for `f32` rounding in [`ClearanceGrid::line_of_sight`]'s skipping, per
/// metre of the largest coordinate involved (the samples' positions and the cell centres are
/// rounded to a few ulp of their coordinates: about 1e-3 m at 10 km, [`MAX_ARENA_SIDE_M`]);
/// `16 * f32::EPSILON`, about 1.9e-6 (0.5 mm on a 240 m arena, 19 mm on a 10 km one).
///
/// [`MAX_ARENA_SIDE_M`]: crate::scenario::limits::MAX_ARENA_SIDE_M
pub const LOS_SKIP_REL: f32 = 16.0 * f32::EPSILON;

/// Per-cell distance to the nearest static obstacle over the arena `[0, W] x [0, H]`.
#[derive(Debug, Clone)]
pub struct ClearanceGrid {
    cell: f32,
    nx: u32,
    ny: u32,
    dist: Vec<f32>,
    /// Move tables of the inflations given to [`ClearanceGrid::tabulate_moves`].
    tables: Vec<MoveTable>,
}

impl ClearanceGrid {
    /// Builds the grid: square cells of side `cell_m` (> 0) from the origin, covering the arena;
    /// each cell holds `min(cap_m, distance from its centre to the nearest obstacle surface)`
    /// (parry2d point distance; 0 inside an obstacle). Only cells within `cap_m` of an
    /// obstacle's bounding box are queried, so building costs O(cells near obstacles).
    pub fn build(arena: &Arena, statics: &[StaticObstacle], cell_m: f64, cap_m: f32) -> Self {
        let cell = cell_m as f32;
        let nx = ((arena.width_m.get() / cell_m).ceil() as u32).max(1);
        let ny = ((arena.height_m.get() / cell_m).ceil() as u32).max(1);
        let mut dist = vec![cap_m; (nx * ny) as usize];
        for o in statics {
            let bb = o.aabb();
            let lo_x = ((bb.mins.x - cap_m) / cell).floor().max(0.0) as u32;
            let lo_y = ((bb.mins.y - cap_m) / cell).floor().max(0.0) as u32;
            let hi_x = ((bb.maxs.x + cap_m) / cell).ceil().max(0.0) as u32;
            let hi_y = ((bb.maxs.y + cap_m) / cell).ceil().max(0.0) as u32;
            for iy in lo_y..hi_y.min(ny) {
                for ix in lo_x..hi_x.min(nx) {
                    let c = Vec2::new((ix as f32 + 0.5) * cell, (iy as f32 + 0.5) * cell);
                    let d = o.distance_to_point(c);
                    let slot = &mut dist[(iy * nx + ix) as usize];
                    if d < *slot {
                        *slot = d;
                    }
                }
            }
        }
        Self {
            cell,
            nx,
            ny,
            dist,
            tables: Vec::new(),
        }
    }

    /// Tabulates every cell's moves for `inflation` metres (one byte per cell), so that grid
    /// searches for that inflation (A*, distance fields and their descents) read them instead
    /// of testing the neighbours' clearances. The same moves in the same order: no search
    /// changes. Does nothing when the inflation is tabulated already or [`MAX_MOVE_TABLES`]
    /// are (then its moves are computed per call, as without a table).
    pub fn tabulate_moves(&mut self, inflation: f32) {
        if self.tables.len() >= MAX_MOVE_TABLES || self.tables.iter().any(|t| t.is_for(inflation)) {
            return;
        }
        let table = MoveTable::new(inflation, self.nx * self.ny, |c| {
            self.move_mask(c, inflation)
        });
        self.tables.push(table);
    }

    /// Side of a cell, metres.
    pub fn cell_m(&self) -> f32 {
        self.cell
    }

    /// Number of cells along x and y.
    pub fn dims(&self) -> (u32, u32) {
        (self.nx, self.ny)
    }

    /// Index of the cell containing `p` (clamped to the grid).
    pub fn cell_index(&self, p: Vec2) -> u32 {
        // `floor(q)` clamped to `[0, n - 1]` (NaN to 0): for `q > 0` the truncating,
        // saturating cast is the floor, and every `q <= 0` (or NaN) clamps to 0. No call to
        // `floorf` (a library call without SSE4.1), the hottest lookup of planning.
        let axis = |q: f32, n: u32| (if q > 0.0 { q as u32 } else { 0 }).min(n - 1);
        axis(p.y / self.cell, self.ny) * self.nx + axis(p.x / self.cell, self.nx)
    }

    /// Centre of cell `idx`, metres.
    pub fn cell_center(&self, idx: u32) -> Vec2 {
        let ix = idx % self.nx;
        let iy = idx / self.nx;
        Vec2::new((ix as f32 + 0.5) * self.cell, (iy as f32 + 0.5) * self.cell)
    }

    /// Clearance (capped distance to the nearest obstacle) of the cell containing `p`, metres.
    pub fn clearance_at(&self, p: Vec2) -> f32 {
        self.clearance_of(self.cell_index(p))
    }

    /// Clearance of cell `idx` (below `nx * ny`; panics otherwise), metres.
    fn clearance_of(&self, idx: u32) -> f32 {
        self.dist[idx as usize]
    }

    /// Whether cell `idx` is free for `inflation` metres.
    pub fn is_free(&self, idx: u32, inflation: f32) -> bool {
        self.dist[idx as usize] >= inflation
    }

    /// Whether every point of segment `a`-`b` (sampled every `cell / 4`) lies in a cell free for
    /// `inflation`. Only the first `max_len` metres of the segment are checked.
    ///
    /// Samples whose cells are provably free are skipped (sphere tracing): a cell's clearance
    /// `c` is a capped distance to the obstacles, which changes by at most the distance moved,
    /// so every cell whose centre lies within `c - inflation` of this cell's centre is free.
    /// A sample `s` metres further along lies in a cell whose centre is at most `s` plus two
    /// half-diagonals (`cell_m * sqrt(2)`) away (clamping a point to the grid, as the lookup
    /// does, moves no two points apart), so the samples within `c - inflation - cell_m *
    /// sqrt(2) - margin` are skipped, the margin for rounding being [`LOS_SKIP_MARGIN_M`] plus
    /// [`LOS_SKIP_REL`] times the largest coordinate of `a`, `b` and the grid. The answer is
    /// that of testing every sample (tested against it, near the origin and 10 km from it;
    /// the tests pass without the two margins too, which the rounding analysis asks for, and
    /// fail with a slack of half a cell); open ground costs a few lookups per metre instead
    /// of four per cell.
    pub fn line_of_sight(&self, a: Vec2, b: Vec2, inflation: f32, max_len: f32) -> bool {
        let d = b - a;
        let len = d.length().min(max_len);
        let step = self.cell * 0.25;
        let n = (len / step).ceil() as u32;
        let dir = if d.length() > 0.0 {
            d / d.length()
        } else {
            Vec2::ZERO
        };
        let extent =
            (a.abs().max(b.abs()).max_element()).max(self.cell * self.nx.max(self.ny) as f32);
        let slack =
            self.cell * std::f32::consts::SQRT_2 + LOS_SKIP_MARGIN_M + LOS_SKIP_REL * extent;
        // u64: `k` may run past `n = u32::MAX` (a segment of unbounded length) and must stop.
        let mut k = 0u64;
        while k <= u64::from(n) {
            let t = (k as f32 * step).min(len);
            let c = self.clearance_at(a + dir * t);
            let free = c >= inflation;
            if !free {
                return false;
            }
            let free_run = c - inflation - slack;
            // Samples k + 1 ..= k + skip are within `free_run` of this one.
            let skip = if free_run >= step {
                u64::from((free_run / step) as u32)
            } else {
                0
            };
            k += skip + 1;
        }
        true
    }

    /// The free cell nearest to `p` (Euclidean, centre to `p`; ties by lower index) within
    /// `radius_m`, if any.
    pub fn nearest_free(&self, p: Vec2, inflation: f32, radius_m: f32) -> Option<u32> {
        let r = (radius_m / self.cell).ceil() as i64;
        let c = self.cell_index(p);
        let (cx, cy) = (i64::from(c % self.nx), i64::from(c / self.nx));
        let mut best: Option<(f32, u32)> = None;
        for iy in (cy - r).max(0)..=(cy + r).min(i64::from(self.ny) - 1) {
            for ix in (cx - r).max(0)..=(cx + r).min(i64::from(self.nx) - 1) {
                let idx = (iy as u32) * self.nx + ix as u32;
                if !self.is_free(idx, inflation) {
                    continue;
                }
                let d2 = (self.cell_center(idx) - p).length_squared();
                if d2 <= radius_m * radius_m && best.is_none_or(|(bd, _)| d2 < bd) {
                    best = Some((d2, idx));
                }
            }
        }
        best.map(|(_, idx)| idx)
    }

    /// The grid moves out of cell `idx` for `inflation` metres, as (cell, cost) in a fixed
    /// order: east, west, north, south, then the diagonals north-east, north-west, south-east,
    /// south-west; a diagonal only when both cells beside it are free too (no corner cutting).
    /// Symmetric: `b` is a successor of `a` with cost `w` if and only if `a` is one of `b`'s.
    /// Read from the inflation's move table if [`ClearanceGrid::tabulate_moves`] made one.
    pub(super) fn successors(
        &self,
        idx: u32,
        inflation: f32,
    ) -> impl Iterator<Item = (u32, u32)> + Clone + use<> {
        let mask = match self.tables.iter().find(|t| t.is_for(inflation)) {
            Some(table) => table.mask(idx),
            None => self.move_mask(idx, inflation),
        };
        Moves::new(idx, self.nx, mask)
    }

    /// The moves of [`ClearanceGrid::successors`] as a mask: bit `b` for `MOVES[b]` of
    /// `grid_moves.rs` (the order of the successors).
    fn move_mask(&self, idx: u32, inflation: f32) -> u8 {
        let ix = i64::from(idx % self.nx);
        let iy = i64::from(idx / self.nx);
        let free = |x: i64, y: i64| {
            x >= 0
                && y >= 0
                && x < i64::from(self.nx)
                && y < i64::from(self.ny)
                && self.is_free((y as u32) * self.nx + x as u32, inflation)
        };
        let mut mask = 0u8;
        for (b, &(dx, dy, _)) in MOVES.iter().enumerate() {
            // No corner cutting: a diagonal needs both orthogonal neighbours free too.
            let diagonal = dx != 0 && dy != 0;
            if free(ix + dx, iy + dy) && (!diagonal || (free(ix + dx, iy) && free(ix, iy + dy))) {
                mask |= 1 << b;
            }
        }
        mask
    }

    /// Octile distance between cells `a` and `b` in planner cost units (A*'s heuristic).
    pub(super) fn octile(&self, a: u32, b: u32) -> u32 {
        let dx = (a % self.nx).abs_diff(b % self.nx);
        let dy = (a / self.nx).abs_diff(b / self.nx);
        octile_cost(dx, dy)
    }
}

/// Octile distance of a cell offset `(dx, dy)`, cells, in planner cost units:
/// `STRAIGHT_COST * max + (DIAGONAL_COST - STRAIGHT_COST) * min`, the cost of the cheapest
/// path without obstacles. At most `u32::MAX`: a longer distance counts as `u32::MAX`, as a
/// path's cost past it does in A* ([`super::grid_astar`]).
pub(super) fn octile_cost(dx: u32, dy: u32) -> u32 {
    let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
    let cost = u64::from(STRAIGHT_COST) * u64::from(hi)
        + u64::from(DIAGONAL_COST - STRAIGHT_COST) * u64::from(lo);
    u32::try_from(cost).unwrap_or(u32::MAX)
}

#[cfg(test)]
mod tests {
    use parry2d::math::Pose;
    use parry2d::shape::Cuboid;

    use super::*;
    use crate::scenario::Positive;
    use crate::world::bodies::StaticShape;
    use crate::world::test_grids::*;

    /// The octile cost of the grid's far corners: exact while it fits a `u32`, `u32::MAX`
    /// beyond (it wrapped, or panicked in a debug build, for a row of over 4.29 million cells).
    #[test]
    fn octile_costs_saturate_instead_of_wrapping() {
        assert_eq!(octile_cost(0, 0), 0);
        assert_eq!(
            octile_cost(3, 1),
            3 * STRAIGHT_COST + (DIAGONAL_COST - STRAIGHT_COST)
        );
        assert_eq!(octile_cost(1, 3), octile_cost(3, 1));
        assert_eq!(octile_cost(4_000_000, 0), 4_000_000_000);
        assert_eq!(octile_cost(5_000_000, 0), u32::MAX);
        assert_eq!(octile_cost(u32::MAX, u32::MAX), u32::MAX);
    }

    /// The successors of cell `idx` by their definition: the free neighbours in the order
    /// east, west, north, south, north-east, north-west, south-east, south-west, a diagonal
    /// only with both cells beside it free.
    fn successors_by_definition(g: &ClearanceGrid, idx: u32, infl: f32) -> Vec<(u32, u32)> {
        let (nx, ny) = (g.dims().0 as i64, g.dims().1 as i64);
        let (x, y) = (i64::from(idx) % nx, i64::from(idx) / nx);
        let free = |x: i64, y: i64| {
            (0..nx).contains(&x) && (0..ny).contains(&y) && g.is_free((y * nx + x) as u32, infl)
        };
        let mut out = Vec::new();
        for (dx, dy) in [(1, 0), (-1, 0), (0, 1), (0, -1)] {
            if free(x + dx, y + dy) {
                out.push((((y + dy) * nx + x + dx) as u32, STRAIGHT_COST));
            }
        }
        for (dx, dy) in [(1, 1), (-1, 1), (1, -1), (-1, -1)] {
            if free(x + dx, y + dy) && free(x + dx, y) && free(x, y + dy) {
                out.push((((y + dy) * nx + x + dx) as u32, DIAGONAL_COST));
            }
        }
        out
    }

    proptest::proptest! {
        /// A move table gives every cell the successors of their definition, in their order,
        /// as computing them per call does; an inflation without a table is computed.
        #[test]
        fn tabulated_moves_are_the_successors(
            discs in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.1f32..1.5), 0..6),
            infl in 0.0f32..1.2,
        ) {
            let statics: Vec<_> = discs.iter().map(|&(x, y, r)| disc(x, y, r)).collect();
            let computed = grid(&statics);
            let mut tabulated = computed.clone();
            tabulated.tabulate_moves(infl);
            proptest::prop_assert_eq!(tabulated.tables.len(), 1);
            for idx in 0..40 * 40 {
                let expected = successors_by_definition(&computed, idx, infl);
                let by_table: Vec<_> = tabulated.successors(idx, infl).collect();
                let by_call: Vec<_> = computed.successors(idx, infl).collect();
                let other: Vec<_> = tabulated.successors(idx, infl + 0.1).collect();
                proptest::prop_assert_eq!(&by_table, &expected, "cell {}", idx);
                proptest::prop_assert_eq!(&by_call, &expected, "cell {}", idx);
                proptest::prop_assert_eq!(other, successors_by_definition(&computed, idx, infl + 0.1));
            }
        }
    }

    /// Line of sight by testing every sample (the definition `line_of_sight` skips within).
    fn line_of_sight_by_sampling(g: &ClearanceGrid, a: Vec2, b: Vec2, infl: f32, max: f32) -> bool {
        let d = b - a;
        let len = d.length().min(max);
        let step = g.cell_m() * 0.25;
        let n = (len / step).ceil() as u32;
        let dir = if d.length() > 0.0 {
            d / d.length()
        } else {
            Vec2::ZERO
        };
        (0..=n).all(|k| g.clearance_at(a + dir * (k as f32 * step).min(len)) >= infl)
    }

    /// Discs `(x, y, r)` and rotated boxes `(x, y, hx, hy, angle)` shifted by `offset`.
    fn shapes_at(offset: Vec2, discs: &[(f32, f32, f32)], boxes: &[LosBox]) -> Vec<StaticObstacle> {
        let mut statics: Vec<_> = discs
            .iter()
            .map(|&(x, y, r)| disc(x + offset.x, y + offset.y, r))
            .collect();
        statics.extend(boxes.iter().map(|&(x, y, hx, hy, angle)| StaticObstacle {
            shape: StaticShape::Cuboid(Cuboid::new(Vec2::new(hx, hy))),
            pose: Pose::new(Vec2::new(x, y) + offset, angle),
            is_wall: false,
        }));
        statics
    }

    type LosBox = (f32, f32, f32, f32, f32);

    /// The first segment (shifted by `offset`) whose line of sight differs from testing every
    /// sample, if any.
    fn los_mismatch(
        g: &ClearanceGrid,
        offset: Vec2,
        segments: &[(f32, f32, f32, f32)],
        infl: f32,
        max: f32,
    ) -> Option<(Vec2, Vec2)> {
        segments.iter().find_map(|&(ax, ay, bx, by)| {
            let (a, b) = (Vec2::new(ax, ay) + offset, Vec2::new(bx, by) + offset);
            (g.line_of_sight(a, b, infl, max) != line_of_sight_by_sampling(g, a, b, infl, max))
                .then_some((a, b))
        })
    }

    fn los_boxes() -> impl proptest::strategy::Strategy<Value = Vec<LosBox>> {
        proptest::collection::vec(
            (
                0.0f32..10.0,
                0.0f32..10.0,
                0.05f32..1.5,
                0.05f32..1.5,
                -3.2f32..3.2,
            ),
            0..4,
        )
    }

    fn los_segments() -> impl proptest::strategy::Strategy<Value = Vec<(f32, f32, f32, f32)>> {
        proptest::collection::vec(
            (-1.0f32..11.0, -1.0f32..11.0, -1.0f32..11.0, -1.0f32..11.0),
            1..20,
        )
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(512))]

        /// Skipping the samples in provably free cells gives the answer of testing them all:
        /// segments near and through discs and rotated boxes, from inside and outside the
        /// grid, any inflation and length limit.
        #[test]
        fn line_of_sight_skips_only_free_samples(
            discs in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.05f32..1.5), 0..5),
            boxes in los_boxes(),
            segments in los_segments(),
            infl in -0.5f32..2.5,
            max in proptest::prop_oneof![proptest::strategy::Just(f32::INFINITY), 0.0f32..8.0],
        ) {
            let g = grid(&shapes_at(Vec2::ZERO, &discs, &boxes));
            let found = los_mismatch(&g, Vec2::ZERO, &segments, infl, max);
            proptest::prop_assert!(found.is_none(), "{:?}", found);
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// The same 10 km from the origin (the largest arena side), where `f32` coordinates
        /// are rounded to about 1e-3 m: the skipping's rounding margin grows with them.
        #[test]
        fn line_of_sight_skips_only_free_samples_far_from_the_origin(
            discs in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.05f32..1.5), 0..5),
            boxes in los_boxes(),
            segments in los_segments(),
            infl in -0.5f32..2.5,
        ) {
            let arena = Arena {
                width_m: Positive::new(10_000.0).unwrap(),
                height_m: Positive::new(10.0).unwrap(),
                wall_thickness_m: Positive::new(0.5).unwrap(),
            };
            let offset = Vec2::new(9_990.0, 0.0);
            let g = ClearanceGrid::build(&arena, &shapes_at(offset, &discs, &boxes), CELL, 2.0);
            let found = los_mismatch(&g, offset, &segments, infl, f32::INFINITY);
            proptest::prop_assert!(found.is_none(), "{:?}", found);
        }
    }

    #[test]
    fn move_tables_stop_at_their_limit() {
        let mut g = grid(&[disc(5.0, 5.0, 1.0)]);
        for k in 0..MAX_MOVE_TABLES + 2 {
            g.tabulate_moves(0.1 * k as f32);
            g.tabulate_moves(0.1 * k as f32);
        }
        assert_eq!(g.tables.len(), MAX_MOVE_TABLES);
    }

    #[test]
    fn clearance_grid_holds_the_capped_exact_distance_at_cell_centres() {
        let statics = [disc(5.0, 5.0, 1.0), block(2.0, 8.0, 1.0, 0.5)];
        let g = grid(&statics);
        assert_eq!(g.dims(), (40, 40));
        for idx in 0..40 * 40 {
            let c = g.cell_center(idx);
            assert_eq!(
                g.clearance_at(c),
                exact(&statics, c).min(2.0),
                "cell {idx} at {c:?}"
            );
        }
        assert_eq!(g.clearance_at(Vec2::new(5.0, 5.0)), 0.0);
        assert!(!g.is_free(g.cell_index(Vec2::new(5.0, 5.0)), 0.01));
        assert!(g.is_free(g.cell_index(Vec2::new(9.0, 1.0)), 2.0));
    }

    #[test]
    fn line_of_sight_respects_inflation_and_max_len() {
        let statics = [disc(5.0, 5.0, 1.0)];
        let g = grid(&statics);
        let (a, b) = (Vec2::new(1.0, 5.0), Vec2::new(9.0, 5.0));
        assert!(!g.line_of_sight(a, b, INFL, f32::INFINITY));
        // Only the first 2 m are checked: they are clear.
        assert!(g.line_of_sight(a, b, INFL, 2.0));
        // Passing 1.5 m from the disc's edge is clear for 0.6 m, not for 2 m.
        let (c, d) = (Vec2::new(1.0, 7.5), Vec2::new(9.0, 7.5));
        assert!(g.line_of_sight(c, d, INFL, f32::INFINITY));
        assert!(!g.line_of_sight(c, d, 2.0, f32::INFINITY));
    }
}
