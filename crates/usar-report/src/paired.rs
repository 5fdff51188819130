//! One-sided paired tests of "x is greater than y" on matched pairs `(x[k], y[k])`: trial `k`
//! of two methods run on the same draws (common random numbers), so that what the trials
//! share (the draw of the map, the robots and the rescuees) cancels in the differences
//! `d[k] = x[k] - y[k]`.
//!
//! - [`paired_t_greater`]: Student's paired t-test on the differences, the p-value from
//!   statrs's `StudentsT` CDF.
//! - [`wilcoxon_greater`]: the Wilcoxon signed-rank test, exact for small samples without ties,
//!   normal approximation (tie and continuity corrected) otherwise.

use statrs::distribution::{ContinuousCDF, Normal};

use crate::stats::{Summary, TestResult, one_sided_t};

/// The largest number of non-zero differences for which [`wilcoxon_greater`] uses the exact
/// null distribution (when the absolute differences have no ties), as R's `wilcox.test` and
/// scipy's `wilcoxon` do: 50.
pub const WILCOXON_EXACT_MAX_N: usize = 50;

/// The differences `x[k] - y[k]` of the pairs; `x` and `y` must have one value per pair.
pub(crate) fn differences(x: &[f64], y: &[f64]) -> Vec<f64> {
    debug_assert_eq!(
        x.len(),
        y.len(),
        "a paired test needs one x and one y per pair"
    );
    x.iter().zip(y).map(|(a, b)| a - b).collect()
}

/// Student's paired t-test of H1: mean(x - y) > 0, one-sided, on the pairs `(x[k], y[k])`
/// (`x` and `y` of equal length; extra values of the longer are ignored).
///
/// `t = mean(d) / (sd(d) / sqrt(n))` over the `n` differences `d = x - y`, `dof = n - 1`,
/// `p = 1 - F_t(t)` with `F_t` statrs's `StudentsT` CDF. When every difference is equal (sd
/// 0), `p` is 0 if they are positive and 1 otherwise. NaN p with fewer than 2 pairs.
///
/// # Reference
/// Student, "The probable error of a mean", Biometrika 6(1), 1908; R's
/// `t.test(x, y, paired = TRUE, alternative = "greater")`.
pub fn paired_t_greater(x: &[f64], y: &[f64]) -> TestResult {
    let s = Summary::of(&differences(x, y));
    if s.n < 2 {
        return TestResult::UNDEFINED;
    }
    one_sided_t(s.mean, s.sd.powi(2) / s.n as f64, (s.n - 1) as f64)
}

/// The Wilcoxon signed-rank test of H1: the differences `x - y` of the pairs `(x[k], y[k])`
/// tend to be positive (symmetric about a positive centre), one-sided.
///
/// Zero differences are dropped (Wilcoxon's convention), leaving `n` non-zero ones; their
/// absolute values are ranked 1..n (ties get their average rank) and the statistic is `W+`,
/// the sum of the ranks of the positive differences (R's `V`), returned as `statistic` with
/// `dof` NaN. The p-value `P(W+ >= observed)` under H0 is
/// - exact (the null distribution of `W+` counted over the `2^n` sign patterns) when
///   `n <= WILCOXON_EXACT_MAX_N` and the absolute differences have no ties;
/// - otherwise the normal approximation with mean `n(n+1)/4`, variance
///   `n(n+1)(2n+1)/24 - sum(t³ - t)/48` over the tie groups of sizes `t`, and a continuity
///   correction of 1/2: `p = 1 - Φ((W+ - n(n+1)/4 - 1/2) / sd)`.
///
/// With no non-zero difference (every pair equal, or no pair) `W+` is 0 and p is 1 (nothing
/// points either way) when there is at least one pair; NaN p with no pair.
///
/// # Reference
/// M. Hollander and D. A. Wolfe, *Nonparametric Statistical Methods*, 2nd ed., Wiley 1999,
/// section 3.1 (the signed-rank statistic, its exact null distribution, the large-sample
/// approximation with ties and the zero convention); F. Wilcoxon, "Individual comparisons by
/// ranking methods", Biometrics Bulletin 1(6), 1945. As R's
/// `wilcox.test(x, y, paired = TRUE, alternative = "greater")`.
pub fn wilcoxon_greater(x: &[f64], y: &[f64]) -> TestResult {
    let all = differences(x, y);
    if all.is_empty() {
        return TestResult::UNDEFINED;
    }
    let mut d: Vec<f64> = all.into_iter().filter(|v| *v != 0.0).collect();
    let n = d.len();
    if n == 0 {
        return TestResult {
            statistic: 0.0,
            dof: f64::NAN,
            p: 1.0,
        };
    }
    d.sort_by(|a, b| a.abs().total_cmp(&b.abs()));
    let (w_plus, tie_sizes) = signed_rank_sum(&d);
    let p = if n <= WILCOXON_EXACT_MAX_N && tie_sizes.iter().all(|&t| t == 1) {
        exact_upper_tail(n, w_plus)
    } else {
        normal_upper_tail(n, w_plus, &tie_sizes)
    };
    TestResult {
        statistic: w_plus,
        dof: f64::NAN,
        p,
    }
}

