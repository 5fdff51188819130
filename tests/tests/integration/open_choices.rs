//! The switches added for the rules the paper leaves open (`usar_sim::scenario::choices`,
//! docs/mission-model.md): each alternative's behaviour on variants of paper-v1.ron (the model before the authors' clock). The older
//! switches (radiation overlap and falloff, round start, refresh, load on leave, quotas) are
//! tested in `mission_rules.rs`.

use integration_tests::{fixed, method, paper_v1, paper_v1_with};
use usar_sim::mission::{MissionEventKind, Phase, Simulation, draw_initial_levels, hp_factor};
use usar_sim::scenario::{
    ClampedNormal, CollisionPriority, HpEffect, LeaveWhenLow, OutsideRange, RescuedAt, Role,
    Scenario, SearchClock,
};

/// The highest speed robot 0 (a carrier) reaches in the first `seconds` of trial 0 of `s`.
fn top_speed(s: &Scenario, seconds: f64) -> f64 {
    let mut sim = Simulation::for_trial(s, method("dis", s), 0);
    let mut top: f64 = 0.0;
    while sim.time_s() < seconds {
        sim.step().unwrap();
        top = top.max(sim.world().robot(0).velocity.norm());
    }
    top
}

#[test]
fn hp_scales_speed_linearly_by_a_threshold_or_not_at_all() {
    let threshold = HpEffect::Threshold {
        below_pct: 50.0.try_into().unwrap(),
        factor: 0.5.try_into().unwrap(),
    };
    for (effect, hp, expected) in [
        (HpEffect::Linear, 40.0, 0.4),
        (threshold, 40.0, 0.5),
        (threshold, 60.0, 1.0),
        (HpEffect::NoEffect, 40.0, 1.0),
    ] {
        let s = paper_v1_with(|s| {
            s.mission.hp_effect = effect;
            s.mission.min_hp_factor = 0.0.try_into().unwrap();
            s.mission.initial_hp = fixed(hp);
            s.mission.initial_energy = fixed(100.0);
        });
        assert!((hp_factor(s.mission(), hp) - expected).abs() < 1e-12);
        let v_max = s.kind_of(0).max_speed_m_per_s;
        let top = top_speed(&s, 6.0);
        assert!(
            (top - expected * v_max).abs() < 0.02 * v_max,
            "{effect:?} at {hp} % HP: top speed {top}, expected {}",
            expected * v_max
        );
    }
}

/// Trial 0 of paper.ron with every robot just above the energy threshold: each falls below it
/// during its first trip. Returns, per `LeftForRest` event, the leaving robot's phase just
/// before it left.
fn phases_when_leaving(rule: LeaveWhenLow) -> Vec<Phase> {
    let s = paper_v1_with(|s| {
        s.mission.initial_energy = fixed(33.0);
        s.mission.initial_hp = fixed(90.0);
        s.mission.leave_when_low = rule;
    });
    let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
        .with_duration_s(200.0)
        .unwrap();
    let mut out = Vec::new();
    while !sim.is_finished() {
        let before: Vec<Phase> = sim.robots().iter().map(|r| r.phase).collect();
        sim.step().unwrap();
        for e in sim.events() {
            if let (MissionEventKind::LeftForRest { low_energy, .. }, Some(id)) = (e.kind, e.robot)
            {
                assert!(low_energy);
                out.push(before[id]);
            }
        }
    }
    out
}

#[test]
fn a_low_robot_leaves_at_once_or_after_its_trip() {
    let at_once = phases_when_leaving(LeaveWhenLow::AtOnce);
    assert!(
        at_once
            .iter()
            .any(|p| matches!(p, Phase::ToSearchArea | Phase::Searching | Phase::Waiting)),
        "AtOnce: some robot leaves mid-trip: {at_once:?}"
    );
    let after = phases_when_leaving(LeaveWhenLow::AfterTrip);
    assert!(after.len() >= 6, "AfterTrip: robots leave: {after:?}");
    // A robot leaves from its start position: on the step it arrives there (the phase before
    // that step was ToStart) or while it waits (AtStart).
    assert!(
        after
            .iter()
            .all(|p| matches!(p, Phase::AtStart | Phase::ToStart)),
        "AfterTrip: every robot finishes its trip first: {after:?}"
    );
}

#[test]
fn a_robot_below_its_threshold_at_the_start_leaves_at_once_under_both_rules() {
    for rule in [LeaveWhenLow::AtOnce, LeaveWhenLow::AfterTrip] {
        let s = paper_v1_with(|s| {
            s.mission.initial_energy = fixed(20.0);
            s.mission.leave_when_low = rule;
        });
        let mut sim = Simulation::for_trial(&s, method("rne", &s), 0);
        sim.step().unwrap();
        assert!(
            sim.robots().iter().all(|r| r.is_resting()),
            "{rule:?}: {:?}",
            sim.robots().iter().map(|r| r.phase).collect::<Vec<_>>()
        );
    }
}

