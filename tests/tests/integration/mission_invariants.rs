//! Invariants of the mission that hold whatever the golden numbers are: checked at every step
//! of a full 600 s paper.ron trial for each built-in grouping method, and with a control
//! period of 0.1 s (`sim.control_period_s`) for two of them.

use integration_tests::{method, paper, paper_with};
use usar_sim::mission::{Phase, RescueeStatus, Simulation};
use usar_sim::scenario::{Positive, RestAt, Scenario};
use usar_sim::world::ControlClock;

const EPS: f64 = 1e-9;

/// paper.ron with the robots deciding every 0.1 s (five steps).
fn paper_at_10_hz() -> Scenario {
    let s = paper_with(|s| s.sim.control_period_s = Some(Positive::new(0.1).expect("positive")));
    assert_eq!(ControlClock::of(s.sim()).period_steps(), 5);
    s
}

fn check_method(name: &str) {
    check(name, &paper());
}

/// How far from its start a robot recharging there (`mission.rest_at: OwnStart`) may stand
/// beyond the goal tolerance: pushes by neighbours while it stands still, metres.
const OWN_START_PUSH_M: f64 = 0.2;

fn check(name: &str, s: &Scenario) {
    let s = s.clone();
    let mut sim = Simulation::for_trial(&s, method(name, &s), 0);
    let mut prev: Vec<(f64, f64, Phase)> = sim
        .robots()
        .iter()
        .map(|r| (r.energy_pct, r.hp_pct, r.phase))
        .collect();
    let mut rounds_seen = 0;
    let dt_s = s.sim().dt_s.get();
    while !sim.is_finished() {
        // The mission decides before a control step, and reviews phases after the step before
        // a control step and after the last.
        let decided = sim.clock().is_control_step(sim.world().steps());
        sim.step().expect("built-in methods do not fail");
        let world = sim.world();
        let reviewed = decided || sim.clock().is_control_step(world.steps()) || sim.is_finished();
        for r in sim.robots() {
            let kind = s.kind_of(r.id);
            let w = world.robot(r.id);
            let (e0, h0, phase0) = prev[r.id];
            assert!(
                (0.0..=100.0).contains(&r.energy_pct),
                "{name}: energy {}",
                r.energy_pct
            );
            assert!((0.0..=100.0).contains(&r.hp_pct), "{name}: hp {}", r.hp_pct);
            assert!(
                r.capacity_free <= kind.carrying_capacity,
                "{name}: capacity"
            );
            assert!(r.resources <= kind.rescuing_resources, "{name}: resources");
            assert!(
                r.load.len() as u32 + r.capacity_free <= kind.carrying_capacity,
                "{name}: robot {} carries more than its capacity",
                r.id
            );
            // Energy falls only on moving steps, by exactly the scenario's rates per moving
            // step (on its cost clock) and per metre moved (or to 0).
            if r.energy_pct < e0 - EPS {
                assert!(
                    w.moved_this_step,
                    "{name}: robot {} lost energy standing still",
                    r.id
                );
                let m = s.mission();
                let per_step = m.per_step_on_cost_clock(m.energy_pct_per_moving_step, dt_s);
                let expected = (per_step + m.energy_pct_per_m.get() * w.step_distance_m).min(e0);
                assert!(
                    (e0 - r.energy_pct - expected).abs() < 1e-9,
                    "{name}: energy rate"
                );
            }
            // Every moving step costs energy, whatever the control period (unless a recharge
            // ended this step or the robot had none left).
            if w.moved_this_step && e0 > EPS && r.energy_pct <= e0 + EPS {
                assert!(
                    r.energy_pct < e0 - EPS,
                    "{name}: robot {} moved for free",
                    r.id
                );
            }
            assert!(
                reviewed || r.phase == phase0,
                "{name}: robot {} changed phase between control steps",
                r.id
            );
            // Energy rises only when a recharge ends, where `mission.rest_at` says.
            if r.energy_pct > e0 + EPS {
                assert!(
                    matches!(phase0, Phase::Recharging { .. }),
                    "{name}: energy rose"
                );
                let at_rest = match s.mission().rest_at {
                    RestAt::RestStation => s.in_rest_station(&w.position),
                    // Within the goal tolerance of its start, plus what a neighbour's push
                    // may move a robot standing still (metres).
                    RestAt::OwnStart => {
                        let start = s.robots()[r.id].start_in_world;
                        let d = (w.position - start).norm();
                        d <= s.navigation().waypoint_tolerance_m.get() + OWN_START_PUSH_M
                    }
                };
                assert!(
                    at_rest,
                    "{name}: robot {} recharged away from where it rests",
                    r.id
                );
                assert_eq!(r.energy_pct, 100.0);
            }
            // HP falls only inside radiation zones, at the paper's rate times the dose factor.
            if r.hp_pct < h0 - EPS {
                let factor = world.radiation_factor(r.id);
                assert!(
                    factor > 0.0,
                    "{name}: robot {} lost HP outside radiation",
                    r.id
                );
                let m = s.mission();
                let per_step = m.per_step_on_cost_clock(m.hp_pct_per_step_in_radiation, dt_s);
                let expected = (per_step * factor).min(h0);
                assert!((h0 - r.hp_pct - expected).abs() < 1e-9, "{name}: HP rate");
            }
            if r.hp_pct > h0 + EPS {
                assert!(
                    matches!(phase0, Phase::Recharging { .. }),
                    "{name}: HP rose"
                );
            }
        }
        // A round ends only with every member of its groups back at its start position (or
        // away at the rest station, having left its group).
        let completed = sim.rounds().iter().filter(|r| r.completed).count();
        if completed > rounds_seen {
            rounds_seen = completed;
            let closed = sim
                .rounds()
                .iter()
                .rev()
                .find(|r| r.completed)
                .expect("completed");
            for group in &closed.groups {
                for &id in group {
                    let r = &sim.robots()[id];
                    let gap = (world.robot(id).position - s.robots()[id].start_in_world).norm();
                    assert!(
                        r.is_resting()
                            || (r.phase == Phase::AtStart
                                && gap <= s.navigation().waypoint_tolerance_m.get() + 1e-6),
                        "{name}: a round closed with robot {id} away ({:?}, {gap} m)",
                        r.phase
                    );
                }
            }
        }
        prev = sim
            .robots()
            .iter()
            .map(|r| (r.energy_pct, r.hp_pct, r.phase))
            .collect();
    }
    let result = sim.result();
    // Every delivered rescuee was picked up exactly once; nobody was picked up twice.
    for (t, task) in s.tasks().iter().enumerate() {
        let field = sim.rescuees(t);
        let mut delivered = 0;
        for i in 0..field.len() {
            assert!(field.pickups(i) <= 1, "{name}: rescuee {i} picked up twice");
            if field.status(i) == RescueeStatus::Delivered {
                assert_eq!(field.pickups(i), 1, "{name}: delivered without pick-up");
                delivered += 1;
            }
        }
        assert_eq!(
            delivered, result.rescued[t],
            "{name}: task {} count",
            task.name
        );
    }
    let delivered: u32 = result.robots.iter().map(|m| m.delivered).sum();
    assert_eq!(delivered, result.rescued_total());
    let per_round: u32 = result
        .rounds
        .iter()
        .map(|r| r.rescued.iter().sum::<u32>())
        .sum();
    assert_eq!(per_round, result.rescued_total());
    assert!(
        result.rescued_total() > 0,
        "{name}: a 600 s trial rescued nobody"
    );
    assert!(
        result.rounds.len() >= 2,
        "{name}: fewer than two rounds in 600 s"
    );
}

#[test]
fn invariants_rne() {
    check_method("rne");
}

#[test]
fn invariants_dis() {
    check_method("dis");
}

#[test]
fn invariants_eng() {
    check_method("eng");
}

#[test]
fn invariants_hp_dis() {
    check_method("hp_dis");
}

#[test]
fn invariants_rne_with_a_control_period() {
    check("rne", &paper_at_10_hz());
}

#[test]
fn invariants_dis_with_a_control_period() {
    check("dis", &paper_at_10_hz());
}

#[test]
fn invariants_rne_recharging_at_the_own_start() {
    let s = paper_with(|s| s.mission.rest_at = RestAt::OwnStart);
    check("rne", &s);
    // The trial checked has recharges to check.
    let r = Simulation::for_trial(&s, method("rne", &s), 0)
        .run_to_end()
        .unwrap();
    let recharges: u32 = r.robots.iter().map(|x| x.recharges).sum();
    assert!(recharges > 0, "no robot recharged");
}
