//! The neighbour index: a uniform grid over the arena per collision layer, rebuilt before
//! every control step (every step without `sim.control_period_s`), that answers every
//! robot-robot query of the world and the mission layer ("which robots of this layer may lie
//! within `r` metres of `p`?") in time proportional to the robots nearby instead of the team
//! size.
//!
//! Each layer (ground, aerial) has its own grid, because robots only interact within a layer
//! (see [`crate::world::bodies::robot_groups`]) and the layers' interaction distances differ
//! (the paper's observers sense 6 times farther than the ground robots). The cell side of a
//! layer is its largest *interaction distance* at the kinds' nominal speed and sensing
//! ([`interaction_distance_m`]): the farthest two robots of the layer can be apart and still
//! take part in one resolver rule. A query of that radius then visits at most 3 x 3 cells; a
//! larger radius (speed or sensing factors above 1) visits more cells and stays exact. A
//! sparse layer gets larger cells (at most about eight cells per robot; see
//! [`NeighbourIndex::new`]), so small teams pay almost nothing for the index.
//!
//! Cost: a rebuild is a counting sort, `O(n + cells)`; a query is `O(cells visited + robots in
//! them)`. The resolver's loops over candidates do not depend on their order (union-find
//! merges give the same components in any order; the steering test is an `all`), so they decide
//! exactly as the all-pairs loops they replace (tested against [`AllRobots`]).

use parry2d::math::Vector as Vec2;

use crate::scenario::{Locomotion, Scenario};

/// Largest number of cells along one side of a layer's grid: a tiny cell size on a large arena
/// is widened to keep the grid at most `MAX_CELLS_PER_SIDE^2` cells (queries stay exact).
pub const MAX_CELLS_PER_SIDE: usize = 1024;

/// Relative slack added to every query box (beyond one `f32` rounding of positions, radii and
/// cell coordinates), so that a robot exactly `radius` away is never missed; dimensionless.
const QUERY_SLACK_REL: f32 = 1e-5;

/// The largest distance at which two robots of one layer can take part in one rule of the
/// resolver at speed and sensing factor 1, metres: `min(S, 2 r + m + 2 v h)` with `S` the
/// largest sensing range, `r` the largest body radius and `v` the largest top speed of the
/// layer's kinds, `m` the safety margin and `h` the look-ahead (`collision` block). Two robots
/// farther apart are either out of sensing range or cannot come within `r_i + r_j + m` of each
/// other within the look-ahead. `None` when the scenario has no robot on `layer`.
pub fn interaction_distance_m(s: &Scenario, layer: Locomotion) -> Option<f64> {
    let kinds = s.kinds.iter().filter(|k| k.locomotion == layer);
    let (mut sensing, mut radius, mut speed, mut any) = (0.0f64, 0.0f64, 0.0f64, false);
    for k in kinds {
        sensing = sensing.max(k.sensing_range_m);
        radius = radius.max(k.body_radius_m);
        speed = speed.max(k.max_speed_m_per_s);
        any = true;
    }
    let reach = 2.0 * radius
        + s.collision.safety_margin_m.get()
        + 2.0 * speed * s.collision.lookahead_s.get();
    any.then(|| sensing.min(reach))
}

/// A uniform grid of points (robot centres) over a `width x height` field with corner `(0,0)`,
/// stored as a compressed list per cell (ids ascending within a cell). Points outside the field
/// fall into the nearest border cell, so queries stay exact for them too.
#[derive(Debug, Clone)]
pub struct NeighbourGrid {
    cell_m: f32,
    nx: usize,
    ny: usize,
    /// `starts[c]..starts[c + 1]` are cell `c`'s entries in `ids` and `pos`.
    starts: Vec<u32>,
    ids: Vec<usize>,
    pos: Vec<Vec2>,
    /// Scratch of the rebuild: (cell, id, position) of every point.
    scratch: Vec<(u32, usize, Vec2)>,
    /// Cell and id of every point of the last rebuild, ascending id, and the slot of `ids`
    /// and `pos` each was placed in: a rebuild whose points all stay in their cells only
    /// writes their new positions to those slots (the same index as a full rebuild).
    placed: Vec<(u32, usize)>,
    slots: Vec<u32>,
}

