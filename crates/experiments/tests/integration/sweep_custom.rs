//! A grouping method of the user's own runs through the sweep machinery (journal, analysis,
//! tables) via `SweepConfig::method_factory`, next to a built-in one: its name kept as
//! written, the factory's calls and trial contexts, and a stochastic method
//! (`crates/usar-sweep/examples/random_method.rs`) reproducible on any thread count.

use crate::common;
#[path = "../../../usar-sweep/examples/random_method.rs"]
mod random_method;

use std::path::PathBuf;

use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
use usar_report::analysis::Analysis;
use usar_report::output::write_outputs;
use usar_sim::scenario;
use usar_sweep::sweep::{MethodFactory, SweepConfig, run_sweep};

use common::PAPER;

/// Deals each kind's robots out in id order, easiest task first: the lowest ids of each kind
/// go to the easy task. Named by its field (`by_id`, `hp_sort`).
struct ById(&'static str);

impl GroupingMethod for ById {
    fn name(&self) -> &str {
        self.0
    }
    fn assign(&self, request: &GroupingRequest) -> rne_core::Result<Assignment> {
        let mut groups = vec![Vec::new(); request.tasks()];
        for (kind, quota) in request.quotas().iter().enumerate() {
            let mut ids = request.members_of_kind(kind).into_iter().map(|r| r.id);
            for &task in request.hardest_first().iter().rev() {
                groups[task].extend(ids.by_ref().take(quota[task]));
            }
        }
        Ok(Assignment::new(groups))
    }
}

fn config(out_dir: PathBuf, methods: &[&str]) -> SweepConfig {
    let scenario = scenario::load(PAPER).unwrap();
    SweepConfig {
        methods: methods.iter().map(|m| m.to_string()).collect(),
        method_factory: MethodFactory::new(|name, model, ctx| match name {
            "by_id" => Ok(Box::new(ById("by_id")) as Box<dyn GroupingMethod>),
            "hp_sort" => Ok(Box::new(ById("hp_sort")) as Box<dyn GroupingMethod>),
            other => MethodFactory::builtin().build(other, model, ctx),
        }),
        trials: 2,
        base_seed: 3,
        duration_s: Some(40.0),
        threads: 2,
        out_dir,
        progress: false,
        ..SweepConfig::new(scenario, PAPER)
    }
}

#[test]
fn a_custom_method_is_swept_like_the_built_ins() {
    let tmp = tempfile::tempdir().unwrap();
    let cfg = config(tmp.path().join("s"), &["by_id", "dis"]);
    let outcome = run_sweep(&cfg).unwrap();
    assert_eq!(outcome.failures().count(), 0);
    assert_eq!(outcome.header.methods, ["by_id", "DIS"]);
    // run_sweep writes only the journal; the outputs are written from the analysis.
    assert!(!tmp.path().join("s/trials.csv").exists());
    assert!(tmp.path().join("s/journal.jsonl").exists());
    let analysis = Analysis::of(&outcome);
    assert_eq!(analysis.cells[0].methods[0].method, "by_id");
    assert_eq!(analysis.cells[0].methods[0].trials, 2);
    write_outputs(&cfg, &outcome, &analysis, &[]).unwrap();
    let by_id: Vec<_> = outcome.cells[0]
        .results
        .iter()
        .filter(|r| r.method == "by_id")
        .collect();
    assert_eq!(by_id.len(), 2);
    // The custom method's groups are what it says: the lowest ids of each kind go easy.
    let easy = cfg.scenario.task_id("easy").unwrap();
    for r in by_id {
        assert_eq!(r.rounds[0].groups[easy], [0, 1, 2, 6, 7, 10]);
    }
    let trials = std::fs::read_to_string(tmp.path().join("s/trials.csv")).unwrap();
    assert_eq!(trials.lines().filter(|l| l.contains(",by_id,")).count(), 2);
}

#[test]
fn an_unknown_name_is_refused_before_anything_runs() {
    let tmp = tempfile::tempdir().unwrap();
    // The typed error's chain, as the `usar` binary prints it.
    let err = anyhow::Error::from(run_sweep(&config(tmp.path().join("s"), &["nope"])).unwrap_err());
    assert!(
        format!("{err:#}").contains("unknown grouping method \"nope\""),
        "{err:#}"
    );
    assert!(!tmp.path().join("s/journal.jsonl").exists());
}

#[test]
fn hooks_observe_trials_and_journaled_records() {
    use std::sync::{Arc, Mutex};

    use usar_sim::mission::{Simulation, StepObserver};
    use usar_sweep::sweep::{SweepHooks, TrialKey};

    /// Counts steps; panics at the 100th step of trial 1 of DIS.
    struct Probe(TrialKey, Arc<Mutex<Vec<(String, u32, u64)>>>, u64);
    impl StepObserver for Probe {
        fn on_step(&mut self, sim: &Simulation) {
            self.2 += 1;
            if self.0.method == "DIS" && self.0.trial == 1 && self.2 == 100 {
                panic!("probe stops here");
            }
            if sim.is_finished() {
                let k = &self.0;
                self.1
                    .lock()
                    .unwrap()
                    .push((k.method.clone(), k.trial, self.2));
            }
        }
    }
    let tmp = tempfile::tempdir().unwrap();
    let steps = Arc::new(Mutex::new(Vec::new()));
    let journaled = Arc::new(Mutex::new(Vec::new()));
    let (s2, j2) = (steps.clone(), journaled.clone());
    let mut cfg = config(tmp.path().join("s"), &["rne", "dis"]);
    cfg.hooks = SweepHooks {
        trial_observer: Some(Arc::new(move |key: &TrialKey| {
            Some(Box::new(Probe(key.clone(), s2.clone(), 0)) as Box<dyn StepObserver>)
        })),
        on_journaled: Some(Arc::new(move |r, n| {
            j2.lock().unwrap().push((r.method.clone(), r.trial, n));
        })),
        stop: None,
    };
    let outcome = run_sweep(&cfg).unwrap();
    // The panicking observer failed its trial only.
    let failed: Vec<_> = outcome
        .failures()
        .map(|f| (f.method.clone(), f.trial))
        .collect();
    assert_eq!(failed, [("DIS".to_string(), 1)]);
    // Every other trial was observed at each of its 40 s / 0.02 s = 2000 steps.
    let mut seen = steps.lock().unwrap().clone();
    seen.sort();
    assert_eq!(
        seen,
        [
            ("DIS".into(), 0, 2000),
            ("RNE".into(), 0, 2000),
            ("RNE".into(), 1, 2000)
        ]
    );
    // Every record, the failed one too, was reported once, numbered in journal order.
    let j = journaled.lock().unwrap();
    assert_eq!(j.iter().map(|x| x.2).collect::<Vec<_>>(), [1, 2, 3, 4]);
}

#[test]
fn a_method_name_is_kept_as_written_and_the_built_ins_keep_the_papers() {
    let tmp = tempfile::tempdir().unwrap();
    let mut cfg = config(
        tmp.path().join("s"),
        &["hp_sort", "rne", "dis", "eng", "hp_dis"],
    );
    cfg.trials = 1;
    let outcome = run_sweep(&cfg).unwrap();
    assert_eq!(outcome.failures().count(), 0);
    let want = ["hp_sort", "RNE", "DIS", "ENG", "HP_DIS"];
    assert_eq!(outcome.header.methods, want);
    let shown: Vec<&str> = outcome.cells[0]
        .results
        .iter()
        .map(|r| r.method.as_str())
        .collect();
    assert_eq!(shown, want);
    write_outputs(&cfg, &outcome, &Analysis::of(&outcome), &[]).unwrap();
    let trials = std::fs::read_to_string(tmp.path().join("s/trials.csv")).unwrap();
    assert_eq!(
        trials.lines().filter(|l| l.contains(",hp_sort,")).count(),
        1
    );
    for file in ["trials.csv", "summary.csv", "report.md", "journal.jsonl"] {
        let text = std::fs::read_to_string(tmp.path().join("s").join(file)).unwrap();
        assert!(text.contains("hp_sort"), "{file}");
        assert!(!text.contains("HP_SORT"), "{file} re-cases the name");
    }
}

#[test]
fn the_factory_is_called_once_per_method_to_name_it_then_once_per_trial() {
    use std::sync::{Arc, Mutex};

    use usar_sim::mission::trial_seed;
    use usar_sweep::sweep::TrialContext;

    let tmp = tempfile::tempdir().unwrap();
    let calls: Arc<Mutex<Vec<(String, TrialContext)>>> = Arc::default();
    let seen = Arc::clone(&calls);
    let inner = config(tmp.path().join("unused"), &[]).method_factory;
    let mut cfg = config(tmp.path().join("s"), &["hp_sort", "dis"]);
    cfg.method_factory = MethodFactory::new(move |name, model, ctx| {
        seen.lock().unwrap().push((name.to_string(), *ctx));
        inner.build(name, model, ctx)
    });
    assert_eq!((cfg.trials, cfg.threads), (2, 2));
    let outcome = run_sweep(&cfg).unwrap();
    assert_eq!(outcome.failures().count(), 0);
    let mut got = calls.lock().unwrap().clone();
    got.sort_by_key(|(m, c)| (m.clone(), c.trial));
    // Per method: trial 0's context once to learn its name, then one call per trial.
    let ctx = |k| TrialContext::for_trial(cfg.base_seed, k);
    let want: Vec<(String, TrialContext)> = ["dis", "hp_sort"]
        .iter()
        .flat_map(|m| [0, 0, 1].map(|k| (m.to_string(), ctx(k))))
        .collect();
    assert_eq!(got, want);
    assert_eq!(ctx(1).seed, trial_seed(3, 1));
    // A resume of the finished sweep runs no trial: the name checks only.
    calls.lock().unwrap().clear();
    drop(outcome);
    cfg.resume = true;
    assert_eq!(run_when_unlocked(&cfg).ran, 0);
    assert_eq!(calls.lock().unwrap().len(), 2);
}

/// `run_sweep(cfg)` again in this process, tried for up to 2 s while its folder's lock is in
/// use: the lock is a `flock` on an open file, and a child process another test of this
/// binary spawns at that moment holds a copy of the descriptor from its fork to its exec, so
/// the lock the finished sweep dropped can outlive it by that long.
fn run_when_unlocked(cfg: &SweepConfig) -> usar_sweep::sweep::SweepOutcome {
    use usar_sweep::error::SweepError;
    use usar_sweep::lock::LockError;
    for _ in 0..100 {
        match run_sweep(cfg) {
            Err(SweepError::Lock(LockError::InUse { .. })) => {
                std::thread::sleep(std::time::Duration::from_millis(20));
            }
            other => return other.expect("the resumed sweep runs"),
        }
    }
    panic!("{}: still locked after 2 s", cfg.out_dir.display())
}

#[test]
fn a_seeded_stochastic_method_is_reproducible_on_any_thread_count() {
    let tmp = tempfile::tempdir().unwrap();
    let run = |dir: &str, threads: usize| {
        let mut cfg = config(tmp.path().join(dir), &["random", "rne"]);
        cfg.method_factory = random_method::factory();
        cfg.trials = 3;
        cfg.threads = threads;
        let outcome = run_sweep(&cfg).unwrap();
        assert_eq!(outcome.failures().count(), 0);
        outcome.cells[0].results.clone()
    };
    let first = run("a", 2);
    assert_eq!(first, run("b", 2));
    assert_eq!(first, run("c", 1));
    let random: Vec<_> = first.iter().filter(|r| r.method == "random").collect();
    assert_eq!(random.len(), 3);
    // Different trials draw differently: their first groups differ.
    let groups: Vec<_> = random.iter().map(|r| &r.rounds[0].groups).collect();
    assert_ne!(groups[0], groups[1]);
    assert_ne!(groups[1], groups[2]);
    // The groups meet the quotas (paper.ron: 6 + 6 robots, quotas of 3 per kind and task).
    for g in &groups {
        assert_eq!(g.iter().map(Vec::len).collect::<Vec<_>>(), [6, 6]);
    }
}

/// A trial owns its method and may move to another thread with it: a method must be `Send`,
/// and need not be `Sync` (the example's method keeps its generator in a `RefCell`).
#[test]
fn a_trial_with_a_method_that_is_not_sync_can_move_between_threads() {
    use usar_sim::mission::Simulation;
    use usar_sweep::sweep::TrialContext;

    let scenario = scenario::load(PAPER).unwrap();
    let method = random_method::RandomQuotas::new(&TrialContext::for_trial(3, 0));
    let sim = Simulation::builder(&scenario)
        .method(Box::new(method))
        .duration_s(5.0)
        .build()
        .unwrap();
    let result = std::thread::spawn(move || {
        let mut sim = sim;
        sim.run_to_end().unwrap()
    })
    .join()
    .unwrap();
    assert_eq!(result.method, "random");
}