/// `W+` of the non-zero differences `d` sorted by absolute value (average ranks over ties),
/// and the sizes of the groups of equal absolute values.
fn signed_rank_sum(d: &[f64]) -> (f64, Vec<usize>) {
    let mut w_plus = 0.0;
    let mut sizes = Vec::new();
    let mut i = 0;
    while i < d.len() {
        let mut j = i + 1;
        while j < d.len() && d[j].abs() == d[i].abs() {
            j += 1;
        }
        // Ranks i+1 ..= j share their average.
        let rank = (i + 1 + j) as f64 / 2.0;
        w_plus += rank * d[i..j].iter().filter(|v| **v > 0.0).count() as f64;
        sizes.push(j - i);
        i = j;
    }
    (w_plus, sizes)
}

/// `P(W+ >= w)` for `n` untied ranks under H0: the number of subsets of `1..=n` whose sum is
/// at least `w`, over `2^n` (counted by dynamic programming; exact in f64 for n <= 50).
fn exact_upper_tail(n: usize, w: f64) -> f64 {
    let max = n * (n + 1) / 2;
    let mut counts = vec![0.0f64; max + 1];
    counts[0] = 1.0;
    for r in 1..=n {
        for s in (r..=max).rev() {
            counts[s] += counts[s - r];
        }
    }
    // Without ties W+ is a whole number.
    let from = w.round().max(0.0) as usize;
    let tail: f64 = counts.iter().skip(from).sum();
    tail / 2f64.powi(n as i32)
}