impl NeighbourGrid {
    /// An empty grid over `[0, width_m] x [0, height_m]` with cells of side at least `cell_m`
    /// metres (widened so that no side has more than [`MAX_CELLS_PER_SIDE`] cells). Non-finite
    /// or non-positive sizes give a single cell (every query returns every point: still exact).
    pub fn new(width_m: f32, height_m: f32, cell_m: f32) -> Self {
        let finite = |v: f32| if v.is_finite() && v > 0.0 { v } else { 0.0 };
        let (w, h) = (finite(width_m), finite(height_m));
        let limit = MAX_CELLS_PER_SIDE as f32;
        let mut cell = finite(cell_m).max(w / limit).max(h / limit);
        if cell <= 0.0 {
            cell = f32::MAX;
        }
        let side = |len: f32| ((len / cell).ceil() as usize).clamp(1, MAX_CELLS_PER_SIDE);
        let (nx, ny) = (side(w), side(h));
        Self {
            cell_m: cell,
            nx,
            ny,
            starts: vec![0; nx * ny + 1],
            ids: Vec::new(),
            pos: Vec::new(),
            scratch: Vec::new(),
            placed: Vec::new(),
            slots: Vec::new(),
        }
    }

    /// The cell side, metres.
    pub fn cell_m(&self) -> f32 {
        self.cell_m
    }

    /// Points indexed by the last [`NeighbourGrid::rebuild`].
    pub fn len(&self) -> usize {
        self.ids.len()
    }

    /// Whether the grid holds no point.
    pub fn is_empty(&self) -> bool {
        self.ids.is_empty()
    }

    /// Cell coordinate of `v` along an axis of `n` cells: `floor(v / cell)` clamped to
    /// `[0, n - 1]` (NaN to 0), monotone in `v`.
    fn coord(&self, v: f32, n: usize) -> usize {
        let c = v / self.cell_m;
        if c >= n as f32 {
            n - 1
        } else if c >= 0.0 {
            c as usize // truncation is the floor for c >= 0
        } else {
            0 // negative, or NaN
        }
    }

    fn cell_of(&self, p: Vec2) -> usize {
        self.coord(p.y, self.ny) * self.nx + self.coord(p.x, self.nx)
    }

    /// Replaces the indexed points by `points` (id and centre, metres). Ids need not be dense;
    /// within a cell they are kept in ascending order. `O(n + cells)` (a counting sort), `O(n)`
    /// when every point has the ids and cells of the last rebuild (only the positions are
    /// written, to the slots they held: the same index), no allocation once the buffers have
    /// grown to the team size.
    pub fn rebuild(&mut self, points: impl IntoIterator<Item = (usize, Vec2)>) {
        let mut scratch = std::mem::take(&mut self.scratch);
        scratch.clear();
        scratch.extend(
            points
                .into_iter()
                .map(|(id, p)| (self.cell_of(p) as u32, id, p)),
        );
        self.index(scratch);
    }

    /// The index of [`NeighbourGrid::rebuild`] over `scratch`: (cell, id, position) of every
    /// point, its cell from [`NeighbourGrid::cell_of`]; kept as the next rebuild's scratch.
    fn index(&mut self, mut scratch: Vec<(u32, usize, Vec2)>) {
        // Ascending ids (already so when built from a robot list: then O(n)).
        scratch.sort_unstable_by_key(|&(_, id, _)| id);
        let same_cells = scratch.len() == self.placed.len()
            && scratch
                .iter()
                .zip(&self.placed)
                .all(|(&(c, id, _), &placed)| (c, id) == placed);
        if same_cells {
            for (&(_, _, p), &slot) in scratch.iter().zip(&self.slots) {
                self.pos[slot as usize] = p;
            }
        } else {
            self.place(&scratch);
        }
        self.scratch = scratch;
    }

    /// The counting sort of [`NeighbourGrid::rebuild`] over `scratch` (cell, id, position;
    /// ascending id), recording each point's cell, id and slot.
    fn place(&mut self, scratch: &[(u32, usize, Vec2)]) {
        let cells = self.nx * self.ny;
        self.starts.fill(0);
        for &(c, _, _) in scratch {
            self.starts[c as usize] += 1;
        }
        // Inclusive prefix sums: starts[c] is the end of cell c ...
        let mut end = 0;
        for s in &mut self.starts[..cells] {
            end += *s;
            *s = end;
        }
        self.starts[cells] = end;
        self.ids.resize(scratch.len(), 0);
        self.pos.resize(scratch.len(), Vec2::ZERO);
        self.slots.resize(scratch.len(), 0);
        // ... and placing in descending id moves it down to the cell's start, leaving each
        // cell in ascending id.
        for (k, &(c, id, p)) in scratch.iter().enumerate().rev() {
            let slot = &mut self.starts[c as usize];
            *slot -= 1;
            self.ids[*slot as usize] = id;
            self.pos[*slot as usize] = p;
            self.slots[k] = *slot;
        }
        self.placed.clear();
        self.placed
            .extend(scratch.iter().map(|&(c, id, _)| (c, id)));
    }

