//! The switches of the authors' clock (issue 71; `usar_sim::scenario::lifecycle_choices`,
//! docs/mission-model.md, "The authors' clock"): the round timer and its recall, rests in a
//! round's slack, the cost clock and which costs count, and where the rescuing resources come
//! from (`mission.resource_stock`), each on variants of paper-v1.ron.

use integration_tests::{fixed, method, paper_v1_with};
use usar_sim::mission::{LeaveCause, MissionEventKind, Phase, Simulation, TrialResult};
use usar_sim::scenario::{
    CollisionPriority, CostClock, CostsCount, HpEffect, LeaveWhenLow, ResourceStock, RestTiming,
    RoundClock, RoundStart, Scenario, ScenarioSpec,
};

/// A round timer of `length_s` seconds.
fn timer(length_s: f64) -> RoundClock {
    RoundClock::Timer {
        length_s: length_s.try_into().unwrap(),
    }
}

/// paper.ron with robots that start with full levels, no search budget (a group stays in its
/// area until it is full or finds nothing more) and rounds that start with the robots
/// available, changed further by `edit`.
fn base(edit: impl FnOnce(&mut ScenarioSpec)) -> Scenario {
    paper_v1_with(|s| {
        s.mission.initial_energy = fixed(100.0);
        s.mission.initial_hp = fixed(100.0);
        s.mission.search_time_budget_s = None;
        s.mission.round_start = RoundStart::Available;
        edit(s);
    })
}

/// [`base`] with every robot starting at `energy_pct` and a search budget of 14 s (robots fall
/// below the energy threshold within a round or two and rest), changed further by `edit`.
fn low_energy(energy_pct: f64, edit: impl FnOnce(&mut ScenarioSpec)) -> Scenario {
    base(|s| {
        s.mission.initial_energy = fixed(energy_pct);
        s.mission.search_time_budget_s = Some(14.0.try_into().unwrap());
        edit(s);
    })
}

/// Trial 0 of `s` by RNE over `duration_s`, with the robots' phases before each step and the
/// events of each step.
fn run_watched(
    s: &Scenario,
    duration_s: f64,
    mut watch: impl FnMut(&Simulation, &[Phase]),
) -> TrialResult {
    let mut sim = Simulation::for_trial(s, method("rne", s), 0)
        .with_duration_s(duration_s)
        .unwrap();
    while !sim.is_finished() {
        let before: Vec<Phase> = sim.robots().iter().map(|r| r.phase).collect();
        sim.step().unwrap();
        watch(&sim, &before);
    }
    sim.result()
}

/// The latest of the times given, seconds (0 if none is).
fn latest(times_s: &[Option<f64>]) -> f64 {
    times_s.iter().flatten().fold(0.0_f64, |a, &b| a.max(b))
}

#[test]
fn a_round_timer_recalls_the_groups_and_no_round_outlasts_it_plus_the_recall_trip() {
    let length_s = 30.0;
    let s = base(|s| s.mission.round_clock = timer(length_s));
    let control_s = s.sim().dt_s.get();
    let r = run_watched(&s, 600.0, |_, _| {});
    let completed: Vec<_> = r.rounds.iter().filter(|round| round.completed).collect();
    assert!(completed.len() >= 4, "{} rounds", completed.len());
    let mut recalled = 0;
    for round in &completed {
        for t in 0..r.tasks.len() {
            if round.groups[t].is_empty() {
                continue;
            }
            // Every group is out of its area by the timer (a step's rounding late at most).
            let left_s = round.left_area_s[t].expect("a completed round's group left its area");
            assert!(
                left_s <= round.start_s + length_s + control_s + 1e-9,
                "round at {} s, task {t}: left at {left_s} s",
                round.start_s
            );
            recalled += usize::from(round.left_because[t] == Some(LeaveCause::RoundTimer));
            // The round closes when its last group is back: its length is the timer plus the
            // recall trip of its slowest member, no longer.
            let back_s = latest(&round.back_s);
            assert!(
                round.end_s <= back_s + control_s + 1e-9,
                "round at {} s ends at {} s, its last group back at {back_s} s",
                round.start_s,
                round.end_s
            );
        }
    }
    // Without a search budget the groups stay in their areas: the timer recalls most of them.
    assert!(
        recalled >= completed.len(),
        "{recalled} recalls in {} rounds",
        completed.len()
    );
    // Under `AllBack` a group of the same first round stays out longer than the timer.
    let all_back = run_watched(&base(|_| {}), 600.0, |_, _| {});
    let first = &all_back.rounds[0];
    let left = latest(&first.left_area_s);
    assert!(
        left > first.start_s + length_s + 1.0,
        "AllBack: left at {left} s"
    );
}

