//! A grouping method of the user's own runs through the sweep machinery (journal, analysis,
//! tables) via `SweepConfig::method_factory`, next to a built-in one.

mod common;

use std::path::PathBuf;

use experiments::analysis::Analysis;
use experiments::output::write_outputs;
use experiments::sweep::{MethodFactory, SweepConfig, run_sweep};
use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
use usar_sim::scenario;

use common::PAPER;

/// Deals each kind's robots out in id order, easiest task first: the lowest ids of each kind
/// go to the easy task.
struct ById;

impl GroupingMethod for ById {
    fn name(&self) -> &str {
        "by_id"
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
        method_factory: MethodFactory::new(|name, model| match name {
            "by_id" => Ok(Box::new(ById) as Box<dyn GroupingMethod>),
            other => MethodFactory::builtin().build(other, model),
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
    assert_eq!(outcome.header.methods, ["BY_ID", "DIS"]);
    // run_sweep writes only the journal; the outputs are written from the analysis.
    assert!(!tmp.path().join("s/trials.csv").exists());
    assert!(tmp.path().join("s/journal.jsonl").exists());
    let analysis = Analysis::of(&outcome);
    assert_eq!(analysis.cells[0].methods[0].method, "BY_ID");
    assert_eq!(analysis.cells[0].methods[0].trials, 2);
    write_outputs(&cfg, &outcome, &analysis, &[]).unwrap();
    let by_id: Vec<_> = outcome.cells[0]
        .results
        .iter()
        .filter(|r| r.method == "BY_ID")
        .collect();
    assert_eq!(by_id.len(), 2);
    // The custom method's groups are what it says: the lowest ids of each kind go easy.
    let easy = cfg.scenario.task_id("easy").unwrap();
    for r in by_id {
        assert_eq!(r.rounds[0].groups[easy], [0, 1, 2, 6, 7, 10]);
    }
    let trials = std::fs::read_to_string(tmp.path().join("s/trials.csv")).unwrap();
    assert_eq!(trials.lines().filter(|l| l.contains(",BY_ID,")).count(), 2);
}

#[test]
fn an_unknown_name_is_refused_before_anything_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let err = run_sweep(&config(tmp.path().join("s"), &["nope"])).unwrap_err();
    assert!(
        format!("{err:#}").contains("unknown grouping method \"nope\""),
        "{err:#}"
    );
    assert!(!tmp.path().join("s/journal.jsonl").exists());
}

#[test]
fn hooks_observe_trials_and_journaled_records() {
    use std::sync::{Arc, Mutex};

    use experiments::sweep::{SweepHooks, TrialKey};
    use usar_sim::mission::{Simulation, StepObserver};

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
