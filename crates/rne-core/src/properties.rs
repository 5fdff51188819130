//! Property tests of RNE (Eqs. 7, 12, 17) over random needs vectors.

use approx::assert_abs_diff_eq;
use proptest::prelude::*;

use crate::{Alignment, LogBase, NeedsVector, RneOptions, Smoothing, TrustModel, Weights};

fn needs(j: usize) -> impl Strategy<Value = Vec<f64>> {
    // Mix exact zeros in so that the smoothing path is exercised.
    prop::collection::vec(prop_oneof![1 => Just(0.0), 4 => 0.0..1000.0f64], j)
}

fn case() -> impl Strategy<Value = (Vec<f64>, Vec<f64>, Vec<f64>)> {
    (1usize..8).prop_flat_map(|j| (prop::collection::vec(0.1..10.0f64, j), needs(j), needs(j)))
}

fn model(w: Vec<f64>, smoothing: Smoothing, alignment: Alignment) -> TrustModel {
    let opts = RneOptions {
        smoothing,
        alignment,
        log_base: LogBase::E,
    };
    TrustModel::new(Weights::new(w).unwrap(), opts).unwrap()
}

proptest! {
    #[test]
    fn rne_is_non_negative_and_never_nan((w, a, b) in case(), sorted in any::<bool>(), smooth in any::<bool>()) {
        let alignment = if sorted { Alignment::Sorted } else { Alignment::Category };
        let smoothing = if smooth { Smoothing::default() } else { Smoothing::None };
        let m = model(w, smoothing, alignment);
        let (a, b) = (NeedsVector::new(a).unwrap(), NeedsVector::new(b).unwrap());
        match m.agent_agent(&a, &b) {
            Ok(t) => {
                prop_assert!(!t.is_nan());
                prop_assert!(t >= 0.0);
                if smooth { prop_assert!(t.is_finite()); }
            }
            // Only an all-zero vector without smoothing has no distribution.
            Err(e) => prop_assert!(!smooth && matches!(e, crate::RneError::ZeroTotal { .. }), "{}", e),
        }
    }

    #[test]
    fn rne_is_zero_for_equal_distributions((w, a, _b) in case(), c in 0.01..100.0f64) {
        prop_assume!(a.iter().any(|x| *x > 0.0));
        let m = model(w, Smoothing::default(), Alignment::Category);
        let scaled: Vec<f64> = a.iter().map(|x| x * c).collect();
        let (a, s) = (NeedsVector::new(a).unwrap(), NeedsVector::new(scaled).unwrap());
        assert_abs_diff_eq!(m.agent_agent(&a, &a).unwrap(), 0.0, epsilon = 1e-12);
        // Scaling a needs vector leaves its distribution, hence RNE, unchanged.
        assert_abs_diff_eq!(m.agent_agent(&a, &s).unwrap(), 0.0, epsilon = 1e-9);
    }

    #[test]
    fn rne_is_invariant_to_scaling((w, a, b) in case(), c in 0.01..100.0f64) {
        prop_assume!(a.iter().any(|x| *x > 0.0) && b.iter().any(|x| *x > 0.0));
        let m = model(w, Smoothing::default(), Alignment::Category);
        let sa: Vec<f64> = a.iter().map(|x| x * c).collect();
        let (a, b, sa) = (NeedsVector::new(a).unwrap(), NeedsVector::new(b).unwrap(), NeedsVector::new(sa).unwrap());
        let t = m.agent_agent(&a, &b).unwrap();
        let ts = m.agent_agent(&sa, &b).unwrap();
        let tb = m.agent_agent(&b, &sa).unwrap();
        assert_abs_diff_eq!(t, ts, epsilon = 1e-9 * t.max(1.0));
        assert_abs_diff_eq!(m.agent_agent(&b, &a).unwrap(), tb, epsilon = 1e-9 * tb.max(1.0));
    }
}

#[test]
fn rne_is_asymmetric() {
    let m = model(vec![1.0, 1.0], Smoothing::None, Alignment::Category);
    let a = NeedsVector::new(vec![1.0, 1.0]).unwrap();
    let b = NeedsVector::new(vec![9.0, 1.0]).unwrap();
    let ab = m.agent_agent(&a, &b).unwrap();
    let ba = m.agent_agent(&b, &a).unwrap();
    // T(a||b) = 0.5 ln(0.5/0.9) + 0.5 ln(0.5/0.1) = 0.5108; T(b||a) = 0.3681.
    assert_abs_diff_eq!(
        ab,
        0.5 * (0.5f64 / 0.9).ln() + 0.5 * 5f64.ln(),
        epsilon = 1e-12
    );
    assert_abs_diff_eq!(ba, 0.9 * 1.8f64.ln() + 0.1 * 0.2f64.ln(), epsilon = 1e-12);
    assert!((ab - ba).abs() > 0.1);
}

#[test]
fn sorted_alignment_ignores_category_order() {
    let cat = model(vec![1.0; 3], Smoothing::None, Alignment::Category);
    let sorted = model(vec![1.0; 3], Smoothing::None, Alignment::Sorted);
    let a = NeedsVector::new(vec![1.0, 2.0, 7.0]).unwrap();
    let b = NeedsVector::new(vec![7.0, 1.0, 2.0]).unwrap();
    assert!(cat.agent_agent(&a, &b).unwrap() > 0.5);
    assert_abs_diff_eq!(sorted.agent_agent(&a, &b).unwrap(), 0.0, epsilon = 1e-15);
}
