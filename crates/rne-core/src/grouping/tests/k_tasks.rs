//! The `K`-task hierarchical RNE grouping: recursive bisection down the difficulty order.

use super::common::{EASY, HARD, paper_team, uniform_model};
use crate::grouping::{GroupingMethod, GroupingRequest, HierarchicalRne, RobotSnapshot};

/// The paper team's robots with the tasks `0..k`, `quotas` per kind and the given order.
fn paper_robots_with(k: usize, quotas: Vec<Vec<usize>>, order: Vec<usize>) -> GroupingRequest {
    let base = paper_team(&[(80.0, 80.0); 12]);
    let robots: Vec<RobotSnapshot> = base
        .robots()
        .iter()
        .map(|r| {
            let mut r = r.clone();
            r.hp_pct -= r.id as f64 * 3.0;
            r.needs = super::common::paper_needs(r.kind, r.hp_pct, r.energy_pct);
            r.distance_to_goal_m = (0..k).map(|t| 10.0 * t as f64 + r.id as f64).collect();
            r
        })
        .collect();
    GroupingRequest::new(robots, quotas, order).unwrap()
}

#[test]
fn one_task_takes_everyone() {
    let req = paper_robots_with(1, vec![vec![6], vec![4], vec![2]], vec![0]);
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&req)
        .unwrap();
    assert_eq!(out.assignment.groups, [(0..12).collect::<Vec<_>>()]);
    assert!(out.bisections.is_empty());
}

#[test]
fn the_first_bisection_is_the_two_task_grouping_of_hardest_vs_rest() {
    // Three tasks, task 2 hardest, then 0, then 1. The first level must equal the two-task
    // grouping of task 2 against tasks 0 and 1 pooled.
    let three = paper_robots_with(
        3,
        vec![vec![2, 1, 3], vec![1, 1, 2], vec![0, 1, 1]],
        vec![2, 0, 1],
    );
    let pooled = paper_robots_with(
        2,
        vec![vec![3, 3], vec![2, 2], vec![1, 1]],
        vec![HARD, EASY],
    );
    let method = HierarchicalRne::new(uniform_model());
    let out3 = method.group_detailed(&three).unwrap();
    let out2 = method.group_detailed(&pooled).unwrap();
    assert_eq!(out3.assignment.ids(2), out2.assignment.ids(HARD));
    assert_eq!(out3.bisections.len(), 2);
    let (b3, b2) = (&out3.bisections[0], &out2.bisections[0]);
    assert_eq!((b3.task, b2.task), (2, HARD));
    assert_eq!(
        (b3.between_rne, b3.within_rne, b3.forced_by_quotas),
        (b2.between_rne, b2.within_rne, b2.forced_by_quotas)
    );
    assert_eq!(out3.bisections[1].task, 0);
    // Level 2 splits the rest 3/1/1 vs 1/1/1 (tasks 1 vs 0): forced by the quotas.
    assert!(out3.bisections[1].forced_by_quotas);
    method.group(&three).unwrap();
}

#[test]
fn empty_groups_are_allowed() {
    // Task 1 gets nobody; task 0 everyone.
    let req = paper_robots_with(
        3,
        vec![vec![6, 0, 0], vec![4, 0, 0], vec![2, 0, 0]],
        vec![1, 2, 0],
    );
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&req)
        .unwrap();
    assert_eq!(out.assignment.groups[0].len(), 12);
    assert!(out.assignment.groups[1].is_empty() && out.assignment.groups[2].is_empty());
    assert!(
        out.bisections
            .iter()
            .all(|b| b.between_rne == 0.0 && b.forced_by_quotas)
    );
    // The hardest tasks take everyone: the easier ones are empty without a bisection.
    let req = paper_robots_with(
        3,
        vec![vec![0, 6, 0], vec![0, 4, 0], vec![0, 2, 0]],
        vec![1, 2, 0],
    );
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&req)
        .unwrap();
    assert_eq!(out.assignment.groups[1].len(), 12);
    assert_eq!(out.bisections.len(), 1);
}
