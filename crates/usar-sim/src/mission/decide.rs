//! The decision system, run before each physics step (paper, sections IV and VI.B): groups
//! leave their search areas when their trip is over; every robot's speed, sensing and
//! collision priority follow its state; ground members claim rescuees or sweep.

use super::error::MissionError;
use super::goals::{send, send_home, stop};
use super::metrics::LeaveCause;
use super::needs::hp_factor;
use super::rescuees::RescueeStatus;
use super::robot::{MissionRobot, Phase};
use super::round_clock::round_time_up;
use super::state::{LeaveFigures, MissionState};
use crate::scenario::{
    CollisionPriority, EmptyOnLeave, IdleBeforeArea, Locomotion, PointM, Rect, Role, Scenario,
    SearchClock, SweepPattern,
};
use crate::world::{World, WorldError};

/// A claim on a rescuee is given up when the robot has not come `CLAIM_PROGRESS_M` closer to
/// it for `CLAIM_STALL_S` seconds (other robots stand in the way, or it is wedged): the
/// rescuee is then `Skipped` until the next round. Seconds.
pub const CLAIM_STALL_S: f64 = 10.0;
/// See [`CLAIM_STALL_S`]. Metres.
pub const CLAIM_PROGRESS_M: f64 = 0.5;

/// Runs the decisions of one step (see the module docs).
///
/// # Errors
/// [`MissionError::World`] if the world refuses a command (a bug).
pub(crate) fn decide(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
) -> Result<(), MissionError> {
    gather_leave_figures(scenario, st);
    if scenario.mission.search_clock == SearchClock::LastArrival {
        start_search_clocks_of_assembled_groups(world, st);
    }
    for t in 0..scenario.tasks.len() {
        if let Some(cause) = group_should_leave(scenario, world, st, t) {
            st.recorder.left_area(t, world.time_s(), cause);
            leave_search_area(scenario, world, st, t)?;
        }
    }
    tally_tasks(scenario, st);
    for id in 0..st.robots.len() {
        let kind = scenario.kind_of(id);
        let r = &st.robots[id];
        let f = hp_factor(&scenario.mission, r.hp_pct);
        let blind = r.task.is_some_and(|t| !st.tally.observer[t]);
        let penalty = if blind {
            scenario.mission.no_observer_speed_factor.get()
        } else {
            1.0
        };
        world.set_speed_factor(id, f * penalty)?;
        world.set_sensing_factor(id, f)?;
        let key = match scenario.collision.priority {
            CollisionPriority::LowestEnergy => r.energy_pct,
            CollisionPriority::LowestHp => r.hp_pct,
            CollisionPriority::RobotId => 0.0,
        };
        world.set_priority_key(id, key)?;
        if kind.locomotion == Locomotion::Ground && r.is_on_task() {
            decide_ground_on_task(scenario, world, st, id, blind)?;
        }
    }
    Ok(())
}

/// Fills `st.tally` for this step: each task's observer flag (an observer is still in its
/// group) and unclaimed pool ([`MissionState::unclaimed_pool`]), in one pass over the team
/// (`O(n + K)`, no allocation once the buffers exist).
fn tally_tasks(scenario: &Scenario, st: &mut MissionState) {
    let k = scenario.tasks.len();
    let tally = &mut st.tally;
    tally.observer.clear();
    tally.observer.resize(k, false);
    // Pool, then claims, summed as `group_pool` does; the unclaimed pool is their difference.
    tally.unclaimed.clear();
    tally.unclaimed.resize(k, 0);
    tally.claims.clear();
    tally.claims.resize(k, 0);
    for r in st.robots.iter().filter(|r| !r.is_resting()) {
        let Some(t) = r.task else { continue };
        tally.observer[t] |= scenario.kind_of(r.id).role == Role::Observer;
        tally.unclaimed[t] = tally.unclaimed[t].saturating_add(r.resources);
        tally.claims[t] += u32::from(r.claim.is_some());
    }
    // A team stock (`resource_stock: TeamPerRound`) is every group's pool, less all claims.
    if let Some(stock) = st.team_stock {
        let all_claims = tally.claims.iter().sum();
        tally.unclaimed.fill(stock.saturating_sub(all_claims));
        return;
    }
    for (pool, &claims) in tally.unclaimed.iter_mut().zip(&tally.claims) {
        *pool = pool.saturating_sub(claims);
    }
}

