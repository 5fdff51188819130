//! Tests of the grouping methods: the paper's team (Sec. VI.B), partitions, brute force.

use proptest::prelude::*;

use super::*;
use crate::{Alignment, NeedsVector, RneError, RneOptions, TrustModel, Weights};

/// Full-level needs `hp, v, sen, eng, res, cap, obs` per kind with the ratios of Sec. VI.B:
/// `hp_s = hp_c = 2 hp_o`, `v_c = v_s = 1.5 v_o`, `sen_o = 6 sen_c = 6 sen_s`,
/// `eng_s = eng_c = 1.5 eng_o`, `cap_c = 6 cap_s`, `cap_o = 0`, `res_s = 10 res_c`, `res_o = 0`,
/// `obs_o = 1000 obs_c = 1000 obs_s`.
const BASE: [[f64; 7]; 3] = [
    [100.0, 1.5, 10.0, 100.0, 1.0, 6.0, 0.01],      // carrier
    [100.0, 1.5, 10.0, 100.0, 10.0, 1.0, 0.01],     // supplier
    [50.0, 1.0, 60.0, 200.0 / 3.0, 0.0, 0.0, 10.0], // observer
];

/// HP scales hp, speed, sensing and observing range (Sec. VI.B); energy scales eng;
/// capacity and resources are full at the start of a round.
pub(crate) fn paper_needs(kind: usize, hp_pct: f64, energy_pct: f64) -> NeedsVector {
    let b = BASE[kind];
    let (h, e) = (hp_pct / 100.0, energy_pct / 100.0);
    NeedsVector::new(vec![
        b[0] * h,
        b[1] * h,
        b[2] * h,
        b[3] * e,
        b[4],
        b[5],
        b[6] * h,
    ])
    .unwrap()
}

/// 6 carriers, 4 suppliers, 2 observers; `levels[i] = (hp %, energy %)` of robot `i`.
fn paper_team(levels: &[(f64, f64); 12]) -> GroupingRequest {
    let kinds = [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2];
    let robots = (0..12)
        .map(|id| RobotSnapshot {
            id,
            kind: kinds[id],
            needs: paper_needs(kinds[id], levels[id].0, levels[id].1),
            energy_pct: levels[id].1,
            hp_pct: levels[id].0,
            distance_to_goal_m: [20.0 + id as f64, 40.0 - id as f64],
        })
        .collect();
    let q = |n| KindQuota { easy: n, hard: n };
    GroupingRequest::new(robots, vec![q(3), q(2), q(1)]).unwrap()
}

fn uniform_model() -> TrustModel {
    TrustModel::with_weights(Weights::uniform(7).unwrap())
}

fn mean_level(req: &GroupingRequest, ids: &[usize]) -> f64 {
    ids.iter()
        .map(|&id| req.robot(id).map_or(0.0, |r| r.hp_pct + r.energy_pct))
        .sum::<f64>()
        / ids.len() as f64
}

/// SplitMix64 + Box-Muller: deterministic Gaussian levels without a `rand` dependency.
struct Gauss(u64);

