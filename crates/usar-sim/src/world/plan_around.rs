//! A detour's search round the robots standing in the way ([`search_around`]), its scratch
//! ([`AroundScratch`]) and a detour planned ahead ([`AroundPlan`]).
//!
//! Not in the paper (the detour rule is `docs/world-model.md`, "Detours"). The search is a
//! function of the grid, the query's endpoints and the standing discs only, so a detour
//! planned ahead on another thread, with its own scratch, is the detour the planner would
//! plan: [`super::path_planner::PathPlanner::take_around`] hands it over when it is asked
//! the same query round the same discs.

use parry2d::math::Vector as Vec2;

use super::clearance_grid::ClearanceGrid;
use super::disc_mask::DiscMask;
use super::error::NavError;
use super::grid_astar::GridAstar;
use super::grid_search::{Blocked, search};
use super::plan_query::{Endpoints, PlanQuery};
use super::standing_disc::StandingDisc;

/// What a detour's search writes besides its answer: A*'s per-cell state (`astar`, three
/// `u32` per grid cell once used), the discs the search goes round and their cell mask (one
/// `u32` per grid cell). The planner keeps one; each other thread that plans detours ahead
/// needs its own.
#[derive(Debug, Clone, Default)]
pub(super) struct AroundScratch {
    pub(super) astar: GridAstar,
    discs: Vec<StandingDisc>,
    mask: DiscMask,
}

impl AroundScratch {
    /// Bytes a scratch holds per grid cell once a search has run on the grid: A*'s three
    /// `u32` and the mask's one.
    pub(super) const BYTES_PER_CELL: usize = 16;
}

/// A detour planned ahead ([`plan_around_ahead`]): the query, its answer (the effective goal,
/// or why there is none), its waypoints (empty on failure) and whether an A* search ran (the
/// planner counts it, [`super::path_planner::PathPlanner::astar_searches`]).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct AroundPlan {
    pub(super) query: PlanQuery,
    pub(super) result: Result<Vec2, NavError>,
    pub(super) path: Vec<Vec2>,
    pub(super) searched: bool,
}

/// The search of a detour from `ends` (snapped from `query`) round `standing` (each disc
/// left out where it holds the goal, shrunk off the start: [`StandingDisc::leaving_out`]):
/// A* outside the discs, smoothed; writes the waypoints into `out` (the start excluded, the
/// effective goal last) and returns the effective goal.
///
/// # Errors
/// [`NavError::NoPath`] when the grid and the discs close every way.
pub(super) fn search_around(
    scratch: &mut AroundScratch,
    grid: &ClearanceGrid,
    ends: &Endpoints,
    query: PlanQuery,
    standing: &[StandingDisc],
    out: &mut Vec<Vec2>,
) -> Result<Vec2, NavError> {
    let starts = [grid.cell_center(ends.start), query.from];
    let AroundScratch { astar, discs, mask } = scratch;
    discs.clear();
    discs.extend(
        standing
            .iter()
            .filter(|d| !d.contains(ends.goal_point))
            .filter_map(|d| d.leaving_out(&starts)),
    );
    mask.mark(grid, discs);
    let blocked = Blocked { discs, mask };
    let cells = search(
        astar,
        grid,
        ends.start,
        ends.goal,
        query.inflation_m,
        Some(blocked),
    )?;
    Ok(ends.write(grid, &cells, out))
}

/// Plans the detour of `query` round `standing` ahead, as
/// [`super::path_planner::PathPlanner::plan_around`] would with regions `known_apart`
/// (cells `a` and `b` known to lie apart at `inflation`: no search), using `scratch`.
pub(super) fn plan_around_ahead(
    known_apart: impl Fn(f32, u32, u32) -> bool,
    scratch: &mut AroundScratch,
    grid: &ClearanceGrid,
    arena: (f32, f32),
    query: PlanQuery,
    standing: &[StandingDisc],
) -> AroundPlan {
    let mut path = Vec::new();
    let (result, searched) = match Endpoints::snap(grid, arena, query) {
        Err(e) => (Err(e), false),
        Ok(ends) if known_apart(query.inflation_m, ends.start, ends.goal) => {
            (Err(NavError::NoPath), false)
        }
        Ok(ends) => (
            search_around(scratch, grid, &ends, query, standing, &mut path),
            true,
        ),
    };
    AroundPlan {
        query,
        result,
        path,
        searched,
    }
}
