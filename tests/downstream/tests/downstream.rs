//! What a researcher's own crate does with rne-usar, through the public API only: pin the
//! rescuee counts of the paper's scenario, sweep a seeded stochastic method of its own on two
//! threads and get the same numbers twice, build a scenario in code, and meet an error (not a
//! panic, not a silent run) when an edit makes the scenario invalid.

use std::path::{Path, PathBuf};

use downstream_example::factory;
use usar_sim::mission::{Simulation, TrialResult};
use usar_sim::scenario::{
    self, KindDraft, Role, Scenario, ScenarioError, ScenarioSpec, TaskDraft, number_at,
};
use usar_sweep::sweep::{SweepConfig, run_in_memory};

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
    // (method, trial, hard, easy): the numbers tests/tests/integration/mission_golden.rs pins too.
    for (method, trial, hard, easy) in [("rne", 0, 69, 84), ("hp_dis", 1, 73, 80)] {
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

/// A two-task scenario of four robots, built in code: everything not written takes the file
/// format's default (mission rules, navigation, collision avoidance, time step, weights).
fn my_site() -> Result<Scenario, ScenarioError> {
    let ugv = KindDraft::ground("ugv", Role::Carrier)
        .body_radius_m(0.4)
        .max_speed_m_per_s(1.5)
        .sensing_range_m(3.0)
        .observing_range_m(1.0)
        .carrying_capacity(2)
        .rescuing_resources(2)
        .hp_needs_full(2.0)
        .energy_needs_full(1.5)
        .starts_row((12.0, 2.0), (2.0, 0.0));
    let drone = KindDraft::aerial("drone", Role::Observer)
        .body_radius_m(0.3)
        .max_speed_m_per_s(2.0)
        .sensing_range_m(8.0)
        .observing_range_m(10.0)
        .carrying_capacity(0)
        .rescuing_resources(0)
        .hp_needs_full(1.0)
        .energy_needs_full(1.0)
        .starts_row((13.0, 4.0), (2.0, 0.0));
    ScenarioSpec::builder("my-site")
        .arena(30.0, 20.0)
        .kind(ugv)
        .kind(drone)
        .rest_station((25.0, 3.0), 1.5)
        .task(
            TaskDraft::new("hard", 1)
                .search_area((3.0, 12.0), (11.0, 18.0))
                .goal_m((7.0, 15.0))
                .drop_off((8.0, 8.0), 2.0)
                .rescuee_grid(2.0, 0.5)
                .quota("ugv", 1)
                .quota("drone", 1),
        )
        .task(
            TaskDraft::new("easy", 0)
                .search_area((18.0, 12.0), (26.0, 18.0))
                .goal_m((22.0, 15.0))
                .drop_off((20.0, 8.0), 2.0)
                .rescuee_grid(2.0, 0.5)
                .quota("ugv", 1)
                .quota("drone", 1),
        )
        .build()
}

#[test]
fn a_scenario_built_in_code_runs_and_an_invalid_edit_is_an_error() {
    let site = my_site().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(site.robots().len(), 4);
    assert_eq!(
        site.mission().duration_s.get(),
        600.0,
        "the default trial length"
    );
    let r = Simulation::builder(&site)
        .method_named("rne")
        .duration_s(90.0)
        .build()
        .expect("a valid trial")
        .run_to_end()
        .expect("the trial runs");
    assert_eq!(r.tasks, ["hard", "easy"]);
    assert!(
        r.rescued_total() > 0,
        "nobody rescued in 90 s: {:?}",
        r.rescued
    );

    // Three carriers with quotas of 1 + 1: an error naming the field, before any trial.
    let err = site
        .edit(|s| s.kinds[0].count = 3)
        .expect_err("quotas no longer add up");
    assert_eq!(err.field(), Some("kinds[0].quota"), "{err}");
    // A negative speed is refused where it is written, not in the middle of a trial.
    let err = site
        .edit(|s| {
            s.kinds[0].max_speed_m_per_s = number_at("kinds[0].max_speed_m_per_s", -1.0)?;
            Ok(())
        })
        .expect_err("a negative speed");
    assert_eq!(err.field(), Some("kinds[0].max_speed_m_per_s"), "{err}");
    // A bad number given to the builder is an error too.
    let err = ScenarioSpec::builder("bad")
        .arena(-30.0, 20.0)
        .build()
        .expect_err("a negative width");
    assert!(err.to_string().contains("arena"), "{err}");
}
