//! Shared helpers of the cross-crate integration tests in `tests/tests/`.

use rne_core::grouping::{GroupingMethod, method_from_name};
use rne_core::{TrustModel, Weights};
use usar_sim::mission::Simulation;
use usar_sim::scenario::{self, ClampedNormal, Scenario};

/// Path of a file in the workspace's `scenarios/` folder.
pub fn scenario_path(file: &str) -> String {
    format!("{}/../scenarios/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// Path of a file in the test data folder `tests/data/` (scenarios only the tests use).
pub fn data_path(file: &str) -> String {
    format!("{}/data/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// A scenario file at `path`, loaded and validated.
///
/// # Panics
/// If the file does not load (that is a test failure).
pub fn load(path: &str) -> Scenario {
    scenario::load(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `scenarios/paper.ron`, loaded and validated.
///
/// # Panics
/// If the file does not load (that is a test failure).
pub fn paper() -> Scenario {
    scenario::load(scenario_path("paper.ron")).expect("scenarios/paper.ron loads")
}

/// A built-in grouping method by name (`rne`, `dis`, `eng`, `hp_dis`), RNE using the
/// scenario's needs weights.
///
/// # Panics
/// On an unknown name.
pub fn method(name: &str, s: &Scenario) -> Box<dyn GroupingMethod> {
    let model = TrustModel::with_weights(
        Weights::new(s.needs_weights.to_array().to_vec()).expect("weights"),
    );
    method_from_name(name, &model).expect("built-in method")
}

/// A "distribution" that always draws `level_pct` (no spread), for fixed starting levels.
///
/// # Panics
/// If `level_pct` is not in `[0, 100]`.
pub fn fixed(level_pct: f64) -> ClampedNormal {
    ClampedNormal::fixed(level_pct).expect("a level in [0, 100]")
}

/// `(method, trial, hard rescuees, easy rescuees)` of whole trials 0 and 1 of `s` for each
/// built-in grouping method, in the order rne, dis, eng, hp_dis: the golden numbers the
/// tests pin.
///
/// # Panics
/// If a trial fails (built-in methods do not).
pub fn golden_counts(s: &Scenario) -> Vec<(&'static str, u32, u32, u32)> {
    let mut out = Vec::new();
    for name in ["rne", "dis", "eng", "hp_dis"] {
        for trial in 0..2 {
            let r = Simulation::for_trial(s, method(name, s), trial)
                .run_to_end()
                .expect("built-in methods do not fail");
            let task = |n: &str| r.task_id(n).map_or(0, |t| r.rescued[t]);
            out.push((name, trial, task("hard"), task("easy")));
        }
    }
    out
}

/// `(method, trial, rescuees per task in the scenario's task order)` of whole trials `trials`
/// of `s` for each built-in grouping method, in the order rne, dis, eng, hp_dis.
///
/// # Panics
/// If a trial fails (built-in methods do not).
pub fn per_task_counts(
    s: &Scenario,
    trials: std::ops::Range<u32>,
) -> Vec<(&'static str, u32, Vec<u32>)> {
    let mut out = Vec::new();
    for name in ["rne", "dis", "eng", "hp_dis"] {
        for trial in trials.clone() {
            let r = Simulation::for_trial(s, method(name, s), trial)
                .run_to_end()
                .expect("built-in methods do not fail");
            assert_eq!(r.tasks, s.task_names());
            assert_eq!(r.rescued.iter().sum::<u32>(), r.rescued_total());
            out.push((name, trial, r.rescued));
        }
    }
    out
}
