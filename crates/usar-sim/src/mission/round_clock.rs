//! The round system (paper, section VI.B): regrouping the team at a round's start, recalling
//! its groups when the round's timer runs out (`mission.round_clock: Timer`), and closing the
//! round when every group is back (and, under `mission.rest_timing: InSlack`, the rests taken
//! in its slack are over, unless its time is up). Who joins a round and who rests in its slack:
//! [`super::rest`].

use rne_core::grouping::GroupingMethod;

use super::error::MissionError;
use super::events::{MissionEvent, MissionEventKind};
use super::goals::send_all;
use super::grouping::group_available;
use super::rest::{may_join, rests_over};
use super::robot::Phase;
use super::state::MissionState;
use crate::scenario::{Locomotion, ResourceStock, RoundClock, RoundStart, Scenario, SearchClock};
use crate::world::World;

/// Tolerance of the round timer's comparisons, seconds: a timer of 100 s runs out on the
/// control step at 100 s even when the sum of the steps is a rounding below it.
const TIMER_TOLERANCE_S: f64 = 1e-9;

/// Starts a round if one is due: the robots at their start positions that may join
/// ([`may_join`]; all of them under `round_start: AllBack`, else at least one) are grouped by
/// `method`; every member gets its task, full capacity and resources (under
/// `mission.resource_stock: AtRest` it keeps the resources it holds; under `TeamPerRound` the
/// team's stock is reset to its units), its start on the
/// blind-search pattern, and its goal (the task's goal point for ground robots, the search
/// area's centre for aerial ones). Each task's rescuee map is forgotten and its search clock
/// reset (started now under `mission.search_clock: RoundStart`).
///
/// # Errors
/// As [`group_available`], and [`MissionError::World`] from the world.
pub(crate) fn start_round(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    method: &dyn GroupingMethod,
) -> Result<(), MissionError> {
    let m = &scenario.mission;
    // Counted first: no allocation on the steps where no round starts.
    let at_start = st.robots.iter().filter(|r| may_join(m, r)).count();
    let everyone_back = at_start == st.robots.len();
    if at_start == 0 || (m.round_start == RoundStart::AllBack && !everyone_back) {
        return Ok(());
    }
    let available: Vec<usize> = st
        .robots
        .iter()
        .filter(|r| may_join(m, r))
        .map(|r| r.id)
        .collect();
    let groups = group_available(scenario, method, &st.robots, &available)?;
    for field in &mut st.fields {
        field.forget();
    }
    // The search clock of each task runs from the round's start, or from its group's first
    // ground member entering the search area (set by the accounting system).
    let clock = (m.search_clock == SearchClock::RoundStart).then(|| world.time_s());
    st.search_started_s.fill(clock);
    // Under `resource_stock: AtRest` a member keeps what it holds (refilled when a rest ends).
    let refill = m.resource_stock == ResourceStock::PerRound;
    st.team_stock = match m.resource_stock {
        ResourceStock::TeamPerRound { units } => Some(units),
        ResourceStock::PerRound | ResourceStock::AtRest => None,
    };
    let mut goals = Vec::with_capacity(available.len());
    for (t, ids) in groups.iter().enumerate() {
        let task = &scenario.tasks[t];
        let sweep_len = st.sweeps[t].len().max(1);
        for (ordinal, &id) in ids.iter().enumerate() {
            let kind = scenario.kind_of(id);
            let r = &mut st.robots[id];
            r.task = Some(t);
            r.last_task = Some(t);
            r.phase = Phase::ToSearchArea;
            r.capacity_free = kind.carrying_capacity;
            if refill {
                r.resources = kind.rescuing_resources;
            }
            r.claim = None;
            r.sweep_next = ordinal * sweep_len / ids.len();
            r.sweep_visited = 0;
            r.reached_area = false;
            let target = match kind.locomotion {
                Locomotion::Ground => task.goal,
                Locomotion::Aerial => task.search_area.center(),
            };
            goals.push((id, target));
        }
    }
    send_all(world, &mut st.recorder, &goals)?;
    st.recorder.round_started(world.time_s(), groups);
    let round = st.recorder.rounds().len() - 1;
    st.events.push(MissionEvent::of_round(
        world.time_s(),
        MissionEventKind::RoundStarted { round },
    ));
    st.round_open = true;
    Ok(())
}

/// Whether the open round's time is up at `now_s` (`mission.round_clock: Timer`: at least
/// `length_s` since its start); never under `AllBack` or without an open round. Its groups
/// still out are then recalled (`decide`, `LeaveCause::RoundTimer`).
pub(crate) fn round_time_up(scenario: &Scenario, st: &MissionState, now_s: f64) -> bool {
    let RoundClock::Timer { length_s } = scenario.mission.round_clock else {
        return false;
    };
    let start_s = st.recorder.rounds().last().map(|r| r.start_s);
    st.round_open && start_s.is_some_and(|s| now_s - s + TIMER_TOLERANCE_S >= length_s.get())
}

/// Whether the open round may close at `now_s`: every robot still in a group is back at its
/// start, and the rests taken in its slack ([`rests_over`]) are over or its time is up
/// ([`round_time_up`]).
pub(crate) fn round_complete(scenario: &Scenario, st: &MissionState, now_s: f64) -> bool {
    let groups_back = st
        .robots
        .iter()
        .filter(|r| r.task.is_some())
        .all(|r| r.phase == Phase::AtStart);
    groups_back && (rests_over(st) || round_time_up(scenario, st, now_s))
}

/// Ends the open round now (`completed`: everyone back; otherwise cut by the time limit); the
/// groups dissolve. A robot still resting from this round's slack sits out the next round if
/// it is not back at its start when that round starts.
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
        r.rests_in_round = false;
    }
    st.round_open = false;
}
