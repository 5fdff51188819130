//! Shared test fixtures: the paper's team (Sec. VI.B), a deterministic Gaussian, random
//! `K`-task requests for property tests.

use proptest::prelude::*;

use crate::grouping::{GroupingRequest, RobotSnapshot};
use crate::{NeedsVector, TrustModel, Weights};

/// Task indices of the paper's two tasks in the test requests.
pub(crate) const EASY: usize = 0;
/// See [`EASY`].
pub(crate) const HARD: usize = 1;

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

/// 6 carriers, 4 suppliers, 2 observers; `levels[i] = (hp %, energy %)` of robot `i`; two
/// tasks, easy = 0 and hard = 1, quotas 3/3, 2/2, 1/1.
pub(crate) fn paper_team(levels: &[(f64, f64); 12]) -> GroupingRequest {
    let kinds = [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2];
    let robots = (0..12)
        .map(|id| RobotSnapshot {
            id,
            kind: kinds[id],
            needs: paper_needs(kinds[id], levels[id].0, levels[id].1),
            energy_pct: levels[id].1,
            hp_pct: levels[id].0,
            distance_to_goal_m: vec![20.0 + id as f64, 40.0 - id as f64],
        })
        .collect();
    let q = |n| vec![n, n];
    GroupingRequest::new(robots, vec![q(3), q(2), q(1)], vec![HARD, EASY]).unwrap()
}

/// The trust model with uniform weights over the paper's 7 needs.
pub(crate) fn uniform_model() -> TrustModel {
    TrustModel::with_weights(Weights::uniform(7).unwrap())
}

/// Mean HP + energy of the robots `ids`.
pub(crate) fn mean_level(req: &GroupingRequest, ids: &[usize]) -> f64 {
    ids.iter()
        .map(|&id| req.robot(id).map_or(0.0, |r| r.hp_pct + r.energy_pct))
        .sum::<f64>()
        / ids.len() as f64
}

/// SplitMix64 + Box-Muller: deterministic Gaussian levels without a `rand` dependency.
pub(crate) struct Gauss(pub u64);

impl Gauss {
    pub(crate) fn uniform(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    pub(crate) fn sample(&mut self, mean: f64, sd: f64) -> f64 {
        let (u1, u2) = (self.uniform().max(1e-300), self.uniform());
        let z = (-2.0 * u1.ln()).sqrt() * (std::f64::consts::TAU * u2).cos();
        (mean + sd * z).clamp(5.0, 100.0)
    }
}

/// A value drawn often from a few fixed points (to make ties) and otherwise from `lo..hi`.
fn tied(lo: f64, hi: f64, points: [f64; 3]) -> impl Strategy<Value = f64> {
    prop_oneof![
        1 => Just(points[0]),
        1 => Just(points[1]),
        1 => Just(points[2]),
        3 => lo..hi,
    ]
}

/// Splits `count` into `tasks` quotas with the pseudo-random `seeds` (some may be 0).
fn compose(count: usize, seeds: &[u64]) -> Vec<usize> {
    let mut left = count;
    let mut q: Vec<usize> = seeds[..seeds.len() - 1]
        .iter()
        .map(|&s| {
            let take = (s as usize) % (left + 1);
            left -= take;
            take
        })
        .collect();
    q.push(left);
    q
}

/// A random request: `K` in `tasks`, 1-3 kinds of 0-6 robots (at least one robot), random
/// per-kind task quotas (zeros and empty tasks included), 3 needs with exact zeros and ties,
/// energies, HPs and distances with frequent ties, ids not in input order, a random difficulty
/// order.
pub(crate) fn random_request(
    tasks: std::ops::RangeInclusive<usize>,
) -> impl Strategy<Value = GroupingRequest> {
    (tasks, prop::collection::vec(0usize..7, 1..4))
        .prop_flat_map(|(k, counts)| {
            let n: usize = counts.iter().sum();
            let order: Vec<usize> = (0..k).collect();
            (
                Just(counts.clone()),
                prop::collection::vec(prop::collection::vec(any::<u64>(), k), counts.len()),
                prop::collection::vec(
                    (
                        tied(1.0, 100.0, [50.0, 80.0, 100.0]),
                        tied(1.0, 100.0, [50.0, 80.0, 100.0]),
                        prop::collection::vec(tied(0.0, 50.0, [10.0, 20.0, 0.0]), k),
                        prop::collection::vec(tied(0.0, 10.0, [0.0, 1.0, 5.0]), 3),
                    ),
                    n,
                ),
                Just(order).prop_shuffle(),
            )
        })
        .prop_filter_map("a team", |(counts, seeds, states, order)| {
            let mut robots = Vec::new();
            let mut quotas = Vec::new();
            for (kind, &count) in counts.iter().enumerate() {
                quotas.push(compose(count, &seeds[kind]));
                for _ in 0..count {
                    let id = robots.len();
                    let (hp, energy, ref dist, ref needs) = states[id];
                    robots.push(RobotSnapshot {
                        id: id * 7 % 101,
                        kind,
                        needs: NeedsVector::new(needs.clone()).unwrap(),
                        energy_pct: energy,
                        hp_pct: hp,
                        distance_to_goal_m: dist.clone(),
                    });
                }
            }
            GroupingRequest::new(robots, quotas, order).ok()
        })
}
