//! Shared helpers of the cross-crate integration tests in `tests/tests/`.

use rne_core::grouping::{GroupingMethod, method_from_name};
use rne_core::{TrustModel, Weights};
use usar_sim::scenario::{self, Scenario};

/// Path of a file in the workspace's `scenarios/` folder.
pub fn scenario_path(file: &str) -> String {
    format!("{}/../scenarios/{file}", env!("CARGO_MANIFEST_DIR"))
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
    let model = TrustModel::with_weights(Weights::new(s.needs_weights.to_vec()).expect("weights"));
    method_from_name(name, &model).expect("built-in method")
}
