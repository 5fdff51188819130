//! The baselines' rules (DIS, ENG, HP_DIS) on two and more tasks, custom methods, names and
//! assignment validation.

use super::common::{EASY, HARD, paper_team, uniform_model};
use crate::grouping::{
    Assignment, Dis, Eng, GroupingMethod, GroupingRequest, HpDis, RobotSnapshot, method_from_name,
};
use crate::{NeedsVector, RneError};

#[test]
fn baselines_follow_their_rules() {
    let mut levels = [(90.0, 80.0); 12];
    for (i, l) in levels.iter_mut().enumerate() {
        *l = (50.0 + i as f64 * 4.0, 100.0 - i as f64 * 5.0);
    }
    let req = paper_team(&levels);
    // ENG: highest energy = lowest ids within each kind.
    assert_eq!(Eng.group(&req).unwrap().ids(HARD), [0, 1, 2, 6, 7, 10]);
    // HP_DIS: highest HP = highest ids within each kind.
    assert_eq!(HpDis.group(&req).unwrap().ids(HARD), [3, 4, 5, 8, 9, 11]);
    // DIS: distances [20 + id, 40 - id]: ids 0..=9 are nearer easy, ids 11 nearer hard.
    assert_eq!(Dis.group(&req).unwrap().ids(EASY), [0, 1, 2, 6, 7, 10]);
}

#[test]
fn hp_dis_breaks_hp_ties_by_distance_to_hard_goal() {
    let req = paper_team(&[(80.0, 80.0); 12]);
    // Equal HP; distance to hard is 40 - id, so the highest ids of each kind are nearest.
    assert_eq!(HpDis.group(&req).unwrap().ids(HARD), [3, 4, 5, 8, 9, 11]);
}

/// One kind of 6 robots, three tasks `0, 1, 2` with difficulty order `[1, 2, 0]` (task 1 the
/// hardest, task 0 the easiest) and quotas `[1, 3, 2]`; robot `i` has energy and HP
/// `90 - 10 i` and the distances `d`.
fn three_tasks(d: [[f64; 3]; 6]) -> GroupingRequest {
    let robots = (0..6)
        .map(|i| RobotSnapshot {
            id: i,
            kind: 0,
            needs: NeedsVector::new(vec![1.0, 2.0]).unwrap(),
            energy_pct: 90.0 - 10.0 * i as f64,
            hp_pct: 90.0 - 10.0 * i as f64,
            distance_to_goal_m: d[i].to_vec(),
        })
        .collect();
    GroupingRequest::new(robots, vec![vec![1, 3, 2]], vec![1, 2, 0]).unwrap()
}

#[test]
fn ranking_baselines_fill_tasks_from_the_hardest_down() {
    let req = three_tasks([[1.0, 2.0, 3.0]; 6]);
    let want = Assignment::new(vec![vec![5], vec![0, 1, 2], vec![3, 4]]);
    assert_eq!(Eng.group(&req).unwrap(), want);
    assert_eq!(HpDis.group(&req).unwrap(), want);
}

#[test]
fn dis_serves_the_nearest_robot_first_and_prefers_the_easier_task_on_ties() {
    let req = three_tasks([
        [5.0, 1.0, 9.0], // third (1.0): task 1
        [5.0, 2.0, 9.0], // fourth: task 1, whose quota of 3 is then full
        [9.0, 3.0, 5.0], // task 1 full: the next nearest with room, task 2
        [9.0, 4.0, 8.0], // task 1 full: task 2 (8 < 9)
        [0.8, 0.8, 0.8], // second (0.8): all equal, so the easiest task, 0
        [6.0, 0.5, 6.0], // served first (0.5): task 1
    ]);
    let got = Dis.group(&req).unwrap();
    assert_eq!(got.groups, [vec![4], vec![0, 1, 5], vec![2, 3]]);
}

#[test]
fn a_custom_method_plugs_in_without_changes() {
    struct AllLowIdsEasy;
    impl GroupingMethod for AllLowIdsEasy {
        fn name(&self) -> &str {
            "low_ids_easy"
        }
        fn assign(&self, request: &GroupingRequest) -> crate::Result<Assignment> {
            let mut groups = vec![Vec::new(); request.tasks()];
            for (kind, q) in request.quotas().iter().enumerate() {
                let mut ids = request.members_of_kind(kind).into_iter().map(|r| r.id);
                for &task in request.hardest_first().iter().rev() {
                    groups[task].extend(ids.by_ref().take(q[task]));
                }
            }
            Ok(Assignment::new(groups))
        }
    }
    let methods: Vec<Box<dyn GroupingMethod>> = vec![
        Box::new(AllLowIdsEasy),
        method_from_name("Rne", &uniform_model()).unwrap(),
    ];
    let req = paper_team(&[(80.0, 80.0); 12]);
    for m in &methods {
        m.group(&req).unwrap();
    }
    assert_eq!(
        methods[0].group(&req).unwrap().ids(EASY),
        [0, 1, 2, 6, 7, 10]
    );
    assert_eq!(methods[0].name(), "low_ids_easy");
}

#[test]
fn method_names_are_case_insensitive_and_errors_list_valid_names() {
    let m = uniform_model();
    for (name, want, shown) in [
        ("RNE", "rne", "RNE"),
        ("Dis", "dis", "DIS"),
        ("ENG", "eng", "ENG"),
        ("hp_dis", "hp_dis", "HP_DIS"),
        ("HP-DIS", "hp_dis", "HP_DIS"),
    ] {
        let method = method_from_name(name, &m).unwrap();
        assert_eq!((method.name(), method.display_name()), (want, shown));
    }
    let err = method_from_name("nearest", &m).err().unwrap();
    assert!(err.to_string().contains("rne, dis, eng, hp_dis"), "{err}");
}

#[test]
fn bad_assignments_are_rejected() {
    let req = paper_team(&[(80.0, 80.0); 12]);
    let ok = Eng.group(&req).unwrap();
    let invalid = |a: &Assignment| match a.validate(&req) {
        Err(RneError::InvalidAssignment(msg)) => msg,
        other => panic!("expected InvalidAssignment, got {other:?}"),
    };
    let mut dup = ok.clone();
    dup.groups[EASY][0] = dup.groups[HARD][0];
    assert!(invalid(&dup).contains("more than once"));
    let swapped = Assignment::new(vec![ok.groups[HARD].clone(), ok.groups[EASY].clone()]);
    assert!(
        swapped.validate(&req).is_ok(),
        "equal quotas: swapping is still valid"
    );
    let mut short = ok.clone();
    short.groups[EASY].pop();
    assert!(invalid(&short).contains("not assigned"));
    let mut stranger = ok.clone();
    stranger.groups[EASY].push(99);
    assert!(invalid(&stranger).contains("not in the team"));
    let three = Assignment::new(vec![ok.groups[0].clone(), ok.groups[1].clone(), vec![]]);
    assert!(invalid(&three).contains("3 groups for 2 tasks"));
    let mut moved = ok.clone();
    let id = moved.groups[EASY].remove(0);
    moved.groups[HARD].push(id);
    assert!(invalid(&moved).contains("quotas"));
    assert_eq!(ok.task_of(ok.groups[HARD][0]), Some(HARD));
    assert_eq!(ok.task_of(99), None);
}
