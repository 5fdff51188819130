//! Criterion benchmarks of the hierarchical RNE grouping (Algorithm 1) and the baselines.
#![allow(missing_docs)]

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rne_core::grouping::{
    GroupingMethod, GroupingRequest, METHOD_NAMES, RobotSnapshot, method_from_name,
};
use rne_core::{NeedsVector, TrustModel, Weights};

/// A deterministic team of `kinds x per_kind` robots with `j` needs, quotas split in half.
fn team(kinds: usize, per_kind: usize, j: usize) -> GroupingRequest {
    let mut robots = Vec::new();
    for kind in 0..kinds {
        for i in 0..per_kind {
            let id = robots.len();
            let level = 40.0 + ((id * 37) % 60) as f64;
            let needs = (0..j)
                .map(|c| ((c + 1) * (kind + 2)) as f64 * level / 10.0 + ((id + c) % 5) as f64)
                .collect::<Vec<_>>();
            robots.push(RobotSnapshot {
                id,
                kind,
                needs: NeedsVector::new(needs).expect("valid needs"),
                energy_pct: level,
                hp_pct: 100.0 - level / 2.0,
                distance_to_goal_m: vec![10.0 + i as f64, 30.0 - i as f64],
            });
        }
    }
    // Two tasks, easy = 0 and hard = 1.
    let quotas = vec![vec![per_kind / 2, per_kind - per_kind / 2]; kinds];
    GroupingRequest::new(robots, quotas, vec![1, 0]).expect("valid request")
}

/// The paper's team: 6 carriers, 4 suppliers, 2 observers, 7 needs.
fn paper_team() -> GroupingRequest {
    let base = [
        [100.0, 1.5, 10.0, 100.0, 1.0, 6.0, 0.01],
        [100.0, 1.5, 10.0, 100.0, 10.0, 1.0, 0.01],
        [50.0, 1.0, 60.0, 66.7, 0.0, 0.0, 10.0],
    ];
    let kinds = [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2];
    let robots = (0..12)
        .map(|id| {
            let (h, e) = (0.6 + 0.03 * id as f64, 0.95 - 0.04 * id as f64);
            let b = base[kinds[id]];
            let needs = vec![b[0] * h, b[1] * h, b[2] * h, b[3] * e, b[4], b[5], b[6] * h];
            RobotSnapshot {
                id,
                kind: kinds[id],
                needs: NeedsVector::new(needs).expect("valid needs"),
                energy_pct: e * 100.0,
                hp_pct: h * 100.0,
                distance_to_goal_m: vec![20.0, 40.0],
            }
        })
        .collect();
    let q = |n| vec![n, n];
    GroupingRequest::new(robots, vec![q(3), q(2), q(1)], vec![1, 0]).expect("valid request")
}

fn bench(c: &mut Criterion) {
    let cases = [
        ("paper_12_robots_3_kinds", paper_team(), 7),
        ("8_kinds_x_8_robots", team(8, 8, 7), 7),
        ("4_kinds_x_12_robots", team(4, 12, 7), 7),
    ];
    for (label, request, j) in &cases {
        let model = TrustModel::with_weights(Weights::uniform(*j).expect("weights"));
        for name in METHOD_NAMES {
            let method: Box<dyn GroupingMethod> = method_from_name(name, &model).expect("method");
            c.bench_function(&format!("{name}/{label}"), |b| {
                b.iter(|| method.group(black_box(request)).expect("grouping"))
            });
        }
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
