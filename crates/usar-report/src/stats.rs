//! Descriptive statistics and two-sample tests for sweep summaries and claim checks.
//!
//! - [`Summary`]: mean, sample standard deviation and the 95 % confidence interval of the mean
//!   from Student's t distribution (`statrs::distribution::StudentsT`).
//! - [`welch_greater`]: Welch's unequal-variance t-test, one-sided. statrs 0.19 has no
//!   two-sample t-test, so the statistic and the Welch-Satterthwaite degrees of freedom are
//!   computed here and the p-value comes from statrs's `StudentsT` CDF.
//! - [`mann_whitney_greater`]: the Mann-Whitney U test, one-sided, from
//!   `statrs::stats_tests::mannwhitneyu` with the normal approximation (tie and continuity
//!   corrected). Not statrs's exact method: in statrs 0.19.1 its exact one-sided p-value is
//!   the complement of the right one when the first sample is not larger than the second
//!   (e.g. `[5, 6, 7, 8]` greater than `[1, 2, 3, 4]` gives 0.986 instead of 1/70).
//!
//! The paired tests (trial k of two methods on the same draws) are in [`crate::paired`].

use statrs::distribution::{ContinuousCDF, StudentsT};
use statrs::stats_tests::Alternative;
use statrs::stats_tests::mannwhitneyu::{MannWhitneyUMethod, mannwhitneyu};

/// Mean, spread and 95 % confidence interval of a sample.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Summary {
    /// Sample size.
    pub n: usize,
    /// Arithmetic mean; NaN when `n == 0`.
    pub mean: f64,
    /// Sample standard deviation (n - 1 in the denominator); NaN when `n < 2`.
    pub sd: f64,
    /// Half width of the 95 % confidence interval of the mean, `t(0.975, n-1) sd / sqrt(n)`;
    /// NaN when `n < 2`.
    pub ci95: f64,
    /// Smallest value the quantity can take: the interval's lower end never goes below it
    /// (`f64::NEG_INFINITY` for [`Summary::of`], 0 for [`Summary::of_non_negative`]).
    pub floor: f64,
}

impl Default for Summary {
    /// The summary of no values: `n = 0`, every statistic NaN.
    fn default() -> Self {
        Self::of(&[])
    }
}

impl Summary {
    /// Summarises `xs`, a sample of a quantity of any sign.
    pub fn of(xs: &[f64]) -> Self {
        let n = xs.len();
        let floor = f64::NEG_INFINITY;
        if n == 0 {
            return Self {
                n,
                mean: f64::NAN,
                sd: f64::NAN,
                ci95: f64::NAN,
                floor,
            };
        }
        let mean = xs.iter().sum::<f64>() / n as f64;
        if n < 2 {
            return Self {
                n,
                mean,
                sd: f64::NAN,
                ci95: f64::NAN,
                floor,
            };
        }
        let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
        let sd = var.sqrt();
        let t = t_quantile(0.975, (n - 1) as f64);
        Self {
            n,
            mean,
            sd,
            ci95: t * sd / (n as f64).sqrt(),
            floor,
        }
    }

    /// Summarises `xs`, a sample of a quantity that cannot be negative (a count, a cost, a
    /// duration): as [`Summary::of`], but the interval's lower end is clipped at 0, so that
    /// `rescued 0.5 [-5.85, 6.85]` (n = 2) reads `[0, 6.85]`. The clipped Student's t interval
    /// is the t interval intersected with the quantity's range; it covers the mean at least as
    /// often as the t interval does.
    pub fn of_non_negative(xs: &[f64]) -> Self {
        Self {
            floor: 0.0,
            ..Self::of(xs)
        }
    }

    /// Lower end of the 95 % confidence interval, not below [`Summary::floor`].
    pub fn ci_low(&self) -> f64 {
        let low = self.mean - self.ci95;
        if low < self.floor { self.floor } else { low }
    }

    /// Upper end of the 95 % confidence interval.
    pub fn ci_high(&self) -> f64 {
        self.mean + self.ci95
    }
}

/// Quantile `p` of Student's t with `dof` degrees of freedom (statrs).
fn t_quantile(p: f64, dof: f64) -> f64 {
    match StudentsT::new(0.0, 1.0, dof) {
        Ok(t) => t.inverse_cdf(p),
        Err(_) => f64::NAN,
    }
}

/// Result of a one-sided two-sample test of "x is greater than y".
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TestResult {
    /// The test statistic (Welch's or the paired t, U of `x` for Mann-Whitney, W+ for
    /// Wilcoxon's signed-rank test).
    pub statistic: f64,
    /// Degrees of freedom (Welch-Satterthwaite; pairs - 1 for the paired t); NaN for the
    /// rank tests.
    pub dof: f64,
    /// One-sided p-value; NaN when the test is undefined (a sample with fewer than 2 values).
    pub p: f64,
}

