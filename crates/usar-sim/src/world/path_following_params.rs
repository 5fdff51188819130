//! The path follower's tunables: how often a ground robot re-checks its path, when it counts a
//! corner as passed, and the no-progress clock and rejoin distance of its detours.

/// Ground robots re-check the line of sight to their current waypoint every this many steps
/// (staggered by id) and re-plan when it is blocked; with a control period of `k` steps
/// (`sim.control_period_s`), every `max(1, 10 / k)` control steps (integer division), so
/// about as often in time.
pub const PATH_CHECK_INTERVAL_STEPS: u64 = 10;
/// Longest stretch of the line of sight checked by the periodic path check, metres.
pub const PATH_CHECK_MAX_M: f32 = 4.0;
/// A ground robot within this distance of a path corner, beyond the line through the corner
/// perpendicular to the next leg and in sight of the next waypoint, counts the corner as
/// passed, metres.
pub const CORNER_PASS_M: f32 = 2.0;
/// The no-progress clock of detours: its default length and the progress that restarts it,
/// scenario defaults (defined in `scenario::params`, re-exported here and by `world`).
pub use crate::scenario::{STALL_PROGRESS_M, STALL_REPLAN_S};
/// A detour first plans only to its rejoin point: the point of the robot's path this far
/// beyond the farthest standing robot it goes round (path length from the robot, at least the
/// straight distance to that robot's disc rim plus this), metres (see `docs/world-model.md`,
/// "Congestion").
pub const DETOUR_REJOIN_BEYOND_M: f32 = 1.0;
