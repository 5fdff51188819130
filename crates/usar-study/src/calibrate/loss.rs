//! The loss a calibration minimises: the sum over targets of `(distance outside the band /
//! the band's half-width)^2`. Exactly 0 when every statistic lies in its band; finite
//! whenever every statistic is (a share or a sum too large for an `f64`, from a tiny band or
//! a huge value, saturates at `f64::MAX`, so that an evaluated point never looks like a failed
//! one); +inf only when a statistic is NaN or infinite (never NaN, never a crash). Targets
//! marked [`Target::report_only`] add nothing.

use usar_report::targets::file::Target;

/// One target's share of the loss for statistic `x`: `(distance outside / half-width)^2`, 0
/// inside the band (and only there: a distance so small that its square underflows counts
/// as the smallest positive number), at most `f64::MAX` for a finite `x` (a share that
/// overflows saturates), +inf for a NaN or infinite `x`.
pub fn target_loss(target: &Target, x: f64) -> f64 {
    if target.report_only {
        return 0.0;
    }
    if !x.is_finite() {
        return f64::INFINITY;
    }
    // Finite bands and values (checked when the targets are read) and a finite `x`: the
    // distance is finite or, past the largest number, +inf; never NaN.
    let d = target.band.distance_outside(target.value, x);
    if d == 0.0 {
        return 0.0;
    }
    let share = (d / target.band.half_width(target.value)).powi(2);
    share.clamp(f64::MIN_POSITIVE, f64::MAX)
}

/// The loss of statistics `values` (one per target, in target order): the sum of
/// [`target_loss`] (0 for a report-only target), saturated at `f64::MAX` while every share is
/// finite; in `[0, f64::MAX]`, or +inf when a fitted target's statistic is NaN or infinite.
///
/// # Panics
/// If `values` and `targets` differ in length (a programming error).
pub fn loss(targets: &[Target], values: &[f64]) -> f64 {
    assert_eq!(targets.len(), values.len(), "one value per target");
    let shares = targets.iter().zip(values).map(|(t, &x)| target_loss(t, x));
    let mut sum = 0.0f64;
    for share in shares {
        if share.is_infinite() {
            return f64::INFINITY;
        }
        sum = (sum + share).min(f64::MAX);
    }
    sum
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use usar_report::targets::band::Band;
    use usar_report::targets::metric_ref::MetricRef;
    use usar_report::targets::statistic::Statistic;

    fn target(value: f64, band: Band) -> Target {
        Target {
            name: "t".into(),
            statistic: Statistic::Mean(MetricRef("rounds".into())),
            value,
            band,
            report_only: false,
        }
    }

    #[test]
    fn a_report_only_target_adds_nothing_to_the_loss() {
        let mut t = target(6.2, Band::PlusMinus(0.5));
        assert!((target_loss(&t, 8.2) - 9.0).abs() < 1e-9);
        t.report_only = true;
        assert_eq!(target_loss(&t, 8.2), 0.0);
        assert_eq!(target_loss(&t, f64::NAN), 0.0);
        assert_eq!(
            loss(&[t, target(1.0, Band::PlusMinus(1.0))], &[99.0, 1.5]),
            0.0
        );
    }

    #[test]
    fn zero_inside_squared_half_widths_outside_inf_for_nan() {
        let ts = [
            target(6.2, Band::PlusMinus(0.5)),
            target(4.69, Band::Between(3.0, 7.0)),
        ];
        assert_eq!(loss(&ts, &[6.2, 3.0]), 0.0);
        assert_eq!(loss(&ts, &[6.7, 7.0]), 0.0);
        // 1 half-width above the first band (0.5), 2 half-widths (4) below the second.
        let l = loss(&ts, &[7.2, -1.0]);
        assert!((l - (1.0 + 4.0)).abs() < 1e-9, "{l}");
        assert_eq!(loss(&ts, &[f64::NAN, 5.0]), f64::INFINITY);
        assert_eq!(loss(&ts, &[6.2, f64::NEG_INFINITY]), f64::INFINITY);
        assert_eq!(target_loss(&ts[0], f64::INFINITY), f64::INFINITY);
    }

    /// Regression (issue 70): a tiny band (`PlusMinus(5e-324)`) or a huge value gave an
    /// infinite loss for statistics that were all finite, which read as a failed evaluation.
    #[test]
    fn finite_statistics_give_a_finite_loss_however_far_out() {
        let tiny = target(1.0, Band::PlusMinus(5e-324));
        let huge = target(1e308, Band::PlusMinus(1.0));
        let far = target(-1e308, Band::PlusMinus(1.0));
        assert_eq!(target_loss(&tiny, 1.5), f64::MAX);
        assert_eq!(target_loss(&huge, 0.0), f64::MAX);
        assert_eq!(target_loss(&ts_one(), 1e300), f64::MAX);
        // x - value overflows: the distance is +inf for a finite statistic.
        assert_eq!(target_loss(&far, 1.7e308), f64::MAX);
        assert_eq!(loss(&[tiny.clone(), huge.clone()], &[1.5, 0.0]), f64::MAX);
        assert_eq!(loss(&[tiny.clone(), huge], &[1.0, 1e308]), 0.0);
        assert_eq!(loss(&[tiny], &[f64::NAN]), f64::INFINITY);
    }

    fn ts_one() -> Target {
        target(6.2, Band::PlusMinus(0.5))
    }

    proptest! {
        /// The loss is 0 exactly when every statistic holds, positive otherwise, never NaN.
        #[test]
        fn loss_is_zero_iff_every_statistic_is_in_its_band(
            bands in prop::collection::vec((-100.0f64..100.0, 0.001f64..50.0, any::<bool>()), 1..6),
            xs in prop::collection::vec(prop_oneof![
                8 => -200.0f64..200.0,
                1 => Just(f64::NAN),
                1 => Just(f64::INFINITY),
            ], 6),
        ) {
            let ts: Vec<Target> = bands
                .iter()
                .map(|&(v, w, between)| {
                    let band = if between {
                        Band::Between(v - w, v + 2.0 * w)
                    } else {
                        Band::PlusMinus(w)
                    };
                    target(v, band)
                })
                .collect();
            let xs = &xs[..ts.len()];
            let l = loss(&ts, xs);
            prop_assert!(!l.is_nan());
            prop_assert!(l >= 0.0);
            prop_assert_eq!(l.is_finite(), xs.iter().all(|x| x.is_finite()));
            let all_hold = ts.iter().zip(xs).all(|(t, &x)| t.holds(x));
            prop_assert_eq!(l == 0.0, all_hold);
        }
    }
}
