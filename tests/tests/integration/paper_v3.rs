//! `scenarios/paper-v3.ron` is paper.ron's model with one stock of rescuing resources per round
//! for the whole team and a 20 s search budget (docs/calibration.md, "A rule that couples the
//! tasks"). While paper.ron has this model it gives `mission_golden`'s counts; when paper.ron
//! next moves, that table is copied here so that paper-v3.ron keeps them.

use integration_tests::{golden_counts, scenario_path};
use usar_sim::scenario;

use super::mission_golden::GOLDEN;

#[test]
fn paper_v3_reproduces_the_model_with_a_team_stock() {
    let s = scenario::load(scenario_path("paper-v3.ron")).expect("paper-v3.ron loads");
    assert_eq!(golden_counts(&s), GOLDEN);
}