#[test]
fn rescues_count_at_the_drop_off_or_at_the_pick_up() {
    // The counting rule changes no decision: both runs of a trial are the same trial.
    let run = |at: RescuedAt, trial: u32| {
        let s = paper_v1_with(|s| {
            s.mission.rescued_at = at;
        });
        Simulation::for_trial(&s, method("eng", &s), trial)
            .with_duration_s(250.0)
            .unwrap()
            .run_to_end()
            .unwrap()
    };
    let mut lost_loads = 0;
    for trial in 0..4 {
        let (drop_off, pick_up) = (
            run(RescuedAt::DropOff, trial),
            run(RescuedAt::PickUp, trial),
        );
        let delivered: u32 = drop_off.robots.iter().map(|r| r.delivered).sum();
        let picked: u32 = pick_up.robots.iter().map(|r| r.picked_up).sum();
        assert_eq!(drop_off.rescued.iter().sum::<u32>(), delivered);
        assert_eq!(pick_up.rescued.iter().sum::<u32>(), picked);
        assert_eq!(drop_off.robots, pick_up.robots);
        for (a, b) in drop_off.rounds.iter().zip(&pick_up.rounds) {
            assert_eq!(
                (a.start_s, a.end_s, &a.groups),
                (b.start_s, b.end_s, &b.groups)
            );
        }
        // Picked up but never delivered: loads abandoned, or still carried at the end.
        lost_loads += picked - delivered;
    }
    assert!(
        lost_loads > 0,
        "no trial lost a load: the test shows nothing"
    );
}

#[test]
fn the_collision_priority_key_is_energy_hp_or_nothing() {
    for priority in [
        CollisionPriority::LowestEnergy,
        CollisionPriority::LowestHp,
        CollisionPriority::RobotId,
    ] {
        let s = paper_v1_with(|s| {
            s.collision.priority = priority;
        });
        let mut sim = Simulation::for_trial(&s, method("dis", &s), 3);
        for _ in 0..10 {
            sim.step().unwrap();
        }
        for r in sim.robots() {
            let expected = match priority {
                CollisionPriority::LowestEnergy => r.energy_pct,
                CollisionPriority::LowestHp => r.hp_pct,
                CollisionPriority::RobotId => 0.0,
            };
            // The key is set before the step from the levels then: within one step's costs.
            let key = sim.world().robot(r.id).priority_key;
            assert!(
                (key - expected).abs() < 0.01,
                "{priority:?}: {key} vs {expected}"
            );
        }
    }
}

#[test]
fn initial_draws_outside_the_range_are_clamped_or_drawn_again() {
    let s = paper_v1();
    let base = s.mission().initial_energy;
    let narrow = |outside_range| ClampedNormal {
        min_pct: 70.0.try_into().unwrap(),
        max_pct: 90.0.try_into().unwrap(),
        outside_range,
        ..base
    };
    let levels = |s: &Scenario| -> Vec<f64> {
        (0..200)
            .flat_map(|seed| draw_initial_levels(s, seed))
            .map(|l| l.energy_pct)
            .collect()
    };
    let with = |rule| {
        s.edit(|s| s.mission.initial_energy = narrow(rule))
            .expect("a valid edit")
    };
    let clamped = levels(&with(OutsideRange::Clamp));
    let redrawn = levels(&with(OutsideRange::Redraw));
    let at_bounds = |xs: &[f64]| xs.iter().filter(|&&x| x == 70.0 || x == 90.0).count();
    // N(80, 20) in [70, 90]: 38 % of the draws are inside; clamping piles the rest on the
    // bounds, drawing again never lands exactly on them.
    assert!(
        at_bounds(&clamped) > clamped.len() / 2,
        "{}",
        at_bounds(&clamped)
    );
    assert_eq!(at_bounds(&redrawn), 0);
    assert!(redrawn.iter().all(|x| (70.0..=90.0).contains(x)));
    // A truncated normal keeps the mean here (symmetric range around it).
    let mean = redrawn.iter().sum::<f64>() / redrawn.len() as f64;
    assert!((mean - 80.0).abs() < 1.0, "{mean}");
}

