//! How far bodies overlap in whole paper.ron trials, at the paper's ground speed and at faster
//! ones up to the step limit the scenario check allows (`(v_a + v_b) * dt_s <= min(r_a, r_b)`:
//! 10 m/s for paper.ron's 0.4 m ground robots at `dt_s` 0.02). Contacts and the resolver keep
//! bodies apart, but not exactly: within a step two robots may close by `2 v dt` before Rapier's
//! contacts push them back. The bound checked here, half of that closing distance, is the one
//! `docs/world-model.md` ("Overlap") gives with the measured figures.

use integration_tests::{method, paper, scenario_path};
use usar_sim::mission::Simulation;
use usar_sim::scenario::{self, Locomotion, Positive, Scenario};

/// paper.ron with every ground kind's top speed set to `speed_m_per_s`, validated again (so
/// the step limit is checked).
fn paper_at(speed_m_per_s: f64) -> Scenario {
    let path = scenario_path("paper.ron");
    let src = std::fs::read_to_string(&path).expect("scenarios/paper.ron");
    let mut spec = scenario::parse_spec(&src, &path).expect("paper.ron parses");
    for kind in &mut spec.kinds {
        if kind.locomotion == Locomotion::Ground {
            kind.max_speed_m_per_s = Positive::new(speed_m_per_s).expect("a positive speed");
        }
    }
    spec.validate(&path).expect("within the step limit")
}

/// Largest `World::max_penetration_m` over every step of trial `trial` of method `name`.
fn worst_overlap_m(s: &Scenario, name: &str, trial: u32) -> f64 {
    let mut sim = Simulation::for_trial(s, method(name, s), trial);
    let mut worst = 0.0f64;
    while !sim.is_finished() {
        sim.step().expect("built-in methods do not fail");
        worst = worst.max(sim.world().max_penetration_m());
    }
    worst
}

#[test]
#[ignore = "long: 60 whole paper.ron trials (about 36 s in debug); just test-all, CI in release"]
fn bodies_overlap_by_less_than_half_a_step_of_closing_up_to_the_speed_limit() {
    let dt_s = paper().sim().dt_s.get();
    for speed_m_per_s in [2.5, 5.0, 10.0] {
        let s = paper_at(speed_m_per_s);
        let bound_m = 0.5 * 2.0 * speed_m_per_s * dt_s;
        for name in ["dis", "eng", "hp_dis", "rne"] {
            let worst_m = (0..5)
                .map(|trial| worst_overlap_m(&s, name, trial))
                .fold(0.0, f64::max);
            println!(
                "{speed_m_per_s} m/s {name}: worst overlap {worst_m:.4} m (bound {bound_m} m)"
            );
            assert!(
                worst_m <= bound_m,
                "{speed_m_per_s} m/s, {name}: bodies overlapped by {worst_m} m, more than {bound_m} m"
            );
        }
    }
}