    /// Calls `f(id, position)` for every indexed point in a cell that meets the square of
    /// half-side `radius_m` around `p` (with a small slack): every point within `radius_m` of
    /// `p`, and possibly others nearby. Cell by cell, not in id order.
    pub fn for_each_candidate(&self, p: Vec2, radius_m: f32, mut f: impl FnMut(usize, Vec2)) {
        self.for_each_row(p, radius_m, |ids, pos| {
            for (&id, &q) in ids.iter().zip(pos) {
                f(id, q);
            }
        });
    }

    /// [`NeighbourGrid::for_each_candidate`] a row of cells at a time: calls `f(ids,
    /// positions)` with the points (equal-length slices) of each row's cells that meet the
    /// square (a row's cells are contiguous in the index).
    fn for_each_row(&self, p: Vec2, radius_m: f32, mut f: impl FnMut(&[usize], &[Vec2])) {
        let r = radius_m.max(0.0);
        let slack = (p.x.abs().max(p.y.abs()) + r + 1.0) * QUERY_SLACK_REL;
        let r = r + slack;
        let (x0, x1) = (self.coord(p.x - r, self.nx), self.coord(p.x + r, self.nx));
        let (y0, y1) = (self.coord(p.y - r, self.ny), self.coord(p.y + r, self.ny));
        for cy in y0..=y1 {
            let row = cy * self.nx;
            let (a, b) = (
                self.starts[row + x0] as usize,
                self.starts[row + x1 + 1] as usize,
            );
            f(&self.ids[a..b], &self.pos[a..b]);
        }
    }

    /// Writes to `out` (cleared first), in ascending order, the ids of the indexed points within
    /// `radius_m` of `p` (`|q - p|^2 <= radius_m^2` in `f32`): the same set as a scan of all
    /// points.
    pub fn within(&self, p: Vec2, radius_m: f32, out: &mut Vec<usize>) {
        out.clear();
        let r2 = radius_m * radius_m;
        self.for_each_candidate(p, radius_m, |id, q| {
            if (q - p).length_squared() <= r2 {
                out.push(id);
            }
        });
        out.sort_unstable();
    }
}

/// The answer to "which robots of `layer` may lie within `radius_m` of `p`?": the resolver asks
/// it through this trait so that tests can compare the grid with a scan of all robots.
pub trait NeighbourQuery {
    /// Appends to `out` (keeping what it holds), in no particular order (deterministic: the
    /// same for the same robots), the ids of robots on `layer` whose centre lies within
    /// `radius_m` (metres, world frame) of `p`, and possibly of some other robots; callers
    /// apply their exact tests to each candidate. Callers must not depend on the order (the
    /// resolver's unions and all-tests do not).
    fn candidates(&self, layer: Locomotion, p: Vec2, radius_m: f32, out: &mut Vec<usize>);
}

/// The brute-force [`NeighbourQuery`] of the all-pairs loops: every id below `.0` (all
/// robots, any layer), in ascending order (the order of the all-pairs scans). The reference
/// the index is tested against.
#[derive(Debug, Clone, Copy)]
pub struct AllRobots(pub usize);

impl NeighbourQuery for AllRobots {
    fn candidates(&self, _: Locomotion, _: Vec2, _: f32, out: &mut Vec<usize>) {
        out.extend(0..self.0);
    }
}

/// The world's neighbour index: one [`NeighbourGrid`] per collision layer, cell side
/// [`interaction_distance_m`] of the layer (at least 1 m).
#[derive(Debug, Clone)]
pub struct NeighbourIndex {
    ground: NeighbourGrid,
    aerial: NeighbourGrid,
}

