//! What a researcher's own crate does with rne-usar, through the public API only: pin the
//! rescuee counts of the paper's scenario, sweep a seeded stochastic method of its own on two
//! threads and get the same numbers twice, build a scenario in code, and meet an error (not a
//! panic, not a silent run) when an edit makes the scenario invalid.

use std::path::{Path, PathBuf};

use downstream_example::factory;
use experiments::sweep::{SweepConfig, run_in_memory};
use usar_sim::mission::{Simulation, TrialResult};
use usar_sim::scenario;

fn paper_path() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/paper.ron")
}

/// `(hard, easy)` rescuees of one whole trial.
fn counts(r: &TrialResult) -> (u32, u32) {
    let task = |name: &str| r.rescued[r.task_id(name).expect("paper.ron has the task")];
    (task("hard"), task("easy"))
}

#[test]
fn the_papers_rescuee_counts_are_pinned() {
    let paper = scenario::load(paper_path()).expect("paper.ron loads");
    // (method, trial, hard, easy): the numbers tests/tests/mission_golden.rs pins too.
    for (method, trial, hard, easy) in [("rne", 0, 40, 69), ("hp_dis", 1, 81, 84)] {
        let mut sim = Simulation::builder(&paper)
            .method_named(method)
            .trial(trial)
            .build()
            .expect("a built-in method and a valid trial");
        let r = sim.run_to_end().expect("the trial runs");
        assert_eq!(counts(&r), (hard, easy), "{method} trial {trial}");
        // Invariants of any trial: rescuees per task add up, no cost is negative, every
        // finished round has a group per task.
        assert_eq!(r.rescued.iter().sum::<u32>(), r.rescued_total());
        assert!(
            r.energy_spent_pct
                .iter()
                .chain(&r.hp_lost_pct)
                .all(|&c| c >= 0.0)
        );
        let finished = r.rounds.iter().filter(|round| round.completed);
        assert!(
            finished
                .into_iter()
                .all(|round| round.groups.len() == r.tasks.len())
        );
    }
}

#[test]
fn a_seeded_stochastic_method_gives_the_same_sweep_twice_on_two_threads() {
    let paper = scenario::load(paper_path()).expect("paper.ron loads");
    let cfg = SweepConfig {
        methods: vec!["random".into(), "rne".into()],
        method_factory: factory(),
        trials: 3,
        duration_s: Some(120.0),
        threads: 2,
        progress: false,
        ..SweepConfig::new(paper, paper_path())
    };
    let first = run_in_memory(&cfg).expect("the sweep runs");
    let second = run_in_memory(&cfg).expect("the sweep runs");
    let a: Vec<&TrialResult> = first.results().collect();
    let b: Vec<&TrialResult> = second.results().collect();
    assert_eq!(a.len(), 6, "2 methods x 3 trials");
    assert_eq!(a, b, "the same sweep twice");
    assert_eq!(first.failures().count(), 0);
    // The method's name is kept as written, and its trials draw different groups.
    let random: Vec<&&TrialResult> = a.iter().filter(|r| r.method == "random").collect();
    assert_eq!(random.len(), 3);
    let first_groups: Vec<_> = random.iter().map(|r| &r.rounds[0].groups).collect();
    assert!(
        first_groups.windows(2).any(|w| w[0] != w[1]),
        "three trials, one draw: {first_groups:?}"
    );
}
