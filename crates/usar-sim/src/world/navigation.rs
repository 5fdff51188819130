//! Path planning of ground robots: a clearance grid built with parry2d distance queries, grid A*
//! (`grid_astar`: the `pathfinding` crate's A* over dense arrays) for a robot's own goals,
//! shared distance fields ([`super::distance_field`]) for goals many robots share, and
//! line-of-sight path smoothing.
//!
//! The grid stores, per cell, the distance from the cell centre to the nearest wall or debris
//! surface (capped). A cell is *free* for inflation `i` when that distance is `>= i`; the world
//! plans with `i = body radius + navigation.clearance_m + cell / 2` (the half cell covers points
//! of a free cell away from its centre).

use parry2d::math::Vector as Vec2;

use super::bodies::StaticObstacle;
use super::disc_mask::DiscMask;
use super::distance_field::DistanceField;
use super::error::NavError;
use super::grid_astar::GridAstar;
use super::grid_moves::{MOVES, MoveTable, Moves};
use super::grid_regions::GridRegions;
use super::plan_cache::PlanCache;
use super::shared_fields::SharedFields;
use crate::scenario::Arena;
use crate::scenario::in_field;

/// A* cost of a straight grid move (a diagonal costs [`DIAGONAL_COST`]).
pub const STRAIGHT_COST: u32 = 1000;
/// A* cost of a diagonal grid move (~ sqrt(2) * [`STRAIGHT_COST`]).
pub const DIAGONAL_COST: u32 = 1414;
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
/// Most heap memory a [`PathPlanner`] keeps in shared distance fields between plans, bytes:
/// 512 MiB, six fields of a grid at the 2^24-cell limit (80 MiB each, 5 bytes a cell), about
/// 6,700 of an 80 m x 60 m arena at 0.25 m. Past it the least recently used fields are
/// dropped and made again when next needed, with the same paths
/// (`docs/world-model.md`, "Shared goals, shared fields").
pub const SHARED_FIELDS_BUDGET_BYTES: usize = 512 << 20;

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
        self.dist[self.cell_index(p) as usize]
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

/// How the planner finds a path to a goal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GoalKind {
    /// A goal of one robot (its start, a rescuee, a sweep waypoint): grid A*.
    Own,
    /// A goal many robots share (a task's goal point, a drop-off, the rest station): descent
    /// of the goal's [`DistanceField`] for the robot's inflation, computed once and reused
    /// while the planner's field budget keeps it ([`SHARED_FIELDS_BUDGET_BYTES`]).
    Shared,
}

/// Grid planning with line-of-sight smoothing and a plan cache keyed by (inflation, start cell,
/// goal cell, goal kind; at most 4,096 entries and 64 MiB, then cleared): A* for a robot's own
/// goals, descent of a shared [`DistanceField`] (one per goal cell and inflation, the most
/// recently used kept within [`SHARED_FIELDS_BUDGET_BYTES`]) for shared goals.
/// Deterministic: a cache hit returns exactly what planning would, and a field dropped and made
/// again gives the same paths, so neither bound changes a plan.
#[derive(Debug, Clone, Default)]
pub struct PathPlanner {
    cache: PlanCache,
    fields: SharedFields,
    raw: Vec<u32>,
    discs: Vec<StandingDisc>,
    /// The cells a detour's A* may not enter (inside `discs`), marked once per detour.
    mask: DiscMask,
    /// A*'s per-cell state, reused between searches.
    astar: GridAstar,
    /// The grid's regions per inflation, labelled after an A* finds no path (or for
    /// [`PathPlanner::connects`]): a later search from another start in another region fails
    /// at once instead of visiting the whole region again.
    regions: GridRegions,
    /// A* searches run (own goals and detours), for [`PathPlanner::astar_searches`].
    astar_searches: u64,
}

/// A robot standing in the way of a detour ([`PathPlanner::plan_around`]): no cell centre and
/// no smoothed leg may come nearer to `center` than `radius_m`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StandingDisc {
    /// Centre of the standing robot, metres.
    pub center: Vec2,
    /// Keep-out radius around it (its body radius plus the planning inflation), metres.
    pub radius_m: f32,
}

impl StandingDisc {
    /// Whether point `p` lies inside the disc (`|p - center|^2 < radius_m^2` in `f32`; the
    /// detour's [`super::disc_mask::DiscMask`] marks cells by this test).
    pub(super) fn contains(&self, p: Vec2) -> bool {
        (p - self.center).length_squared() < self.radius_m * self.radius_m
    }