/// Fills `st.tally.leave` with every task's [`LeaveFigures`], in one pass over the team
/// (`O(n + K)`, no allocation once the buffer exists). Leaving one task's area changes no
/// other task's figures, so they hold for the whole leave loop of [`decide`].
fn gather_leave_figures(scenario: &Scenario, st: &mut MissionState) {
    let leave = &mut st.tally.leave;
    leave.clear();
    leave.resize(scenario.tasks.len(), LeaveFigures::default());
    let team_stock = st.team_stock;
    for r in &st.robots {
        let Some(t) = r.task else { continue };
        let f = &mut leave[t];
        if let Some(stock) = team_stock {
            f.pool = stock;
        } else if !r.is_resting() {
            f.pool = f.pool.saturating_add(r.resources);
        }
        if !r.is_on_task() {
            continue;
        }
        f.any_on_task = true;
        f.all_arrived &= r.reached_area;
        let kind = scenario.kind_of(r.id);
        if kind.locomotion == Locomotion::Ground {
            f.free_capacity = f.free_capacity.saturating_add(r.capacity_free);
            f.ground_all_waiting &= r.phase == Phase::Waiting;
        }
        if kind.role == Role::Observer && r.phase == Phase::ToSearchArea {
            f.observer_arriving = true;
        }
    }
}

/// Starts the search clock of every task whose members have all reached its search area now
/// (`mission.search_clock: LastArrival`), if it is not running yet. Reads `st.tally.leave`.
fn start_search_clocks_of_assembled_groups(world: &World, st: &mut MissionState) {
    let now = world.time_s();
    for (clock, f) in st.search_started_s.iter_mut().zip(&st.tally.leave) {
        if f.any_on_task && f.all_arrived {
            clock.get_or_insert(now);
        }
    }
}

/// Whether task `t`'s group must leave its search area (see `docs/mission-model.md`): its
/// pool of resources or its ground members' free capacity is used up, nothing more is to be
/// had (every ground member waits and no observer is still flying in), or its search time
/// budget (`mission.search_time_budget_s`) or its round's time (`mission.round_clock: Timer`)
/// is spent; returns why (the first that holds, in
/// [`LeaveCause`]'s order), or `None` to stay. Reads `st.tally.leave` (see
/// [`gather_leave_figures`]).
fn group_should_leave(
    scenario: &Scenario,
    world: &World,
    st: &MissionState,
    t: usize,
) -> Option<LeaveCause> {
    let f = st.tally.leave[t];
    if !f.any_on_task {
        return None;
    }
    let (pool, free_capacity) = (f.pool, f.free_capacity);
    let nothing_more = f.ground_all_waiting && !f.observer_arriving;
    let out_of_time = match (
        scenario.mission.search_time_budget_s,
        st.search_started_s[t],
    ) {
        (Some(budget_s), Some(start_s)) => world.time_s() - start_s >= budget_s.get(),
        _ => false,
    };
    [
        (pool == 0, LeaveCause::ResourcesUsed),
        (free_capacity == 0, LeaveCause::CapacityFull),
        (nothing_more, LeaveCause::NothingLeft),
        (out_of_time, LeaveCause::SearchBudget),
        (
            round_time_up(scenario, st, world.time_s()),
            LeaveCause::RoundTimer,
        ),
    ]
    .into_iter()
    .find_map(|(holds, cause)| holds.then_some(cause))
}

/// Sends every member of task `t`'s group still searching to the task's drop-off, releasing
/// their claims; under `mission.empty_on_leave: StraightToStart` a member carrying nothing goes
/// straight back to its start instead.
fn leave_search_area(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    t: usize,
) -> Result<(), MissionError> {
    let drop_off = scenario.tasks[t].drop_off.center;
    let straight = scenario.mission.empty_on_leave == EmptyOnLeave::StraightToStart;
    for id in 0..st.robots.len() {
        let r = &mut st.robots[id];
        if r.task != Some(t) || !r.is_on_task() {
            continue;
        }
        if let Some(i) = r.claim.take() {
            st.fields[t].release(i);
        }
        r.picking_until_s = None;
        if straight && r.load.is_empty() {
            r.phase = Phase::ToStart;
            send_home(scenario, world, &mut st.recorder, id)?;
        } else {
            r.phase = Phase::ToDropOff;
            send(world, &mut st.recorder, id, drop_off)?;
        }
    }
    Ok(())
}

