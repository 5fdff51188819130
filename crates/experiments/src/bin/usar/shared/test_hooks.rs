//! The hidden `usar sweep` options its integration tests use, built on the library's
//! [`SweepHooks`]: `--fail-trial METHOD:K` makes a trial panic half-way (one failing trial
//! must not take the sweep down) and `--stop-after N` exits abruptly once N trials are
//! journaled (a killed sweep must resume). They live in the binary, not the library.

use std::sync::Arc;

use usar_sim::mission::{Simulation, StepObserver};
use usar_sweep::sweep::{SweepHooks, TrialKey};

/// Exit status of a sweep stopped by `--stop-after`.
pub const STOP_EXIT_CODE: i32 = 75;

/// Hooks that fail the trials `fail` names (method's display name, trial index) half-way and
/// exit the process with [`STOP_EXIT_CODE`] once `stop_after` trials are journaled.
pub fn test_hooks(fail: Vec<(String, u32)>, stop_after: Option<usize>) -> SweepHooks {
    let trial_observer = (!fail.is_empty()).then(|| {
        Arc::new(move |key: &TrialKey| {
            fail.iter()
                .any(|(m, k)| *m == key.method && *k == key.trial)
                .then(|| Box::new(FailHalfWay(key.clone())) as Box<dyn StepObserver>)
        }) as _
    });
    let on_journaled = stop_after.map(|limit| {
        Arc::new(move |_: &_, n: usize| {
            if n >= limit {
                crate::shared::stderr_lines::warn(format!("--stop-after {n}: stopping abruptly"));
                std::process::exit(STOP_EXIT_CODE);
            }
        }) as _
    });
    SweepHooks {
        trial_observer,
        on_journaled,
        stop: None,
    }
}

/// Panics once half of the trial's steps are done.
struct FailHalfWay(TrialKey);

impl StepObserver for FailHalfWay {
    fn on_step(&mut self, sim: &Simulation) {
        let (done, total) = sim.progress();
        if done * 2 >= total {
            panic!(
                "failing on purpose (--fail-trial {}:{})",
                self.0.method, self.0.trial
            );
        }
    }
}
