//! The paper's team (Sec. VI.B): what the hierarchical RNE grouping does with it.

use super::common::{EASY, Gauss, HARD, mean_level, paper_team, uniform_model};
use crate::grouping::{GroupingMethod, GroupingRequest, HierarchicalRne};

#[test]
fn paper_team_two_clusters_high_cluster_goes_hard() {
    // Per kind, half the robots are strong (~95 %) and half weak (~55 %), interleaved by id.
    let mut levels = [(0.0, 0.0); 12];
    for (i, l) in levels.iter_mut().enumerate() {
        *l = if i % 2 == 0 {
            (95.0 - i as f64 * 0.3, 92.0 + i as f64 * 0.2)
        } else {
            (55.0 + i as f64 * 0.4, 50.0 - i as f64 * 0.3)
        };
    }
    let req = paper_team(&levels);
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&req)
        .unwrap();
    out.assignment.validate(&req).unwrap();
    assert!(!out.bisections[0].forced_by_quotas);
    // The strong carriers (0, 2, 4) and suppliers (6, 8) go to the hard task, and that group
    // trusts itself more. But the *weak* observer (11) joins them: at the last merge the
    // pairing "strong C+S with weak O" maximises J, because the observer alone carries the
    // group's obs/sen shares, so mismatching levels across kinds makes the two groups'
    // distributions differ most. This is the algorithm as specified, reported honestly
    // (docs/trust-model.md, "Does the hard task get the stronger robots?").
    assert_eq!(out.assignment.ids(HARD), [0, 2, 4, 6, 8, 11]);
    let within = out.bisections[0].within_rne; // [rest = easy, task = hard]
    assert!(within[1] < within[0], "{out:?}");
}

#[test]
fn paper_team_random_levels_hard_group_is_stronger_in_most_trials() {
    // Levels as in Sec. VI.B: energy ~ N(80, 20), HP ~ N(90, 10) (clamped to 5..100).
    let method = HierarchicalRne::new(uniform_model());
    let trials = 100;
    let mut stronger = 0;
    let mut per_kind = [0; 3];
    for seed in 0..trials {
        let mut g = Gauss(seed);
        let mut levels = [(0.0, 0.0); 12];
        for l in &mut levels {
            let energy = g.sample(80.0, 20.0);
            *l = (g.sample(90.0, 10.0), energy);
        }
        let req = paper_team(&levels);
        let a = method.group(&req).unwrap();
        if mean_level(&req, a.ids(HARD)) > mean_level(&req, a.ids(EASY)) {
            stronger += 1;
        }
        for (kind, count) in per_kind.iter_mut().enumerate() {
            let of_kind = |ids: &[usize]| {
                ids.iter()
                    .copied()
                    .filter(|&id| req.robot(id).is_some_and(|r| r.kind == kind))
                    .collect::<Vec<_>>()
            };
            if mean_level(&req, &of_kind(a.ids(HARD))) > mean_level(&req, &of_kind(a.ids(EASY))) {
                *count += 1;
            }
        }
    }
    println!(
        "hard group stronger: {stronger}/{trials}; per kind (carrier, supplier, observer): {per_kind:?}"
    );
    // Not guaranteed trial by trial (RNE sees needs *shares*, not levels). The run is
    // deterministic and gives 97/100 and per kind [90, 84, 70], the figures docs/trust-model.md
    // quotes; the bounds keep those statements true, including that the observer is the
    // exception.
    assert!(
        stronger >= 95,
        "hard group stronger in only {stronger}/{trials} trials"
    );
    assert!(
        per_kind[0] >= 85 && per_kind[1] >= 80,
        "per kind {per_kind:?}"
    );
    assert!(
        per_kind[2] <= 80,
        "the observer caveat no longer holds: {per_kind:?}"
    );
}

#[test]
fn unequal_quotas_fix_the_orientation() {
    let mut levels = [(90.0, 80.0); 12];
    for (i, l) in levels.iter_mut().enumerate() {
        l.0 -= i as f64 * 3.0;
    }
    let base = paper_team(&levels);
    let q = vec![vec![2, 4], vec![2, 2], vec![1, 1]];
    let req = GroupingRequest::new(base.robots().to_vec(), q, vec![HARD, EASY]).unwrap();
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&req)
        .unwrap();
    out.assignment.validate(&req).unwrap();
    assert!(out.bisections[0].forced_by_quotas);
    assert_eq!(
        out.assignment
            .ids(HARD)
            .iter()
            .filter(|&&id| id < 6)
            .count(),
        4
    );
}

#[test]
fn random_paper_teams_match_the_two_task_oracle() {
    use super::oracle_two_task as oracle;
    use crate::grouping::{Dis, Eng, HpDis};
    // 300 teams with the paper's needs ratios and Sec. VI.B's random levels (7 needs, kinds
    // of 6, 4, 2): the simulator's case, where K = 2 must not move by one bit.
    let rne = HierarchicalRne::new(uniform_model());
    for seed in 1000..1300 {
        let mut g = Gauss(seed);
        let mut levels = [(0.0, 0.0); 12];
        for l in &mut levels {
            let energy = g.sample(80.0, 20.0);
            *l = (g.sample(90.0, 10.0), energy);
        }
        let req = paper_team(&levels);
        let pair = |a: crate::grouping::Assignment| oracle::EasyHard {
            easy: a.groups[EASY].clone(),
            hard: a.groups[HARD].clone(),
        };
        assert_eq!(
            Ok(pair(rne.group(&req).unwrap())),
            oracle::rne(&rne, &req),
            "seed {seed}"
        );
        assert_eq!(
            pair(Dis.group(&req).unwrap()),
            oracle::dis(&req),
            "seed {seed}"
        );
        assert_eq!(
            pair(Eng.group(&req).unwrap()),
            oracle::eng(&req),
            "seed {seed}"
        );
        assert_eq!(
            pair(HpDis.group(&req).unwrap()),
            oracle::hp_dis(&req),
            "seed {seed}"
        );
    }
}
