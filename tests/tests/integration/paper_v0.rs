//! `scenarios/paper-v0.ron` is the model before calibration (commit 7382cd6): the same layout
//! and the rules of that commit written out. It must give that commit's numbers exactly, so a
//! reader can compare the calibrated model with it (docs/calibration.md).

use integration_tests::{golden_counts, scenario_path};
use usar_sim::scenario;

/// (method, trial, hard, easy) of paper.ron at commit 7382cd6 (its `mission_golden` table).
const AT_7382CD6: &[(&str, u32, u32, u32)] = &[
    ("rne", 0, 54, 71),
    ("rne", 1, 100, 55),
    ("dis", 0, 72, 55),
    ("dis", 1, 80, 56),
    ("eng", 0, 93, 52),
    ("eng", 1, 99, 55),
    ("hp_dis", 0, 92, 51),
    ("hp_dis", 1, 80, 61),
];

#[test]
fn paper_v0_reproduces_the_uncalibrated_model() {
    let s = scenario::load(scenario_path("paper-v0.ron")).expect("paper-v0.ron loads");
    assert_eq!(golden_counts(&s), AT_7382CD6);
}
