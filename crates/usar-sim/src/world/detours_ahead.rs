//! Detours and re-plans made ahead, side by side, for the robots whose path following needs
//! the planner this control step ([`plan_ahead`], [`DetoursAhead`]).
//!
//! Not in the paper. Path following runs the planner's part robot by robot in id order
//! (`path_following.rs`), because a detour reads the robots before it as they are after
//! their own path following. For a team that steps in parallel the world first plans, side
//! by side, what each of those robots will most likely ask for: its detour round the robots
//! standing near it, seen as they will be when its turn comes (the robots before it that
//! follow their paths without the planner as they will have followed them, the others as
//! they stand), and its re-plan to a shared goal (the planner's plans made ahead,
//! `shared_descents.rs`). When its turn comes, a robot takes a detour planned ahead only if
//! it asks for the same query round the very same discs
//! ([`super::path_planner::PathPlanner::take_around`]), and the planner takes a plan made
//! ahead only for the same key: every answer is the one planned in turn, bit for bit, on any
//! number of threads; a guess that proves wrong costs only the time it took.

use parry2d::math::Vector as Vec2;

use super::control_clock::ControlClock;
use super::detour::{Team, rejoin_point, standing_round};
use super::follow::{Follow, FollowCtx, Followed, Stage, follow};
use super::nav_state::Nav;
use super::path_planner::PathPlanner;
use super::plan_around::{AroundPlan, AroundScratch};
use super::plan_query::{PlanQuery, plan_inflation_m};
use super::robot_planning::ground_query;
use super::standing_disc::StandingDisc;

/// The detours planned ahead for one control step, by robot id, and the scratch of the
/// threads that plan them beside the planner's own (one [`AroundScratch`] per extra thread,
/// grown to the grid on first use and kept).
#[derive(Debug, Default)]
pub(super) struct DetoursAhead {
    /// Ascending robot id: the discs the detour went round and its plans (to the rejoin
    /// point, then, unless that one rejoined, to the requested goal).
    planned: Vec<(usize, Vec<StandingDisc>, Vec<AroundPlan>)>,
    scratch: Vec<AroundScratch>,
}

impl DetoursAhead {
    /// The plan of robot `id`'s detour for `query` round `standing`, if it was planned ahead
    /// round the same discs (compared exactly) for the same query; taken (a second ask plans).
    pub(super) fn take(
        &mut self,
        id: usize,
        standing: &[StandingDisc],
        query: &PlanQuery,
    ) -> Option<AroundPlan> {
        let k = self.planned.binary_search_by_key(&id, |p| p.0).ok()?;
        let (_, discs, plans) = &mut self.planned[k];
        if discs.as_slice() != standing {
            return None;
        }
        let j = plans.iter().position(|p| p.query == *query)?;
        Some(plans.swap_remove(j))
    }

    /// Forgets the detours planned ahead (the scratch is kept).
    pub(super) fn clear(&mut self) {
        self.planned.clear();
    }
}

/// What path following reads to plan ahead, borrowed from the world for one control step.
pub(super) struct AheadInputs<'a> {
    /// Grid, `navigation`, the crowd rule and the clock of this control step.
    pub(super) ctx: &'a FollowCtx<'a>,
    /// The team as a detour reads it (navigation states, states, neighbour index).
    pub(super) team: Team<'a>,
    /// Arena width and height at physics precision, metres.
    pub(super) arena: (f32, f32),
    /// The goals many robots share, at physics precision.
    pub(super) shared_goals: &'a [Vec2],
    /// Each robot's path following without the planner this control step (`None`: it needs
    /// the planner), by id.
    pub(super) followed: &'a [Option<Followed>],
    /// When each robot checks its path ([`ControlClock::path_check_due`]).
    pub(super) clock: &'a ControlClock,
    /// The control steps taken before this one.
    pub(super) tick: u64,
}

/// Most bytes the scratch of the threads that plan detours ahead beside the planner's may
/// take together (256 MiB): each takes [`AroundScratch::BYTES_PER_CELL`] per grid cell once
/// used, 24 MB on `swarm-10000.ron`'s grid and 240 MB on `swarm-100000.ron`'s.
pub(super) const AHEAD_SCRATCH_BUDGET_BYTES: usize = 256 << 20;

