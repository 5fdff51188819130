//! One robot's path following on a control step as a function of its own state ([`follow`]):
//! the goal test, the no-progress clock, the periodic path check's skip of visible waypoints,
//! corner passing and the intended velocity, written to a [`Followed`] and not to the robot.
//! It stops where the robot needs the planner (a detour or a re-plan: they write the planner's
//! shared caches, and a detour reads other robots), which the world runs serially and then
//! resumes it (`path_following.rs`). Up to that point it reads only the robot's own state, the
//! clearance grid (fixed for a trial) and constants, so a large team computes it for every
//! robot in parallel and applies the results in id order (`parallel.rs`): the same bits on any
//! number of threads.
//!
//! Not in the paper: how robots follow their paths is this simulator's choice
//! (`docs/world-model.md`).

use parry2d::math::Vector as Vec2;

use super::clearance_grid::ClearanceGrid;
use super::nav_state::{Following, Nav};
use super::path_following_params::{CORNER_PASS_M, PATH_CHECK_MAX_M, STALL_PROGRESS_M};
use super::robot::RobotState;
use crate::scenario::{Locomotion, NavigationParams};

/// What path following reads besides the robot: the world's grid, parameters and clock.
#[derive(Debug, Clone, Copy)]
pub(super) struct FollowCtx<'a> {
    /// The clearance grid (line-of-sight checks), fixed for the trial.
    pub(super) grid: &'a ClearanceGrid,
    /// `navigation` of the scenario (waypoint tolerance, clearance, detour clock).
    pub(super) navigation: &'a NavigationParams,
    /// `collision.hold_rule` is `Yield`: list members keep their no-progress clock running.
    pub(super) crowd: bool,
    /// Steps taken before this control step.
    pub(super) steps: u64,
    /// The physics step, seconds.
    pub(super) dt: f64,
    /// The control period (the step `dt` without `sim.control_period_s`), seconds.
    pub(super) period_s: f64,
}

/// The navigation fields path following changes in one control step ([`Following`]), and
/// the robot's "goal reached" flag: computed by [`follow`], written by [`Followed::apply`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Followed {
    /// Waypoint, no-progress clock and intended velocity (the intent is zero until
    /// [`follow`] sets it).
    pub(super) following: Following,
    /// Whether the robot has reached its goal.
    pub(super) goal_reached: bool,
}

impl Followed {
    /// The robot's fields as they stand, with a zero intent (the start of a control step).
    pub(super) fn of(nav: &Nav, state: &RobotState) -> Self {
        Self {
            following: Following {
                intent: Vec2::ZERO,
                ..nav.following
            },
            goal_reached: state.goal_reached,
        }
    }

    /// Writes the fields into the robot's navigation state and public state.
    pub(super) fn apply(self, nav: &mut Nav, state: &mut RobotState) {
        nav.following = self.following;
        state.goal_reached = self.goal_reached;
    }
}

/// Where [`follow`] starts or resumes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Stage {
    /// The start: the goal test, then the no-progress clock.
    Start,
    /// After the no-progress clock (and its detour): the periodic path check.
    PathCheck,
    /// After the path check (and its re-plan): corner passing and the intent.
    Corners,
}

/// How [`follow`] ended.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Follow {
    /// Done: the [`Followed`] is the robot's new state.
    Done,
    /// The no-progress clock ran out: the robot takes a detour, then follows on from
    /// [`Stage::PathCheck`].
    Detour,
    /// The line of sight to the current waypoint is blocked: the robot re-plans to its
    /// requested goal, then follows on from [`Stage::Corners`].
    Replan(Vec2),
}

/// Robot `nav`'s path following from `from` (see the module docs), into `f` (which holds
/// [`Followed::of`] the robot at [`Stage::Start`]); `check_due` is whether a ground robot
/// checks its path this control step. Reads `f.following.wp` as the current waypoint. Returns
/// where the planner must act, if it must: the world then applies `f`, runs the planner, takes
/// `Followed::of` the robot again and resumes at the stage named by [`Follow`].
pub(super) fn follow(
    ctx: &FollowCtx<'_>,
    nav: &Nav,
    state: &RobotState,
    check_due: bool,
    f: &mut Followed,
    from: Stage,
) -> Follow {
    let ground = nav.layer == Locomotion::Ground;
    if from == Stage::Start {
        let Some(goal) = nav.goal else {
            return Follow::Done;
        };
        if f.goal_reached {
            return Follow::Done;
        }
        if (goal - nav.pos).length() <= nav.goal_tolerance_m {
            f.goal_reached = true;
            return Follow::Done;
        }
        if ground && stalled(ctx, nav, state, &mut f.following) {
            return Follow::Detour;
        }
    }
    if from != Stage::Corners
        && ground
        && check_due
        && let Some(requested) = path_blocked(ctx, nav, &mut f.following)
    {
        return Follow::Replan(requested);
    }
    pass_corners(ctx, nav, &mut f.following);
    f.following.intent = intent_to_waypoint(ctx, nav, state, f.following.wp);
    Follow::Done
}