impl TestResult {
    /// An undefined test (too few values): statistic, dof and p all NaN.
    pub(crate) const UNDEFINED: TestResult = TestResult {
        statistic: f64::NAN,
        dof: f64::NAN,
        p: f64::NAN,
    };
}

/// Welch's t-test of H1: mean(x) > mean(y), one-sided.
///
/// `t = (mx - my) / sqrt(vx/nx + vy/ny)`, `dof` by Welch-Satterthwaite, `p = 1 - F_t(t)` with
/// `F_t` the CDF of statrs's `StudentsT`. When both samples have zero variance, `p` is 0 if
/// `mx > my` and 1 otherwise. NaN p when either sample has fewer than two values.
pub fn welch_greater(x: &[f64], y: &[f64]) -> TestResult {
    let (sx, sy) = (Summary::of(x), Summary::of(y));
    if sx.n < 2 || sy.n < 2 {
        return TestResult::UNDEFINED;
    }
    let (ax, ay) = (sx.sd.powi(2) / sx.n as f64, sy.sd.powi(2) / sy.n as f64);
    let se2 = ax + ay;
    // 0 / 0 = NaN when both variances are 0.
    let dof = se2.powi(2) / (ax.powi(2) / (sx.n - 1) as f64 + ay.powi(2) / (sy.n - 1) as f64);
    one_sided_t(sx.mean - sy.mean, se2, dof)
}

/// The one-sided t-test of H1: `diff > 0` for an estimate `diff` with squared standard error
/// `se2` and `dof` degrees of freedom: `t = diff / sqrt(se2)`, `p = 1 - F_t(t)` (statrs's
/// `StudentsT`). With `se2 == 0`, `t` is ±infinity (0 for `diff == 0`) and `p` is 0 if
/// `diff > 0`, 1 otherwise.
pub(crate) fn one_sided_t(diff: f64, se2: f64, dof: f64) -> TestResult {
    if se2 == 0.0 {
        let statistic = if diff > 0.0 {
            f64::INFINITY
        } else if diff < 0.0 {
            f64::NEG_INFINITY
        } else {
            0.0
        };
        let p = if diff > 0.0 { 0.0 } else { 1.0 };
        return TestResult { statistic, dof, p };
    }
    let t = diff / se2.sqrt();
    let p = match StudentsT::new(0.0, 1.0, dof) {
        Ok(d) => d.sf(t),
        Err(_) => f64::NAN,
    };
    TestResult {
        statistic: t,
        dof,
        p,
    }
}

/// The difference of two means with its two-sided 95 % Welch confidence interval
/// ([`welch_interval`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Interval {
    /// `mean(x) - mean(y)`; NaN when either sample is empty.
    pub diff: f64,
    /// Lower end of the interval; NaN when either sample has fewer than two values.
    pub low: f64,
    /// Upper end of the interval; NaN when either sample has fewer than two values.
    pub high: f64,
}

/// The 95 % confidence interval of `mean(x) - mean(y)` by Welch's method, from the two
/// samples' summaries: `diff ± t(0.975, dof) sqrt(sd_x²/n_x + sd_y²/n_y)` with the
/// Welch-Satterthwaite `dof` (the interval that goes with [`welch_greater`]). When both
/// standard deviations are 0 the interval is the point `diff`; with fewer than two values in
/// either sample its ends are NaN.
pub fn welch_interval(x: &Summary, y: &Summary) -> Interval {
    let diff = x.mean - y.mean;
    if x.n < 2 || y.n < 2 {
        return Interval {
            diff,
            low: f64::NAN,
            high: f64::NAN,
        };
    }
    let (ax, ay) = (x.sd.powi(2) / x.n as f64, y.sd.powi(2) / y.n as f64);
    let se2 = ax + ay;
    if se2 == 0.0 {
        return Interval {
            diff,
            low: diff,
            high: diff,
        };
    }
    let dof = se2.powi(2) / (ax.powi(2) / (x.n - 1) as f64 + ay.powi(2) / (y.n - 1) as f64);
    let half = t_quantile(0.975, dof) * se2.sqrt();
    Interval {
        diff,
        low: diff - half,
        high: diff + half,
    }
}