impl NeighbourIndex {
    /// An empty index for `s`'s arena and kinds: each layer's cell side is the larger of its
    /// [`interaction_distance_m`] and `sqrt(area / (8 n))` for the layer's `n` robots (at most
    /// about eight cells per robot: a small team needs few cells, and a rebuild costs
    /// `O(n + cells)`), and at least 1 m.
    pub fn new(s: &Scenario) -> Self {
        let (w, h) = (s.arena.width_m.get(), s.arena.height_m.get());
        let cell = |layer| {
            let n = s
                .robots
                .iter()
                .filter(|r| s.kinds[r.kind].locomotion == layer)
                .count()
                .max(1);
            let sparse = (w * h / (8.0 * n as f64)).sqrt();
            let near = interaction_distance_m(s, layer).unwrap_or(1.0);
            near.max(sparse).max(1.0) as f32
        };
        Self::with_cells(
            w as f32,
            h as f32,
            cell(Locomotion::Ground),
            cell(Locomotion::Aerial),
        )
    }

    /// An empty index over `[0, width_m] x [0, height_m]` with the given cell sides, metres
    /// (see [`NeighbourGrid::new`] for the limits).
    pub fn with_cells(width_m: f32, height_m: f32, ground_cell_m: f32, aerial_cell_m: f32) -> Self {
        Self {
            ground: NeighbourGrid::new(width_m, height_m, ground_cell_m),
            aerial: NeighbourGrid::new(width_m, height_m, aerial_cell_m),
        }
    }

    /// The grid of `layer`.
    pub fn grid(&self, layer: Locomotion) -> &NeighbourGrid {
        match layer {
            Locomotion::Ground => &self.ground,
            Locomotion::Aerial => &self.aerial,
        }
    }

    /// Re-indexes the robots: `robots` yields each robot's layer and centre (metres, world
    /// frame), robot id = position in the sequence, read once for both layers (a centre off
    /// the arena falls into the nearest border cell, [`NeighbourGrid`]; never fails). `O(n +
    /// cells)`, no allocation once the buffers have grown to the team; with `parallel` the two
    /// layers' grids are built side by side on the calling rayon pool (the same index; worth it
    /// only for a large team, whose rebuild reads every robot).
    pub fn rebuild(&mut self, robots: impl Iterator<Item = (Locomotion, Vec2)>, parallel: bool) {
        let mut ground = std::mem::take(&mut self.ground.scratch);
        let mut aerial = std::mem::take(&mut self.aerial.scratch);
        ground.clear();
        aerial.clear();
        for (id, (layer, p)) in robots.enumerate() {
            match layer {
                Locomotion::Ground => ground.push((self.ground.cell_of(p) as u32, id, p)),
                Locomotion::Aerial => aerial.push((self.aerial.cell_of(p) as u32, id, p)),
            }
        }
        let (g, a) = (&mut self.ground, &mut self.aerial);
        if parallel {
            rayon::join(|| g.index(ground), || a.index(aerial));
        } else {
            g.index(ground);
            a.index(aerial);
        }
    }
}

