//! `scenarios/paper-v3.ron` is paper.ron's model with one stock of rescuing resources per round
//! for the whole team and a 20 s search budget (docs/calibration.md, "A rule that couples the
//! tasks"). It must give the same numbers as paper.ron (`mission_golden`) while paper.ron has
//! this model, and keep them afterwards.

use integration_tests::{golden_counts, scenario_path};
use usar_sim::scenario;

/// (method, trial, hard, easy) of paper-v3.ron: `mission_golden`'s table of paper.ron.
const PAPER_V3: &[(&str, u32, u32, u32)] = &[
    ("rne", 0, 69, 84),
    ("rne", 1, 64, 88),
    ("dis", 0, 57, 88),
    ("dis", 1, 66, 82),
    ("eng", 0, 64, 77),
    ("eng", 1, 70, 80),
    ("hp_dis", 0, 80, 74),
    ("hp_dis", 1, 73, 80),
];

#[test]
fn paper_v3_reproduces_the_model_with_a_team_stock() {
    let s = scenario::load(scenario_path("paper-v3.ron")).expect("paper-v3.ron loads");
    assert_eq!(golden_counts(&s), PAPER_V3);
}
