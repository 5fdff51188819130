//! The calibrated paper mission: a whole paper sweep (4 methods x 10 trials x 600 s of
//! scenarios/paper.ron, the sweep's default seeds) lands inside every band of the calibration
//! targets (scenarios/paper-targets.ron, experiments::calibration::paper_targets,
//! docs/calibration.md), pooled over all methods.

use experiments::calibration::check;
use integration_tests::{method, paper};
use rayon::prelude::*;
use usar_sim::mission::{Simulation, TrialResult};

#[test]
fn a_paper_sweep_lies_inside_every_calibration_band() {
    let s = paper();
    let jobs: Vec<(&str, u32)> = ["rne", "dis", "eng", "hp_dis"]
        .into_iter()
        .flat_map(|m| (0..10).map(move |k| (m, k)))
        .collect();
    let results: Vec<TrialResult> = jobs
        .par_iter()
        .map(|&(name, k)| {
            Simulation::for_trial(&s, method(name, &s), k)
                .run_to_end()
                .expect("built-in methods do not fail")
        })
        .collect();
    let checked = check(&results);
    let table: Vec<String> = checked
        .iter()
        .map(|(t, x)| {
            let mark = if t.holds(*x) { "ok" } else { "OUT" };
            format!("{}: {x:.3} (target {}) {mark}", t.name, t.describe())
        })
        .collect();
    assert!(
        checked.iter().all(|(t, x)| t.holds(*x)),
        "pooled statistics of the paper sweep:\n{}",
        table.join("\n")
    );
}