#[test]
fn a_load_in_hand_at_the_recall_is_carried_to_the_drop_off_and_counts() {
    let s = base(|s| s.mission.round_clock = timer(30.0));
    // Per robot: the load it held when its group was recalled, while it is still to deliver.
    let mut owed: Vec<Option<usize>> = vec![None; s.robots().len()];
    let (mut recalled_loads, mut delivered_loads) = (0, 0);
    run_watched(&s, 300.0, |sim, before| {
        for (id, r) in sim.robots().iter().enumerate() {
            let recalled = r.phase == Phase::ToDropOff
                && matches!(
                    before[id],
                    Phase::Searching | Phase::Waiting | Phase::ToSearchArea
                );
            if recalled && !r.load.is_empty() {
                owed[id] = Some(r.load.len());
                recalled_loads += 1;
            }
        }
        for e in sim.events() {
            if let (MissionEventKind::Delivered { rescuees }, Some(id)) = (e.kind, e.robot)
                && let Some(n) = owed[id].take()
            {
                assert_eq!(rescuees as usize, n, "robot {id} delivers its load");
                delivered_loads += 1;
            }
        }
    });
    assert!(
        recalled_loads >= 3,
        "{recalled_loads} loads in hand at a recall"
    );
    assert_eq!(
        delivered_loads, recalled_loads,
        "every recalled load is delivered"
    );
}

/// The round starts and, for each, the robots grouped, of trial 0 of `s` over 400 s; asserts on
/// the way that a round never leaves a robot at its start that may join it.
fn rounds_and_joins(s: &Scenario) -> (TrialResult, Vec<usize>) {
    let mut grouped = Vec::new();
    let r = run_watched(s, 400.0, |sim, _| {
        for e in sim.events() {
            if let MissionEventKind::RoundStarted { round } = e.kind {
                let g = &sim.rounds()[round].groups;
                grouped.push(g.iter().map(Vec::len).sum());
                // A rest over before the round starts makes the robot join it.
                for r in sim.robots() {
                    let (low_energy, low_hp) = r.low_levels(sim.scenario().mission());
                    assert!(
                        r.phase != Phase::AtStart || low_energy || low_hp,
                        "round {round}: robot {} waits at its start, not grouped",
                        r.id
                    );
                }
            }
        }
    });
    (r, grouped)
}

#[test]
fn a_rest_in_the_slack_holds_the_round_and_the_robot_joins_the_next() {
    // Every robot falls below the energy threshold on its first trip.
    let low = |rest: RestTiming, clock: RoundClock| {
        base(move |s| {
            s.mission.initial_energy = fixed(33.0);
            s.mission.leave_when_low = LeaveWhenLow::AfterTrip;
            s.mission.search_time_budget_s = Some(14.0.try_into().unwrap());
            s.mission.rest_timing = rest;
            s.mission.round_clock = clock;
        })
    };
    let team = 12;
    // In the slack, with time to spare: the first round waits for the rests, the second groups
    // the whole team.
    let (r, grouped) = rounds_and_joins(&low(RestTiming::InSlack, timer(300.0)));
    assert_eq!(grouped[1], team, "rounds' sizes {grouped:?}");
    let recharged_by = r.robots.iter().filter(|m| m.recharges > 0).count();
    assert!(recharged_by >= 6, "{recharged_by} robots rested");
    // Out of the round (today's rule): the first round closes without waiting, and the robots
    // still resting sit the second out.
    let (_, grouped) = rounds_and_joins(&low(RestTiming::OutOfRound, timer(300.0)));
    assert!(grouped[1] < team, "rounds' sizes {grouped:?}");
    // In the slack of a round whose time is up before the rests end: the round closes when its
    // groups are back, and the robots still resting sit the next round out.
    let (_, grouped) = rounds_and_joins(&low(RestTiming::InSlack, timer(20.0)));
    assert!(grouped[1] < team, "rounds' sizes {grouped:?}");
}

