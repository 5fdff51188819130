//! The path planner of ground robots ([`PathPlanner`]).
//!
//! A plan cache, grid A* (`grid_search`) for a robot's own goals and detours, and descents of
//! shared distance fields ([`super::distance_field`]) for goals many robots share, each
//! smoothed by line of sight.

use std::collections::HashMap;

use parry2d::math::Vector as Vec2;

use super::clearance_grid::ClearanceGrid;
use super::distance_field::DistanceField;
use super::error::NavError;
use super::grid_regions::GridRegions;
use super::grid_search::search;
use super::plan_around::{AroundPlan, AroundScratch, plan_around_ahead, search_around};
use super::plan_cache::{PlanCache, PlanKey, Planned};
use super::plan_query::{Endpoints, PlanQuery};
use super::shared_descents::{prepare_descents, smoothed};
pub use super::shared_fields::SHARED_FIELDS_BUDGET_BYTES;
use super::shared_fields::SharedFields;
use super::standing_disc::StandingDisc;

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
    /// A*'s per-cell state (own goals and detours) and a detour's discs and cell mask.
    around: AroundScratch,
    /// The grid's regions per inflation, labelled after an A* finds no path (or for
    /// [`PathPlanner::connects`]): a later search from another start in another region fails
    /// at once instead of visiting the whole region again.
    regions: GridRegions,
    /// A* searches run (own goals and detours), for [`PathPlanner::astar_searches`].
    astar_searches: u64,
    /// Plans to shared goals made ahead ([`PathPlanner::prepare_shared`]), taken by the
    /// first [`PathPlanner::plan`] that misses the cache on their key.
    prepared: HashMap<PlanKey, Planned>,
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
        let planned = match (kind, self.prepared.remove(&key)) {
            (_, Some(prepared)) => prepared,
            (GoalKind::Own, None) => self.search_own(grid, start, goal, inflation),
            (GoalKind::Shared, None) => self.descend(grid, start, goal, inflation),
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
        let ends = Endpoints::snap(grid, arena, query)?;
        // Standing robots only close ways: two regions of the bare grid stay apart.
        if self
            .regions
            .known_apart(query.inflation_m, ends.start, ends.goal)
        {
            return Err(NavError::NoPath);
        }
        self.astar_searches += 1;
        search_around(&mut self.around, grid, &ends, query, standing, out)
    }

    /// [`PathPlanner::plan_around`] of `plan.query` round the discs `plan` was planned
    /// ahead round ([`PathPlanner::plan_arounds_ahead`]): the same answer, waypoints (into
    /// `out`) and count of searches, without searching again; `None` for a plan that ran no
    /// search ahead (its query plans at once in turn). The regions may have learnt, or
    /// forgotten (they keep a few inflations), that the query's ends lie apart since: a query
    /// they now know apart fails here as `plan_around` fails it, uncounted; any other was
    /// searched ahead as `plan_around` would search it now.
    ///
    /// # Errors
    /// As [`PathPlanner::plan_around`].
    pub(super) fn take_around(
        &mut self,
        grid: &ClearanceGrid,
        arena: (f32, f32),
        plan: &AroundPlan,
        out: &mut Vec<Vec2>,
    ) -> Option<Result<Vec2, NavError>> {
        if !plan.searched {
            return None;
        }
        out.clear();
        let ends = match Endpoints::snap(grid, arena, plan.query) {
            Ok(ends) => ends,
            Err(e) => return Some(Err(e)),
        };
        let apart = (self.regions).known_apart(plan.query.inflation_m, ends.start, ends.goal);
        if apart {
            return Some(Err(NavError::NoPath));
        }
        self.astar_searches += 1;
        out.extend_from_slice(&plan.path);
        Some(plan.result)
    }

    /// Runs `each(i, planner)` for `i` in `0..n`, side by side on the calling rayon pool (the
    /// global pool outside one), where `planner` plans detours ahead
    /// ([`AheadPlanner::plan_around`]) with this planner's regions and a scratch of its own:
    /// this planner's for one of `scratch.len() + 1` tasks, `scratch[k]` for each other
    /// (`each` must keep no planner beyond its call; an empty `scratch` runs one task, all of
    /// `i` in turn). Each task takes the next `i` not taken yet, so a task whose plans run
    /// long leaves the rest to the others. Results are in `i` order, whatever ran where.
    pub(super) fn plan_arounds_ahead<T: Send>(
        &mut self,
        n: usize,
        scratch: &mut [AroundScratch],
        each: impl Fn(usize, &mut AheadPlanner) -> T + Sync,
    ) -> Vec<T> {
        use rayon::prelude::*;
        use std::sync::atomic::{AtomicUsize, Ordering};
        let regions = &self.regions;
        let mut own = [std::mem::take(&mut self.around)];
        let all: Vec<&mut AroundScratch> = own.iter_mut().chain(scratch.iter_mut()).collect();
        let next = AtomicUsize::new(0);
        let run = |s: &mut AroundScratch| {
            let mut planner = AheadPlanner {
                regions,
                scratch: s,
            };
            let taken = std::iter::from_fn(|| Some(next.fetch_add(1, Ordering::Relaxed)));
            (taken.take_while(|&i| i < n))
                .map(|i| (i, each(i, &mut planner)))
                .collect::<Vec<(usize, T)>>()
        };
        let parts: Vec<Vec<(usize, T)>> = all.into_par_iter().map(run).collect();
        let mut parts: Vec<(usize, T)> = parts.into_iter().flatten().collect();
        parts.sort_unstable_by_key(|&(i, _)| i);
        let [own] = own;
        self.around = own;
        parts.into_iter().map(|(_, t)| t).collect()
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
        smoothed(grid, &self.raw, (start, goal), inflation, found)
    }

    /// Makes ahead, side by side on the calling rayon pool when `parallel`, the plans that
    /// [`PathPlanner::plan`] of each of `queries` with [`GoalKind::Shared`] would make (every
    /// query's goal a shared goal), for the plans that follow to take instead of planning:
    /// the same plans, made at once ([`super::shared_descents`]). Those not taken stay until
    /// [`PathPlanner::clear_prepared`].
    pub(super) fn prepare_shared(
        &mut self,
        grid: &ClearanceGrid,
        arena: (f32, f32),
        queries: &[PlanQuery],
        parallel: bool,
    ) {
        let cache = &self.cache;
        prepare_descents(
            &mut self.fields,
            grid,
            arena,
            queries,
            |key| cache.get(key).is_some(),
            parallel,
            &mut self.prepared,
        );
    }

    /// Drops the plans made ahead that no plan took ([`PathPlanner::prepare_shared`]).
    pub(super) fn clear_prepared(&mut self) {
        self.prepared.clear();
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
        let found = search(&mut self.around.astar, grid, start, goal, inflation, None);
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

    /// Shared fields made so far in the memory of the least recently used field, dropped to
    /// make room for them within the budget, rather than in memory of their own (the same
    /// costs and paths: [`DistanceField::renew`]).
    pub fn fields_renewed(&self) -> u64 {
        self.fields.renewed()
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

/// A planner of detours ahead ([`PathPlanner::plan_arounds_ahead`]): the planner's regions,
/// read, and a scratch of its own.
pub(super) struct AheadPlanner<'a> {
    regions: &'a GridRegions,
    scratch: &'a mut AroundScratch,
}

impl AheadPlanner<'_> {
    /// The detour [`PathPlanner::plan_around`] would plan for `query` round `standing`, with
    /// the regions as they stand, planned ahead ([`plan_around_ahead`]).
    pub(super) fn plan_around(
        &mut self,
        grid: &ClearanceGrid,
        arena: (f32, f32),
        query: PlanQuery,
        standing: &[StandingDisc],
    ) -> AroundPlan {
        let regions = self.regions;
        let known_apart = |inflation, a, b| regions.known_apart(inflation, a, b);
        plan_around_ahead(known_apart, self.scratch, grid, arena, query, standing)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::test_grids::*;

    const ARENA: (f32, f32) = (10.0, 10.0);

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

    /// A detour planned ahead while the regions knew its ends apart ran no search; when the
    /// regions have since forgotten that inflation (they keep four), planned in turn it
    /// searches, and so does the detour taken in turn: the same answer and count of searches.
    #[test]
    fn a_detour_planned_ahead_without_a_search_is_planned_in_turn() {
        let g = grid(&[block(5.0, 5.0, 5.5, 0.25)]);
        let across = |inflation_m: f32| PlanQuery {
            from: Vec2::new(2.0, 2.0),
            to: Vec2::new(2.0, 8.0),
            inflation_m,
        };
        let fail = |p: &mut PathPlanner, inflation: f32| {
            let found = p.plan(&g, ARENA, across(inflation), GoalKind::Own, &mut Vec::new());
            assert_eq!(
                found,
                Err(NavError::NoPath),
                "the wall parts them at {inflation}"
            );
        };
        let (mut ahead, mut in_turn) = (PathPlanner::new(), PathPlanner::new());
        for p in [&mut ahead, &mut in_turn] {
            for inflation in [0.20, 0.21, 0.22, 0.23] {
                fail(p, inflation);
            }
        }
        let planned = ahead.plan_arounds_ahead(1, &mut [], |_, p| {
            p.plan_around(&g, ARENA, across(0.20), &[])
        });
        assert!(!planned[0].searched, "known apart: no search ahead");
        // A fifth inflation: the regions forget 0.20.
        for p in [&mut ahead, &mut in_turn] {
            fail(p, 0.24);
        }
        let mut out = Vec::new();
        assert_eq!(ahead.take_around(&g, ARENA, &planned[0], &mut out), None);
        let taken = ahead.plan_around(&g, ARENA, across(0.20), &[], &mut out);
        let reference = in_turn.plan_around(&g, ARENA, across(0.20), &[], &mut Vec::new());
        assert_eq!(taken, reference);
        assert_eq!(ahead.astar_searches(), in_turn.astar_searches());
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

    /// A scene of the shared-field proptests: debris discs (x, y, radius; metres) on the
    /// 10 m x 10 m grid, shared goals (x, y) and queries (start x, y, goal index, clearance
    /// class).
    type SharedScene = (
        Vec<(f32, f32, f32)>,
        Vec<(f32, f32)>,
        Vec<(f32, f32, usize, usize)>,
    );

    fn shared_scenes() -> impl proptest::strategy::Strategy<Value = SharedScene> {
        use proptest::collection::vec;
        (
            vec((0.0f32..10.0, 0.0f32..10.0, 0.1f32..1.2), 0..6),
            vec((0.0f32..10.0, 0.0f32..10.0), 1..6),
            vec((0.0f32..10.0, 0.0f32..10.0, 0usize..6, 0usize..2), 1..40),
        )
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
            (debris, goals, queries) in shared_scenes(),
            halves in proptest::sample::select(vec![0usize, 4, 7]),
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

        /// Detours planned ahead on two threads ([`PathPlanner::plan_arounds_ahead`], one
        /// scratch beside the planner's) and taken in turn ([`PathPlanner::take_around`]) are
        /// the detours planned one by one ([`PathPlanner::plan_around`]): the same answers,
        /// waypoints and count of A* searches, over random debris, standing robots, starts,
        /// goals and two clearance classes; also when, between the two, a failed plan across
        /// a closed wall teaches the regions that the wall parts them, so that a detour
        /// searched ahead across it fails in turn uncounted, as it does planned in turn.
        #[test]
        fn detours_planned_ahead_are_the_detours(
            (debris, goals, queries) in shared_scenes(),
            robots in proptest::collection::vec((0.0f32..10.0, 0.0f32..10.0, 0.2f32..1.2), 0..6),
            wall in proptest::prelude::any::<bool>(),
        ) {
            let mut statics: Vec<_> = debris.iter().map(|&(x, y, r)| disc(x, y, r)).collect();
            if wall {
                statics.push(block(5.0, 5.0, 5.5, 0.25));
            }
            let g = grid(&statics);
            let standing: Vec<StandingDisc> = robots
                .iter()
                .map(|&(x, y, r)| StandingDisc { center: Vec2::new(x, y), radius_m: r })
                .collect();
            let asked: Vec<PlanQuery> = queries
                .iter()
                .map(|&(x, y, k, class)| PlanQuery {
                    from: Vec2::new(x, y),
                    to: Vec2::new(goals[k % goals.len()].0, goals[k % goals.len()].1),
                    inflation_m: [INFL, 0.35][class % 2],
                })
                .collect();
            let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().expect("a pool");
            let mut ahead = PathPlanner::new();
            let mut extra = [AroundScratch::default()];
            let planned = pool.install(|| {
                ahead.plan_arounds_ahead(asked.len(), &mut extra, |i, p| {
                    p.plan_around(&g, ARENA, asked[i], &standing)
                })
            });
            proptest::prop_assert_eq!(planned.len(), asked.len());
            let mut one_by_one = PathPlanner::new();
            if wall {
                for planner in [&mut ahead, &mut one_by_one] {
                    let across = PlanQuery {
                        from: Vec2::new(2.0, 2.0),
                        to: Vec2::new(2.0, 8.0),
                        inflation_m: INFL,
                    };
                    // No path across (debris may block the start or the goal besides).
                    let found = planner.plan(&g, ARENA, across, GoalKind::Own, &mut Vec::new());
                    proptest::prop_assert!(found.is_err());
                }
            }
            let (mut ours, mut theirs) = (Vec::new(), Vec::new());
            for (q, plan) in asked.iter().zip(&planned) {
                proptest::prop_assert_eq!(plan.query, *q);
                let taken = match ahead.take_around(&g, ARENA, plan, &mut ours) {
                    Some(taken) => taken,
                    None => ahead.plan_around(&g, ARENA, *q, &standing, &mut ours),
                };
                let reference = one_by_one.plan_around(&g, ARENA, *q, &standing, &mut theirs);
                proptest::prop_assert_eq!(taken, reference);
                proptest::prop_assert_eq!(&ours, &theirs);
            }
            proptest::prop_assert_eq!(ahead.astar_searches(), one_by_one.astar_searches());
        }

        /// Plans made ahead ([`PathPlanner::prepare_shared`], on two threads) are the plans a
        /// planner makes one by one, over random debris, goals, starts and two clearance
        /// classes, under a field budget that keeps no field, two, or all (the fields then
        /// expanded one after the other or side by side); the plans to come take every plan
        /// made ahead, and the fields hold at most the budget after it.
        #[test]
        fn prepared_plans_are_the_plans(
            (debris, goals, queries) in shared_scenes(),
            fields_kept in proptest::sample::select(vec![0usize, 2, usize::MAX]),
        ) {
            let statics: Vec<_> = debris.iter().map(|&(x, y, r)| disc(x, y, r)).collect();
            let g = grid(&statics);
            let budget = DistanceField::new_heap_bytes(&g).saturating_mul(fields_kept);
            let mut ahead = PathPlanner::with_field_budget(budget);
            let mut reference = PathPlanner::with_field_budget(usize::MAX);
            let to = |k: usize| Vec2::new(goals[k % goals.len()].0, goals[k % goals.len()].1);
            let asked: Vec<PlanQuery> = queries
                .iter()
                .map(|&(x, y, k, class)| PlanQuery {
                    from: Vec2::new(x, y),
                    to: to(k),
                    inflation_m: [INFL, 0.35][class],
                })
                .collect();
            let pool = rayon::ThreadPoolBuilder::new().num_threads(2).build().unwrap();
            pool.install(|| ahead.prepare_shared(&g, ARENA, &asked, true));
            proptest::prop_assert!(ahead.field_bytes() <= budget, "{}", ahead.field_bytes());
            for &(x, y, k, class) in &queries {
                let ours = shared_plan(&mut ahead, &g, to(k), (x, y, class));
                let theirs = shared_plan(&mut reference, &g, to(k), (x, y, class));
                proptest::prop_assert_eq!(ours, theirs);
            }
            proptest::prop_assert!(ahead.prepared.is_empty(), "{} not taken", ahead.prepared.len());
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
        // Past the third, a field of the second planner that has to drop one to fit is made
        // in the dropped one's memory (not every one: a field whose open set grew may have
        // been dropped after its plan); the first drops none, the third drops its one field
        // only after the plan.
        let [all, three, none] = planners.each_ref().map(PathPlanner::fields_renewed);
        assert_eq!((all, none), (0, 0));
        assert!((1..=17).contains(&three), "{three}");
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
