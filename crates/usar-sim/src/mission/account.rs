//! The accounting system, run after each physics step (paper, section VI.B): energy and HP
//! costs, rescuee detection, and each robot's phase (pick-ups, deliveries, arrivals, the rest
//! station). The rules: `docs/mission-model.md`.

use super::decide::{CLAIM_PROGRESS_M, CLAIM_STALL_S};
use super::error::MissionError;
use super::events::{MissionEvent, MissionEventKind};
use super::goals::{send_home, stop};
use super::needs::hp_factor;
use super::rescuees::RescueeStatus;
use super::rest::{arrive_at_rest, end_rest, go_rest, review_levels};
use super::robot::Phase;
use super::state::MissionState;
use super::step_costs::charge_step_costs;
use crate::scenario::{Locomotion, PointM, RestAt, Scenario, SearchClock};
use crate::world::World;

/// Accounts the step just taken: every robot's energy (per moving step and per metre moved)
/// and HP (per step in radiation, both per-step rates charged for the step's length on
/// `mission.cost_clock`, [`MissionParams::per_step_on_cost_clock`]) every step, counted in the
/// metrics for a task by `mission.costs_count` ([`charge_step_costs`], robot by robot, the
/// tasks' sums in id order); then, with `review` (after the step before a control step,
/// `sim.control_period_s`, and after the last step: every step without a control period),
/// robot by robot in id order, detections of its group, its phase, and a leave for a rest when
/// energy or HP fell below its threshold ([`review_levels`]). A robot's review reads only its
/// own costs, so charging every robot first gives the bits of charging each before its review.
///
/// [`MissionParams::per_step_on_cost_clock`]: crate::scenario::MissionParams::per_step_on_cost_clock
///
/// # Errors
/// [`MissionError::World`] if the world refuses a command (a bug).
pub(crate) fn account(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    review: bool,
) -> Result<(), MissionError> {
    let mut costs = std::mem::take(&mut st.step_costs);
    let totals = st.recorder.robot_costs_mut();
    let rest = world.read_back_rest();
    charge_step_costs(scenario, &rest, &mut st.robots, totals, &mut costs);
    st.recorder.add_task_costs(&costs);
    st.step_costs = costs;
    if !review {
        return Ok(());
    }
    let m = &scenario.mission;
    let now = world.time_s();
    for id in 0..st.robots.len() {
        let w = world.robot(id);
        let (pos, reached, radius) = (w.position, w.goal_reached, w.radius_m);
        let r = &st.robots[id];
        if let Some(t) = r.task
            && r.is_on_task()
        {
            let f = hp_factor(m, r.hp_pct);
            let range = radius + scenario.kind_of(id).observing_range_m * f;
            st.fields[t].detect(&pos, range);
        }
        advance_phase(scenario, world, st, id, pos, reached, now)?;
        review_levels(scenario, world, st, id, now)?;
    }
    Ok(())
}

/// Moves robot `id` on in its phase after a step that left it at `pos` (`reached`: at its
/// goal).
fn advance_phase(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    id: usize,
    pos: PointM,
    reached: bool,
    now: f64,
) -> Result<(), MissionError> {
    let r = &st.robots[id];
    match (r.phase, r.task) {
        (Phase::ToSearchArea | Phase::Searching | Phase::Waiting, Some(t)) => {
            if r.claim.is_some() {
                try_pick_up(scenario, world, st, id, t, pos, reached)?;
            }
            let in_area = scenario.tasks[t].search_area.contains(&pos);
            let first_arrival = scenario.mission.search_clock == SearchClock::FirstArrival;
            if first_arrival && in_area && scenario.kind_of(id).locomotion == Locomotion::Ground {
                st.search_started_s[t].get_or_insert(now);
            }
            // Within reach of the area, a robot can rescue at its edge without entering it.
            let r = &mut st.robots[id];
            if !r.reached_area {
                let reach = scenario.kind_of(id).body_radius_m
                    + scenario.navigation.waypoint_tolerance_m.get();
                r.reached_area = scenario.tasks[t].search_area.distance_to(&pos) <= reach;
            }
            if r.phase == Phase::ToSearchArea && (reached || in_area) {
                r.phase = Phase::Searching;
                if r.claim.is_none() {
                    // In the area now: the approach goal (the task's goal point, where others
                    // may stand) is dropped; the next decision picks a rescuee, a sweep
                    // waypoint, or waiting.
                    stop(world, id)?;
                }
            }
        }
        (Phase::ToDropOff, Some(t)) if (reached || scenario.tasks[t].drop_off.contains(&pos)) => {
            deliver(st, id, t, now);
            if st.robots[id].leaving {
                go_rest(scenario, world, st, id)?;
            } else {
                st.robots[id].phase = Phase::ToStart;
                send_home(scenario, world, &mut st.recorder, id)?;
            }
        }
        (Phase::ToStart | Phase::RestToStart, _) if reached => {
            st.robots[id].phase = Phase::AtStart;
            st.recorder.back_at_start(id, now);
            stop(world, id)?;
        }
        (Phase::ToRest, _)
            if reached
                || (scenario.mission.rest_at == RestAt::RestStation
                    && scenario.in_rest_station(&pos)) =>
        {
            let recharge_s = scenario.mission.recharge_s.get();
            arrive_at_rest(world, &mut st.robots[id], recharge_s, now)?;
        }
        (Phase::Recharging { until_s }, _) if now + 1e-9 >= until_s => {
            end_rest(scenario, world, st, id, now)?;
        }
        // At the start, or (never in a valid state) on a task's work without a task.
        _ => {}
    }
    Ok(())
}

