//! Tasks as data: scenarios with K = 1, 2, 3 and 4 tasks run whole trials with every built-in
//! grouping method; groups respect each kind's quota per task; rescuee counts per task are
//! pinned for `scenarios/three-tasks.ron` (regenerate as in `mission_golden.rs`: the failing
//! test prints the new table).

use integration_tests::{data_path, load, method, paper, per_task_counts, scenario_path};
use usar_sim::mission::{RescueeStatus, Simulation};
use usar_sim::scenario::Scenario;

/// (method, trial, rescuees per task: hard, medium, easy) of three-tasks.ron.
const THREE_TASKS: &[(&str, u32, [u32; 3])] = &[
    ("rne", 0, [56, 75, 76]),
    ("rne", 1, [33, 42, 56]),
    ("dis", 0, [50, 67, 78]),
    ("dis", 1, [58, 66, 70]),
    ("eng", 0, [75, 78, 61]),
    ("eng", 1, [54, 45, 40]),
    ("hp_dis", 0, [60, 62, 58]),
    ("hp_dis", 1, [72, 63, 76]),
];

/// Runs trial 0 of `s` with every built-in method and checks what holds for any K: one
/// group and one rescuee count per task, groups that split the available team within each
/// kind's quota per task (exactly the quotas in the first round, when the whole team is
/// there), rescuee fields that agree with the counts, and rescuees in every task.
fn check_k_tasks(s: &Scenario, k: usize) {
    assert_eq!(s.tasks().len(), k);
    for name in ["rne", "dis", "eng", "hp_dis"] {
        let mut sim = Simulation::for_trial(s, method(name, s), 0);
        let r = sim.run_to_end().unwrap();
        assert_eq!(r.tasks, s.task_names(), "{name}");
        assert_eq!(r.rescued.len(), k, "{name}");
        assert!(r.rounds.len() >= 2, "{name}: {} rounds", r.rounds.len());
        for (i, round) in r.rounds.iter().enumerate() {
            assert_eq!(round.groups.len(), k, "{name} round {i}");
            let mut seen = vec![false; s.robots().len()];
            for (t, group) in round.groups.iter().enumerate() {
                for (kind, spec) in s.kinds().iter().enumerate() {
                    let n = group
                        .iter()
                        .filter(|&&id| s.robots()[id].kind == kind)
                        .count();
                    assert!(n <= spec.quota[t], "{name} round {i}: task {t} kind {kind}");
                    if i == 0 {
                        assert_eq!(
                            n, spec.quota[t],
                            "{name}: first round, task {t}, kind {kind}"
                        );
                    }
                }
                for &id in group {
                    assert!(!seen[id], "{name} round {i}: robot {id} in two groups");
                    seen[id] = true;
                }
            }
        }
        for t in 0..k {
            let field = sim.rescuees(t);
            let delivered = (0..field.len())
                .filter(|&i| field.status(i) == RescueeStatus::Delivered)
                .count();
            assert_eq!(delivered, r.rescued[t] as usize, "{name}: task {t}");
            assert!(r.rescued[t] > 0, "{name}: nobody rescued in task {t}");
        }
    }
}

#[test]
fn one_task() {
    check_k_tasks(&load(&data_path("one-task.ron")), 1);
}

#[test]
fn two_tasks() {
    check_k_tasks(&paper(), 2);
}

#[test]
fn three_tasks() {
    check_k_tasks(&load(&scenario_path("three-tasks.ron")), 3);
}

#[test]
fn four_tasks() {
    check_k_tasks(&load(&data_path("four-tasks.ron")), 4);
}

#[test]
fn three_tasks_rescuee_counts_are_pinned() {
    let s = load(&scenario_path("three-tasks.ron"));
    assert_eq!(s.task_names(), ["hard", "medium", "easy"]);
    let actual = per_task_counts(&s, 0..2);
    let expected: Vec<(&str, u32, Vec<u32>)> = THREE_TASKS
        .iter()
        .map(|(m, t, n)| (*m, *t, n.to_vec()))
        .collect();
    if actual != expected {
        println!("const THREE_TASKS: &[(&str, u32, [u32; 3])] = &[");
        for (m, t, n) in &actual {
            println!("    ({m:?}, {t}, {n:?}),");
        }
        println!("];");
    }
    assert_eq!(actual, expected, "three-tasks.ron rescuee counts moved");
}
