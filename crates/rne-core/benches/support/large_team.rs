//! A deterministic large team for the scaling benchmark and example: kinds with the paper's
//! needs ratios (Sec. VI.B) and random HP and energy levels, `K` tasks, random distances.
//! Shared by the `grouping` bench and the `grouping_scale` and `split_quality` examples, each
//! of which uses only some of it.
#![allow(dead_code)]

use rne_core::NeedsVector;
use rne_core::grouping::{GroupingRequest, RobotSnapshot};

/// Full-level needs `hp, v, sen, eng, res, cap, obs` of carrier, supplier, observer.
const BASE: [[f64; 7]; 3] = [
    [100.0, 1.5, 10.0, 100.0, 1.0, 6.0, 0.01],
    [100.0, 1.5, 10.0, 100.0, 10.0, 1.0, 0.01],
    [50.0, 1.0, 60.0, 66.7, 0.0, 0.0, 10.0],
];

/// Deterministic uniform numbers in `[0, 1)` (SplitMix64 on `state`).
pub fn unit(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

/// The needs of a robot of kind `kind` (0-2) at HP and energy fractions `hp`, `energy`
/// (`0..=1`): HP scales hp, v, sen, obs; energy scales eng (Sec. VI.B).
pub fn paper_needs(kind: usize, hp: f64, energy: f64) -> Vec<f64> {
    let b = BASE[kind];
    vec![
        b[0] * hp,
        b[1] * hp,
        b[2] * hp,
        b[3] * energy,
        b[4],
        b[5],
        b[6] * hp,
    ]
}

/// A team with `counts[k]` robots of kind `k` (kinds 0-2: carrier, supplier, observer; ids in
/// kind order), `tasks` tasks with task 0 the hardest (`hardest_first = [0, 1, ..]`), each
/// kind's robots spread evenly over the tasks (the remainder to the easiest), HP 60-100 % and
/// energy 40-100 % at random, distances 10-110 m at random.
pub fn large_team(counts: [usize; 3], tasks: usize, seed: u64) -> GroupingRequest {
    let mut state = seed;
    let mut robots = Vec::new();
    for (kind, &count) in counts.iter().enumerate() {
        for _ in 0..count {
            let hp = 0.6 + 0.4 * unit(&mut state);
            let energy = 0.4 + 0.6 * unit(&mut state);
            let needs = paper_needs(kind, hp, energy);
            robots.push(RobotSnapshot {
                id: robots.len(),
                kind,
                needs: NeedsVector::new(needs).expect("valid needs"),
                energy_pct: 100.0 * energy,
                hp_pct: 100.0 * hp,
                distance_to_goal_m: (0..tasks)
                    .map(|_| 10.0 + 100.0 * unit(&mut state))
                    .collect(),
            });
        }
    }
    let quotas = counts
        .iter()
        .map(|&n| {
            let mut q = vec![n / tasks; tasks];
            q[tasks - 1] += n % tasks;
            q
        })
        .collect();
    GroupingRequest::new(robots, quotas, (0..tasks).collect()).expect("valid request")
}