/// A ground member of a group without a claim: claims the nearest known rescuee it can reach
/// (while it has capacity and its group unpromised resources), else sweeps (blind groups),
/// drives on to its search area (not reached yet, `mission.idle_before_area: GoToArea`) or
/// waits.
fn decide_ground_on_task(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    id: usize,
    blind: bool,
) -> Result<(), MissionError> {
    let Some(t) = st.robots[id].task else {
        return Ok(());
    };
    if st.robots[id].claim.is_some() {
        return Ok(());
    }
    let can_rescue = st.robots[id].capacity_free > 0 && st.tally.unclaimed[t] > 0;
    if can_rescue && claim_nearest(scenario, world, st, id, t)? {
        return Ok(());
    }
    let r = &st.robots[id];
    let edge_to_edge = scenario.mission.sweep_pattern == SweepPattern::EdgeToEdge;
    match r.phase {
        Phase::ToSearchArea => {}
        // Sweeping: waypoints are left, or the last one is still being driven to (a robot
        // without a claim is `Searching` only while it sweeps; `CentreToCentre` stopped
        // once the last was assigned).
        _ if blind
            && can_rescue
            && (r.sweep_visited < st.sweeps[t].len()
                || (r.phase == Phase::Searching && edge_to_edge)) =>
        {
            let w = world.robot(id);
            let stalled = match w.goal {
                None => true,
                Some(g) => {
                    let d = (g - w.position).norm();
                    w.goal_reached || sweep_stalled(world.time_s(), &mut st.robots[id], d)
                }
            };
            if stalled && st.robots[id].sweep_visited < st.sweeps[t].len() {
                let turns = edge_to_edge.then_some(&scenario.tasks[t].search_area);
                next_sweep_waypoint(world, st, id, t, turns)?;
            } else if stalled {
                st.robots[id].phase = Phase::Waiting;
                stop(world, id)?;
            }
        }
        Phase::Waiting => {}
        // Nothing to claim before the area (`mission.idle_before_area: GoToArea`): on to it.
        _ if scenario.mission.idle_before_area == IdleBeforeArea::GoToArea && !r.reached_area => {
            st.robots[id].phase = Phase::ToSearchArea;
            send(world, &mut st.recorder, id, scenario.tasks[t].goal)?;
        }
        _ => {
            st.robots[id].phase = Phase::Waiting;
            stop(world, id)?;
        }
    }
    Ok(())
}

/// Claims for robot `id` the nearest known, waiting rescuee of task `t` whose spot is free (no
/// other ground robot's body plus the safety margin covers it: [`World::is_spot_clear`]) and
/// that the planner can reach; marks unreachable ones on the way. Returns whether it claimed
/// one (and then counts the claim in `st.tally`).
fn claim_nearest(
    scenario: &Scenario,
    world: &mut World,
    st: &mut MissionState,
    id: usize,
    t: usize,
) -> Result<bool, MissionError> {
    let pos = world.robot(id).position;
    let reach = world.robot(id).radius_m + scenario.collision.safety_margin_m.get();
    loop {
        let free = |p: &PointM| world.is_spot_clear(p, id, reach);
        let Some(i) = st.fields[t].nearest_known_waiting(&pos, free) else {
            return Ok(false);
        };
        let target = st.fields[t].position(i);
        match world.set_goal(id, Some(target)) {
            Ok(()) => {
                st.fields[t].claim(i, id);
                if st.team_stock.is_some() {
                    // The team's stock: a claim in one task is promised out of every group's.
                    for u in &mut st.tally.unclaimed {
                        *u = u.saturating_sub(1);
                    }
                } else {
                    st.tally.unclaimed[t] = st.tally.unclaimed[t].saturating_sub(1);
                }
                let r = &mut st.robots[id];
                r.claim = Some(i);
                r.target_best_m = (target - pos).norm();
                r.target_progress_s = world.time_s();
                r.phase = Phase::Searching;
                return Ok(true);
            }
            Err(WorldError::Unreachable { .. }) => {
                st.fields[t].settle(i, RescueeStatus::Unreachable);
            }
            Err(e) => return Err(e.into()),
        }
    }
}

/// Whether a sweeping robot, `d` metres from its waypoint, has stalled (no `CLAIM_PROGRESS_M`
/// of progress for `CLAIM_STALL_S`, e.g. a robot parked on the waypoint); records progress
/// otherwise.
fn sweep_stalled(now: f64, r: &mut MissionRobot, d: f64) -> bool {
    if d < r.target_best_m - CLAIM_PROGRESS_M {
        r.target_best_m = d;
        r.target_progress_s = now;
    }
    now - r.target_progress_s > CLAIM_STALL_S
}

