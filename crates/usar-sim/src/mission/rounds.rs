//! The round system (paper, section VI.B): regrouping the team at a round's start, and closing
//! the round when every grouped robot is back.

use rne_core::grouping::GroupingMethod;

use super::error::MissionError;
use super::events::{MissionEvent, MissionEventKind};
use super::goals::send;
use super::grouping::group_available;
use super::robot::{MissionRobot, Phase};
use super::state::MissionState;
use crate::scenario::{LeaveWhenLow, Locomotion, RoundStart, Scenario, SearchClock};
use crate::world::World;

/// Starts a round if one is due: the robots at their start positions (all of them under
/// `round_start: AllBack`, else at least one) are grouped by `method`; every member gets its
/// task, full capacity and resources, its start on the blind-search pattern, and its goal (the
/// task's goal point for ground robots, the search area's centre for aerial ones). Each task's
/// rescuee map is forgotten and its search clock reset (started now under `mission.search_clock:
/// RoundStart`).
///
/// # Errors
/// As [`group_available`], and [`MissionError::World`] from the world.
pub(crate) fn start_round(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    method: &dyn GroupingMethod,
) -> Result<(), MissionError> {
    // A robot waiting at its start joins the round; under `leave_when_low: AfterTrip` one below
    // a threshold does not (it leaves for the rest station at the next review), so a round
    // never groups a robot that is due for the rest station.
    let after_trip = scenario.mission.leave_when_low == LeaveWhenLow::AfterTrip;
    let joins = |r: &MissionRobot| {
        let (low_energy, low_hp) = r.low_levels(&scenario.mission);
        r.phase == Phase::AtStart && !(after_trip && (low_energy || low_hp))
    };
    // Counted first: no allocation on the steps where no round starts.
    let at_start = st.robots.iter().filter(|r| joins(r)).count();
    let everyone_back = at_start == st.robots.len();
    if at_start == 0 || (scenario.mission.round_start == RoundStart::AllBack && !everyone_back) {
        return Ok(());
    }
    let available: Vec<usize> = st
        .robots
        .iter()
        .filter(|r| joins(r))
        .map(|r| r.id)
        .collect();
    let groups = group_available(scenario, method, &st.robots, &available)?;
    for field in &mut st.fields {
        field.forget();
    }
    // The search clock of each task runs from the round's start, or from its group's first
    // ground member entering the search area (set by the accounting system).
    let clock = (scenario.mission.search_clock == SearchClock::RoundStart).then(|| world.time_s());
    st.search_started_s.fill(clock);
    for (t, ids) in groups.iter().enumerate() {
        let task = &scenario.tasks[t];
        let sweep_len = st.sweeps[t].len().max(1);
        for (ordinal, &id) in ids.iter().enumerate() {
            let kind = scenario.kind_of(id);
            let r = &mut st.robots[id];
            r.task = Some(t);
            r.phase = Phase::ToSearchArea;
            r.capacity_free = kind.carrying_capacity;
            r.resources = kind.rescuing_resources;
            r.claim = None;
            r.sweep_next = ordinal * sweep_len / ids.len();
            r.sweep_visited = 0;
            r.reached_area = false;
            let target = match kind.locomotion {
                Locomotion::Ground => task.goal,
                Locomotion::Aerial => task.search_area.center(),
            };
            send(world, &mut st.recorder, id, target)?;
        }
    }
    st.recorder.round_started(world.time_s(), groups);
    let round = st.recorder.rounds().len() - 1;
    st.events.push(MissionEvent::of_round(
        world.time_s(),
        MissionEventKind::RoundStarted { round },
    ));
    st.round_open = true;
    Ok(())
}

/// Whether every robot still in a group this round is back at its start.
pub(crate) fn round_complete(st: &MissionState) -> bool {
    st.robots
        .iter()
        .filter(|r| r.task.is_some())
        .all(|r| r.phase == Phase::AtStart)
}

/// Ends the open round now (`completed`: everyone back; otherwise cut by the time limit); the
/// groups dissolve.
pub(crate) fn close_round(world: &World, st: &mut MissionState, completed: bool) {
    let members = st.robots.iter().filter_map(|r| r.task.map(|t| (r.id, t)));
    st.recorder.round_closed(world.time_s(), completed, members);
    let round = st.recorder.rounds().len().saturating_sub(1);
    st.events.push(MissionEvent::of_round(
        world.time_s(),
        MissionEventKind::RoundEnded { round, completed },
    ));
    for r in &mut st.robots {
        r.task = None;
    }
    st.round_open = false;
}
