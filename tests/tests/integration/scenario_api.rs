//! A scenario in code through the public API only: a five-robot, two-task scenario built with
//! `ScenarioSpec::builder` and run as a trial; edits of a validated scenario validated again
//! (an invalid one is an error, not a panic in `run_to_end` or a silent run).

use integration_tests::paper;
use usar_sim::mission::Simulation;
use usar_sim::scenario::{
    KindDraft, ReportSpec, Role, Scenario, ScenarioSpec, TaskDraft, from_str, number_at,
};

/// Three carriers and two aerial observers, a hard task on the left and an easy one on the
/// right of a 40 m x 30 m field: the scenario a user writes first, in code.
fn five_robots() -> Scenario {
    ScenarioSpec::builder("five")
        .arena(40.0, 30.0)
        .kind(
            // Listed starts, and the count written out (it must match the quotas).
            KindDraft::ground("carrier", Role::Carrier)
                .count(3)
                .starts_at(&[(17.0, 2.0), (19.5, 2.0), (22.0, 2.0)])
                .body_radius_m(0.45)
                .max_speed_m_per_s(2.0)
                .sensing_range_m(4.0)
                .observing_range_m(0.5)
                .carrying_capacity(3)
                .rescuing_resources(2)
                .hp_needs_full(2.0)
                .energy_needs_full(1.5),
        )
        .kind(
            KindDraft::aerial("observer", Role::Observer)
                .body_radius_m(0.3)
                .max_speed_m_per_s(1.0)
                .sensing_range_m(18.0)
                .observing_range_m(10.0)
                .carrying_capacity(0)
                .rescuing_resources(0)
                .hp_needs_full(1.0)
                .energy_needs_full(1.0)
                .starts_row((18.0, 5.0), (4.0, 0.0)),
        )
        .rest_station((35.0, 3.0), 2.0)
        .task(
            TaskDraft::new("hard", 1)
                .search_area((2.0, 20.0), (12.0, 28.0))
                .goal_m((7.0, 24.0))
                .drop_off((7.0, 8.0), 2.0)
                .rescuee_grid(1.0, 0.5)
                .quota("carrier", 2)
                .quota("observer", 1),
        )
        .task(
            TaskDraft::new("easy", 0)
                .search_area((28.0, 20.0), (38.0, 28.0))
                .goal_m((33.0, 24.0))
                .drop_off((33.0, 10.0), 2.0)
                .rescuee_grid(1.0, 0.5)
                .quota("carrier", 1)
                .quota("observer", 1),
        )
        .build()
        .unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn a_scenario_built_in_code_with_defaults_runs_a_trial() {
    let s = five_robots();
    assert_eq!(s.robots().len(), 5);
    assert_eq!(s.task_names(), ["hard", "easy"]);
    assert_eq!(s.kinds()[0].quota, [2, 1]);
    assert_eq!(s.kinds()[1].quota, [1, 1]);
    assert_eq!(s.mission().duration_s.get(), 600.0, "the file's default");
    assert_eq!(*s.report(), ReportSpec::default());
    let result = Simulation::builder(&s)
        .method_named("rne")
        .trial(0)
        .duration_s(120.0)
        .build()
        .expect("a valid trial")
        .run_to_end()
        .expect("built-in methods do not fail");
    assert_eq!(result.rescued.len(), 2);
    let delivered: u32 = result.robots.iter().map(|r| r.delivered).sum();
    assert_eq!(result.rescued.iter().sum::<u32>(), delivered);
    assert!(
        delivered > 0,
        "nobody rescued in 120 s: {:?}",
        result.rescued
    );
    // Written as RON and read back, it is the same scenario.
    let text = usar_sweep::spec_ron::spec_to_ron(s.spec(), &[]).expect("RON");
    assert_eq!(from_str(&text, "five.ron").expect("valid"), s);
}

#[test]
fn an_invalid_edit_is_an_error_not_a_panic_or_a_silent_run() {
    let paper = paper();
    // A count of 7 with the paper's quotas of 3 + 3.
    let err = paper
        .edit(|s| s.kinds[0].count = 7)
        .expect_err("quotas below the count");
    assert_eq!(err.field(), Some("kinds[0].quota"), "{err}");
    // Quotas of 4 + 3 for the paper's 6 carriers.
    let err = paper
        .edit(|s| {
            s.kinds[0].quota.0.insert("easy".into(), 4);
        })
        .expect_err("quotas above the count");
    assert_eq!(err.field(), Some("kinds[0].quota"), "{err}");
    // The speed that made `run_to_end` panic (mission/needs.rs) cannot reach a trial.
    let err = paper
        .edit(|s| {
            s.kinds[0].max_speed_m_per_s = number_at("kinds[0].max_speed_m_per_s", -1.0)?;
            Ok(())
        })
        .expect_err("negative speed");
    assert_eq!(
        err.to_string(),
        "paper (edited): kinds[0].max_speed_m_per_s: expected a finite number > 0, found -1"
    );
    // A valid edit runs, and the original is unchanged.
    let seven = paper
        .edit(|s| {
            s.kinds[0].count = 7;
            s.kinds[0].quota.0.insert("hard".into(), 4);
        })
        .expect("valid");
    assert_eq!((seven.robots().len(), paper.robots().len()), (13, 12));
    assert_eq!(seven.to_spec().validate("again").expect("valid"), seven);
}