/// How many scratches beside the planner's the detours of a step on a pool of `threads`
/// threads plan with, on a grid of `dims` cells: one per extra thread, as many as
/// [`AHEAD_SCRATCH_BUDGET_BYTES`] holds, and at least one on a pool of two or more threads.
fn extra_scratch(dims: (u32, u32), threads: usize) -> usize {
    let cells = dims.0 as usize * dims.1 as usize;
    let each = cells.saturating_mul(AroundScratch::BYTES_PER_CELL).max(1);
    let held = (AHEAD_SCRATCH_BUDGET_BYTES / each).max(1);
    threads.saturating_sub(1).min(held)
}

/// What one robot that needs the planner was found to need, planned ahead.
enum Need {
    /// Nothing to plan ahead (no standing robot, no requested goal, an own goal).
    Nothing,
    /// A detour round these discs, with its plans.
    Detour(Vec<StandingDisc>, Vec<AroundPlan>),
    /// A re-plan to a shared goal, this query.
    Replan(PlanQuery),
}

/// Plans ahead, side by side on the calling rayon pool, the detours and re-plans to shared
/// goals of the robots `w.followed` leaves to the planner (see the module docs): the detours
/// into `ahead` (replacing what it held), the re-plans into `planner`'s plans made ahead
/// ([`PathPlanner::prepare_shared`]). Only robots whose path following, run again from its
/// start, asks for the planner are planned for; nothing when fewer than two robots need it.
/// Called on a thread of a rayon pool: a step whose phases run in parallel is handed over
/// whole to one when stepped from outside every pool ([`World::step_beside`]).
///
/// [`World::step_beside`]: super::World::step_beside
pub(super) fn plan_ahead(w: &AheadInputs, planner: &mut PathPlanner, ahead: &mut DetoursAhead) {
    ahead.clear();
    let needs: Vec<usize> = (0..w.followed.len())
        .filter(|&id| w.followed[id].is_none())
        .collect();
    if needs.len() < 2 {
        return;
    }
    let extra = extra_scratch(w.ctx.grid.dims(), rayon::current_num_threads());
    if ahead.scratch.len() < extra {
        ahead.scratch.resize_with(extra, AroundScratch::default);
    }
    let found =
        planner.plan_arounds_ahead(needs.len(), &mut ahead.scratch[..extra], |i, around| {
            let id = needs[i];
            let (nav, state) = (&w.team.nav[id], &w.team.robots[id]);
            let mut f = Followed::of(nav, state);
            let due = w.clock.path_check_due(w.tick, id);
            match follow(w.ctx, nav, state, due, &mut f, Stage::Start) {
                Follow::Done => Need::Nothing,
                Follow::Replan(goal) => ground_query(nav, goal, w.ctx.navigation)
                    .filter(|_| w.shared_goals.contains(&goal))
                    .map_or(Need::Nothing, Need::Replan),
                Follow::Detour => detour_ahead(w, id, nav, |q, s| {
                    around.plan_around(w.ctx.grid, w.arena, q, s)
                }),
            }
        });
    let mut replans = Vec::new();
    for (id, need) in needs.into_iter().zip(found) {
        match need {
            Need::Nothing => {}
            Need::Detour(discs, plans) => ahead.planned.push((id, discs, plans)),
            Need::Replan(q) => replans.push(q),
        }
    }
    if !replans.is_empty() {
        planner.prepare_shared(w.ctx.grid, w.arena, &replans, true);
    }
}