impl Gauss {
    fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn sample(&mut self, mean: f64, sd: f64) -> f64 {
        let (u1, u2) = (self.uniform().max(1e-300), self.uniform());
        let z = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
        (mean + sd * z).clamp(5.0, 100.0)
    }
}

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
    assert!(!out.forced_by_quotas);
    // The strong carriers (0, 2, 4) and suppliers (6, 8) go to the hard task, and that group
    // trusts itself more. But the *weak* observer (11) joins them: at the last merge the
    // pairing "strong C+S with weak O" maximises J, because the observer alone carries the
    // group's obs/sen shares, so mismatching levels across kinds makes the two groups'
    // distributions differ most. This is the algorithm as specified, reported honestly
    // (docs/trust-model.md, "Does the hard task get the stronger robots?").
    assert_eq!(out.assignment.hard, vec![0, 2, 4, 6, 8, 11]);
    assert!(out.within_rne[1] < out.within_rne[0], "{out:?}");
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
        if mean_level(&req, &a.hard) > mean_level(&req, &a.easy) {
            stronger += 1;
        }
        for (kind, count) in per_kind.iter_mut().enumerate() {
            let of_kind = |ids: &[usize]| {
                ids.iter()
                    .copied()
                    .filter(|&id| req.robot(id).is_some_and(|r| r.kind == kind))
                    .collect::<Vec<_>>()
            };
            if mean_level(&req, &of_kind(&a.hard)) > mean_level(&req, &of_kind(&a.easy)) {
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
    let q = vec![
        KindQuota { easy: 2, hard: 4 },
        KindQuota { easy: 2, hard: 2 },
        KindQuota { easy: 1, hard: 1 },
    ];
    let req = GroupingRequest::new(base.robots().to_vec(), q).unwrap();
    let out = HierarchicalRne::new(uniform_model())
        .group_detailed(&req)
        .unwrap();
    out.assignment.validate(&req).unwrap();
    assert!(out.forced_by_quotas);
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

fn small_team() -> impl Strategy<Value = (Vec<Vec<f64>>, usize)> {
    (1usize..8, 2usize..5).prop_flat_map(|(n, j)| {
        (
            prop::collection::vec(prop::collection::vec(0.0..100.0f64, j), n),
            0..=n,
        )
    })
}

/// A random team: 1-4 kinds of 1-5 robots, random per-kind quotas with both tasks non-empty.
fn random_request() -> impl Strategy<Value = GroupingRequest> {
    prop::collection::vec((1usize..6, any::<u64>()), 1..5)
        .prop_flat_map(|kinds| {
            let n: usize = kinds.iter().map(|k| k.0).sum();
            (
                Just(kinds),
                prop::collection::vec(
                    (1.0..100.0f64, 1.0..100.0f64, 0.0..50.0f64, 0.0..50.0f64),
                    n,
                ),
                prop::collection::vec(0.0..10.0f64, n * 3),
            )
        })
        .prop_filter_map("both tasks need a robot", |(kinds, states, needs)| {
            let mut robots = Vec::new();
            let mut quotas = Vec::new();
            for (kind, &(count, seed)) in kinds.iter().enumerate() {
                let easy = (seed as usize) % (count + 1);
                quotas.push(KindQuota {
                    easy,
                    hard: count - easy,
                });
                for _ in 0..count {
                    let id = robots.len();
                    let (hp, eng, de, dh) = states[id];
                    robots.push(RobotSnapshot {
                        // Ids deliberately not in input order.
                        id: id * 7 % 101,
                        kind,
                        needs: NeedsVector::new(needs[id * 3..id * 3 + 3].to_vec()).unwrap(),
                        energy_pct: eng,
                        hp_pct: hp,
                        distance_to_goal_m: [de, dh],
                    });
                }
            }
            GroupingRequest::new(robots, quotas).ok()
        })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn every_method_returns_a_partition_meeting_quotas(req in random_request(), sorted in any::<bool>()) {
        let alignment = if sorted { Alignment::Sorted } else { Alignment::Category };
        let opts = RneOptions { alignment, ..Default::default() };
        let model = TrustModel::new(Weights::uniform(3).unwrap(), opts).unwrap();
        for name in METHOD_NAMES {
            let method = method_from_name(name, &model).unwrap();
            // `assign`, not `group`: `group` would validate the partition itself.
            match method.assign(&req) {
                Ok(a) => {
                    prop_assert_eq!(a.easy.len() + a.hard.len(), req.robots().len());
                    for r in req.robots() {
                        let in_easy = a.easy.contains(&r.id);
                        prop_assert!(in_easy != a.hard.contains(&r.id), "{}: robot {} placed {} times", name, r.id, if in_easy { 2 } else { 0 });
                    }
                    for (kind, q) in req.quotas().iter().enumerate() {
                        let of_kind = |ids: &[usize]| ids.iter().filter(|&&id| req.robot(id).is_some_and(|r| r.kind == kind)).count();
                        prop_assert_eq!((of_kind(&a.easy), of_kind(&a.hard)), (q.easy, q.hard), "{}: kind {}", name, kind);
                    }
                }
                // RNE cannot build the distribution of an all-zero group; nothing else fails.
                Err(e) => prop_assert!(name == "rne" && matches!(e, RneError::ZeroTotal { .. }), "{}: {}", name, e),
            }
        }
    }

    #[test]
    fn split_within_a_kind_is_the_brute_force_maximum((rows, m) in small_team()) {
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

#[test]
fn split_ties_go_to_the_first_in_asc_order() {
    let method = HierarchicalRne::new(TrustModel::with_weights(Weights::uniform(2).unwrap()));
    let same = NeedsVector::new(vec![1.0, 1.0]).unwrap();
    let (split, score) = method.best_split(&[&same, &same, &same, &same], 2).unwrap();
    assert_eq!(score, 0.0);
    assert_eq!(split.first, vec![0, 1]);
}

#[test]
fn baselines_follow_their_rules() {
    let mut levels = [(90.0, 80.0); 12];
    for (i, l) in levels.iter_mut().enumerate() {
        *l = (50.0 + i as f64 * 4.0, 100.0 - i as f64 * 5.0);
    }
    let req = paper_team(&levels);
    // ENG: highest energy = lowest ids within each kind.
    assert_eq!(Eng.group(&req).unwrap().hard, vec![0, 1, 2, 6, 7, 10]);
    // HP_DIS: highest HP = highest ids within each kind.
    assert_eq!(HpDis.group(&req).unwrap().hard, vec![3, 4, 5, 8, 9, 11]);
    // DIS: distances [20 + id, 40 - id]: ids 0..=9 are nearer easy, ids 11 nearer hard.
    let dis = Dis.group(&req).unwrap();
    assert_eq!(dis.easy, vec![0, 1, 2, 6, 7, 10]);
}

#[test]
fn hp_dis_breaks_hp_ties_by_distance_to_hard_goal() {
    let req = paper_team(&[(80.0, 80.0); 12]);
    // Equal HP; distance to hard is 40 - id, so the highest ids of each kind are nearest.
    assert_eq!(HpDis.group(&req).unwrap().hard, vec![3, 4, 5, 8, 9, 11]);
}

#[test]
fn a_custom_method_plugs_in_without_changes() {
    struct AllLowIdsEasy;
    impl GroupingMethod for AllLowIdsEasy {
        fn name(&self) -> &str {
            "low_ids_easy"
        }
        fn assign(&self, request: &GroupingRequest) -> crate::Result<Assignment> {
            let (mut easy, mut hard) = (vec![], vec![]);
            for (kind, q) in request.quotas().iter().enumerate() {
                for (i, r) in request.members_of_kind(kind).into_iter().enumerate() {
                    if i < q.easy {
                        easy.push(r.id)
                    } else {
                        hard.push(r.id)
                    }
                }
            }
            Ok(Assignment::new(easy, hard))
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
    assert_eq!(methods[0].name(), "low_ids_easy");
    std::thread::scope(|s| {
        s.spawn(|| methods[1].group(&req).unwrap());
    });
}

#[test]
fn method_names_are_case_insensitive_and_errors_list_valid_names() {
    let m = uniform_model();
    for (name, want) in [
        ("RNE", "rne"),
        ("Dis", "dis"),
        ("ENG", "eng"),
        ("hp_dis", "hp_dis"),
        ("HP-DIS", "hp_dis"),
    ] {
        assert_eq!(method_from_name(name, &m).unwrap().name(), want);
    }
    let err = method_from_name("nearest", &m).err().unwrap();
    assert!(err.to_string().contains("rne, dis, eng, hp_dis"), "{err}");
}

#[test]
fn bad_assignments_are_rejected() {
    let req = paper_team(&[(80.0, 80.0); 12]);
    let ok = Eng.group(&req).unwrap();
    let mut dup = ok.clone();
    dup.easy[0] = dup.hard[0];
    assert!(matches!(
        dup.validate(&req),
        Err(RneError::InvalidAssignment(_))
    ));
    let swapped = Assignment::new(ok.hard.clone(), ok.easy.clone());
    assert!(
        swapped.validate(&req).is_ok(),
        "equal quotas: swapping is still valid"
    );
    let mut short = ok.clone();
    short.easy.pop();
    assert!(
        short
            .validate(&req)
            .unwrap_err()
            .to_string()
            .contains("not assigned")
    );
}
