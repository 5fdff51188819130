//! Helpers shared by the world tests: the shipped corridor and debris-crossing scenarios.

#![allow(dead_code)] // each test file uses a subset

use usar_sim::scenario::{self, PointM, Scenario};

/// `scenarios/corridor.ron`.
pub const CORRIDOR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/corridor.ron");
/// `scenarios/debris-crossing.ron`.
pub const DEBRIS_CROSSING: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenarios/debris-crossing.ron"
);
/// Distance between neighbouring goal slots at each end of the corridor, metres (see
/// `corridor.ron`).
pub const SLOT_STEP_M: f64 = 1.5;

/// `scenarios/corridor.ron` with `per_side` robots of each kind (all on their kind's task).
pub fn corridor(per_side: usize) -> Scenario {
    let src = std::fs::read_to_string(CORRIDOR).expect("scenarios/corridor.ron");
    let mut spec = scenario::parse_spec(&src, CORRIDOR).unwrap_or_else(|e| panic!("{e}"));
    spec.kinds[0].count = per_side;
    spec.kinds[0].quota.0.insert("easy".into(), per_side);
    spec.kinds[1].count = per_side;
    spec.kinds[1].quota.0.insert("hard".into(), per_side);
    spec.validate(&format!("corridor.ron ({per_side} per end)"))
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Swap goals: the `k`-th east-bound robot (kind 0, the easy task at the east end) drives to
/// the easy goal moved `k` slots back towards the middle, the `k`-th west-bound robot (kind 1)
/// likewise to the hard goal, so the front robot of a row takes the deepest slot and arrivals
/// never block later ones.
pub fn swap_goals(s: &Scenario) -> Vec<PointM> {
    let task = |name: &str| &s.tasks()[s.task_id(name).expect("corridor has easy and hard")];
    let (easy, hard) = (task("easy").goal, task("hard").goal);
    let mut seen = [0usize; 2];
    s.robots()
        .iter()
        .map(|r| {
            let k = seen[r.kind] as f64;
            seen[r.kind] += 1;
            match r.kind {
                0 => PointM::new(easy.x - SLOT_STEP_M * k, easy.y),
                _ => PointM::new(hard.x + SLOT_STEP_M * k, hard.y),
            }
        })
        .collect()
}

/// `scenarios/debris-crossing.ron`: a ground robot (id 0) and an aerial robot (id 1) whose
/// straight lines to their goals cross one debris block (`debris[0]`).
pub fn debris_crossing() -> Scenario {
    scenario::load(DEBRIS_CROSSING).unwrap_or_else(|e| panic!("{e}"))
}
