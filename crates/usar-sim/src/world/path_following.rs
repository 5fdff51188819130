//! Path following: a robot's intended velocity from its goal and path (rule: follow waypoints
//! at top speed times the speed factor, slowing only to stop on the goal), with corner passing
//! and, for ground robots, the periodic line-of-sight check that skips visible waypoints and
//! re-plans when the current one is hidden, and the detour: a ground robot outside collision
//! lists that makes no progress along its path for [`STALL_REPLAN_S`](super::STALL_REPLAN_S)
//! re-plans around the robots standing near it. The per-robot part is `follow.rs`; this file
//! runs it and does the planner's part (re-plans and detours) in robot order.

use parry2d::math::Vector as Vec2;

use super::bodies::to_point;
use super::control_clock::ControlClock;
use super::detour::{Team, rejoin_point, standing_round};
use super::detours_ahead::{AheadInputs, DetoursAhead, plan_ahead};
use super::follow::{Follow, FollowCtx, Followed, Stage, follow};
use super::nav_state::Nav;
use super::neighbours::NeighbourIndex;
use super::path_planner::PathPlanner;
use super::plan_into::PlanInto;
use super::plan_query::{PlanQuery, plan_inflation_m};
use super::robot::RobotState;
use super::robot_planning::{PlanInputs, plan_robot};
use super::standing_disc::StandingDisc;

/// Path following's stage over explicit borrows of the world for one control step: what it
/// reads (`&`) and what it writes (`&mut`: the planner's caches, the scratch buffers, every
/// robot's navigation state and state, by id). A detour reads the other robots near one, so
/// it borrows the whole team; nothing else of the world is touched.
pub(super) struct PathFollowing<'a> {
    /// What path following reads besides the robot: grid, `navigation`, the hold rule, the
    /// steps taken before this control step, the step and the control period.
    pub(super) ctx: FollowCtx<'a>,
    /// Arena width and height at physics precision, metres.
    pub(super) arena: (f32, f32),
    /// The goals many robots share, at physics precision ([`PlanInputs::shared_goals`]).
    pub(super) shared_goals: &'a [Vec2],
    /// Largest body radius of the ground and the aerial robots, metres.
    pub(super) max_radius_m: [f64; 2],
    /// The neighbour index, holding the robots' positions (rebuilt before a control step).
    pub(super) neighbours: &'a NeighbourIndex,
    /// The path planner (its caches are written).
    pub(super) planner: &'a mut PathPlanner,
    /// Plans that may be discarded (re-plans, detours) are written here.
    pub(super) scratch: &'a mut Vec<Vec2>,
    /// Robots standing in the way of a detour.
    pub(super) standing: &'a mut Vec<StandingDisc>,
    /// Robot ids from the neighbour index.
    pub(super) near_ids: &'a mut Vec<usize>,
    /// Every robot's navigation state, by id.
    pub(super) nav: &'a mut [Nav],
    /// Every robot's state, by id.
    pub(super) robots: &'a mut [RobotState],
    /// Detours planned ahead this control step (`detours_ahead.rs`), taken by the detours
    /// that ask for them.
    pub(super) ahead: &'a mut DetoursAhead,
}

