//! Giving robots goals from the mission layer: every world call's result is handled here.

use super::error::MissionError;
use super::recorder::Recorder;
use crate::scenario::{PointM, Scenario};
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
    sent(rec, id, world.set_goal(id, Some(goal)))
}

/// Sends each robot of `goals` (robot id, goal) to its goal, as [`send`] one after the other
/// in that order does, through [`World::set_goals`] (which plans a large team's shared goals
/// side by side).
///
/// # Errors
/// As [`send`], for the first robot that fails so (the robots after it have their goals).
pub(crate) fn send_all(
    world: &mut World,
    rec: &mut Recorder,
    goals: &[(usize, PointM)],
) -> Result<(), MissionError> {
    let results = world.set_goals(goals);
    for (&(id, _), result) in goals.iter().zip(results) {
        sent(rec, id, result)?;
    }
    Ok(())
}

/// What [`send`] makes of the world's `result` of sending robot `id`.
fn sent(rec: &mut Recorder, id: usize, result: Result<(), WorldError>) -> Result<(), MissionError> {
    match result {
        Ok(()) => Ok(()),
        Err(WorldError::Unreachable { .. }) => {
            rec.unreachable_goal(id);
            Ok(())
        }
        Err(e) => Err(e.into()),
    }
}

/// Sends robot `id` to its start position (`Scenario::robots[id].start_in_world`), as
/// [`send`].
///
/// # Errors
/// As [`send`].
pub(crate) fn send_home(
    scenario: &Scenario,
    world: &mut World,
    rec: &mut Recorder,
    id: usize,
) -> Result<(), MissionError> {
    send(world, rec, id, scenario.robots[id].start_in_world)
}

/// Clears robot `id`'s goal: it stands still.
///
/// # Errors
/// [`MissionError::World`] for an unknown robot id (a bug).
pub(crate) fn stop(world: &mut World, id: usize) -> Result<(), MissionError> {
    world.set_goal(id, None).map_err(MissionError::from)
}

/// The index in [`Scenario::rest_stations`] of the station robot `id` goes to when it leaves
/// to recharge: with one station that one; with several, the one with the shortest path
/// from where the robot stands ([`World::path_length_m`]; on equal lengths the one listed
/// first), or, when no station is reachable, the nearest in a straight line
/// ([`Scenario::nearest_rest_station`]; the robot then stands, as for any unreachable goal).
/// The paper has one station: how a robot chooses among several is ours
/// (`docs/scenario-format.md`, "Rest stations").
pub(crate) fn rest_station_for(scenario: &Scenario, world: &mut World, id: usize) -> usize {
    if scenario.rest_stations.len() == 1 {
        return 0;
    }
    let mut best: Option<(usize, f64)> = None;
    for (i, c) in scenario.rest_stations.iter().enumerate() {
        if let Some(len) = world.path_length_m(id, c.center)
            && best.is_none_or(|(_, b)| len < b)
        {
            best = Some((i, len));
        }
    }
    best.map_or_else(
        || scenario.nearest_rest_station(&world.robot(id).position),
        |(i, _)| i,
    )
}