/// Energy spent and HP lost by each robot in the first 4 s of trial 0 of paper.ron (per-step
/// rates only, every robot inside a radiation zone) on cost clock `clock`.
fn first_costs(clock: CostClock) -> Vec<(f64, f64)> {
    let s = base(|s| {
        s.mission.cost_clock = clock;
        s.mission.energy_pct_per_m = 0.0.try_into().unwrap();
        s.mission.energy_pct_per_moving_step = 0.0045.try_into().unwrap();
        s.mission.hp_pct_per_step_in_radiation = 0.0003.try_into().unwrap();
        // Collision order by id and speed free of HP: the levels, which differ between the
        // clocks, then change no path.
        s.collision.priority = CollisionPriority::RobotId;
        s.mission.hp_effect = HpEffect::NoEffect;
        s.radiation_zones = vec![usar_sim::scenario::RadiationZoneSpec {
            center_m: [40.0, 30.0],
            radius_m: 30.0.try_into().unwrap(),
            dose_rate_factor: 1.0.try_into().unwrap(),
        }];
    });
    let r = run_watched(&s, 4.0, |_, _| {});
    r.robots
        .iter()
        .map(|m| (m.energy_spent_pct, m.hp_lost_pct))
        .collect()
}

#[test]
fn a_frame_clock_charges_the_per_step_rates_per_frame() {
    let paper_step = first_costs(CostClock::PaperStep);
    let frames = first_costs(CostClock::Frames {
        steps_per_s: 130.0.try_into().unwrap(),
    });
    for (id, (p, f)) in paper_step.iter().zip(&frames).enumerate() {
        // 130 frames per second against the paper's 50 steps: 2.6 times the charge, the same
        // moving steps.
        assert!(p.0 > 0.05, "robot {id} moved: {p:?}");
        assert!(
            (f.0 / p.0 - 2.6).abs() < 1e-9,
            "robot {id}: energy {f:?} vs {p:?}"
        );
        // HP: 4 s in radiation, 0.0003 % per frame at 130 frames per second.
        assert!(
            (f.1 - 0.0003 * 130.0 * 4.0).abs() < 1e-9,
            "robot {id}: HP {f:?}"
        );
        assert!(
            (p.1 - 0.0003 * 50.0 * 4.0).abs() < 1e-9,
            "robot {id}: HP {p:?}"
        );
    }
}

#[test]
fn every_cost_counts_for_the_latest_task_or_only_costs_in_a_group() {
    // Robots rest on their way (energy 33 %): their trips to and from the rest station count
    // only under `Every`.
    let run = |count: CostsCount| {
        let s = low_energy(33.0, |s| s.mission.costs_count = count);
        run_watched(&s, 300.0, |_, _| {})
    };
    for count in [CostsCount::Every, CostsCount::InGroup] {
        let r = run(count);
        let by_robots: f64 = r.robots.iter().map(|m| m.energy_spent_pct).sum();
        let by_tasks = r.energy_total_pct();
        let rested = r.robots.iter().filter(|m| m.recharges > 0).count();
        assert!(rested >= 6, "{count:?}: {rested} robots rested");
        match count {
            // Every robot was grouped at t = 0 (full levels above the threshold): all counts.
            CostsCount::Every => assert!(
                (by_tasks - by_robots).abs() < 1e-9 * by_robots,
                "Every: tasks {by_tasks}, robots {by_robots}"
            ),
            CostsCount::InGroup => assert!(
                by_tasks < by_robots - 1.0,
                "InGroup: tasks {by_tasks}, robots {by_robots}"
            ),
        }
    }
}

