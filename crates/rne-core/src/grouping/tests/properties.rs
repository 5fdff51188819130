//! Property tests over random requests: every method returns a partition meeting the quotas
//! for any `K` in 1..=5, and for `K = 2` each built-in method gives exactly the groups of the
//! pre-`K`-task implementation ([`super::oracle_two_task`]).

use proptest::prelude::*;

use super::common::random_request;
use super::oracle_two_task as oracle;
use crate::grouping::{
    Assignment, GroupingMethod, GroupingRequest, HierarchicalRne, METHOD_NAMES, method_from_name,
};
use crate::{Alignment, NeedsVector, RneOptions, TrustModel, Weights};

fn model(sorted: bool) -> TrustModel {
    let alignment = if sorted {
        Alignment::Sorted
    } else {
        Alignment::Category
    };
    let opts = RneOptions {
        alignment,
        ..Default::default()
    };
    TrustModel::new(Weights::uniform(3).unwrap(), opts).unwrap()
}

/// Checks that `a` is a partition of the team meeting every quota, without
/// [`Assignment::validate`] (which the methods' `group` uses).
fn check_partition(req: &GroupingRequest, a: &Assignment, name: &str) -> Result<(), TestCaseError> {
    prop_assert_eq!(a.groups.len(), req.tasks(), "{}: number of groups", name);
    let placed: usize = a.groups.iter().map(Vec::len).sum();
    prop_assert_eq!(placed, req.robots().len(), "{}: robots placed", name);
    for r in req.robots() {
        let times = a.groups.iter().filter(|g| g.contains(&r.id)).count();
        prop_assert_eq!(times, 1, "{}: robot {} placed {} times", name, r.id, times);
    }
    for (kind, q) in req.quotas().iter().enumerate() {
        for (task, group) in a.groups.iter().enumerate() {
            let of_kind = group
                .iter()
                .filter(|&&id| req.robot(id).is_some_and(|r| r.kind == kind))
                .count();
            prop_assert_eq!(of_kind, q[task], "{}: kind {} task {}", name, kind, task);
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn every_method_returns_a_partition_meeting_quotas(req in random_request(1..=5), sorted in any::<bool>()) {
        let model = model(sorted);
        for name in METHOD_NAMES {
            let method = method_from_name(name, &model).unwrap();
            // Nothing fails, not even RNE on an all-zero group (uniform with smoothing).
            match method.assign(&req) {
                Ok(a) => check_partition(&req, &a, name)?,
                Err(e) => prop_assert!(false, "{}: {}", name, e),
            }
        }
    }

    #[test]
    fn split_within_a_kind_is_the_brute_force_maximum((rows, m) in small_kind()) {
        let method = HierarchicalRne::new(TrustModel::with_weights(Weights::uniform(rows[0].len()).unwrap()));
        let needs: Vec<NeedsVector> = rows.into_iter().map(|r| NeedsVector::new(r).unwrap()).collect();
        prop_assume!(needs.iter().all(|n| n.as_slice().iter().any(|x| *x > 0.0)));
        let members: Vec<&NeedsVector> = needs.iter().collect();
        let (split, score) = method.best_split(&members, m).unwrap();
        prop_assert_eq!(split.first.len(), m);
        let brute = brute_force_best(&method, &members, m);
        prop_assert!((score - brute).abs() <= 1e-12 * brute.abs().max(1.0), "{} vs {}", score, brute);
    }
}

proptest! {
    // Cheap (tiny teams) and the guarantee the simulator's results rest on: many cases.
    #![proptest_config(ProptestConfig::with_cases(2048))]

    #[test]
    fn two_tasks_match_the_oracle_exactly(req in random_request(2..=2), sorted in any::<bool>()) {
        let (easy, hard) = (req.hardest_first()[1], req.hardest_first()[0]);
        let as_easy_hard = |a: Assignment| oracle::EasyHard { easy: a.groups[easy].clone(), hard: a.groups[hard].clone() };
        let rne = HierarchicalRne::new(model(sorted));
        let got = rne.assign(&req).map(as_easy_hard);
        prop_assert_eq!(got, oracle::rne(&rne, &req), "rne");
        for (name, want) in [("dis", oracle::dis(&req)), ("eng", oracle::eng(&req)), ("hp_dis", oracle::hp_dis(&req))] {
            let got = method_from_name(name, &model(sorted)).unwrap().assign(&req).unwrap();
            prop_assert_eq!(as_easy_hard(got), want, "{}", name);
        }
    }
}

/// Best `J` over all subsets of size `m` by bitmask enumeration.
fn brute_force_best(method: &HierarchicalRne, members: &[&NeedsVector], m: usize) -> f64 {
    let n = members.len();
    let mut best = f64::NEG_INFINITY;
    for mask in 0u32..(1 << n) {
        if mask.count_ones() as usize != m {
            continue;
        }
        let (a, b): (Vec<_>, Vec<_>) = (0..n).partition(|i| mask & (1 << i) != 0);
        let a: Vec<_> = a.into_iter().map(|i| members[i]).collect();
        let b: Vec<_> = b.into_iter().map(|i| members[i]).collect();
        best = best.max(method.between_rne(&a, &b).unwrap());
    }
    best
}

fn small_kind() -> impl Strategy<Value = (Vec<Vec<f64>>, usize)> {
    (1usize..8, 2usize..5).prop_flat_map(|(n, j)| {
        (
            prop::collection::vec(prop::collection::vec(0.0..100.0f64, j), n),
            0..=n,
        )
    })
}