impl NeighbourQuery for NeighbourIndex {
    /// The robots of the cells the query's square meets, less those farther than `radius_m`
    /// plus the query slack from `p` (a disc covers about a third of the square's cells'
    /// area, so the callers' exact tests run on fewer robots; none within `radius_m` is
    /// dropped).
    fn candidates(&self, layer: Locomotion, p: Vec2, radius_m: f32, out: &mut Vec<usize>) {
        let r = radius_m.max(0.0);
        let r = r + (p.x.abs().max(p.y.abs()) + r + 1.0) * QUERY_SLACK_REL;
        let r2 = r * r;
        const CHUNK: usize = 16;
        let mut chunk = [0usize; CHUNK];
        self.grid(layer).for_each_row(p, radius_m, |ids, pos| {
            // Branch-free: every id is written, only those within the radius are kept (the
            // test passes for about a third of a row's robots, so a branch mispredicts often).
            for (ids, pos) in ids.chunks(CHUNK).zip(pos.chunks(CHUNK)) {
                let mut kept = 0;
                for (k, (&id, &q)) in ids.iter().zip(pos).enumerate() {
                    chunk[kept.min(k)] = id;
                    kept += usize::from((q - p).length_squared() <= r2);
                }
                out.extend_from_slice(&chunk[..kept]);
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;

    fn paper() -> &'static Scenario {
        static PAPER: std::sync::OnceLock<Scenario> = std::sync::OnceLock::new();
        PAPER.get_or_init(|| {
            crate::scenario::load(concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../scenarios/paper.ron"
            ))
            .expect("paper.ron loads")
        })
    }

    fn brute(points: &[Vec2], p: Vec2, r: f32) -> Vec<usize> {
        let r2 = r * r;
        (0..points.len())
            .filter(|&i| (points[i] - p).length_squared() <= r2)
            .collect()
    }

    /// Coordinates in and around a 40 m x 30 m field, a quarter of them on 2.5 m cell borders.
    fn coord(max: f32) -> impl Strategy<Value = f32> {
        prop_oneof![
            3 => -5.0f32..max + 5.0,
            1 => (-2i32..=(max / 2.5) as i32 + 2).prop_map(|k| k as f32 * 2.5),
        ]
    }

    fn point() -> impl Strategy<Value = Vec2> {
        (coord(40.0), coord(30.0)).prop_map(|(x, y)| Vec2::new(x, y))
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(256))]

        /// A grid rebuilt over moved points (most within their cells, some across, some
        /// dropped) holds exactly what a fresh grid of the new points holds, cell by cell.
        #[test]
        fn a_rebuild_over_moved_points_equals_a_fresh_grid(
            points in prop::collection::vec(point(), 0..60),
            moves in prop::collection::vec((-0.3f32..0.3, -0.3f32..0.3), 60),
            keep in 0usize..60,
        ) {
            let mut grid = NeighbourGrid::new(40.0, 30.0, 2.5);
            grid.rebuild(points.iter().copied().enumerate());
            let moved: Vec<Vec2> = points
                .iter()
                .zip(&moves)
                .map(|(&p, &(dx, dy))| p + Vec2::new(dx, dy))
                .collect();
            // Within their cells but on a border (a jitter of 1 mm crosses few).
            let nudged: Vec<Vec2> = moved.iter().map(|&p| p + Vec2::new(1e-3, -1e-3)).collect();
            let subset = &moved[..keep.min(moved.len())];
            let mut fast = 0;
            for next in [&moved[..], &moved[..], &nudged[..], subset, &moved[..]] {
                fast += usize::from(
                    next.len() == grid.placed.len()
                        && next.iter().zip(&grid.placed).all(|(&p, &(c, _))| grid.cell_of(p) as u32 == c),
                );
                grid.rebuild(next.iter().copied().enumerate());
                let mut fresh = NeighbourGrid::new(40.0, 30.0, 2.5);
                fresh.rebuild(next.iter().copied().enumerate());
                prop_assert_eq!(&grid.starts, &fresh.starts);
                prop_assert_eq!(&grid.ids, &fresh.ids);
                prop_assert_eq!(&grid.pos, &fresh.pos);
            }
            prop_assert!(fast >= 1, "the second rebuild over the same points keeps every cell");
        }

        /// `within` equals a scan of all points, for random points (on cell borders and outside
        /// the field too), cells and radii (smaller and larger than a cell).
        #[test]
        fn within_equals_brute_force(
            points in prop::collection::vec(point(), 0..120),
            queries in prop::collection::vec((point(), 0.0f32..12.0), 1..20),
            cell in prop_oneof![Just(2.5f32), 0.3f32..8.0],
        ) {
            let mut grid = NeighbourGrid::new(40.0, 30.0, cell);
            grid.rebuild(points.iter().copied().enumerate());
            prop_assert_eq!(grid.len(), points.len());
            let mut out = Vec::new();
            for &(p, r) in &queries {
                grid.within(p, r, &mut out);
                prop_assert_eq!(&out, &brute(&points, p, r), "p {:?} r {}", p, r);
                // A query centred on a point at exactly a neighbour's distance finds it.
                for &q in points.iter().take(5) {
                    let d = (q - p).length();
                    grid.within(p, d, &mut out);
                    prop_assert_eq!(&out, &brute(&points, p, d));
                }
            }
        }

        /// An index rebuilt over robots of both layers (again over moved robots), in turn or
        /// with its two grids built side by side on a two-thread pool, holds for each layer
        /// exactly the grid of that layer's robots alone, ids as in the team.
        #[test]
        fn an_index_holds_each_layer_grid_in_turn_or_side_by_side(
            robots in prop::collection::vec((point(), any::<bool>()), 0..80),
            moves in prop::collection::vec((-3.0f32..3.0, -3.0f32..3.0), 80),
        ) {
            let s = paper();
            let layer = |g: bool| if g { Locomotion::Ground } else { Locomotion::Aerial };
            let moved: Vec<(Vec2, bool)> = robots
                .iter()
                .zip(&moves)
                .map(|(&(p, g), &(dx, dy))| (p + Vec2::new(dx, dy), g))
                .collect();
            let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
            let (mut serial, mut side_by_side) = (NeighbourIndex::new(s), NeighbourIndex::new(s));
            for next in [&robots, &moved, &moved] {
                let team = || next.iter().map(|&(p, g)| (layer(g), p));
                serial.rebuild(team(), false);
                pool.install(|| side_by_side.rebuild(team(), true));
                for (g, cell) in [(true, serial.ground.cell_m()), (false, serial.aerial.cell_m())] {
                    let mut alone = NeighbourGrid::new(s.arena.width_m.get() as f32, s.arena.height_m.get() as f32, cell);
                    alone.rebuild(next.iter().enumerate().filter(|(_, r)| r.1 == g).map(|(id, r)| (id, r.0)));
                    for built in [serial.grid(layer(g)), side_by_side.grid(layer(g))] {
                        prop_assert_eq!(&built.starts, &alone.starts);
                        prop_assert_eq!(&built.ids, &alone.ids);
                        prop_assert_eq!(&built.pos, &alone.pos);
                    }
                }
            }
        }

        /// The index's candidates of a layer include every robot of that layer within the
        /// radius, each once, no robot of the other layer and none beyond the radius (plus
        /// slack).
        #[test]
        fn index_candidates_cover_the_layer(
            robots in prop::collection::vec((point(), any::<bool>()), 0..80),
            queries in prop::collection::vec((point(), 0.0f32..10.0, any::<bool>()), 1..10),
        ) {
            let s = paper();
            let layer = |g: bool| if g { Locomotion::Ground } else { Locomotion::Aerial };
            let mut index = NeighbourIndex::new(s);
            index.rebuild(robots.iter().map(|&(p, g)| (layer(g), p)), false);
            let mut out = Vec::new();
            for &(p, r, g) in &queries {
                // Appends: what `out` held stays in front.
                out.clear();
                out.push(usize::MAX);
                index.candidates(layer(g), p, r, &mut out);
                prop_assert_eq!(out.remove(0), usize::MAX);
                let mut sorted = out.clone();
                sorted.sort_unstable();
                sorted.dedup();
                prop_assert_eq!(sorted.len(), out.len(), "no id twice");
                for (id, &(q, qg)) in robots.iter().enumerate() {
                    let near = (q - p).length_squared() <= r * r;
                    prop_assert!(!(near && qg == g) || out.contains(&id), "missed {}", id);
                    prop_assert!(qg == g || !out.contains(&id), "wrong layer {}", id);
                    // Beyond the radius plus the query slack: never a candidate.
                    let far = (q - p).length() > r * 1.001 + 1e-3;
                    prop_assert!(!far || !out.contains(&id), "too far {}", id);
                }
            }
        }
    }