/// `P(W+ >= w)` by the normal approximation with tie and continuity correction.
fn normal_upper_tail(n: usize, w: f64, tie_sizes: &[usize]) -> f64 {
    let nf = n as f64;
    let mean = nf * (nf + 1.0) / 4.0;
    let ties: f64 = tie_sizes
        .iter()
        .map(|&t| (t as f64).powi(3) - t as f64)
        .sum();
    // At least 1/4 for n >= 1: a tie group of t removes (t³ - t)/48, less than it adds.
    let var = nf * (nf + 1.0) * (2.0 * nf + 1.0) / 24.0 - ties / 48.0;
    let z = (w - mean - 0.5) / var.sqrt();
    match Normal::new(0.0, 1.0) {
        Ok(d) => d.sf(z),
        Err(_) => f64::NAN,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::welch_greater;
    use approx::assert_abs_diff_eq;
    use proptest::prelude::*;

    /// Hollander & Wolfe's Hamilton depression scale data (R's `?wilcox.test` example): first
    /// (x) and second (y) visit of nine patients.
    const X: [f64; 9] = [1.83, 0.50, 1.62, 2.48, 1.68, 1.88, 1.55, 3.06, 1.30];
    #[allow(clippy::approx_constant)] // 3.14 is a patient's score, not pi.
    const Y: [f64; 9] = [0.878, 0.647, 0.598, 2.05, 1.06, 1.29, 1.06, 3.14, 1.29];

    #[test]
    fn wilcoxon_matches_hollander_and_wolfe() {
        // R: wilcox.test(x, y, paired = TRUE, alternative = "greater"): V = 40,
        // p-value = 0.01953 (= 10 / 512, exact).
        let r = wilcoxon_greater(&X, &Y);
        assert_abs_diff_eq!(r.statistic, 40.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.p, 10.0 / 512.0, epsilon = 1e-12);
        // Every difference positive: W+ = 15 of 5 ranks, p = 1/32; the other way p = 1.
        let up = wilcoxon_greater(&[2.0, 3.0, 4.0, 5.0, 6.0], &[1.0; 5]);
        assert_abs_diff_eq!(up.p, 1.0 / 32.0, epsilon = 1e-15);
        let down = wilcoxon_greater(&[1.0; 5], &[2.0, 3.0, 4.0, 5.0, 6.0]);
        assert_abs_diff_eq!(down.p, 1.0, epsilon = 1e-15);
    }

    #[test]
    fn wilcoxon_drops_zeros_and_uses_the_tie_corrected_normal_approximation() {
        // d = 1, 1, 2, 2, 2, 3, -1, 4, 0, 5: the zero is dropped (n = 9); |d| ranks: the three
        // 1s share 2, the three 2s share 5, 3 -> 7, 4 -> 8, 5 -> 9; W+ = 2 + 2 + 15 + 24 = 43.
        // Mean 9 * 10 / 4 = 22.5; variance 9 * 10 * 19 / 24 - (24 + 24) / 48 = 70.25;
        // z = (43 - 22.5 - 0.5) / sqrt(70.25) = 2.386200; 1 - Φ(z) = 0.0085117.
        let x = [1.0, 1.0, 2.0, 2.0, 2.0, 3.0, -1.0, 4.0, 0.0, 5.0];
        let r = wilcoxon_greater(&x, &[0.0; 10]);
        assert_abs_diff_eq!(r.statistic, 43.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.p, 0.008_511_7, epsilon = 1e-6);
        // Only equal pairs: nothing points either way; no pair: undefined.
        assert_abs_diff_eq!(wilcoxon_greater(&[3.0, 4.0], &[3.0, 4.0]).p, 1.0);
        assert!(wilcoxon_greater(&[], &[]).p.is_nan());
    }

    #[test]
    fn paired_t_matches_hand_computation() {
        // d = x - y: mean 0.431889, sd 0.426855, t = 3.035375 on 8 dof; the one-sided p
        // integrated numerically from the t density is 0.0080883 (R's two-sided 0.01618 / 2).
        let r = paired_t_greater(&X, &Y);
        assert_abs_diff_eq!(r.statistic, 3.035_375_4, epsilon = 1e-6);
        assert_abs_diff_eq!(r.dof, 8.0, epsilon = 1e-12);
        assert_abs_diff_eq!(r.p, 0.008_088_3, epsilon = 1e-6);
        let back = paired_t_greater(&Y, &X);
        assert_abs_diff_eq!(back.p + r.p, 1.0, epsilon = 1e-9);
        assert!(paired_t_greater(&[1.0], &[0.0]).p.is_nan());
        assert_eq!(paired_t_greater(&[2.0, 3.0], &[1.0, 2.0]).p, 0.0);
        assert_eq!(paired_t_greater(&[1.0, 2.0], &[1.0, 2.0]).p, 1.0);
    }

    #[test]
    fn pairing_finds_a_small_steady_edge_under_a_large_spread() {
        // Ten trials whose level varies by 100 from trial to trial; x beats y by 1 in each.
        let y: Vec<f64> = (0..10).map(|k| 100.0 * ((k * 7) % 10) as f64).collect();
        let x: Vec<f64> = y
            .iter()
            .enumerate()
            .map(|(k, v)| v + 1.0 + 0.1 * k as f64)
            .collect();
        assert!(paired_t_greater(&x, &y).p < 1e-6);
        assert_abs_diff_eq!(wilcoxon_greater(&x, &y).p, 1.0 / 1024.0, epsilon = 1e-15);
        assert!(welch_greater(&x, &y).p > 0.4);
    }

    /// Equal, or both NaN.
    fn same(a: f64, b: f64) -> bool {
        a == b || (a.is_nan() && b.is_nan())
    }

    fn finite() -> impl Strategy<Value = f64> {
        (-1000i32..1000).prop_map(|v| f64::from(v) / 8.0)
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, failure_persistence: None, ..ProptestConfig::default() })]

        /// The point of pairing: what trial k adds to both methods alike does not change the
        /// paired tests.
        #[test]
        fn paired_tests_ignore_a_per_trial_constant(
            rows in prop::collection::vec((finite(), finite(), finite()), 2..20)
        ) {
            let x: Vec<f64> = rows.iter().map(|r| r.0).collect();
            let y: Vec<f64> = rows.iter().map(|r| r.1).collect();
            let xs: Vec<f64> = rows.iter().map(|r| r.0 + r.2).collect();
            let ys: Vec<f64> = rows.iter().map(|r| r.1 + r.2).collect();
            // Eighths added to eighths are exact, so the differences are the same numbers.
            for test in [paired_t_greater, wilcoxon_greater] {
                let (a, b) = (test(&x, &y), test(&xs, &ys));
                prop_assert!(same(a.statistic, b.statistic) && same(a.p, b.p), "{a:?} {b:?}");
            }
        }
    }
}
