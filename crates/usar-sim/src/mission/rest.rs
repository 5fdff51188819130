//! The rest lifecycle (paper, section VI.B: "if the individual battery (energy) or HP level is
//! below 30%, it needs to go to the pre-defined rest position for recharging energy (or for
//! refreshing its health HP) 30 seconds, then back to the initial position waiting for the
//! next round to start"): leaving for a rest, resting, refreshing, and joining a round again.
//! When a robot leaves is `mission.leave_when_low` and `mission.rest_timing`; where it rests
//! `mission.rest_at`; what a rest restores `mission.refresh`. The round system
//! ([`super::round_clock`]) asks [`may_join`] and [`rests_over`].

use super::error::MissionError;
use super::events::{MissionEvent, MissionEventKind};
use super::goals::{rest_station_for, send, send_home, stop};
use super::robot::{MissionRobot, Phase};
use super::state::MissionState;
use crate::scenario::{
    LeaveWhenLow, LoadOnLeave, MissionParams, Refresh, ResourceStock, RestAt, RestTiming, Scenario,
};
use crate::world::World;

/// Whether a robot below a threshold waits until it is back at its start before it leaves for
/// a rest: `leave_when_low: AfterTrip`, or a rest taken in the round's slack
/// (`rest_timing: InSlack`).
fn leaves_after_trip(m: &MissionParams) -> bool {
    m.leave_when_low == LeaveWhenLow::AfterTrip || m.rest_timing == RestTiming::InSlack
}

/// Whether robot `r` joins a round that starts now: it is at its start and, when robots leave
/// for a rest after their trip ([`leaves_after_trip`]), not below a threshold (it leaves for
/// its rest at its next review instead, so a round never groups a robot due for a rest).
pub(crate) fn may_join(m: &MissionParams, r: &MissionRobot) -> bool {
    let (low_energy, low_hp) = r.low_levels(m);
    r.phase == Phase::AtStart && !(leaves_after_trip(m) && (low_energy || low_hp))
}

/// Whether every rest taken in the open round's slack (`rest_timing: InSlack`) is over: each
/// robot that left for a rest after its trip in this round is back at its start. Always true
/// under `OutOfRound`, where no robot rests in a round.
pub(crate) fn rests_over(st: &MissionState) -> bool {
    st.robots
        .iter()
        .filter(|r| r.rests_in_round)
        .all(|r| r.phase == Phase::AtStart)
}

/// Robot `id`'s review of its levels at `now_s`: below `mission.low_energy_pct` or
/// `low_hp_pct`, and not away already, it leaves for a rest (at once, or once back at its
/// start: [`leaves_after_trip`]); the leave is an event and counts for its group's task.
///
/// # Errors
/// [`MissionError::World`] if the world refuses a command (a bug).
pub(crate) fn review_levels(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    id: usize,
    now_s: f64,
) -> Result<(), MissionError> {
    let m = &scenario.mission;
    let r = &st.robots[id];
    let (low_energy, low_hp) = r.low_levels(m);
    let may_leave = !leaves_after_trip(m) || r.phase == Phase::AtStart;
    if r.is_resting() || !(low_energy || low_hp) || !may_leave {
        return Ok(());
    }
    if let Some(t) = r.task {
        st.recorder.left_for_rest(t);
    }
    let kind = MissionEventKind::LeftForRest { low_energy, low_hp };
    st.events
        .push(MissionEvent::of_robot(now_s, id, r.task, kind));
    // Back from its round's trip with the round still open: under `InSlack` it rests in that
    // round's slack, and the round waits for it (up to its timer).
    let in_slack = m.rest_timing == RestTiming::InSlack && r.task.is_some() && st.round_open;
    st.robots[id].rests_in_round = in_slack;
    go_rest(scenario, world, st, id)
}

/// Robot `id`, on its way to rest, arrived (`reached` its goal, or entered a rest station's
/// disc under `rest_at: RestStation`): it stands and rests for `recharge_s` seconds from
/// `now_s` (`mission.recharge_s`).
///
/// # Errors
/// [`MissionError::World`] if the world refuses a command (a bug).
pub(crate) fn arrive_at_rest(
    world: &mut World,
    r: &mut MissionRobot,
    recharge_s: f64,
    now_s: f64,
) -> Result<(), MissionError> {
    r.phase = Phase::Recharging {
        until_s: now_s + recharge_s,
    };
    stop(world, r.id)
}

/// Ends robot `id`'s rest at `now_s`: restores what `mission.refresh` says (and, under
/// `mission.resource_stock: AtRest`, its kind's rescuing resources) and sends it back
/// towards its start, where it waits for a round it may join ([`may_join`]).
///
/// # Errors
/// [`MissionError::World`] if the world refuses a command (a bug).
pub(crate) fn end_rest(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    id: usize,
    now_s: f64,
) -> Result<(), MissionError> {
    let m = &scenario.mission;
    let r = &mut st.robots[id];
    let both = m.refresh == Refresh::Both;
    if both || r.energy_pct < m.low_energy_pct.get() {
        r.energy_pct = 100.0;
    }
    if both || r.hp_pct < m.low_hp_pct.get() {
        r.hp_pct = 100.0;
    }
    if m.resource_stock == ResourceStock::AtRest {
        r.resources = scenario.kind_of(id).rescuing_resources;
    }
    r.phase = Phase::RestToStart;
    st.recorder.recharged(id);
    let kind = MissionEventKind::Recharged;
    st.events
        .push(MissionEvent::of_robot(now_s, id, None, kind));
    send_home(scenario, world, &mut st.recorder, id)
}

/// Robot `id` leaves its task and group for the nearest rest station
/// ([`rest_station_for`]: by path from where it stands), or for its own start under
/// `mission.rest_at: OwnStart`. Its claim is released; its load is abandoned, put back, or
/// first delivered (`mission.load_on_leave`). A robot delivering first stays in its group,
/// marked [`MissionRobot::leaving`], until it reaches the drop-off, and comes back here then.
///
/// # Errors
/// [`MissionError::World`] if the world refuses a command (a bug).
pub(crate) fn go_rest(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    id: usize,
) -> Result<(), MissionError> {
    let rule = scenario.mission.load_on_leave;
    let r = &mut st.robots[id];
    if let Some(t) = r.task {
        let field = &mut st.fields[t];
        if let Some(i) = r.claim.take() {
            field.release(i);
        }
        r.picking_until_s = None;
        if rule == LoadOnLeave::DeliverFirst && !r.leaving && !r.load.is_empty() {
            r.leaving = true;
            r.phase = Phase::ToDropOff;
            let drop_off = scenario.tasks[t].drop_off.center;
            return send(world, &mut st.recorder, id, drop_off);
        }
        for i in r.load.drain(..) {
            match rule {
                LoadOnLeave::ReturnToArea => field.put_back(i),
                LoadOnLeave::Abandon | LoadOnLeave::DeliverFirst => {
                    field.settle(i, super::rescuees::RescueeStatus::Abandoned);
                }
            }
        }
    }
    r.leaving = false;
    r.task = None;
    r.phase = Phase::ToRest;
    let rest_m = match scenario.mission.rest_at {
        RestAt::RestStation => scenario.rest_stations[rest_station_for(scenario, world, id)].center,
        RestAt::OwnStart => scenario.robots[id].start_in_world,
    };
    send(world, &mut st.recorder, id, rest_m)
}
