//! Path following: a robot's intended velocity from its goal and path (rule: follow waypoints
//! at top speed times the speed factor, slowing only to stop on the goal), with corner passing
//! and, for ground robots, the periodic line-of-sight check that skips visible waypoints and
//! re-plans when the current one is hidden.

use parry2d::math::Vector as Vec2;

use super::bodies::to_point;
use super::planning::PlanInto;
use super::world::World;
use crate::scenario::Locomotion;

/// Ground robots re-check the line of sight to their current waypoint every this many steps
/// (staggered by id) and re-plan when it is blocked.
pub const PATH_CHECK_INTERVAL_STEPS: u64 = 10;
/// Longest stretch of the line of sight checked by the periodic path check, metres.
pub const PATH_CHECK_MAX_M: f32 = 4.0;
/// A ground robot within this distance of a path corner, beyond the line through the corner
/// perpendicular to the next leg and in sight of the next waypoint, counts the corner as
/// passed, metres.
pub const CORNER_PASS_M: f32 = 2.0;

impl World {
    /// Inflation of robot `id`'s line-of-sight checks while following its path: body radius +
    /// half of `navigation.clearance_m`, metres.
    fn check_inflation(&self, id: usize) -> f32 {
        self.nav[id].radius + 0.5 * self.navigation.clearance_m.get() as f32
    }

    /// Updates robot `id`'s intended velocity from its goal and path (zero without a goal or
    /// once it is reached; marks the goal reached within `navigation.waypoint_tolerance_m`).
    pub(super) fn update_intent(&mut self, id: usize) {
        let nav = &mut self.nav[id];
        nav.intent = Vec2::ZERO;
        let Some(goal) = nav.goal else {
            return;
        };
        if self.robots[id].goal_reached {
            return;
        }
        if (goal - nav.pos).length() <= self.navigation.waypoint_tolerance_m.get() as f32 {
            self.robots[id].goal_reached = true;
            return;
        }
        if nav.layer == Locomotion::Ground
            && (self.stats.steps + id as u64).is_multiple_of(PATH_CHECK_INTERVAL_STEPS)
        {
            self.check_path(id);
        }
        self.pass_corners(id);
        self.nav[id].intent = self.intent_to_waypoint(id);
    }

    /// The periodic path check of ground robot `id`: skips the waypoints it can see (within
    /// [`PATH_CHECK_MAX_M`]) and, if the line of sight to its waypoint (first
    /// [`PATH_CHECK_MAX_M`]) is blocked, re-plans from where it stands. On failure the old path
    /// is kept; physics keeps the robot out of obstacles.
    fn check_path(&mut self, id: usize) {
        let check_infl = self.check_inflation(id);
        let nav = &mut self.nav[id];
        let p = nav.pos;
        let mut skipped = false;
        while nav.wp + 1 < nav.path.len()
            && (nav.path[nav.wp + 1] - p).length() < PATH_CHECK_MAX_M
            && self
                .grid
                .line_of_sight(p, nav.path[nav.wp + 1], check_infl, f32::INFINITY)
        {
            nav.wp += 1;
            skipped = true;
        }
        // After a skip the new waypoint was just seen in full (it is nearer than
        // PATH_CHECK_MAX_M), so only an unskipped waypoint needs its line of sight checked.
        if skipped
            || self
                .grid
                .line_of_sight(p, nav.waypoint(), check_infl, PATH_CHECK_MAX_M)
        {
            return;
        }
        let Some(requested) = nav.requested else {
            return;
        };
        if let Ok(eff) = self.plan(id, requested, PlanInto::Scratch) {
            let nav = &mut self.nav[id];
            std::mem::swap(&mut nav.path, &mut self.scratch);
            nav.goal = Some(eff);
            nav.wp = 0;
            let state = &mut self.robots[id];
            state.goal = Some(to_point(eff));
            state.counters.replans += 1;
        }
    }

    /// Advances robot `id`'s waypoint past the corners it has passed: a corner is passed when
    /// reached (within `navigation.waypoint_tolerance_m`), or when the robot is within
    /// [`CORNER_PASS_M`] of it, already beyond the line through it perpendicular to the next
    /// leg, and sees the next waypoint. Without the second rule robots queueing at a corner all
    /// aim at the same point, which their own bodies cover: a jam no priority order resolves.
    fn pass_corners(&mut self, id: usize) {
        let tol = self.navigation.waypoint_tolerance_m.get() as f32;
        let check_infl = self.check_inflation(id);
        let nav = &mut self.nav[id];
        let p = nav.pos;
        let last = nav.path.len() - 1;
        while nav.wp < last {
            let corner = nav.path[nav.wp];
            let next = nav.path[nav.wp + 1];
            let d = (corner - p).length();
            let passed = d <= tol
                || (d <= CORNER_PASS_M
                    && (p - corner).dot(next - corner) > 0.0
                    && self.grid.line_of_sight(p, next, check_infl, f32::INFINITY));
            if !passed {
                break;
            }
            nav.wp += 1;
        }
    }

    /// Velocity towards robot `id`'s current waypoint at top speed times the speed factor; on
    /// the last leg at most `distance / dt`, so the goal is not overshot.
    fn intent_to_waypoint(&self, id: usize) -> Vec2 {
        let nav = &self.nav[id];
        let to_target = nav.waypoint() - nav.pos;
        let dist = to_target.length();
        if dist <= f32::EPSILON {
            return Vec2::ZERO;
        }
        let mut speed = nav.max_speed * self.robots[id].speed_factor as f32;
        if nav.wp >= nav.path.len() - 1 {
            speed = speed.min(dist / self.dt as f32);
        }
        to_target * (speed / dist)
    }
}