    /// The disc, shrunk if needed so that none of `points` lies inside it (to 0.999 of the
    /// nearest one's distance); `None` when a point is at its centre.
    fn leaving_out(&self, points: &[Vec2]) -> Option<Self> {
        let nearest = points
            .iter()
            .map(|&p| (p - self.center).length())
            .fold(f32::INFINITY, f32::min);
        let radius_m = self.radius_m.min(nearest * 0.999);
        (radius_m > 0.0).then_some(Self {
            center: self.center,
            radius_m,
        })
    }

    /// Whether segment `a`-`b` passes through the disc.
    pub(super) fn crosses(&self, a: Vec2, b: Vec2) -> bool {
        let d = b - a;
        let len2 = d.length_squared();
        let t = if len2 > 0.0 {
            ((self.center - a).dot(d) / len2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        self.contains(a + d * t)
    }
}

/// One planning query of a ground robot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlanQuery {
    /// Where the robot stands, world frame, metres.
    pub from: Vec2,
    /// The requested goal, world frame, metres (inside the arena, or the plan fails).
    pub to: Vec2,
    /// Planning inflation: a cell is free when its clearance is at least this, metres (> 0;
    /// the world uses body radius + `navigation.clearance_m` + half a cell).
    pub inflation_m: f32,
}

/// Start and goal of a plan after snapping (see [`PathPlanner::plan`]).
struct Endpoints {
    start_raw: u32,
    start: u32,
    goal: u32,
    goal_point: Vec2,
}

impl Endpoints {
    /// Snaps the query's start and goal to free cells for its inflation.
    fn snap(grid: &ClearanceGrid, arena: (f32, f32), query: PlanQuery) -> Result<Self, NavError> {
        let PlanQuery {
            from,
            to,
            inflation_m: inflation,
        } = query;
        if !in_field(to.x, to.y, arena.0, arena.1) {
            return Err(NavError::GoalOutsideArena);
        }
        let snap_radius = inflation + 2.0 * grid.cell_m();
        let start_raw = grid.cell_index(from);
        let start = if grid.is_free(start_raw, inflation) {
            start_raw
        } else {
            grid.nearest_free(from, inflation, snap_radius)
                .ok_or(NavError::StartBlocked)?
        };
        let goal_raw = grid.cell_index(to);
        let (goal, goal_point) = if grid.is_free(goal_raw, inflation) {
            (goal_raw, to)
        } else {
            let g = grid
                .nearest_free(to, inflation, snap_radius)
                .ok_or(NavError::GoalBlocked)?;
            (g, grid.cell_center(g))
        };
        Ok(Self {
            start_raw,
            start,
            goal,
            goal_point,
        })
    }

    /// Writes the waypoints of the smoothed `cells` (start to goal) into `out`: the snapped
    /// start's centre if the start moved, the interior cells' centres, the effective goal.
    fn write(&self, grid: &ClearanceGrid, cells: &[u32], out: &mut Vec<Vec2>) -> Vec2 {
        out.clear();
        if self.start != self.start_raw {
            out.push(grid.cell_center(self.start));
        }
        if cells.len() > 2 {
            out.extend(
                cells[1..cells.len() - 1]
                    .iter()
                    .map(|&c| grid.cell_center(c)),
            );
        }
        out.push(self.goal_point);
        self.goal_point
    }
}

impl PathPlanner {
    /// An empty planner that keeps at most [`SHARED_FIELDS_BUDGET_BYTES`] of shared fields.
    pub fn new() -> Self {
        Self::default()
    }

    /// An empty planner that keeps at most `budget_bytes` of shared distance fields between
    /// plans (any value: 0 keeps none, and every plan to a shared goal makes its field
    /// afresh). A field larger than the budget is still made and used for the plan that asks
    /// for it, then dropped. The budget changes how often fields are computed, never a plan.
    pub fn with_field_budget(budget_bytes: usize) -> Self {
        Self {
            fields: SharedFields::new(budget_bytes),
            ..Self::default()
        }
    }

