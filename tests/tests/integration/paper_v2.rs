//! `scenarios/paper-v2.ron` is paper.ron as calibrated on the authors' clock (round timer, rests
//! in the slack, costs per frame) against all eighteen targets, before the team's stock of
//! rescuing resources (docs/calibration.md). It must give that model's numbers exactly, so a
//! reader can compare it with today's paper.ron.

use integration_tests::{golden_counts, scenario_path};
use usar_sim::scenario;

/// (method, trial, hard, easy) of paper.ron before the team stock (its `mission_golden` table
/// then).
const PAPER_V2: &[(&str, u32, u32, u32)] = &[
    ("rne", 0, 72, 81),
    ("rne", 1, 61, 85),
    ("dis", 0, 56, 80),
    ("dis", 1, 65, 64),
    ("eng", 0, 55, 62),
    ("eng", 1, 63, 72),
    ("hp_dis", 0, 74, 67),
    ("hp_dis", 1, 67, 76),
];

#[test]
fn paper_v2_reproduces_the_model_calibrated_on_the_authors_clock() {
    let s = scenario::load(scenario_path("paper-v2.ron")).expect("paper-v2.ron loads");
    assert_eq!(golden_counts(&s), PAPER_V2);
}
