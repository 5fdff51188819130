//! One smoothed grid search: A* between two cells, optionally outside standing robots.
//!
//! The planner's search for a robot's own goal and for a detour: A* from a start cell to a goal
//! cell (outside the discs of robots standing in the way, for a detour), then greedy
//! line-of-sight smoothing.

use super::clearance_grid::ClearanceGrid;
use super::disc_mask::DiscMask;
use super::error::NavError;
use super::grid_astar::GridAstar;
use super::path_smoothing::smooth;
use super::standing_disc::StandingDisc;

/// Robots standing in the way of a detour: their discs (for the smoothed legs) and the grid
/// cells inside them (for A*'s successors), marked from the same discs.
#[derive(Clone, Copy)]
pub(super) struct Blocked<'a> {
    /// The standing robots' keep-out discs.
    pub(super) discs: &'a [StandingDisc],
    /// The cells whose centre lies inside one of `discs`.
    pub(super) mask: &'a DiscMask,
}

/// A* (outside the `blocked` discs, if any) plus smoothing; returns smoothed cell indices from
/// `start` to `goal` (both included). A successor cell is dropped when its centre lies in a
/// disc (one mask read per successor). A* reaches the goal only by a move into it, so a goal
/// cell no move may enter (not free, or inside a standing robot's disc that leaves the goal
/// point itself out) has no path: that is found out at once, not after a flood of every cell
/// reachable from the start (the same answer).
pub(super) fn search(
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

#[cfg(test)]
mod tests {
    use parry2d::math::Vector as Vec2;

    use super::*;
    use crate::world::test_grids::*;

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
}