    /// Plans `query` (A* or a shared field, as `kind` says); writes the waypoints (the start
    /// excluded, the effective goal last) into `out` and returns the effective goal: `query.to`
    /// if its cell is free, else the nearest free cell centre within `inflation + 2 cells`. A
    /// start in a blocked cell is moved the same way (its cell centre is the first waypoint).
    ///
    /// # Errors
    /// [`NavError`] when the goal is outside `[0, w] x [0, h]`, start or goal are blocked with no
    /// free cell near, or no path exists.
    pub fn plan(
        &mut self,
        grid: &ClearanceGrid,
        arena: (f32, f32),
        query: PlanQuery,
        kind: GoalKind,
        out: &mut Vec<Vec2>,
    ) -> Result<Vec2, NavError> {
        out.clear();
        let inflation = query.inflation_m;
        let ends = Endpoints::snap(grid, arena, query)?;
        let (start, goal) = (ends.start, ends.goal);
        let key = (inflation.to_bits(), start, goal, kind == GoalKind::Shared);
        // Failures are cached too: the grid never changes, so a search that found no path
        // finds none again (it would otherwise scan the whole reachable grid on every retry).
        if let Some(cached) = self.cache.get(&key) {
            let cells = cached.as_ref().map_err(|e| *e)?;
            return Ok(ends.write(grid, cells, out));
        }
        let planned = match kind {
            GoalKind::Own => self.search_own(grid, start, goal, inflation),
            GoalKind::Shared => self.descend(grid, start, goal, inflation),
        };
        let written = match &planned {
            Ok(cells) => Ok(ends.write(grid, cells, out)),
            Err(e) => Err(*e),
        };
        self.cache.insert(key, planned);
        written
    }

    /// A detour: plans like [`PathPlanner::plan`] with A* (never cached, never a shared field)
    /// but also keeps every cell centre and smoothed leg out of the `standing` discs (robots
    /// standing in the way). A disc that holds the goal is dropped (a robot parked on the goal
    /// is left to the mission); a disc that holds the start (a robot touching the planner's
    /// robot) shrinks to just leave the start out, so the detour still goes round that robot
    /// and not through it (dropping it left a robot pressed against a parked one on a path
    /// through it for good).
    ///
    /// # Errors
    /// As [`PathPlanner::plan`]; [`NavError::NoPath`] also when the standing robots close
    /// every way.
    pub fn plan_around(
        &mut self,
        grid: &ClearanceGrid,
        arena: (f32, f32),
        query: PlanQuery,
        standing: &[StandingDisc],
        out: &mut Vec<Vec2>,
    ) -> Result<Vec2, NavError> {
        out.clear();
        let inflation = query.inflation_m;
        let ends = Endpoints::snap(grid, arena, query)?;
        // Standing robots only close ways: two regions of the bare grid stay apart.
        if self.regions.known_apart(inflation, ends.start, ends.goal) {
            return Err(NavError::NoPath);
        }
        let starts = [grid.cell_center(ends.start), query.from];
        self.discs.clear();
        self.discs.extend(
            standing
                .iter()
                .filter(|d| !d.contains(ends.goal_point))
                .filter_map(|d| d.leaving_out(&starts)),
        );
        self.mask.mark(grid, &self.discs);
        let blocked = Blocked {
            discs: &self.discs,
            mask: &self.mask,
        };
        self.astar_searches += 1;
        let cells = search(
            &mut self.astar,
            grid,
            ends.start,
            ends.goal,
            inflation,
            Some(blocked),
        )?;
        Ok(ends.write(grid, &cells, out))
    }

    /// Descent of the shared field towards `goal` for `inflation` (made if not kept, see
    /// [`SharedFields`]) plus smoothing; returns smoothed cell indices from `start` to `goal`
    /// (both included).
    fn descend(
        &mut self,
        grid: &ClearanceGrid,
        start: u32,
        goal: u32,
        inflation: f32,
    ) -> Result<Vec<u32>, NavError> {
        let raw = &mut self.raw;
        let found = self
            .fields
            .with_field(grid, goal, inflation, |f| f.descend(grid, start, raw));
        if !found {
            return Err(NavError::NoPath);
        }
        if self.raw.len() < 2 {
            return Ok(vec![start, goal]);
        }
        Ok(smooth_galloping(grid, &self.raw, inflation))
    }

