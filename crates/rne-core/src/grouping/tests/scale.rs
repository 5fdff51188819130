//! Grouping at scale: the exact split limit, the heuristic split (partitions, local optimality,
//! quality against the exact optimum) and large teams.

use proptest::prelude::*;

use super::common::{Gauss, paper_needs, paper_team, random_request, uniform_model};
use crate::grouping::{
    DEFAULT_EXACT_SPLIT_LIMIT, GroupingMethod, GroupingRequest, HierarchicalRne, RobotSnapshot,
};
use crate::{NeedsVector, RneError, TrustModel, Weights};

#[test]
fn the_limit_counts_splits() {
    let m = HierarchicalRne::new(uniform_model());
    assert_eq!(m.exact_split_limit(), DEFAULT_EXACT_SPLIT_LIMIT);
    assert!(m.split_is_exact(20, 10)); // 92,378 splits
    assert!(!m.split_is_exact(21, 10)); // 352,716 splits
    assert!(m.split_is_exact(1000, 0) && m.split_is_exact(1000, 1000));
    let none = m.clone().with_exact_split_limit(0);
    assert!(none.split_is_exact(5, 0) && none.split_is_exact(2, 1)); // a single split
    assert!(!none.split_is_exact(3, 1));
}

#[test]
fn the_paper_team_stays_exact() {
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&paper_team(&[(80.0, 80.0); 12]))
        .unwrap();
    assert!(out.bisections.iter().all(|b| b.heuristic_kinds.is_empty()));
}

/// One kind of `n` robots with the paper's carrier ratios and random levels, two tasks
/// (task 1 hardest) with quotas `[n - hard, hard]`.
fn big_kind(n: usize, hard: usize, seed: u64) -> GroupingRequest {
    let mut g = Gauss(seed);
    let robots = (0..n)
        .map(|id| {
            let (hp, energy) = (g.sample(90.0, 10.0), g.sample(80.0, 20.0));
            RobotSnapshot {
                id,
                kind: 0,
                needs: paper_needs(0, hp, energy),
                energy_pct: energy,
                hp_pct: hp,
                distance_to_goal_m: vec![10.0, 20.0],
            }
        })
        .collect();
    GroupingRequest::new(robots, vec![vec![n - hard, hard]], vec![1, 0]).unwrap()
}

#[test]
fn a_kind_beyond_the_limit_is_split_heuristically_in_little_memory() {
    // C(48, 24) / 2 = 1.6e13 splits: enumerating them is impossible; the heuristic is instant.
    let req = big_kind(48, 24, 5);
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&req)
        .unwrap();
    out.assignment.validate(&req).unwrap();
    assert_eq!(out.bisections[0].heuristic_kinds, [0]);
    assert!(out.bisections[0].between_rne > 0.0);
}

#[test]
fn heuristic_split_size_errors_are_reported() {
    let n = NeedsVector::new(vec![1.0, 2.0]).unwrap();
    let m = HierarchicalRne::new(TrustModel::with_weights(Weights::uniform(2).unwrap()));
    assert_eq!(
        m.best_split_heuristic(&[&n, &n], 3),
        Err(RneError::InvalidSubgroupSize { size: 3, total: 2 })
    );
}

/// 3-5 random needs per robot (some exact zeros) for `n` robots and a first-side size.
fn random_kind(n: std::ops::Range<usize>) -> impl Strategy<Value = (Vec<Vec<f64>>, usize)> {
    (n, 3usize..6).prop_flat_map(|(n, j)| {
        (
            prop::collection::vec(
                prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 0.1..100.0f64], j),
                n,
            ),
            1..n,
        )
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(128))]

    #[test]
    fn heuristic_grouping_returns_a_partition_meeting_quotas(req in random_request(1..=5)) {
        let method = HierarchicalRne::new(TrustModel::with_weights(Weights::uniform(3).unwrap()))
            .with_exact_split_limit(0);
        // With smoothing (the default) even an all-zero subgroup has a distribution.
        let a = method.group(&req);
        prop_assert!(a.as_ref().is_ok_and(|a| a.validate(&req).is_ok()), "{:?}", a);
    }

    #[test]
    fn no_single_swap_improves_the_heuristic_split((rows, m) in random_kind(2..12)) {
        let method = HierarchicalRne::new(TrustModel::with_weights(Weights::uniform(rows[0].len()).unwrap()));
        let needs: Vec<NeedsVector> = rows.into_iter().map(|r| NeedsVector::new(r).unwrap()).collect();
        let members: Vec<&NeedsVector> = needs.iter().collect();
        let Ok((split, score)) = method.best_split_heuristic(&members, m) else {
            return Ok(()); // an all-zero subgroup
        };
        prop_assert_eq!(split.first.len(), m);
        for &a in &split.first {
            for &b in &split.second {
                let swap = |side: &[usize]| side.iter().map(|&i| if i == a { b } else if i == b { a } else { i }).map(|i| members[i]).collect::<Vec<_>>();
                if let Ok(j) = method.between_rne(&swap(&split.first), &swap(&split.second)) {
                    prop_assert!(j <= score + 1e-9 * score.max(1.0), "swap {} <-> {}: {} > {}", a, b, j, score);
                }
            }
        }
    }
}

#[test]
fn heuristic_is_close_to_the_exact_optimum_on_small_kinds() {
    // 150 deterministic random kinds of 2-14 robots with the paper's needs ratios; the full
    // figures (1,000 kinds up to 20 robots) are in docs/trust-model.md.
    let method = HierarchicalRne::new(uniform_model());
    let mut g = Gauss(11);
    let (mut sum, mut worst) = (0.0, f64::INFINITY);
    let cases = 150;
    for case in 0..cases {
        let n = 2 + (g.uniform() * 13.0) as usize;
        let m = 1 + (g.uniform() * (n - 1) as f64) as usize;
        let needs: Vec<NeedsVector> = (0..n)
            .map(|_| paper_needs(case % 3, g.sample(90.0, 10.0), g.sample(80.0, 20.0)))
            .collect();
        let members: Vec<&NeedsVector> = needs.iter().collect();
        let (_, exact) = method.best_split_exact(&members, m).unwrap();
        let (_, heur) = method.best_split_heuristic(&members, m).unwrap();
        assert!(
            heur <= exact * (1.0 + 1e-9),
            "case {case}: heuristic {heur} > exact {exact}"
        );
        let ratio = if exact > 0.0 { heur / exact } else { 1.0 };
        sum += ratio;
        worst = worst.min(ratio);
    }
    let mean = sum / cases as f64;
    assert!(mean >= 0.999 && worst >= 0.9, "mean {mean}, worst {worst}");
}