/// Robot `id` with a claim on a rescuee of task `t`: gives the claim up when the rescuee is out
/// of reach at the goal (inside inflated debris) or the robot stalls; within reach it rescues
/// it (after `mission.pickup_s` standing still), using one unit of its capacity and one
/// resource ([`draw_resource`]).
fn try_pick_up(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    id: usize,
    t: usize,
    pos: PointM,
    reached: bool,
) -> Result<(), MissionError> {
    let Some(i) = st.robots[id].claim else {
        return Ok(());
    };
    let field = &mut st.fields[t];
    let reach = scenario.kind_of(id).body_radius_m + scenario.navigation.waypoint_tolerance_m.get();
    let d = (field.position(i) - pos).norm();
    if d > reach + 1e-9 {
        let now = world.time_s();
        let r = &mut st.robots[id];
        if reached {
            // Arrived at the effective goal but the rescuee is out of reach (it lies inside
            // inflated debris): nobody will get it.
            field.settle(i, RescueeStatus::Unreachable);
            r.claim = None;
        } else if d < r.target_best_m - CLAIM_PROGRESS_M {
            r.target_best_m = d;
            r.target_progress_s = now;
        } else if now - r.target_progress_s > CLAIM_STALL_S {
            field.settle(i, RescueeStatus::Skipped);
            r.claim = None;
        }
        return Ok(());
    }
    // Within reach: the rescue takes `pickup_s` of standing still (0: at once).
    let pickup_s = scenario.mission.pickup_s.get();
    if pickup_s > 0.0 {
        let now = world.time_s();
        match st.robots[id].picking_until_s {
            None => {
                st.robots[id].picking_until_s = Some(now + pickup_s);
                return stop(world, id);
            }
            Some(until_s) if now + 1e-9 < until_s => return Ok(()),
            Some(_) => st.robots[id].picking_until_s = None,
        }
    }
    if !draw_resource(st, t) {
        st.fields[t].release(i);
        st.robots[id].claim = None;
        return Ok(());
    }
    st.fields[t].pick_up(i, id);
    let r = &mut st.robots[id];
    r.claim = None;
    r.capacity_free -= 1;
    r.load.push(i);
    st.recorder.picked_up(id, t);
    let kind = MissionEventKind::PickedUp { rescuee: i };
    st.events
        .push(MissionEvent::of_robot(world.time_s(), id, Some(t), kind));
    stop(world, id)
}

/// Draws one rescuing resource for a pick-up in task `t`: from the team's stock under
/// `mission.resource_stock: TeamPerRound`, else from the first member of the group in id order
/// that holds one (not away for its needs); false when there is none.
fn draw_resource(st: &mut MissionState, t: usize) -> bool {
    if let Some(stock) = &mut st.team_stock {
        let drawn = *stock > 0;
        *stock = stock.saturating_sub(1);
        return drawn;
    }
    let donor = st
        .robots
        .iter()
        .position(|r| r.task == Some(t) && !r.is_resting() && r.resources > 0);
    if let Some(d) = donor {
        st.robots[d].resources -= 1;
    }
    donor.is_some()
}

/// Robot `id` delivers its load at task `t`'s drop-off at `now` (seconds): each rescuee counts
/// for the task once.
fn deliver(st: &mut MissionState, id: usize, t: usize, now: f64) {
    let load = std::mem::take(&mut st.robots[id].load);
    let n = load.len() as u32;
    for i in load {
        st.fields[t].settle(i, RescueeStatus::Delivered);
    }
    st.recorder.delivered(id, t, n);
    let kind = MissionEventKind::Delivered { rescuees: n };
    st.events
        .push(MissionEvent::of_robot(now, id, Some(t), kind));
}
