//! Where a robot's plan is written: into its path, or into the world's scratch buffer.

/// Where `World::plan` (`robot_planning.rs`) writes the waypoints.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum PlanInto {
    /// Into the robot's path, from its first waypoint (the robot follows the plan).
    Path,
    /// Into the world's scratch buffer (a goal check, or a re-plan that replaces the path only
    /// when it succeeds); the robot is not changed.
    Scratch,
}
