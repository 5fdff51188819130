//! Golden rescuee counts of paper.ron: the exact (hard, easy) numbers each built-in grouping
//! method gets in trials 0 and 1 (seeds `trial_seed(paper.sim.seed, k)`).
//!
//! These pin the whole model: any change to the world, the mission rules, the grouping methods
//! or `scenarios/paper.ron` that moves a number fails this test. When such a change is made
//! on purpose, regenerate the table with
//!
//! ```sh
//! cargo test -p integration-tests --test integration mission_golden -- --nocapture
//! ```
//!
//! which prints the new table in this file's format on failure, then paste it below and say
//! in the commit message why the numbers moved.

use integration_tests::{golden_counts, paper};

/// (method, trial, hard, easy).
pub(crate) const GOLDEN: &[(&str, u32, u32, u32)] = &[
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
fn paper_rescuee_counts_are_pinned() {
    let actual = golden_counts(&paper());
    if actual != GOLDEN {
        println!("pub(crate) const GOLDEN: &[(&str, u32, u32, u32)] = &[");
        for (m, t, h, e) in &actual {
            println!("    ({m:?}, {t}, {h}, {e}),");
        }
        println!("];");
    }
    assert_eq!(
        actual, GOLDEN,
        "paper.ron rescuee counts moved; see this file's docs"
    );
}