#[test]
fn a_team_stock_per_round_bounds_both_tasks_together() {
    // No search budget: a group stays until it is full, so 8 units bind in every round.
    let units = 8;
    let s = base(|s| s.mission.resource_stock = ResourceStock::TeamPerRound { units });
    let r = run_watched(&s, 400.0, |sim, _| {
        let picked: u32 = sim.rounds().last().map_or(0, |_| {
            // Picked up this round: held in the loads, or delivered this round.
            let held: usize = sim.robots().iter().map(|m| m.load.len()).sum();
            let delivered: u32 = sim.rounds().last().unwrap().rescued.iter().sum();
            held as u32 + delivered
        });
        assert!(
            picked <= units,
            "{picked} rescuees picked up from a stock of {units}"
        );
        if let Some(left) = sim.state().team_stock {
            assert!(left <= units, "stock {left}");
        }
    });
    let completed: Vec<_> = r.rounds.iter().filter(|round| round.completed).collect();
    assert!(completed.len() >= 3, "{} rounds", completed.len());
    for round in &completed {
        let both: u32 = round.rescued.iter().sum();
        assert!(both <= units, "round at {} s: {both}", round.start_s);
        assert!(
            round
                .left_because
                .contains(&Some(LeaveCause::ResourcesUsed)),
            "round at {} s left because {:?}",
            round.start_s,
            round.left_because
        );
    }
    // The stock is spent, split between the tasks: most rounds deliver all of it.
    let full = completed
        .iter()
        .filter(|round| round.rescued.iter().sum::<u32>() == units)
        .count();
    assert!(
        full * 2 >= completed.len(),
        "{full} of {} rounds",
        completed.len()
    );
    // Each group drawing on its own members (the default), a round yields far more.
    let own = run_watched(&base(|_| {}), 400.0, |_, _| {});
    let first: u32 = own.rounds[0].rescued.iter().sum();
    assert!(first > 2 * units, "PerRound: {first} in the first round");
}

#[test]
fn resources_refilled_at_rest_are_not_refilled_at_a_round_start() {
    // Low energy: robots rest after a round or two, so refills at rests are seen.
    let run = |stock: ResourceStock| {
        let s = low_energy(45.0, |s| s.mission.resource_stock = stock);
        // Refills, told apart by the phase the robot left on the step of the refill, and
        // members that start a round short of their kind's resources.
        let (mut at_rest, mut at_round_start, mut short_at_start) = (0, 0, 0);
        let mut last: Vec<u32> = Vec::new();
        run_watched(&s, 400.0, |sim, before| {
            if last.is_empty() {
                last = sim.robots().iter().map(|m| m.resources).collect();
            }
            let started = sim
                .events()
                .iter()
                .any(|e| matches!(e.kind, MissionEventKind::RoundStarted { .. }));
            for (id, m) in sim.robots().iter().enumerate() {
                if m.resources > last[id] {
                    match before[id] {
                        Phase::Recharging { .. } => at_rest += 1,
                        _ => at_round_start += 1,
                    }
                }
                last[id] = m.resources;
                let full = sim.scenario().kind_of(id).rescuing_resources;
                short_at_start += usize::from(started && m.task.is_some() && m.resources < full);
            }
        });
        (at_rest, at_round_start, short_at_start)
    };
    let (at_rest, at_round_start, short) = run(ResourceStock::AtRest);
    assert!(at_rest >= 2, "AtRest: {at_rest} refills at rests");
    assert_eq!(at_round_start, 0, "AtRest: refilled at a round start");
    assert!(short >= 1, "AtRest: every member started its rounds full");
    let (at_rest, at_round_start, short) = run(ResourceStock::PerRound);
    assert_eq!(at_rest, 0, "PerRound: refilled at a rest");
    assert!(at_round_start >= 4, "PerRound: {at_round_start} refills");
    assert_eq!(short, 0, "PerRound: a member started a round short");
}