    #[test]
    fn paper_cells_follow_interaction_distances_and_team_size() {
        let s = paper();
        // Ground: sensing 3 m < 2 * 0.4 + 0.2 + 2 * 4 * 1 = 9 m.
        let g = interaction_distance_m(s, Locomotion::Ground).unwrap();
        assert!((g - 3.0).abs() < 1e-12, "{g}");
        // Aerial: 2 * 0.3 + 0.2 + 2 * (8/3) * 1 = 6.133 m < sensing 18 m.
        let a = interaction_distance_m(s, Locomotion::Aerial).unwrap();
        assert!((a - (0.8 + 16.0 / 3.0)).abs() < 1e-9, "{a}");
        // 10 ground robots on 80 m x 60 m: sqrt(4800 / 80) = 7.75 m cells (sparse team).
        let index = NeighbourIndex::new(s);
        let cell = index.grid(Locomotion::Ground).cell_m();
        assert!((cell - 60f32.sqrt()).abs() < 1e-4, "{cell}");
    }

    #[test]
    fn degenerate_sizes_stay_exact() {
        let points = [
            Vec2::new(1.0, 1.0),
            Vec2::new(-50.0, 7.0),
            Vec2::new(1e6, 3.0),
        ];
        for (w, h, c) in [(0.0, 10.0, 1.0), (10.0, 10.0, 0.0), (10.0, 10.0, f32::NAN)] {
            let mut grid = NeighbourGrid::new(w, h, c);
            grid.rebuild(points.iter().copied().enumerate());
            let mut out = Vec::new();
            grid.within(Vec2::new(0.0, 0.0), 60.0, &mut out);
            assert_eq!(out, brute(&points, Vec2::new(0.0, 0.0), 60.0));
        }
    }
}
