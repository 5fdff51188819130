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
const GOLDEN: &[(&str, u32, u32, u32)] = &[
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
fn paper_rescuee_counts_are_pinned() {
    let actual = golden_counts(&paper());
    if actual != GOLDEN {
        println!("const GOLDEN: &[(&str, u32, u32, u32)] = &[");
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
