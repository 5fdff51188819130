//! A stochastic grouping method that stays reproducible in a parallel sweep: `random` deals
//! each kind's robots to the tasks at random, meeting the quotas, with random numbers drawn
//! from the trial's own stream ([`TrialContext::rng`]). The same sweep gives the same results
//! on any number of threads, and trial `k` gets the same draws in every run.
//!
//! This example runs RNE against `random` twice on two threads over `scenarios/paper.ron` and
//! checks that both runs agree; `crates/experiments/tests/integration/sweep_custom.rs` tests the same
//! method. Copy [`RandomQuotas`] and [`factory`] into your own crate as they are (`rand` is
//! the one `usar_sweep::sweep` re-exports).
//!
//! ```sh
//! cargo run --release -p usar-sweep --example random_method -- [TRIALS]
//! ```

use std::cell::RefCell;
use std::path::PathBuf;

/// What `main` returns: any error, printed by the runtime.
type Result<T> = std::result::Result<T, Box<dyn std::error::Error>>;

use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
use usar_sweep::sweep::rand::seq::SliceRandom;
use usar_sweep::sweep::{ChaCha8Rng, MethodFactory, SweepConfig, TrialContext, run_sweep};

/// Deals each kind's robots to the tasks in a random order, each task taking its quota.
///
/// The generator sits in a `RefCell`: `assign` takes `&self`, and a method only has to be
/// `Send` (a trial owns its method and no other thread calls it), so no `Mutex` is needed.
/// It is taken from the trial's context when the method is built, once per trial, and
/// advances from round to round within the trial.
pub struct RandomQuotas {
    rng: RefCell<ChaCha8Rng>,
}

impl RandomQuotas {
    /// The method for the trial `ctx`, drawing from `ctx.rng()`.
    pub fn new(ctx: &TrialContext) -> Self {
        Self {
            rng: RefCell::new(ctx.rng()),
        }
    }
}

impl GroupingMethod for RandomQuotas {
    fn name(&self) -> &str {
        "random"
    }

    fn assign(&self, request: &GroupingRequest) -> rne_core::Result<Assignment> {
        let mut rng = self.rng.borrow_mut();
        let mut groups = vec![Vec::new(); request.tasks()];
        for (kind, quota) in request.quotas().iter().enumerate() {
            let mut ids: Vec<usize> = request
                .members_of_kind(kind)
                .into_iter()
                .map(|r| r.id)
                .collect();
            ids.shuffle(&mut *rng);
            let mut ids = ids.into_iter();
            for (task, &n) in quota.iter().enumerate() {
                groups[task].extend(ids.by_ref().take(n));
            }
        }
        Ok(Assignment::new(groups))
    }
}

/// The built-in methods and `random`, built for each trial from its context.
pub fn factory() -> MethodFactory {
    MethodFactory::new(|name, model, ctx| match name {
        "random" => Ok(Box::new(RandomQuotas::new(ctx)) as Box<dyn GroupingMethod>),
        other => MethodFactory::builtin().build(other, model, ctx),
    })
}

#[allow(dead_code)] // the integration test includes this file for its method only
fn main() -> Result<()> {
    let trials: u32 = std::env::args()
        .nth(1)
        .map_or(Ok(4), |a| a.parse())
        .map_err(|e| format!("TRIALS: {e}"))?;
    let path = PathBuf::from(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/paper.ron"
    ));
    let scenario = usar_sim::scenario::load(&path)?;
    let out = std::env::temp_dir().join("usar-random-method");
    let cfg = SweepConfig {
        methods: vec!["rne".into(), "random".into()],
        method_factory: factory(),
        trials,
        duration_s: Some(300.0),
        threads: 2,
        out_dir: out,
        overwrite: true,
        progress: false,
        ..SweepConfig::new(scenario, path)
    };
    // Two separate folders, so that the second run cannot reuse the first one's journal.
    let run = |dir: &str| -> Result<_> {
        let cfg = SweepConfig {
            out_dir: cfg.out_dir.join(dir),
            ..cfg.clone()
        };
        Ok(run_sweep(&cfg)?.cells.remove(0).results)
    };
    let (first, second) = (run("a")?, run("b")?);
    if first != second {
        return Err("two runs of the same sweep differ".into());
    }
    println!("method  trial  rescued (two runs, identical)");
    for r in &first {
        println!("{:<7} {:>5}  {:>7}", r.method, r.trial, r.rescued_total());
    }
    Ok(())
}