/// Inflation of a robot's line-of-sight checks while following its path: body radius + half of
/// `navigation.clearance_m`, metres.
fn check_inflation(ctx: &FollowCtx<'_>, nav: &Nav) -> f32 {
    nav.radius + 0.5 * ctx.navigation.clearance_m.get() as f32
}

/// The no-progress clock of a ground robot (`navigation.stall_replan_s`, default
/// [`STALL_REPLAN_S`](super::STALL_REPLAN_S)): restarts on progress, and under
/// `collision.hold_rule: ListHead` while the robot was in a collision list at the last step;
/// `true` when it has run out (the robot takes a detour; the world restarts the clock). Under
/// `Yield` a list member stuck in a jam no rotation clears, e.g. robots meeting head-on in a
/// gap between debris, detours too. Reads the remaining path from the robot's own waypoint
/// (`f.wp` is still `nav.following.wp` here).
fn stalled(ctx: &FollowCtx<'_>, nav: &Nav, state: &RobotState, f: &mut Following) -> bool {
    let remaining = nav.remaining();
    let listed = state.in_collision_list && !ctx.crowd;
    if listed || remaining < f.best_remaining - STALL_PROGRESS_M {
        f.best_remaining = remaining;
        f.progress_step = ctx.steps;
        return false;
    }
    let Some(stall_s) = ctx.navigation.stall_replan_s else {
        return false;
    };
    (ctx.steps - f.progress_step) as f64 * ctx.dt >= stall_s.get()
}

/// The periodic path check of a ground robot: skips the waypoints it can see (within
/// [`PATH_CHECK_MAX_M`]) and, if the line of sight to its waypoint (first
/// [`PATH_CHECK_MAX_M`]) is blocked, returns its requested goal to re-plan to (none without
/// one: it keeps its path, and physics keeps it out of obstacles).
fn path_blocked(ctx: &FollowCtx<'_>, nav: &Nav, f: &mut Following) -> Option<Vec2> {
    let infl = check_inflation(ctx, nav);
    let p = nav.pos;
    let path = &nav.path;
    let mut skipped = false;
    while f.wp + 1 < path.len()
        && (path[f.wp + 1] - p).length() < PATH_CHECK_MAX_M
        && ctx
            .grid
            .line_of_sight(p, path[f.wp + 1], infl, f32::INFINITY)
    {
        f.wp += 1;
        skipped = true;
    }
    // After a skip the new waypoint was just seen in full (it is nearer than
    // PATH_CHECK_MAX_M), so only an unskipped waypoint needs its line of sight checked.
    let waypoint = nav.waypoint_at(f.wp);
    if skipped || ctx.grid.line_of_sight(p, waypoint, infl, PATH_CHECK_MAX_M) {
        return None;
    }
    nav.requested
}

/// Advances the waypoint past the corners the robot has passed: a corner is passed when
/// reached (within `navigation.waypoint_tolerance_m`), or when the robot is within
/// [`CORNER_PASS_M`] of it, already beyond the line through it perpendicular to the next
/// leg, and sees the next waypoint. Without the second rule robots queueing at a corner all
/// aim at the same point, which their own bodies cover: a jam no priority order resolves.
fn pass_corners(ctx: &FollowCtx<'_>, nav: &Nav, f: &mut Following) {
    let tol = ctx.navigation.waypoint_tolerance_m.get() as f32;
    let infl = check_inflation(ctx, nav);
    let p = nav.pos;
    let last = nav.path.len() - 1;
    while f.wp < last {
        let corner = nav.path[f.wp];
        let next = nav.path[f.wp + 1];
        let d = (corner - p).length();
        let passed = d <= tol
            || (d <= CORNER_PASS_M
                && (p - corner).dot(next - corner) > 0.0
                && ctx.grid.line_of_sight(p, next, infl, f32::INFINITY));
        if !passed {
            break;
        }
        f.wp += 1;
    }
}

/// Velocity towards waypoint `wp` at top speed times the speed factor; on the last leg at most
/// `distance / period` (the control period), so the goal is not overshot before the next
/// control step.
fn intent_to_waypoint(ctx: &FollowCtx<'_>, nav: &Nav, state: &RobotState, wp: usize) -> Vec2 {
    let to_target = nav.waypoint_at(wp) - nav.pos;
    let dist = to_target.length();
    if dist <= f32::EPSILON {
        return Vec2::ZERO;
    }
    let mut speed = nav.max_speed * state.speed_factor as f32;
    if wp >= nav.path.len() - 1 {
        speed = speed.min(dist / ctx.period_s as f32);
    }
    to_target * (speed / dist)
}