    /// A* from cell `start` to cell `goal` ([`search`]), failing at once when the two are
    /// known to lie in different regions; a search that finds no path to a free goal labels
    /// the regions at `inflation` for the searches after it. The same result as the search
    /// alone, since a region is what A* can reach.
    fn search_own(
        &mut self,
        grid: &ClearanceGrid,
        start: u32,
        goal: u32,
        inflation: f32,
    ) -> Result<Vec<u32>, NavError> {
        if self.regions.known_apart(inflation, start, goal) {
            return Err(NavError::NoPath);
        }
        self.astar_searches += 1;
        let found = search(&mut self.astar, grid, start, goal, inflation, None);
        if found == Err(NavError::NoPath) && grid.is_free(goal, inflation) {
            self.regions.label(grid, inflation);
        }
        found
    }

    /// Whether [`PathPlanner::plan`] would find a path for `query`, with either
    /// [`GoalKind`] (A* and a shared goal's distance field find a path exactly when start and
    /// goal share a region), answered from the grid's region labels (made once per inflation)
    /// instead of a search: `Ok` exactly when that plan succeeds.
    ///
    /// # Errors
    /// As [`PathPlanner::plan`].
    pub fn connects(
        &mut self,
        grid: &ClearanceGrid,
        arena: (f32, f32),
        query: PlanQuery,
    ) -> Result<(), NavError> {
        let ends = Endpoints::snap(grid, arena, query)?;
        if ends.start == ends.goal
            || self
                .regions
                .connected(grid, query.inflation_m, ends.start, ends.goal)
        {
            Ok(())
        } else {
            Err(NavError::NoPath)
        }
    }

    /// A* searches run so far, for a robot's own goals and for detours (a cached plan, a
    /// shared goal's descent and a search known to fail from the regions run none).
    pub fn astar_searches(&self) -> u64 {
        self.astar_searches
    }

    /// The shared fields kept now (one per goal cell and inflation, at most
    /// [`PathPlanner::field_budget_bytes`] of them together), least recently used first.
    pub fn fields(&self) -> impl ExactSizeIterator<Item = &DistanceField> {
        self.fields.iter()
    }

    /// Heap bytes the kept shared fields hold ([`DistanceField::heap_bytes`] summed, as at
    /// each field's last use): at most [`PathPlanner::field_budget_bytes`] between plans.
    pub fn field_bytes(&self) -> usize {
        self.fields.held_bytes()
    }

    /// The shared fields' budget, bytes ([`SHARED_FIELDS_BUDGET_BYTES`] unless made with
    /// [`PathPlanner::with_field_budget`]).
    pub fn field_budget_bytes(&self) -> usize {
        self.fields.budget_bytes()
    }

    /// Bytes the plan cache's entries hold (at most 64 MiB): each entry's fixed size plus 4
    /// bytes per cell of its smoothed plan.
    pub fn cache_bytes(&self) -> usize {
        self.cache.bytes()
    }
}

/// Robots standing in the way of a detour: their discs (for the smoothed legs) and the grid
/// cells inside them (for A*'s successors), marked from the same discs.
#[derive(Clone, Copy)]
struct Blocked<'a> {
    discs: &'a [StandingDisc],
    mask: &'a DiscMask,
}

/// A* (outside the `blocked` discs, if any) plus smoothing; returns smoothed cell indices from
/// `start` to `goal` (both included). A successor cell is dropped when its centre lies in a
/// disc (one mask read per successor). A* reaches the goal only by a move into it, so a goal
/// cell no move may enter (not free, or inside a standing robot's disc that leaves the goal
/// point itself out) has no path: that is found out at once, not after a flood of every cell
/// reachable from the start (the same answer).
fn search(
    astar: &mut GridAstar,
    grid: &ClearanceGrid,
    start: u32,
    goal: u32,
    inflation: f32,
    blocked: Option<Blocked>,
) -> Result<Vec<u32>, NavError> {
    if start == goal {
        return Ok(vec![start, goal]);
    }
    let outside_discs = |c: u32| blocked.is_none_or(|b| !b.mask.is_marked(c));
    if !grid.is_free(goal, inflation) || !outside_discs(goal) {
        return Err(NavError::NoPath);
    }
    let (nx, ny) = grid.dims();
    let raw = astar
        .search(
            nx as usize * ny as usize,
            start,
            goal,
            |n| {
                grid.successors(n, inflation)
                    .filter(move |&(c, _)| outside_discs(c))
            },
            |n| grid.octile(n, goal),
        )
        .ok_or(NavError::NoPath)?;
    Ok(smooth(
        grid,
        &raw,
        inflation,
        blocked.map_or(&[], |b| b.discs),
    ))
}

