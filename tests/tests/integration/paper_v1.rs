//! `scenarios/paper-v1.ron` is paper.ron as calibrated against the nine pooled means of the
//! authors' sheet, before the trial-to-trial spread was a target (docs/calibration.md). It must
//! give that model's numbers exactly, so a reader can compare it with today's paper.ron.

use integration_tests::{golden_counts, scenario_path};
use usar_sim::scenario;

/// (method, trial, hard, easy) of paper.ron before the spread calibration (its
/// `mission_golden` table then).
const PAPER_V1: &[(&str, u32, u32, u32)] = &[
    ("rne", 0, 40, 69),
    ("rne", 1, 61, 68),
    ("dis", 0, 37, 80),
    ("dis", 1, 46, 81),
    ("eng", 0, 84, 71),
    ("eng", 1, 56, 69),
    ("hp_dis", 0, 75, 82),
    ("hp_dis", 1, 81, 84),
];

#[test]
fn paper_v1_reproduces_the_model_calibrated_to_the_pooled_means() {
    let s = scenario::load(scenario_path("paper-v1.ron")).expect("paper-v1.ron loads");
    assert_eq!(golden_counts(&s), PAPER_V1);
}
