//! Golden rescuee counts of paper.ron: the exact (hard, easy) numbers each built-in grouping
//! method gets in trials 0 and 1 (seeds `trial_seed(paper.sim.seed, k)`).
//!
//! These pin the whole model: any change to the world, the mission rules, the grouping methods
//! or `scenarios/paper.ron` that moves a number fails this test. When such a change is made
//! on purpose, regenerate the table with
//!
//! ```sh
//! cargo test -p integration-tests --test mission_golden -- --nocapture
//! ```
//!
//! which prints the new table in this file's format on failure, then paste it below and say
//! in the commit message why the numbers moved.

use integration_tests::{method, paper};
use usar_sim::mission::Simulation;

/// (method, trial, hard, easy).
const GOLDEN: &[(&str, u32, u32, u32)] = &[
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
fn paper_rescuee_counts_are_pinned() {
    let s = paper();
    let mut actual = Vec::new();
    for name in ["rne", "dis", "eng", "hp_dis"] {
        for trial in 0..2 {
            let r = Simulation::for_trial(&s, method(name, &s), trial)
                .run_to_end()
                .unwrap();
            actual.push((name, trial, r.rescued.hard, r.rescued.easy));
        }
    }
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
