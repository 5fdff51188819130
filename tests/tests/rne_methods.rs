//! Cross-crate check: every grouping method named on the command line builds from its name and
//! returns a valid partition of the paper's team (6 carriers, 4 suppliers, 2 observers).

use rne_core::grouping::{
    GroupingRequest, KindQuota, METHOD_NAMES, RobotSnapshot, method_from_name,
};
use rne_core::{NeedsVector, TrustModel, Weights};

fn paper_team() -> GroupingRequest {
    let base = [
        [100.0, 1.5, 10.0, 100.0, 1.0, 6.0, 0.01],
        [100.0, 1.5, 10.0, 100.0, 10.0, 1.0, 0.01],
        [50.0, 1.0, 60.0, 200.0 / 3.0, 0.0, 0.0, 10.0],
    ];
    let kinds = [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2];
    let robots = (0..12)
        .map(|id| {
            let (h, e) = (0.5 + 0.04 * id as f64, 1.0 - 0.03 * id as f64);
            let b = base[kinds[id]];
            RobotSnapshot {
                id,
                kind: kinds[id],
                needs: NeedsVector::new(vec![
                    b[0] * h,
                    b[1] * h,
                    b[2] * h,
                    b[3] * e,
                    b[4],
                    b[5],
                    b[6] * h,
                ])
                .expect("valid needs"),
                energy_pct: 100.0 * e,
                hp_pct: 100.0 * h,
                distance_to_goal_m: [15.0 + id as f64, 35.0 - 2.0 * id as f64],
            }
        })
        .collect();
    let q = |n| KindQuota { easy: n, hard: n };
    GroupingRequest::new(robots, vec![q(3), q(2), q(1)]).expect("valid request")
}

#[test]
fn every_named_method_partitions_the_paper_team() {
    let model = TrustModel::with_weights(Weights::uniform(7).expect("weights"));
    let request = paper_team();
    for name in METHOD_NAMES {
        let method = method_from_name(&name.to_uppercase(), &model).expect("known name");
        assert_eq!(method.name(), name);
        let a = method.group(&request).expect("grouping succeeds");
        assert_eq!((a.easy.len(), a.hard.len()), (6, 6), "{name}");
    }
}
