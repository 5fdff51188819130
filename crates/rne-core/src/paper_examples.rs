//! Golden tests: the paper's Examples 1-3, exact and as printed (see docs/trust-model.md,
//! "Errata").

use approx::assert_abs_diff_eq;

use crate::{
    LogBase, NeedsMatrix, NeedsVector, RneOptions, Smoothing, TrustModel, Weights, relative_entropy,
};

fn model(smoothing: Smoothing) -> TrustModel {
    let opts = RneOptions {
        smoothing,
        ..Default::default()
    };
    TrustModel::new(Weights::new(vec![6.0, 4.0, 2.0]).unwrap(), opts).unwrap()
}

fn nv(v: [f64; 3]) -> NeedsVector {
    NeedsVector::new(v.to_vec()).unwrap()
}

fn g1() -> NeedsMatrix {
    NeedsMatrix::from_rows(&[vec![82.0, 114.0, 24.0], vec![79.0, 117.0, 23.0]]).unwrap()
}

fn g2() -> NeedsMatrix {
    NeedsMatrix::from_rows(&[vec![40.0, 56.0, 12.0], vec![56.0, 48.0, 15.0]]).unwrap()
}

/// Rounds (`round = true`) or truncates each share to `decimals` decimals.
fn cut(v: &[f64], decimals: i32, round: bool) -> Vec<f64> {
    let s = 10f64.powi(decimals);
    v.iter()
        .map(|x| {
            if round {
                (x * s).round() / s
            } else {
                (x * s).floor() / s
            }
        })
        .collect()
}

#[test]
fn example1_agent_agent() {
    for smoothing in [Smoothing::None, Smoothing::default()] {
        let m = model(smoothing);
        let r1 = nv([86.0, 120.0, 30.0]);
        assert_abs_diff_eq!(
            m.agent_agent(&r1, &nv([20.0, 30.0, 10.0])).unwrap(),
            0.003_725_46,
            epsilon = 1e-8
        );
        assert_abs_diff_eq!(
            m.agent_agent(&r1, &nv([80.0, 115.0, 25.0])).unwrap(),
            0.000_504_44,
            epsilon = 1e-8
        );
    }
}

#[test]
fn example2_agent_group_exact() {
    let m = model(Smoothing::None);
    let r1 = nv([86.0, 120.0, 30.0]);
    assert_abs_diff_eq!(
        m.agent_group(&r1, &g1()).unwrap(),
        0.001_022,
        epsilon = 1e-6
    );
    assert_abs_diff_eq!(
        m.agent_group(&r1, &g2()).unwrap(),
        0.007_767,
        epsilon = 1e-6
    );
}

#[test]
fn example2_as_printed_from_4_decimal_distributions() {
    let m = model(Smoothing::None);
    let d1 = cut(
        m.distribution(&nv([86.0, 120.0, 30.0])).unwrap().as_slice(),
        4,
        true,
    );
    let dg1 = cut(m.group_distribution(&g1()).unwrap().as_slice(), 4, true);
    let dg2 = cut(m.group_distribution(&g2()).unwrap().as_slice(), 4, true);
    assert_eq!(dg1, vec![0.4869, 0.4657, 0.0474]);
    assert_eq!(dg2, vec![0.5507, 0.3977, 0.0516]);
    // Paper: 0.000915 (reproduced) and 0.007674 (we get 0.0076703: 4e-6 off, see errata).
    assert_abs_diff_eq!(
        relative_entropy(&d1, &dg1, LogBase::E).unwrap(),
        0.000_915,
        epsilon = 5e-7
    );
    assert_abs_diff_eq!(
        relative_entropy(&d1, &dg2, LogBase::E).unwrap(),
        0.007_670_3,
        epsilon = 5e-8
    );
    assert_abs_diff_eq!(
        relative_entropy(&d1, &dg2, LogBase::E).unwrap(),
        0.007_674,
        epsilon = 5e-6
    );
}

#[test]
fn example3_group_group_exact() {
    let m = model(Smoothing::None);
    assert_abs_diff_eq!(
        m.group_group(&g1(), &g2()).unwrap(),
        0.009_535,
        epsilon = 1e-6
    );
    assert_abs_diff_eq!(
        m.group_group(&g2(), &g1()).unwrap(),
        0.009_419,
        epsilon = 1e-6
    );
}

#[test]
fn example3_as_printed_from_truncated_distributions_base10() {
    let m = model(Smoothing::None);
    let d1 = cut(m.group_distribution(&g1()).unwrap().as_slice(), 2, false);
    let d2 = cut(m.group_distribution(&g2()).unwrap().as_slice(), 2, false);
    // "ceiling ... to two decimals" in the paper is in fact truncation.
    assert_eq!(d1, vec![0.48, 0.46, 0.04]);
    assert_eq!(d2, vec![0.55, 0.39, 0.05]);
    let t12 = relative_entropy(&d1, &d2, LogBase::TEN).unwrap();
    let t21 = relative_entropy(&d2, &d1, LogBase::TEN).unwrap();
    assert_abs_diff_eq!(t12, 0.0007, epsilon = 5e-5);
    assert_abs_diff_eq!(t21, 0.0094, epsilon = 5e-5);
    // With the natural log the printed numbers do not come out.
    assert!(relative_entropy(&d1, &d2, LogBase::E).unwrap() > 0.0016);
}