/// Greedy line-of-sight smoothing: from each anchor, jump to the farthest following cell still
/// visible (checked on cell centres, against the grid and the `discs`).
fn smooth(grid: &ClearanceGrid, raw: &[u32], inflation: f32, discs: &[StandingDisc]) -> Vec<u32> {
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
fn smooth_galloping(grid: &ClearanceGrid, raw: &[u32], inflation: f32) -> Vec<u32> {
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
    use parry2d::math::Pose;
    use parry2d::shape::{Ball, Cuboid};

    use super::*;
    use crate::scenario::Positive;
    use crate::world::bodies::StaticShape;

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

    const CELL: f64 = 0.25;
    /// Planning inflation of the tests, metres (a 0.4 m body, 0.075 m clearance, half a cell).
    const INFL: f32 = 0.6;
    const ARENA: (f32, f32) = (10.0, 10.0);

    fn block(cx: f32, cy: f32, hx: f32, hy: f32) -> StaticObstacle {
        StaticObstacle {
            shape: StaticShape::Cuboid(Cuboid::new(Vec2::new(hx, hy))),
            pose: Pose::translation(cx, cy),
            is_wall: false,
        }
    }

    fn disc(cx: f32, cy: f32, r: f32) -> StaticObstacle {
        StaticObstacle {
            shape: StaticShape::Ball(Ball::new(r)),
            pose: Pose::translation(cx, cy),
            is_wall: false,
        }
    }

    /// A 10 m x 10 m grid of 0.25 m cells, clearance capped at 2 m.
    fn grid(statics: &[StaticObstacle]) -> ClearanceGrid {
        let arena = Arena {
            width_m: Positive::new(f64::from(ARENA.0)).unwrap(),
            height_m: Positive::new(f64::from(ARENA.1)).unwrap(),
            wall_thickness_m: Positive::new(0.5).unwrap(),
        };
        ClearanceGrid::build(&arena, statics, CELL, 2.0)
    }

    /// Exact distance from `p` to the nearest of `statics`.
    fn exact(statics: &[StaticObstacle], p: Vec2) -> f32 {
        statics
            .iter()
            .map(|o| o.distance_to_point(p))
            .fold(f32::INFINITY, f32::min)
    }

    /// Plans `from` -> `to`; returns the waypoints with `from` prepended, or the error.
    fn plan(g: &ClearanceGrid, from: Vec2, to: Vec2) -> Result<Vec<Vec2>, NavError> {
        let mut out = Vec::new();
        let q = PlanQuery {
            from,
            to,
            inflation_m: INFL,
        };
        let eff = PathPlanner::new().plan(g, ARENA, q, GoalKind::Own, &mut out)?;
        assert_eq!(
            out.last(),
            Some(&eff),
            "the effective goal is the last waypoint"
        );
        Ok(std::iter::once(from).chain(out).collect())
    }

    /// Every point of every leg (sampled each centimetre) keeps at least `min` metres from
    /// `statics`.
    fn legs_clear(statics: &[StaticObstacle], path: &[Vec2], min: f32) {
        for leg in path.windows(2) {
            let n = ((leg[1] - leg[0]).length() / 0.01).ceil() as u32;
            for k in 0..=n {
                let p = leg[0] + (leg[1] - leg[0]) * (k as f32 / n.max(1) as f32);
                let d = exact(statics, p);
                assert!(d >= min, "{p:?} on leg {leg:?} is {d} m from debris");
            }
        }
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

    proptest::proptest! {
        /// A detour's search answers as plain A* over the cells outside the standing discs
        /// (then smoothing) does, also when a disc covers the goal cell (no path at once).
        #[test]
        fn search_answers_as_a_star_outside_the_discs(
            debris in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.1f32..1.0), 0..4),
            standing in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.2f32..1.5), 0..8),
            (start, goal) in (0u32..1600, 0u32..1600),
        ) {
            let statics: Vec<_> = debris.iter().map(|&(x, y, r)| disc(x, y, r)).collect();
            let g = grid(&statics);
            let discs: Vec<_> = standing
                .iter()
                .map(|&(x, y, r)| StandingDisc { center: Vec2::new(x, y), radius_m: r })
                .collect();
            let mut mask = DiscMask::default();
            mask.mark(&g, &discs);
            let blocked = Blocked { discs: &discs, mask: &mask };
            let ours = search(&mut GridAstar::default(), &g, start, goal, INFL, Some(blocked));
            let reference = if start == goal {
                Ok(vec![start, goal])
            } else {
                GridAstar::default()
                    .search(
                        1600,
                        start,
                        goal,
                        |n| g.successors(n, INFL).filter(|&(c, _)| !mask.is_marked(c)),
                        |n| g.octile(n, goal),
                    )
                    .map(|raw| smooth(&g, &raw, INFL, &discs))
                    .ok_or(NavError::NoPath)
            };
            proptest::prop_assert_eq!(ours, reference);
        }
    }

    #[test]
    fn a_goal_cell_inside_a_standing_disc_has_no_path() {
        let g = grid(&[]);
        let goal = g.cell_index(Vec2::new(5.01, 5.01));
        // The disc holds the goal cell's centre (5.125, 5.125), 0.25 m from its centre, but
        // not the goal point, 0.41 m from it: a detour would keep it.
        let discs = [StandingDisc {
            center: Vec2::new(5.3, 5.3),
            radius_m: 0.3,
        }];
        let mut mask = DiscMask::default();
        mask.mark(&g, &discs);
        assert!(mask.is_marked(goal));
        assert!(!discs[0].contains(Vec2::new(5.01, 5.01)));
        let blocked = Blocked {
            discs: &discs,
            mask: &mask,
        };
        let found = search(&mut GridAstar::default(), &g, 0, goal, INFL, Some(blocked));
        assert_eq!(found, Err(NavError::NoPath));
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

    #[test]
    fn a_star_goes_around_a_wall_through_its_gap() {
        // A wall across the arena at y = 5 from x = 0 to 7; the gap is east of it.
        let statics = [block(3.5, 5.0, 3.5, 0.25)];
        let g = grid(&statics);
        let (from, to) = (Vec2::new(2.0, 2.0), Vec2::new(2.0, 8.0));
        let path = plan(&g, from, to).expect("a path through the gap");
        assert_eq!(*path.last().unwrap(), to);
        assert!(
            path.iter().any(|p| p.x > 7.0 + INFL),
            "the path rounds the wall's end: {path:?}"
        );
        // Free cells are at least INFL from debris at their centre, so no point of a smoothed
        // leg is nearer than INFL minus half a cell diagonal.
        legs_clear(&statics, &path, INFL - CELL as f32 * 0.5f32.sqrt());
        for leg in path.windows(2) {
            assert!(
                g.line_of_sight(leg[0], leg[1], INFL, f32::INFINITY),
                "{leg:?}"
            );
        }
    }

    #[test]
    fn a_star_finds_no_path_through_a_closed_wall() {
        let g = grid(&[block(5.0, 5.0, 5.5, 0.25)]);
        assert_eq!(
            plan(&g, Vec2::new(2.0, 2.0), Vec2::new(2.0, 8.0)),
            Err(NavError::NoPath)
        );
        // The same goal on the start's side is reachable.
        assert!(plan(&g, Vec2::new(2.0, 2.0), Vec2::new(8.0, 3.0)).is_ok());
    }

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

    #[test]
    fn a_goal_inside_an_obstacle_moves_to_the_nearest_free_cell() {
        let statics = [disc(5.1, 5.1, 0.3)];
        let g = grid(&statics);
        let requested = Vec2::new(5.1, 5.1);
        let path = plan(&g, Vec2::new(2.0, 2.0), requested).expect("snapped goal");
        let eff = *path.last().unwrap();
        assert_ne!(eff, requested);
        let idx = g.cell_index(eff);
        assert_eq!(
            eff,
            g.cell_center(idx),
            "the effective goal is a cell centre"
        );
        assert!(g.is_free(idx, INFL));
        let d = (eff - requested).length_squared();
        for other in 0..40 * 40 {
            if g.is_free(other, INFL) {
                let o = (g.cell_center(other) - requested).length_squared();
                assert!(d < o || (d == o && idx <= other), "cell {other} is nearer");
            }
        }
        // Deep inside a large block no free cell is near enough.
        let g = grid(&[block(5.0, 5.0, 2.0, 2.0)]);
        assert_eq!(
            plan(&g, Vec2::new(1.0, 1.0), Vec2::new(5.0, 5.0)),
            Err(NavError::GoalBlocked)
        );
    }

    #[test]
    fn goals_outside_the_arena_are_rejected_and_plans_are_cached_exactly() {
        let g = grid(&[block(5.0, 5.0, 1.0, 1.0)]);
        let from = Vec2::new(1.0, 1.0);
        for to in [
            Vec2::new(10.5, 5.0),
            Vec2::new(-0.1, 5.0),
            Vec2::new(f32::NAN, 5.0),
            Vec2::new(5.0, f32::INFINITY),
        ] {
            assert_eq!(
                plan(&g, from, to),
                Err(NavError::GoalOutsideArena),
                "{to:?}"
            );
        }
        let mut planner = PathPlanner::new();
        let (mut first, mut second) = (Vec::new(), Vec::new());
        let to = Vec2::new(9.0, 9.0);
        let q = PlanQuery {
            from,
            to,
            inflation_m: INFL,
        };
        let a = planner.plan(&g, ARENA, q, GoalKind::Own, &mut first);
        let b = planner.plan(&g, ARENA, q, GoalKind::Own, &mut second);
        assert_eq!(a, b);
        assert_eq!(first, second);
        assert_eq!(planner.cache.len(), 1);
        assert!(planner.cache_bytes() > 0);
    }

    /// A robot touching the planner's robot on the straight way to the goal: the detour goes
    /// round it (its disc shrunk to leave the start out), not through it.
    #[test]
    fn a_detour_goes_round_a_robot_touching_the_start() {
        let g = grid(&[]);
        let (from, to) = (Vec2::new(3.0, 5.0), Vec2::new(8.0, 5.0));
        let standing = [StandingDisc {
            center: Vec2::new(3.9, 5.0),
            radius_m: 0.4 + INFL,
        }];
        let q = PlanQuery {
            from,
            to,
            inflation_m: INFL,
        };
        let mut out = Vec::new();
        let mut planner = PathPlanner::new();
        planner
            .plan_around(&g, ARENA, q, &standing, &mut out)
            .expect("a way round");
        let path: Vec<Vec2> = std::iter::once(from).chain(out).collect();
        for leg in path.windows(2) {
            let n = ((leg[1] - leg[0]).length() / 0.01).ceil() as u32;
            for k in 0..=n {
                let p = leg[0] + (leg[1] - leg[0]) * (k as f32 / n.max(1) as f32);
                let d = (p - standing[0].center).length();
                assert!(
                    d >= 0.75,
                    "{p:?} on leg {leg:?} is {d} m from the standing robot"
                );
            }
        }
        assert!(
            (path.last().copied().unwrap() - to).length() < 0.2,
            "{path:?}"
        );
    }

    /// Shared-goal plans of the queries `(x, y, goal, class)` (start, index into `goals`,
    /// index into the inflations 0.6 and 0.35 m) by `planner`, with the waypoints.
    type SharedPlan = (Result<Vec2, NavError>, Vec<Vec2>);

    fn shared_plan(
        planner: &mut PathPlanner,
        g: &ClearanceGrid,
        goal: Vec2,
        (x, y, class): (f32, f32, usize),
    ) -> SharedPlan {
        let q = PlanQuery {
            from: Vec2::new(x, y),
            to: goal,
            inflation_m: [INFL, 0.35][class % 2],
        };
        let mut out = Vec::new();
        let found = planner.plan(g, ARENA, q, GoalKind::Shared, &mut out);
        (found, out)
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// A planner whose field budget keeps no field, one, or two or three (so fields are
        /// dropped and made again, in every order of use) plans exactly what a planner that
        /// keeps every field plans, over random debris, goals, starts and two clearance
        /// classes; between plans its fields never hold more than the budget, as counted
        /// from the fields themselves. Once a plan has found a path, a budget of two new
        /// fields keeps exactly one field (a field outgrows its new size once searched, so a
        /// budget of one new field would keep none), one of three and a half one to three.
        #[test]
        fn a_field_budget_changes_no_plan_and_holds(
            debris in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.1f32..1.2), 0..6),
            goals in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0), 1..6),
            queries in proptest::collection::vec(
                (0.0f32..10.0, 0.0f32..10.0, 0usize..6, 0usize..2),
                1..40,
            ),
            halves in proptest::prop_oneof![
                proptest::strategy::Just(0usize),
                proptest::strategy::Just(4),
                proptest::strategy::Just(7),
            ],
        ) {
            let statics: Vec<_> = debris.iter().map(|&(x, y, r)| disc(x, y, r)).collect();
            let g = grid(&statics);
            let budget = DistanceField::new_heap_bytes(&g) * halves / 2;
            let mut small = PathPlanner::with_field_budget(budget);
            let mut unlimited = PathPlanner::with_field_budget(usize::MAX);
            proptest::prop_assert_eq!(small.field_budget_bytes(), budget);
            let mut found_any = false;
            for &(x, y, k, class) in &queries {
                let (gx, gy) = goals[k % goals.len()];
                let goal = Vec2::new(gx, gy);
                let ours = shared_plan(&mut small, &g, goal, (x, y, class));
                let reference = shared_plan(&mut unlimited, &g, goal, (x, y, class));
                proptest::prop_assert_eq!(&ours, &reference);
                let held: usize = small.fields().map(DistanceField::heap_bytes).sum();
                proptest::prop_assert_eq!(held, small.field_bytes());
                proptest::prop_assert!(held <= budget, "{} bytes held, budget {}", held, budget);
                // Every plan that found a path used a field (or the cache, filled by one).
                found_any |= ours.0.is_ok();
                let kept = small.fields().count();
                let least = usize::from(found_any && halves > 0);
                let most = [0, 1, 3][halves / 3];
                proptest::prop_assert!(
                    (least..=most).contains(&kept),
                    "{} fields kept, budget of {} halves",
                    kept,
                    halves
                );
            }
        }

        /// A goal check from the regions ([`PathPlanner::connects`]) answers as a plan by a
        /// shared field does: `Ok` exactly when the plan succeeds, the same error otherwise.
        #[test]
        fn connects_answers_as_a_shared_plan(
            debris in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.1f32..2.0), 0..8),
            queries in proptest::collection::vec(
                (0.0f32..10.0, 0.0f32..10.0, -0.5f32..10.5, -0.5f32..10.5),
                1..20,
            ),
        ) {
            let statics: Vec<_> = debris.iter().map(|&(x, y, r)| disc(x, y, r)).collect();
            let g = grid(&statics);
            let mut planner = PathPlanner::new();
            for &(x, y, gx, gy) in &queries {
                let q = PlanQuery {
                    from: Vec2::new(x, y),
                    to: Vec2::new(gx, gy),
                    inflation_m: INFL,
                };
                let mut out = Vec::new();
                let planned = planner.plan(&g, ARENA, q, GoalKind::Shared, &mut out).map(|_| ());
                proptest::prop_assert_eq!(planner.connects(&g, ARENA, q), planned);
            }
        }
    }

    /// Twenty shared goals: a planner with the default budget keeps all twenty fields of this
    /// small grid, one with a budget of three fields keeps at most three (the least recently
    /// used dropped), and one whose budget is smaller than one field keeps none, each with the
    /// same plans. The old planner kept every field for its whole life, whatever it held.
    #[test]
    fn the_fields_kept_stay_within_the_budget() {
        let g = grid(&[disc(5.0, 5.0, 1.0), block(2.0, 8.0, 1.0, 0.5)]);
        let one = DistanceField::new_heap_bytes(&g);
        let mut planners = [
            PathPlanner::new(),
            PathPlanner::with_field_budget(3 * one + one / 2),
            PathPlanner::with_field_budget(one / 2),
        ];
        let goals: Vec<Vec2> = (0..20)
            .map(|k| Vec2::new(0.5 + 0.45 * k as f32, 3.0 + 0.3 * (k % 3) as f32))
            .collect();
        for (k, &goal) in goals.iter().enumerate() {
            let from = (9.0, 9.0 - 0.1 * k as f32, 0);
            let [a, b, c] = &mut planners;
            let plans = [a, b, c].map(|p| shared_plan(p, &g, goal, from));
            assert!(plans[0].0.is_ok(), "goal {goal:?}: {:?}", plans[0]);
            assert_eq!(plans[1], plans[0], "goal {goal:?}");
            assert_eq!(plans[2], plans[0], "goal {goal:?}");
        }
        let kept = planners.each_ref().map(|p| p.fields().len());
        assert_eq!(kept, [20, 3, 0]);
        for p in &planners {
            assert!(
                p.field_bytes() <= p.field_budget_bytes(),
                "{}",
                p.field_bytes()
            );
        }
        assert_eq!(planners[0].field_budget_bytes(), SHARED_FIELDS_BUDGET_BYTES);
        // The three kept are the three used last, oldest first.
        let last: Vec<u32> = goals[17..].iter().map(|&p| g.cell_index(p)).collect();
        let goals_kept: Vec<u32> = planners[1].fields().map(DistanceField::goal).collect();
        assert_eq!(goals_kept, last);
    }
}