/// Sends robot `id` to its next reachable waypoint of task `t`'s sweep, if any is left. With
/// `turns_in` (the search area of an `EdgeToEdge` pattern) a turn, a row's end on the area's
/// left or right edge, is reached only at it (the world's smallest tolerance,
/// [`World::set_goal_within`]); every other waypoint within `navigation.waypoint_tolerance_m`.
/// A robot that turned within the tolerance of a row's end cut the corner and missed rescuees
/// along the edges (see [`sweep_waypoints`](super::search_pattern::sweep_waypoints)).
fn next_sweep_waypoint(
    world: &mut World,
    st: &mut MissionState,
    id: usize,
    t: usize,
    turns_in: Option<&Rect>,
) -> Result<(), MissionError> {
    let sweep = &st.sweeps[t];
    let pos = world.robot(id).position;
    let now = world.time_s();
    while st.robots[id].sweep_visited < sweep.len() {
        let r = &mut st.robots[id];
        let p = sweep[r.sweep_next % sweep.len()];
        r.sweep_next = (r.sweep_next + 1) % sweep.len();
        r.sweep_visited += 1;
        r.phase = Phase::Searching;
        r.target_best_m = (p - pos).norm();
        r.target_progress_s = now;
        let turn = turns_in.is_some_and(|a| p.x == a.min.x || p.x == a.max.x);
        let sent = if turn {
            world.set_goal_within(id, p, 0.0)
        } else {
            world.set_goal(id, Some(p))
        };
        match sent {
            Ok(()) => return Ok(()),
            Err(WorldError::Unreachable { .. }) => {}
            Err(e) => return Err(e.into()),
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::mission::draw_initial_levels;
    use crate::scenario;
    use crate::world::ControlClock;

    fn three_tasks() -> &'static Scenario {
        static S: std::sync::OnceLock<Scenario> = std::sync::OnceLock::new();
        S.get_or_init(|| {
            let path = concat!(
                env!("CARGO_MANIFEST_DIR"),
                "/../../scenarios/three-tasks.ron"
            );
            scenario::load(std::path::Path::new(path)).expect("three-tasks.ron loads")
        })
    }

    const PHASES: [Phase; 9] = [
        Phase::AtStart,
        Phase::ToSearchArea,
        Phase::Searching,
        Phase::Waiting,
        Phase::ToDropOff,
        Phase::ToStart,
        Phase::ToRest,
        Phase::Recharging { until_s: 1.0 },
        Phase::RestToStart,
    ];

    /// The per-task scans the one-pass figures replace (the code before them).
    fn old_should_leave_figures(
        s: &Scenario,
        st: &MissionState,
        t: usize,
    ) -> (bool, u32, u32, bool, bool) {
        let on_task = || {
            st.robots
                .iter()
                .filter(move |r| r.task == Some(t) && r.is_on_task())
        };
        let ground = |r: &&MissionRobot| s.kind_of(r.id).locomotion == Locomotion::Ground;
        let free = on_task()
            .filter(ground)
            .fold(0u32, |sum, r| sum.saturating_add(r.capacity_free));
        let arriving = on_task()
            .any(|r| s.kind_of(r.id).role == Role::Observer && r.phase == Phase::ToSearchArea);
        let waiting = on_task().filter(ground).all(|r| r.phase == Phase::Waiting);
        (
            on_task().next().is_some(),
            st.group_pool(t).0,
            free,
            arriving,
            waiting,
        )
    }

    proptest! {
        #[test]
        fn one_pass_figures_equal_the_per_task_scans(
            states in prop::collection::vec(
                (0usize..9, 0usize..4, 0u32..12, 0u32..8, any::<bool>(), any::<bool>()),
                1..200,
            ),
            team_stock in prop::option::of(0u32..40),
        ) {
            let s = three_tasks();
            let mut st = MissionState::new(s, &draw_initial_levels(s, 7));
            // With a team stock (`resource_stock: TeamPerRound`) the public figures are the
            // stock's, as the decisions count them.
            st.team_stock = team_stock;
            let k = s.tasks.len();
            for (r, &(phase, task, resources, capacity, claim, leaving)) in
                st.robots.iter_mut().zip(states.iter().cycle())
            {
                r.phase = PHASES[phase];
                r.task = (task < k).then_some(task);
                r.resources = if resources == 11 { u32::MAX } else { resources };
                r.capacity_free = capacity;
                r.claim = claim.then_some(0);
                r.leaving = leaving && r.phase == Phase::ToDropOff;
            }
            gather_leave_figures(s, &mut st);
            tally_tasks(s, &mut st);
            for t in 0..k {
                let f = st.tally.leave[t];
                let got = (f.any_on_task, f.pool, f.free_capacity, f.observer_arriving, f.ground_all_waiting);
                prop_assert_eq!(got, old_should_leave_figures(s, &st, t));
                let observer = st.members(t).any(|r| s.kind_of(r.id).role == Role::Observer);
                prop_assert_eq!(st.tally.observer[t], observer);
                prop_assert_eq!(st.tally.unclaimed[t], st.unclaimed_pool(t));
            }
        }
    }

    #[test]
    fn a_member_with_nothing_to_claim_before_its_area_waits_or_drives_on() {
        for (rule, before) in [
            (IdleBeforeArea::Wait, Phase::Waiting),
            (IdleBeforeArea::GoToArea, Phase::ToSearchArea),
        ] {
            let s = three_tasks()
                .edit(|spec| spec.mission.idle_before_area = rule)
                .unwrap();
            let clock = ControlClock::of(&s.sim);
            let mut world = World::new(&s, &clock);
            let mut st = MissionState::new(&s, &draw_initial_levels(&s, 7));
            let id = (0..s.robots.len())
                .find(|&id| s.kind_of(id).locomotion == Locomotion::Ground)
                .unwrap();
            // A claim just finished on the way: no claim, and no rescuee known to claim (no
            // observer has looked yet).
            let r = &mut st.robots[id];
            (r.task, r.phase, r.claim, r.reached_area) = (Some(0), Phase::Searching, None, false);
            gather_leave_figures(&s, &mut st);
            tally_tasks(&s, &mut st);
            decide_ground_on_task(&s, &mut world, &mut st, id, false).unwrap();
            assert_eq!(st.robots[id].phase, before, "{rule:?}");
            let goal = world.robot(id).goal;
            match rule {
                IdleBeforeArea::Wait => assert_eq!(goal, None),
                IdleBeforeArea::GoToArea => {
                    let d = (goal.expect("a goal") - s.tasks[0].goal).norm();
                    assert!(d < 1e-6, "goal {d} m from the task's goal");
                }
            }
            // Within reach of the area, both wait.
            st.robots[id].reached_area = true;
            st.robots[id].phase = Phase::Searching;
            decide_ground_on_task(&s, &mut world, &mut st, id, false).unwrap();
            assert_eq!(st.robots[id].phase, Phase::Waiting, "{rule:?}");
        }
    }

    #[test]
    fn an_empty_member_leaves_via_the_drop_off_or_straight_to_its_start() {
        for rule in [EmptyOnLeave::ViaDropOff, EmptyOnLeave::StraightToStart] {
            let s = three_tasks()
                .edit(|spec| spec.mission.empty_on_leave = rule)
                .unwrap();
            let clock = ControlClock::of(&s.sim);
            let mut world = World::new(&s, &clock);
            let mut st = MissionState::new(&s, &draw_initial_levels(&s, 7));
            let ground: Vec<usize> = (0..s.robots.len())
                .filter(|&id| s.kind_of(id).locomotion == Locomotion::Ground)
                .take(2)
                .collect();
            let (loaded, empty) = (ground[0], ground[1]);
            for &id in &ground {
                let r = &mut st.robots[id];
                (r.task, r.phase, r.reached_area) = (Some(0), Phase::Waiting, true);
            }
            st.robots[loaded].load.push(0);
            leave_search_area(&s, &mut world, &mut st, 0).unwrap();
            let goal_m = |world: &World, id: usize| world.robot(id).goal.expect("a goal");
            let drop_off = s.tasks[0].drop_off.center;
            assert_eq!(st.robots[loaded].phase, Phase::ToDropOff, "{rule:?}");
            assert!(
                (goal_m(&world, loaded) - drop_off).norm() < 1e-6,
                "{rule:?}"
            );
            let (phase, target) = match rule {
                EmptyOnLeave::ViaDropOff => (Phase::ToDropOff, drop_off),
                EmptyOnLeave::StraightToStart => (Phase::ToStart, s.robots[empty].start_in_world),
            };
            assert_eq!(st.robots[empty].phase, phase, "{rule:?}");
            let d = (goal_m(&world, empty) - target).norm();
            assert!(d < 1e-6, "{rule:?}: goal {d} m from where it should go");
        }
    }
}
