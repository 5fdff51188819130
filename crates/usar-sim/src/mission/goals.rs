//! Giving robots goals from the mission layer: every world call's result is handled here.

use super::error::MissionError;
use super::recorder::Recorder;
use crate::scenario::PointM;
use crate::world::{World, WorldError};

/// Sends robot `id` to `goal`. A goal the planner cannot reach from where the robot stands
/// leaves it standing still (the world clears its goal): that is counted in the robot's
/// `unreachable_goals` and the mission goes on; the robot gets its next goal when its phase
/// next changes.
///
/// # Errors
/// [`MissionError::World`] for any other world error (an unknown robot id: a bug).
pub(crate) fn send(
    world: &mut World,
    rec: &mut Recorder,
    id: usize,
    goal: PointM,
) -> Result<(), MissionError> {
    match world.set_goal(id, Some(goal)) {
        Ok(()) => Ok(()),
        Err(WorldError::Unreachable { .. }) => {
            rec.unreachable_goal(id);
            Ok(())
        }
        Err(e) => Err(e.into()),
    }
}

/// Clears robot `id`'s goal: it stands still.
///
/// # Errors
/// [`MissionError::World`] for an unknown robot id (a bug).
pub(crate) fn stop(world: &mut World, id: usize) -> Result<(), MissionError> {
    world.set_goal(id, None).map_err(MissionError::from)
}