impl PathFollowing<'_> {
    /// Updates robot `id`'s intended velocity from its goal and path (zero without a goal or
    /// once it is reached; marks the goal reached within its tolerance, by default
    /// `navigation.waypoint_tolerance_m`: see
    /// [`World::set_goal_within`](super::World::set_goal_within)); a ground robot also checks
    /// its path when `check_due` ([`PATH_CHECK_INTERVAL_STEPS`](super::PATH_CHECK_INTERVAL_STEPS)).
    /// [`follow`] does all but the planner's work: a detour when the no-progress clock runs
    /// out ([`PathFollowing::detour`], then the clock restarts) and a re-plan from where the
    /// robot stands when the periodic check finds its waypoint hidden (on failure the old path
    /// is kept; physics keeps the robot out of obstacles). The control period is
    /// `ctx.period_s`, seconds.
    pub(super) fn update_intent(&mut self, id: usize, check_due: bool) {
        let mut f = Followed::of(&self.nav[id], &self.robots[id]);
        let mut from = Stage::Start;
        loop {
            let outcome = follow(
                &self.ctx,
                &self.nav[id],
                &self.robots[id],
                check_due,
                &mut f,
                from,
            );
            f.apply(&mut self.nav[id], &mut self.robots[id]);
            from = match outcome {
                Follow::Done => return,
                Follow::Detour => {
                    let steps = self.ctx.steps;
                    self.detour(id);
                    let nav = &mut self.nav[id];
                    nav.following.best_remaining =
                        nav.following.best_remaining.min(nav.remaining());
                    nav.following.progress_step = steps;
                    Stage::PathCheck
                }
                Follow::Replan(requested) => {
                    if let Ok(eff) = self.plan(id, requested, PlanInto::Scratch) {
                        self.take_scratch_path(id, eff);
                    }
                    Stage::Corners
                }
            };
            f = Followed::of(&self.nav[id], &self.robots[id]);
        }
    }

    /// Makes the plan in the scratch buffer (effective goal `eff`) robot `id`'s path; counts a
    /// re-plan. The no-progress clock keeps running, measured against the new path.
    fn take_scratch_path(&mut self, id: usize, eff: Vec2) {
        let nav = &mut self.nav[id];
        std::mem::swap(&mut nav.path, self.scratch);
        nav.goal = Some(eff);
        nav.restart_on_new_path();
        let state = &mut self.robots[id];
        state.goal = Some(to_point(eff));
        state.counters.replans += 1;
    }

    /// Re-plans ground robot `id` around the robots of its layer standing still within its
    /// sensing range, or within its body radius plus theirs plus its planning inflation
    /// whatever its sensing (no goal, goal reached, or no intended motion; under
    /// `collision.hold_rule: Yield` also held or blocked at the last step), each kept out to
    /// its body radius plus the robot's planning inflation
    /// ([`super::path_planner::PathPlanner::plan_around`]). A local detour first: from where it
    /// stands to its path's point
    /// [`DETOUR_REJOIN_BEYOND_M`](super::path_following_params::DETOUR_REJOIN_BEYOND_M) beyond the farthest of those
    /// robots ([`PathFollowing::rejoin_point`]), then on along the rest of its path. Where the
    /// path ends before such a point, or no local detour exists, it re-plans all the way to
    /// its requested goal around them. On failure the path is kept. Robots are found through the
    /// neighbour index (`O(robots nearby)`). Allocates nothing once the scratch buffers have
    /// grown.
    fn detour(&mut self, id: usize) {
        let Some(requested) = self.nav[id].requested else {
            return;
        };
        self.collect_standing(id);
        if self.standing.is_empty() {
            return;
        }
        // The local detour must end on the rejoin point itself: a goal the planner moved (to a
        // free cell centre) would join the kept path by a leg nobody checked.
        if let Some((rejoin, next)) = self.rejoin_point(id)
            && self.plan_detour(id, rejoin) == Ok(rejoin)
        {
            let nav = &mut self.nav[id];
            self.scratch.extend_from_slice(&nav.path[next..]);
            std::mem::swap(&mut nav.path, self.scratch);
            nav.restart_on_new_path();
            self.robots[id].counters.replans += 1;
            return;
        }
        if let Ok(eff) = self.plan_detour(id, requested) {
            self.take_scratch_path(id, eff);
        }
    }

    /// Plans robot `id` from where it stands to `to` round `self.standing` into the scratch
    /// buffer ([`super::path_planner::PathPlanner::plan_around`]), or takes that plan if it
    /// was planned ahead round the same discs (`self.ahead`); returns the effective goal.
    fn plan_detour(&mut self, id: usize, to: Vec2) -> Result<Vec2, super::NavError> {
        let query = PlanQuery {
            from: self.nav[id].pos,
            to,
            inflation_m: self.plan_inflation(id),
        };
        if let Some(plan) = self.ahead.take(id, self.standing, &query) {
            let (grid, arena) = (self.ctx.grid, self.arena);
            if let Some(taken) = self.planner.take_around(grid, arena, &plan, self.scratch) {
                return taken;
            }
        }
        self.planner.plan_around(
            self.ctx.grid,
            self.arena,
            query,
            self.standing,
            self.scratch,
        )
    }

    /// Fills `self.standing` with the robots ground robot `id`'s detour goes round
    /// ([`standing_round`], seeing every robot as it stands now), in id order.
    fn collect_standing(&mut self, id: usize) {
        let team = Team {
            nav: self.nav,
            robots: self.robots,
            neighbours: self.neighbours,
            crowd: self.ctx.crowd,
            max_radius_m: self.max_radius_m,
        };
        let (nav, robots) = (&*self.nav, &*self.robots);
        let seen = |j: usize| (nav[j].following.intent, robots[j].goal_reached);
        let infl = self.plan_inflation(id);
        standing_round(&team, id, infl, seen, self.near_ids, self.standing);
    }

    /// Where robot `id`'s local detour round `self.standing` rejoins its path
    /// ([`rejoin_point`]).
    fn rejoin_point(&self, id: usize) -> Option<(Vec2, usize)> {
        rejoin_point(&self.nav[id], self.standing)
    }

    /// Inflation robot `id` plans with ([`plan_inflation_m`]), metres.
    fn plan_inflation(&self, id: usize) -> f32 {
        plan_inflation_m(self.nav[id].radius, self.ctx.navigation)
    }

    /// Every robot's path following of this control step, in id order: `followed[id]` (by id,
    /// [`super::parallel::follow_all`]) applied where it is `Some`, and
    /// [`PathFollowing::update_intent`] (checking its path when `due(id)`) where it is
    /// `None` or missing (every robot, for an empty `followed`); then forgets what was
    /// planned ahead ([`PathFollowing::plan_ahead`]).
    pub(super) fn follow_team(
        &mut self,
        followed: &[Option<Followed>],
        due: impl Fn(usize) -> bool,
    ) {
        for id in 0..self.nav.len() {
            match followed.get(id).copied().flatten() {
                Some(f) => f.apply(&mut self.nav[id], &mut self.robots[id]),
                None => self.update_intent(id, due(id)),
            }
        }
        self.ahead.clear();
        self.planner.clear_prepared();
    }

    /// Plans ahead, side by side, the detours and re-plans of the robots `followed` (by id;
    /// `None`: the robot needs the planner this control step, [`super::parallel::follow_all`])
    /// leaves to the planner, for [`PathFollowing::update_intent`] to take in turn
    /// ([`plan_ahead`]); `tick` counts the control steps before this one.
    pub(super) fn plan_ahead(
        &mut self,
        followed: &[Option<Followed>],
        tick: u64,
        clock: &ControlClock,
    ) {
        let w = AheadInputs {
            ctx: &self.ctx,
            team: Team {
                nav: self.nav,
                robots: self.robots,
                neighbours: self.neighbours,
                crowd: self.ctx.crowd,
                max_radius_m: self.max_radius_m,
            },
            arena: self.arena,
            shared_goals: self.shared_goals,
            followed,
            clock,
            tick,
        };
        plan_ahead(&w, self.planner, self.ahead);
    }

    /// [`plan_robot`] for robot `id` from where it stands to `goal` (world frame, metres),
    /// into its path or the scratch buffer as `into` says; returns the effective goal.
    fn plan(&mut self, id: usize, goal: Vec2, into: PlanInto) -> Result<Vec2, super::NavError> {
        let w = PlanInputs {
            grid: self.ctx.grid,
            arena: self.arena,
            navigation: self.ctx.navigation,
            shared_goals: self.shared_goals,
        };
        plan_robot(
            &w,
            self.planner,
            &mut self.nav[id],
            goal,
            into,
            self.scratch,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{self, PointM, Scenario};
    use crate::world::detour::first_point_beyond;
    use crate::world::path_following_params::DETOUR_REJOIN_BEYOND_M;
    use crate::world::{ControlClock, World};

    /// `scenarios/corridor.ron` (24 m x 3.4 m, no debris) with one robot per end: robot 0 at
    /// the west end, robot 1 at the east end.
    fn corridor() -> Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/corridor.ron");
        let src = std::fs::read_to_string(path).expect("corridor.ron");
        let mut spec = scenario::parse_spec(&src, path).expect("parses");
        for (kind, task) in [(0, "easy"), (1, "hard")] {
            spec.kinds[kind].count = 1;
            spec.kinds[kind].quota.0.insert(task.into(), 1);
        }
        spec.validate(path).expect("valid")
    }

    /// Shortest distance from `c` to the segment `a`-`b`.
    fn to_segment(c: Vec2, a: Vec2, b: Vec2) -> f32 {
        let d = b - a;
        let t = ((c - a).dot(d) / d.length_squared().max(f32::MIN_POSITIVE)).clamp(0.0, 1.0);
        (a + d * t - c).length()
    }

    /// A world where robot 0 drives east from (2, 1.7) to `goal` and robot 1 stands at
    /// `parked`; robot 0's path and goal before any detour.
    fn parked_in_the_way(goal: PointM, parked: PointM) -> (World, Vec<Vec2>, Option<Vec2>) {
        let s = corridor();
        let clock = ControlClock::of(&s.sim);
        let mut w = World::new(&s, &clock);
        w.teleport(0, PointM::new(2.0, 1.7)).expect("in the arena");
        w.teleport(1, parked).expect("in the arena");
        w.set_goal(0, Some(goal)).expect("plans");
        let nav = &w.parts().nav[0];
        let (path, goal) = (nav.path.clone(), nav.goal);
        (w, path, goal)
    }

    /// Every leg of robot 0's path, from where it stands, keeps out of robot 1's keep-out disc
    /// (its radius plus robot 0's planning inflation, less 1 mm).
    fn clear_of_robot_1(w: &mut World) {
        let parts = w.parts();
        let nav = &parts.nav;
        let keep_out = nav[1].radius + plan_inflation_m(nav[0].radius, parts.navigation) - 1e-3;
        let mut at = nav[0].pos;
        for &p in &nav[0].path[nav[0].following.wp..] {
            let d = to_segment(nav[1].pos, at, p);
            assert!(d >= keep_out, "leg {at:?}-{p:?} passes {d} m from robot 1");
            at = p;
        }
    }

    #[test]
    fn a_local_detour_rejoins_the_path_beyond_the_standing_robot() {
        // Robot 1 stands 1.5 m ahead, 0.7 m right of robot 0's straight path to the east end
        // (within robot 0's 2 m sensing range).
        let (mut w, before, goal) =
            parked_in_the_way(PointM::new(22.5, 1.7), PointM::new(3.5, 1.0));
        assert_eq!(before.len(), 1, "a straight corridor path: {before:?}");
        w.path_following(w.dt_s()).detour(0);
        let parts = w.parts();
        let nav = &parts.nav[0];
        assert_eq!(nav.goal, goal, "a local detour keeps the goal");
        assert_eq!(nav.path.last(), before.last(), "and the rest of the path");
        assert!(nav.path.len() >= 2, "{:?}", nav.path);
        assert_eq!(parts.robots[0].counters.replans, 1);
        // It rejoins the straight path (y = 1.7) at least 1 m beyond robot 1's disc rim,
        // measured along the path, and not much farther.
        let rejoin = nav.path[nav.path.len() - 2];
        let rim = (parts.nav[1].pos - Vec2::new(2.0, 1.7)).length()
            + parts.nav[1].radius
            + plan_inflation_m(parts.nav[0].radius, parts.navigation);
        let along = rejoin.x - 2.0;
        assert!(
            along >= rim + DETOUR_REJOIN_BEYOND_M - 0.3 && along <= rim + 3.0,
            "rejoins at {rejoin:?}, {along} m along; rim {rim} m"
        );
        assert!((rejoin.y - 1.7).abs() <= 0.3, "{rejoin:?}");
        clear_of_robot_1(&mut w);
    }

    /// [`PathFollowing::rejoin_point`] of robot `id` of `w` after collecting the standing
    /// robots, as a detour does.
    fn rejoin_point_for_test(w: &mut World, id: usize) -> Option<(Vec2, usize)> {
        let mut stage = w.path_following(w.dt_s());
        stage.collect_standing(id);
        stage.rejoin_point(id)
    }

    #[test]
    fn a_path_that_winds_back_past_the_standing_robot_is_planned_again_whole() {
        let (mut w, _, _) = parked_in_the_way(PointM::new(22.5, 1.7), PointM::new(3.5, 1.0));
        // A path east, then back west through robot 1's disc, then north.
        let winding = vec![
            Vec2::new(6.0, 1.7),
            Vec2::new(3.5, 1.7),
            Vec2::new(3.5, 3.0),
        ];
        w.parts().nav[0].path.clone_from(&winding);
        w.parts().nav[0].following.wp = 0;
        let mut stage = w.path_following(w.dt_s());
        stage.collect_standing(0);
        assert!(
            first_point_beyond(&stage.nav[0], stage.standing).is_some(),
            "a point beyond robot 1"
        );
        assert_eq!(
            stage.rejoin_point(0),
            None,
            "the rest of the path passes robot 1"
        );
        // The straight path has a rejoin point.
        stage.nav[0].path = vec![Vec2::new(22.5, 1.7)];
        assert!(stage.rejoin_point(0).is_some());
    }

    #[test]
    fn a_detour_near_the_goal_plans_to_the_goal() {
        // Robot 1 stands 1.5 m before the goal: no point of the path lies 1 m beyond its rim.
        let goal = PointM::new(5.0, 1.7);
        let (mut w, _, eff) = parked_in_the_way(goal, PointM::new(3.5, 1.0));
        let s = w.parts().nav[0].pos;
        assert!((s - Vec2::new(2.0, 1.7)).length() < 1e-6);
        assert_eq!(rejoin_point_for_test(&mut w, 0), None);
        w.path_following(w.dt_s()).detour(0);
        let nav = &w.parts().nav[0];
        assert_eq!(nav.goal, eff, "the same goal, planned afresh");
        assert!(nav.path.len() >= 2, "a path round robot 1: {:?}", nav.path);
        clear_of_robot_1(&mut w);
    }
}