/// The time (seconds since the round's start) at which each task's ground members turn for the
/// drop-off in the first round of trial 0 of `s`, and when its last member (observer included)
/// entered the search area.
fn first_trip(s: &Scenario) -> Vec<(Option<f64>, Option<f64>)> {
    let mut sim = Simulation::for_trial(s, method("dis", s), 0)
        .with_duration_s(400.0)
        .unwrap();
    let k = s.tasks().len();
    let mut out = vec![(None, None); k];
    while !sim.is_finished() && sim.rounds().len() < 2 {
        sim.step().unwrap();
        if std::env::var("DBG").is_ok() && (sim.time_s() * 50.0).round() as i64 % 100 == 0 {
            eprintln!(
                "{} {:?}",
                sim.time_s(),
                sim.robots()
                    .iter()
                    .map(|r| (r.task, r.reached_area, r.phase))
                    .collect::<Vec<_>>()
            );
        }
        let now = sim.time_s();
        for (t, (turned, assembled)) in out.iter_mut().enumerate() {
            let members: Vec<_> = sim.robots().iter().filter(|r| r.task == Some(t)).collect();
            if assembled.is_none() && !members.is_empty() && members.iter().all(|r| r.reached_area)
            {
                *assembled = Some(now);
            }
            let ground_turned = members
                .iter()
                .filter(|r| s.kind_of(r.id).role != Role::Observer)
                .any(|r| r.phase == Phase::ToDropOff);
            if turned.is_none() && ground_turned {
                *turned = Some(now);
            }
        }
    }
    out
}

#[test]
fn the_search_clock_starts_at_the_round_start_or_when_the_group_is_assembled() {
    let dt = paper_v1().sim().dt_s.get();
    // Round start: a budget shorter than the way out turns every group before it arrives.
    let s = paper_v1_with(|s| {
        s.mission.search_clock = SearchClock::RoundStart;
        s.mission.search_time_budget_s = Some(10.0.try_into().unwrap());
    });
    for (t, (turned, assembled)) in first_trip(&s).into_iter().enumerate() {
        let turned = turned.expect("the group turns");
        assert!(
            (turned - 10.0).abs() <= 2.0 * dt,
            "task {t}: turned at {turned} s"
        );
        assert!(assembled.is_none(), "task {t}: no group gets there in 10 s");
    }
    // Last arrival: the budget runs from the moment the whole group is in the area.
    let s = paper_v1_with(|s| {
        s.mission.search_clock = SearchClock::LastArrival;
        s.mission.search_time_budget_s = Some(8.0.try_into().unwrap());
        s.mission.pickup_s = 5.0.try_into().unwrap();
    });
    for (t, (turned, assembled)) in first_trip(&s).into_iter().enumerate() {
        let (turned, assembled) = (turned.expect("turns"), assembled.expect("assembles"));
        assert!(
            (turned - (assembled + 8.0)).abs() <= 2.0 * dt,
            "task {t}: assembled at {assembled} s, turned at {turned} s"
        );
    }
}

#[test]
fn per_step_rates_do_not_depend_on_the_step_length() {
    // One radiation zone covers the whole arena: the HP lost in the first 4 s is the same at 50
    // and 100 steps per second, and so, up to the first steps of the motion, is the energy
    // spent per moving step.
    let run = |dt_s: f64| {
        let s = paper_v1_with(|s| {
            s.sim.dt_s = dt_s.try_into().unwrap();
            s.mission.energy_pct_per_m = 0.0.try_into().unwrap();
            s.mission.energy_pct_per_moving_step = 0.01.try_into().unwrap();
            s.mission.hp_pct_per_step_in_radiation = 0.01.try_into().unwrap();
            s.mission.initial_energy = fixed(100.0);
            s.mission.initial_hp = fixed(100.0);
            // [10, 70] x [0, 60]: every robot for the first 4 s (a zone lies inside the arena).
            s.radiation_zones = vec![usar_sim::scenario::RadiationZoneSpec {
                center_m: [40.0, 30.0],
                radius_m: 30.0.try_into().unwrap(),
                dose_rate_factor: 1.0.try_into().unwrap(),
            }];
        });
        let mut sim = Simulation::for_trial(&s, method("dis", &s), 0)
            .with_duration_s(4.0)
            .unwrap();
        let r = sim.run_to_end().unwrap();
        let hp: f64 = r.robots.iter().map(|m| m.hp_lost_pct).sum();
        let energy: f64 = r.robots.iter().map(|m| m.energy_spent_pct).sum();
        (hp, energy)
    };
    let (hp_50, energy_50) = run(0.02);
    let (hp_100, energy_100) = run(0.01);
    // 12 robots x 4 s x 0.01 % per 1/50 s = 0.5 % per second each: 24 %.
    assert!((hp_50 - 24.0).abs() < 1e-9, "{hp_50}");
    assert!((hp_100 - 24.0).abs() < 1e-9, "{hp_100}");
    // Energy: 0.5 % per second of moving; the robots start at rest, so a few steps differ.
    assert!(
        (energy_50 - energy_100).abs() < 0.05 * energy_50,
        "{energy_50} vs {energy_100}"
    );
    assert!(energy_50 > 20.0, "{energy_50}");
}
