//! Helpers for property tests of figures and statistics, shared with the crates above
//! (feature `testing`, for their tests only; always in this crate's own tests): random finite
//! numbers with the extremes as likely as ordinary values, a time limit on drawing, and a
//! hand-made trial.

use std::sync::mpsc;
use std::time::Duration;

use proptest::prelude::*;
use usar_sim::mission::TrialResult;

/// How long all the cases of one figure kind may take together (debug build).
pub const LIMIT: Duration = Duration::from_secs(25);
/// Cases per figure kind.
pub const CASES: u32 = 64;

/// Runs `f` on a thread of its own; fails if it takes longer than [`LIMIT`] (a hung figure
/// leaves its thread behind, and the test fails instead of hanging the suite).
pub fn within(kind: &str, f: impl FnOnce() + Send + 'static) {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(f));
        let _ = tx.send(outcome);
    });
    match rx.recv_timeout(LIMIT) {
        Ok(Ok(())) => {}
        Ok(Err(panic)) => std::panic::resume_unwind(panic),
        Err(_) => panic!("{kind}: not drawn within {} s", LIMIT.as_secs()),
    }
}

/// A finite number, the extremes as likely as ordinary values.
pub fn number() -> impl Strategy<Value = f64> {
    prop_oneof![
        -1e3..1e3f64,
        Just(0.0),
        Just(1e308),
        Just(-1e308),
        Just(f64::MAX),
        Just(f64::MIN),
        Just(1e-300),
        Just(1e16),
        (-1e308..1e308f64),
    ]
}

/// A non-negative finite number (counts, costs).
pub fn amount() -> impl Strategy<Value = f64> {
    number().prop_map(f64::abs)
}

/// The proptest configuration of a figure's property test: [`CASES`] cases, no failure file.
pub fn config() -> ProptestConfig {
    ProptestConfig {
        cases: CASES,
        failure_persistence: None,
        ..ProptestConfig::default()
    }
}

/// A trial of `method` with tasks `hard`, `easy` (in that order, as in paper.ron): `rounds`
/// completed rounds, `(easy, hard)` rescuees, and `energy` and `hp` spent per task as
/// `(easy, hard)` percentages; 600 s long, seed 0, no robots.
pub fn trial(
    method: &str,
    rounds: usize,
    (easy, hard): (u32, u32),
    energy: (f64, f64),
    hp: (f64, f64),
) -> TrialResult {
    TrialResult {
        scenario: "t".into(),
        method: method.into(),
        trial: 0,
        seed: 0,
        duration_s: 600.0,
        tasks: vec!["hard".into(), "easy".into()],
        rescued: vec![hard, easy],
        energy_spent_pct: vec![energy.1, energy.0],
        hp_lost_pct: vec![hp.1, hp.0],
        rounds: vec![
            usar_sim::mission::RoundRecord {
                start_s: 0.0,
                end_s: 1.0,
                completed: true,
                groups: vec![vec![], vec![]],
                rescued: vec![0, 0],
                ..Default::default()
            };
            rounds
        ],
        robots: vec![],
    }
}
