//! The split scorer: its running-sum `J` and its first-order gains agree with the exact
//! between-RNE for every smoothing and alignment.

use proptest::prelude::*;

use crate::grouping::HierarchicalRne;
use crate::grouping::split_scorer::SplitScorer;
use crate::{Alignment, LogBase, NeedsVector, RneOptions, Smoothing, TrustModel, Weights};

fn model(smoothing: Smoothing, alignment: Alignment, j: usize) -> TrustModel {
    let opts = RneOptions {
        smoothing,
        alignment,
        log_base: LogBase::TWO,
    };
    TrustModel::new(
        Weights::new((1..=j).map(|w| w as f64).collect::<Vec<_>>()).unwrap(),
        opts,
    )
    .unwrap()
}

fn options() -> impl Strategy<Value = (Smoothing, Alignment)> {
    (
        prop_oneof![
            Just(Smoothing::default()),
            Just(Smoothing::Absolute(0.5)),
            Just(Smoothing::None)
        ],
        prop_oneof![Just(Alignment::Category), Just(Alignment::Sorted)],
    )
}

/// 2-9 members with 2-5 needs in `0.5..50`, and a membership flag per member.
fn kind() -> impl Strategy<Value = (Vec<Vec<f64>>, Vec<bool>)> {
    (2usize..10, 2usize..6).prop_flat_map(|(n, j)| {
        (
            prop::collection::vec(prop::collection::vec(0.5..50.0f64, j), n),
            prop::collection::vec(any::<bool>(), n),
        )
    })
}

proptest! {
    #[test]
    fn running_sum_score_matches_the_exact_between_rne((rows, flags) in kind(), (smoothing, alignment) in options()) {
        prop_assume!(flags.iter().any(|&f| f) && flags.iter().any(|&f| !f));
        let m = model(smoothing, alignment, rows[0].len());
        let needs: Vec<NeedsVector> = rows.into_iter().map(|r| NeedsVector::new(r).unwrap()).collect();
        let members: Vec<&NeedsVector> = needs.iter().collect();
        let scorer = SplitScorer::new(&m, &members).unwrap();
        let (first, second): (Vec<usize>, Vec<usize>) = (0..members.len()).partition(|&r| flags[r]);
        let exact = scorer.exact(&first, &second).unwrap();
        // The exact path is bit-identical to `between_rne`.
        let pick = |idx: &[usize]| idx.iter().map(|&i| members[i]).collect::<Vec<_>>();
        let method = HierarchicalRne::new(m.clone());
        prop_assert_eq!(exact, method.between_rne(&pick(&first), &pick(&second)).unwrap());
        let (sa, sb) = scorer.sums_of(&flags);
        let fast = scorer.score(&sa, &sb, &mut scorer.scratch());
        prop_assert!((fast - exact).abs() <= 1e-10 * exact.max(1e-3), "{} vs {}", fast, exact);
    }

    #[test]
    fn move_gains_are_the_derivative_of_j((rows, flags) in kind(), (smoothing, alignment) in options()) {
        prop_assume!(flags.iter().filter(|&&f| f).count() >= 2 && flags.iter().any(|&f| !f));
        let m = model(smoothing, alignment, rows[0].len());
        let needs: Vec<NeedsVector> = rows.into_iter().map(|r| NeedsVector::new(r).unwrap()).collect();
        let members: Vec<&NeedsVector> = needs.iter().collect();
        let scorer = SplitScorer::new(&m, &members).unwrap();
        let mut w = scorer.scratch();
        let (sa, sb) = scorer.sums_of(&flags);
        let mut gains = vec![0.0; members.len()];
        scorer.move_gains(&sa, &sb, &mut w, &mut gains);
        let r = flags.iter().position(|&f| f).unwrap();
        // Move a small fraction t of member r from the first side to the second, and back: a
        // central difference, whose error is O(t^2) (a one-sided one's, O(t), was 1e-5 where
        // J bends sharply, as large as the tolerance for a small gain).
        let t = 1e-6;
        let v = scorer.row(r).to_vec();
        let moved = |t: f64, w: &mut _| {
            let na: Vec<f64> = sa.iter().zip(&v).map(|(s, v)| s - t * v).collect();
            let nb: Vec<f64> = sb.iter().zip(&v).map(|(s, v)| s + t * v).collect();
            scorer.score(&na, &nb, w)
        };
        let numeric = (moved(t, &mut w) - moved(-t, &mut w)) / (2.0 * t);
        // In the model's log base (bits): gains are in nats.
        let analytic = gains[r] / 2f64.ln();
        prop_assert!((numeric - analytic).abs() <= 1e-3 * analytic.abs().max(1e-2), "numeric {} vs analytic {}", numeric, analytic);
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// Needs near `f64::MAX` (their weighted total overflows) are scaled as the distributions
    /// scale them, so the heuristic finds as good a split as at ordinary magnitudes, with the
    /// same exact `J` (it kept an arbitrary start when every candidate scored `-inf`).
    #[test]
    fn the_heuristic_is_scale_invariant_up_to_f64_max((rows, _) in kind(), relative in any::<bool>()) {
        let smoothing = if relative { Smoothing::default() } else { Smoothing::None };
        let j = rows[0].len();
        let n = rows.len();
        let weights = |c: f64| Weights::new((1..=j).map(|w| c * w as f64).collect::<Vec<_>>()).unwrap();
        let opts = RneOptions { smoothing, alignment: Alignment::Category, log_base: LogBase::TWO };
        let j_of = |scale: f64, w_scale: f64| {
            let method = HierarchicalRne::new(TrustModel::new(weights(w_scale), opts).unwrap());
            let needs: Vec<NeedsVector> = rows
                .iter()
                .map(|r| NeedsVector::new(r.iter().map(|x| x * scale).collect::<Vec<_>>()).unwrap())
                .collect();
            let members: Vec<&NeedsVector> = needs.iter().collect();
            let (split, _) = method.best_split_heuristic(&members, n / 2).unwrap();
            // Score both splits on the ordinary scale.
            let plain: Vec<NeedsVector> = rows.iter().map(|r| NeedsVector::new(r.clone()).unwrap()).collect();
            let pick = |idx: &[usize]| idx.iter().map(|&i| &plain[i]).collect::<Vec<_>>();
            let m1 = HierarchicalRne::new(TrustModel::new(weights(1.0), opts).unwrap());
            m1.between_rne(&pick(&split.first), &pick(&split.second)).unwrap()
        };
        let ordinary = j_of(1.0, 1.0);
        let huge = j_of(1e305, 10.0);
        prop_assert!((huge - ordinary).abs() <= 1e-9 * ordinary.max(1e-12), "{} vs {}", huge, ordinary);
    }
}