/// Mann-Whitney U test of H1: x tends to be greater than y, one-sided (statrs, normal
/// approximation with tie and continuity correction; see the module docs for why not the
/// exact method). NaN p when a sample is empty.
pub fn mann_whitney_greater(x: &[f64], y: &[f64]) -> TestResult {
    match mannwhitneyu(
        x,
        y,
        MannWhitneyUMethod::AsymptoticInclContinuityCorrection,
        Alternative::Greater,
    ) {
        Ok((u, p)) => TestResult {
            statistic: u,
            dof: f64::NAN,
            p,
        },
        Err(_) => TestResult::UNDEFINED,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_matches_hand_values() {
        let s = Summary::of(&[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(s.n, 4);
        assert!((s.mean - 2.5).abs() < 1e-12);
        assert!((s.sd - 1.290_994_448_7).abs() < 1e-9);
        // t(0.975, 3) = 3.182446305
        assert!((s.ci95 - 3.182_446_305 * 1.290_994_448_7 / 2.0).abs() < 1e-6);
        assert!(Summary::of(&[]).mean.is_nan());
        // A count's interval stops at 0; one of any sign does not.
        let counts = Summary::of_non_negative(&[0.0, 1.0]);
        assert!((Summary::of(&[0.0, 1.0]).ci_low() - (0.5 - 6.353_102)).abs() < 1e-5);
        assert_eq!(counts.ci_low(), 0.0);
        assert!((counts.ci_high() - (0.5 + 6.353_102)).abs() < 1e-5);
        assert!(Summary::of_non_negative(&[]).ci_low().is_nan());
        assert_eq!(
            Summary::of_non_negative(&[4.0, 5.0, 6.0]).ci_low(),
            Summary::of(&[4.0, 5.0, 6.0]).ci_low()
        );
        assert!(Summary::of(&[1.0]).sd.is_nan());
    }

    #[test]
    fn welch_matches_hand_computation() {
        // Equal variances 5/3 and sizes 4: t = 2 / sqrt(2 (5/3) / 4) = 2.19089, dof = 6,
        // one-sided p = 0.0354938 (t CDF integrated numerically).
        let x = [3.0, 4.0, 5.0, 6.0];
        let y = [1.0, 2.0, 3.0, 4.0];
        let r = welch_greater(&x, &y);
        assert!((r.statistic - 2.190_890_230).abs() < 1e-8);
        assert!((r.dof - 6.0).abs() < 1e-9);
        assert!((r.p - 0.035_493_827).abs() < 1e-6, "p = {}", r.p);
        let back = welch_greater(&y, &x);
        assert!((back.p + r.p - 1.0).abs() < 1e-9);
        assert!(welch_greater(&[1.0], &x).p.is_nan());
        assert_eq!(welch_greater(&[2.0, 2.0], &[1.0, 1.0]).p, 0.0);
        assert_eq!(welch_greater(&[1.0, 1.0], &[1.0, 1.0]).p, 1.0);
    }

    #[test]
    fn welch_interval_matches_hand_computation() {
        // x = [3, 4, 5, 6], y = [1, 2, 3, 4]: diff 2, se sqrt(2 (5/3) / 4) = 0.912871, dof 6,
        // t(0.975, 6) = 2.446912: 2 ± 2.233715.
        let (x, y) = (
            Summary::of(&[3.0, 4.0, 5.0, 6.0]),
            Summary::of(&[1.0, 2.0, 3.0, 4.0]),
        );
        let i = welch_interval(&x, &y);
        assert!((i.diff - 2.0).abs() < 1e-12);
        assert!((i.low - (2.0 - 2.233_715)).abs() < 1e-5, "{i:?}");
        assert!((i.high - (2.0 + 2.233_715)).abs() < 1e-5, "{i:?}");
        // Unequal variances: the interval is wider than the pooled one would be, and the
        // other way round it is the mirror image.
        let z = Summary::of(&[0.0, 10.0, 20.0]);
        let a = welch_interval(&x, &z);
        let b = welch_interval(&z, &x);
        assert!((a.low + b.high).abs() < 1e-12 && (a.high + b.low).abs() < 1e-12);
        let point = welch_interval(&Summary::of(&[2.0, 2.0]), &Summary::of(&[1.0, 1.0]));
        assert_eq!((point.diff, point.low, point.high), (1.0, 1.0, 1.0));
        let short = welch_interval(&Summary::of(&[2.0]), &y);
        assert!((short.diff + 0.5).abs() < 1e-12 && short.low.is_nan() && short.high.is_nan());
    }

    #[test]
    fn mann_whitney_one_sided() {
        let r = mann_whitney_greater(&[5.0, 6.0, 7.0, 8.0], &[1.0, 2.0, 3.0, 4.0]);
        assert_eq!(r.statistic, 16.0);
        // scipy.stats.mannwhitneyu(x, y, alternative="greater", method="asymptotic")
        // -> 0.015191 (z = (16 - 8 - 0.5) / sqrt(12)); the exact p would be 1/70 = 0.0143.
        assert!((r.p - 0.015_191).abs() < 1e-5, "p = {}", r.p);
        let back = mann_whitney_greater(&[1.0, 2.0, 3.0, 4.0], &[5.0, 6.0, 7.0, 8.0]);
        assert!(back.p > 0.98, "p = {}", back.p);
    }
}
