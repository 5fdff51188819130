//! A grouping method of the user's own runs through the sweep machinery (journal, analysis,
//! tables) via `SweepConfig::method_factory`, next to a built-in one.

use std::path::PathBuf;

use experiments::analysis::Analysis;
use experiments::output::write_outputs;
use experiments::sweep::{MethodFactory, SweepConfig, run_sweep};
use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
use usar_sim::scenario;

const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");

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