/// Robot `id`'s detour (navigation state `nav`) planned ahead with `plan_around(query,
/// discs)`: round the robots standing near it as it will see them in its turn (the robots
/// before it that need no planner after their path following this step, the others as they
/// stand), first to its rejoin point, then, unless that plan rejoined there, to its
/// requested goal, as `PathFollowing::detour` plans.
fn detour_ahead(
    w: &AheadInputs,
    id: usize,
    nav: &Nav,
    mut plan_around: impl FnMut(PlanQuery, &[StandingDisc]) -> AroundPlan,
) -> Need {
    let Some(requested) = nav.requested else {
        return Need::Nothing;
    };
    let (navs, robots, followed) = (w.team.nav, w.team.robots, w.followed);
    let seen = |j: usize| match followed[j] {
        Some(f) if j < id => (f.following.intent, f.goal_reached),
        _ => (navs[j].following.intent, robots[j].goal_reached),
    };
    let inflation_m = plan_inflation_m(nav.radius, w.ctx.navigation);
    let mut standing = Vec::new();
    standing_round(
        &w.team,
        id,
        inflation_m,
        seen,
        &mut Vec::new(),
        &mut standing,
    );
    if standing.is_empty() {
        return Need::Nothing;
    }
    let query = |to| PlanQuery {
        from: nav.pos,
        to,
        inflation_m,
    };
    let mut plans = Vec::new();
    if let Some((rejoin, _)) = rejoin_point(nav, &standing) {
        let first = plan_around(query(rejoin), &standing);
        let rejoined = first.result == Ok(rejoin);
        plans.push(first);
        if rejoined {
            return Need::Detour(standing, plans);
        }
    }
    plans.push(plan_around(query(requested), &standing));
    Need::Detour(standing, plans)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::error::NavError;

    fn disc(x: f32) -> StandingDisc {
        StandingDisc {
            center: Vec2::new(x, 1.0),
            radius_m: 0.5,
        }
    }

    fn query(to_x: f32) -> PlanQuery {
        PlanQuery {
            from: Vec2::ZERO,
            to: Vec2::new(to_x, 0.0),
            inflation_m: 0.3,
        }
    }

    fn plan(to_x: f32) -> AroundPlan {
        AroundPlan {
            query: query(to_x),
            result: Err(NavError::NoPath),
            path: Vec::new(),
            searched: true,
        }
    }

    /// The threads beside the planner's plan detours ahead with a scratch each while the
    /// budget holds them, one at least: up to 11 on `swarm-10000.ron`'s grid (1,504,000
    /// cells), one on `swarm-100000.ron`'s, none on a one-thread pool.
    #[test]
    fn the_scratch_of_detours_planned_ahead_keeps_to_its_budget() {
        let small = (1600, 940);
        let large = (16000, 940);
        assert_eq!(extra_scratch(small, 2), 1);
        assert_eq!(extra_scratch(small, 8), 7);
        assert_eq!(extra_scratch(small, 16), 11);
        assert_eq!(extra_scratch(large, 2), 1);
        assert_eq!(extra_scratch(large, 64), 1);
        assert_eq!(extra_scratch(large, 1), 0);
        assert_eq!(extra_scratch((0, 0), 3), 2);
        for (dims, threads) in [(small, 64), ((4000, 4000), 8)] {
            let n = extra_scratch(dims, threads);
            let bytes = n * dims.0 as usize * dims.1 as usize * AroundScratch::BYTES_PER_CELL;
            assert!(
                n == 1 || bytes <= AHEAD_SCRATCH_BUDGET_BYTES,
                "{dims:?}: {n}"
            );
        }
    }

    /// A detour planned ahead is handed over only to its robot, for the same query round
    /// the same discs, and only once.
    #[test]
    fn a_detour_planned_ahead_is_taken_only_as_planned() {
        let mut ahead = DetoursAhead {
            planned: vec![
                (3, vec![disc(1.0)], vec![plan(5.0), plan(9.0)]),
                (7, vec![disc(2.0)], vec![plan(5.0)]),
            ],
            scratch: Vec::new(),
        };
        assert_eq!(
            ahead.take(4, &[disc(1.0)], &query(5.0)),
            None,
            "another robot"
        );
        assert_eq!(
            ahead.take(3, &[disc(2.0)], &query(5.0)),
            None,
            "other discs"
        );
        assert_eq!(ahead.take(3, &[], &query(5.0)), None, "no discs");
        assert_eq!(
            ahead.take(3, &[disc(1.0)], &query(6.0)),
            None,
            "another query"
        );
        assert_eq!(ahead.take(3, &[disc(1.0)], &query(9.0)), Some(plan(9.0)));
        assert_eq!(ahead.take(3, &[disc(1.0)], &query(9.0)), None, "taken once");
        assert_eq!(ahead.take(3, &[disc(1.0)], &query(5.0)), Some(plan(5.0)));
        assert_eq!(ahead.take(7, &[disc(2.0)], &query(5.0)), Some(plan(5.0)));
        ahead.planned.push((9, vec![disc(3.0)], vec![plan(5.0)]));
        ahead.clear();
        assert_eq!(ahead.take(9, &[disc(3.0)], &query(5.0)), None, "cleared");
    }
}
