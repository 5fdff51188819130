//! The statistics a target constrains, computed from a set of trials pooled over methods
//! (every trial weighs the same, whatever its method): `Mean`, `RatioOfMeans`, `MeanOfRatios`,
//! `PooledSd` and `PooledCv` of `trials.csv` metrics ([`MetricRef`]), and the structure of the
//! trials: `WithinMethodCorrelation` of two metrics and `CrossMethodCorrelation` of one
//! (issue 55's S3 to S6, as `shared/tools/structure.py` computes them).

use std::fmt;

use serde::{Deserialize, Serialize};
use usar_sim::mission::TrialResult;

use super::metric_ref::MetricRef;

/// A statistic of a set of trials, as written in a targets file (`Mean("rounds")`,
/// `RatioOfMeans("rescued_easy", "rescued_hard")`).
///
/// A trial where a metric is undefined (a cost per rescuee without rescuees) is left out of
/// that metric's mean; no defined value at all gives NaN. A ratio with a zero denominator is
/// infinite or NaN, as IEEE division gives; so is a mean of ratios with such a ratio in it.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Statistic {
    /// The mean of the metric over the trials.
    Mean(MetricRef),
    /// The mean of the first metric over the mean of the second (each over the trials where
    /// it is defined).
    RatioOfMeans(MetricRef, MetricRef),
    /// The mean over the trials (where both are defined) of the first metric over the second.
    MeanOfRatios(MetricRef, MetricRef),
    /// The pooled within-method standard deviation: `sqrt(mean over methods of each method's
    /// sample variance (n - 1))`; NaN unless every method has at least 2 trials defining it.
    PooledSd(MetricRef),
    /// The within-method coefficient of variation, percent: `100 * PooledSd(m) / Mean(m)`
    /// (how much a method's trials scatter around the pooled mean); NaN as `PooledSd`, or for a
    /// zero mean.
    PooledCv(MetricRef),
    /// The mean over methods of the Pearson correlation of the two metrics across each
    /// method's trials (the trials where both are defined): `sum((a - mean a)(b - mean b)) /
    /// sqrt(sum((a - mean a)^2) sum((b - mean b)^2))`, taken as 0 when either metric is
    /// constant; in `[-1, 1]`; NaN unless every method has at least 2 such trials. Whether a
    /// trial that yields more of one yields less of the other (S5: hard and easy rescuees).
    WithinMethodCorrelation(MetricRef, MetricRef),
    /// The mean over every pair of methods of the Pearson correlation of the metric between
    /// the two methods' trials of the same number (the same seed and initial draws, common
    /// random numbers; the trials both have), 0 for a constant side; in `[-1, 1]`; NaN with
    /// fewer than two methods or a pair with fewer than 2 common trials. Whether a trial's
    /// draws decide its outcome whatever the method (S6: total rescuees).
    CrossMethodCorrelation(MetricRef),
}

impl Statistic {
    /// The metrics it reads, in the order written.
    pub fn metrics(&self) -> Vec<&MetricRef> {
        match self {
            Statistic::Mean(m)
            | Statistic::PooledSd(m)
            | Statistic::PooledCv(m)
            | Statistic::CrossMethodCorrelation(m) => vec![m],
            Statistic::RatioOfMeans(a, b)
            | Statistic::MeanOfRatios(a, b)
            | Statistic::WithinMethodCorrelation(a, b) => vec![a, b],
        }
    }

    /// Its value over `results` (pooled over methods; `results` may come in any order, the
    /// per-method groups of `PooledSd` are taken by [`TrialResult::method`]). NaN for no
    /// results.
    pub fn value(&self, results: &[TrialResult]) -> f64 {
        match self {
            Statistic::Mean(m) => mean(results.iter().filter_map(|r| m.value(r))),
            Statistic::RatioOfMeans(a, b) => {
                mean(results.iter().filter_map(|r| a.value(r)))
                    / mean(results.iter().filter_map(|r| b.value(r)))
            }
            Statistic::MeanOfRatios(a, b) => mean(
                results
                    .iter()
                    .filter_map(|r| Some(a.value(r)? / b.value(r)?)),
            ),
            Statistic::PooledSd(m) => pooled_sd(results, m),
            Statistic::PooledCv(m) => {
                100.0 * pooled_sd(results, m) / mean(results.iter().filter_map(|r| m.value(r)))
            }
            Statistic::WithinMethodCorrelation(a, b) => within_method_correlation(results, a, b),
            Statistic::CrossMethodCorrelation(m) => cross_method_correlation(results, m),
        }
    }
}

impl Statistic {
    /// The fewest trials per method it can be computed from: 2 for a spread or a
    /// correlation (`PooledSd`, `PooledCv`, `WithinMethodCorrelation`,
    /// `CrossMethodCorrelation`: NaN from one trial), 1 for the others.
    pub fn min_trials_per_method(&self) -> u32 {
        match self {
            Statistic::Mean(_) | Statistic::RatioOfMeans(..) | Statistic::MeanOfRatios(..) => 1,
            Statistic::PooledSd(_)
            | Statistic::PooledCv(_)
            | Statistic::WithinMethodCorrelation(..)
            | Statistic::CrossMethodCorrelation(_) => 2,
        }
    }

    /// What it needs to have a finite value, in words, for a message about a statistic
    /// that came out NaN or infinite (`it needs at least 2 trials per method defining
    /// rescued_total`).
    pub fn needs(&self) -> String {
        match self {
            Statistic::Mean(m) => format!("it needs a trial defining {m}"),
            Statistic::RatioOfMeans(a, b) => {
                format!("it needs trials defining {a} and {b}, and a mean of {b} other than 0")
            }
            Statistic::MeanOfRatios(a, b) => {
                format!("it needs trials defining {a} and {b}, with {b} other than 0")
            }
            Statistic::PooledSd(m) => {
                format!("it needs at least 2 trials per method defining {m}")
            }
            Statistic::PooledCv(m) => format!(
                "it needs at least 2 trials per method defining {m}, and a mean other than 0"
            ),
            Statistic::WithinMethodCorrelation(a, b) => {
                format!("it needs at least 2 trials per method defining both {a} and {b}")
            }
            Statistic::CrossMethodCorrelation(m) => format!(
                "it needs at least 2 methods, each with at least 2 trials of the same numbers \
                 defining {m}"
            ),
        }
    }

    /// How many of `results` it leaves out because one of its metrics is undefined there (a
    /// cost per rescuee in a trial without rescuees): reports say so next to the value.
    pub fn left_out(&self, results: &[TrialResult]) -> usize {
        results
            .iter()
            .filter(|r| self.metrics().iter().any(|m| m.value(r).is_none()))
            .count()
    }
}

impl fmt::Display for Statistic {
    /// As written in a targets file, without quotes: `RatioOfMeans(rescued_easy, rescued_hard)`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Statistic::Mean(m) => write!(f, "Mean({m})"),
            Statistic::RatioOfMeans(a, b) => write!(f, "RatioOfMeans({a}, {b})"),
            Statistic::MeanOfRatios(a, b) => write!(f, "MeanOfRatios({a}, {b})"),
            Statistic::PooledSd(m) => write!(f, "PooledSd({m})"),
            Statistic::PooledCv(m) => write!(f, "PooledCv({m})"),
            Statistic::WithinMethodCorrelation(a, b) => {
                write!(f, "WithinMethodCorrelation({a}, {b})")
            }
            Statistic::CrossMethodCorrelation(m) => write!(f, "CrossMethodCorrelation({m})"),
        }
    }
}

/// The arithmetic mean of `xs`, NaN for none.
fn mean(xs: impl Iterator<Item = f64>) -> f64 {
    let (sum, n) = xs.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
    if n == 0 { f64::NAN } else { sum / n as f64 }
}

/// The methods of `results` in order of first appearance.
fn methods_of(results: &[TrialResult]) -> Vec<&str> {
    let mut methods: Vec<&str> = Vec::new();
    for r in results {
        if !methods.contains(&r.method.as_str()) {
            methods.push(&r.method);
        }
    }
    methods
}

/// The Pearson correlation of `pairs` (0 when either side is constant); NaN for fewer than 2.
fn pearson(pairs: &[(f64, f64)]) -> f64 {
    if pairs.len() < 2 {
        return f64::NAN;
    }
    let n = pairs.len() as f64;
    let (ma, mb) = (
        pairs.iter().map(|p| p.0).sum::<f64>() / n,
        pairs.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let (mut sab, mut saa, mut sbb) = (0.0, 0.0, 0.0);
    for &(a, b) in pairs {
        sab += (a - ma) * (b - mb);
        saa += (a - ma).powi(2);
        sbb += (b - mb).powi(2);
    }
    let scale = (saa * sbb).sqrt();
    if scale > 0.0 { sab / scale } else { 0.0 }
}

/// [`Statistic::WithinMethodCorrelation`] of `a` and `b` over `results`.
fn within_method_correlation(results: &[TrialResult], a: &MetricRef, b: &MetricRef) -> f64 {
    let per_method = methods_of(results).into_iter().map(|method| {
        let pairs: Vec<(f64, f64)> = results
            .iter()
            .filter(|r| r.method == method)
            .filter_map(|r| Some((a.value(r)?, b.value(r)?)))
            .collect();
        pearson(&pairs)
    });
    mean(per_method)
}

/// [`Statistic::CrossMethodCorrelation`] of `metric` over `results`.
fn cross_method_correlation(results: &[TrialResult], metric: &MetricRef) -> f64 {
    let methods = methods_of(results);
    if methods.len() < 2 {
        return f64::NAN;
    }
    // Per method, (trial number, value), by trial number.
    let by_trial: Vec<Vec<(u32, f64)>> = methods
        .iter()
        .map(|&method| {
            let mut v: Vec<(u32, f64)> = results
                .iter()
                .filter(|r| r.method == method)
                .filter_map(|r| Some((r.trial, metric.value(r)?)))
                .collect();
            v.sort_by_key(|&(t, _)| t);
            v
        })
        .collect();
    let mut correlations = Vec::new();
    for i in 0..by_trial.len() {
        for j in i + 1..by_trial.len() {
            let pairs: Vec<(f64, f64)> = by_trial[i]
                .iter()
                .filter_map(|&(t, x)| {
                    let k = by_trial[j].binary_search_by_key(&t, |&(u, _)| u).ok()?;
                    Some((x, by_trial[j][k].1))
                })
                .collect();
            correlations.push(pearson(&pairs));
        }
    }
    mean(correlations.into_iter())
}

/// `sqrt(mean over methods of the sample variance of `metric` among that method's trials)`,
/// methods in order of first appearance; NaN when a method has fewer than 2 defined values or
/// there are no results.
fn pooled_sd(results: &[TrialResult], metric: &MetricRef) -> f64 {
    let methods = methods_of(results);
    let variances = methods.iter().map(|&method| {
        let xs: Vec<f64> = results
            .iter()
            .filter(|r| r.method == method)
            .filter_map(|r| metric.value(r))
            .collect();
        if xs.len() < 2 {
            return f64::NAN;
        }
        let m = xs.iter().sum::<f64>() / xs.len() as f64;
        xs.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (xs.len() - 1) as f64
    });
    mean(variances).sqrt()
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::testing::trial;

    fn m(name: &str) -> MetricRef {
        MetricRef(name.into())
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-12 * b.abs().max(1.0)
    }

    #[test]
    fn means_and_ratios_pool_every_trial_alike() {
        let r = [
            trial("A", 6, (90, 60), (400.0, 500.0), (40.0, 300.0)),
            trial("B", 4, (70, 40), (300.0, 400.0), (20.0, 200.0)),
        ];
        let value = |s: Statistic| s.value(&r);
        assert!(close(value(Statistic::Mean(m("rounds"))), 5.0));
        assert!(close(value(Statistic::Mean(m("rescued_total"))), 130.0));
        assert!(close(
            value(Statistic::RatioOfMeans(
                m("rescued_easy"),
                m("rescued_hard")
            )),
            80.0 / 50.0
        ));
        // Per trial 90/60 = 1.5 and 70/40 = 1.75.
        assert!(close(
            value(Statistic::MeanOfRatios(
                m("rescued_easy"),
                m("rescued_hard")
            )),
            1.625
        ));
        assert!(close(
            value(Statistic::RatioOfMeans(
                m("hp_hard_pct"),
                m("energy_hard_pct")
            )),
            250.0 / 450.0
        ));
        assert!(value(Statistic::Mean(m("rounds"))).is_finite());
        assert!(Statistic::Mean(m("rounds")).value(&[]).is_nan());
        // A task the trials lack makes the statistic undefined.
        assert!(value(Statistic::Mean(m("rescued_medium"))).is_nan());
        // A zero denominator: IEEE division.
        let zero = [trial("A", 1, (5, 0), (1.0, 1.0), (1.0, 1.0))];
        assert_eq!(
            Statistic::RatioOfMeans(m("rescued_easy"), m("rescued_hard")).value(&zero),
            f64::INFINITY
        );
        assert_eq!(
            Statistic::MeanOfRatios(m("rescued_easy"), m("rescued_hard")).value(&zero),
            f64::INFINITY
        );
        // Undefined per-trial values are left out: no hard rescuees, no hard cost per rescuee.
        let mixed = [zero[0].clone(), r[0].clone()];
        let per_rescuee = Statistic::Mean(m("energy_per_hard_rescuee_pct"));
        assert!(close(per_rescuee.value(&mixed), 500.0 / 60.0));
        assert_eq!(per_rescuee.left_out(&mixed), 1);
        assert_eq!(per_rescuee.left_out(&r), 0);
        assert_eq!(Statistic::Mean(m("rounds")).left_out(&mixed), 0);
    }

    #[test]
    fn pooled_sd_is_the_root_of_the_mean_within_method_variance() {
        // Method A: rescued_total 100, 110, 120 (variance 100); B: 150, 154 (variance 8).
        let t = |method, easy| trial(method, 1, (easy, 50), (1.0, 1.0), (1.0, 1.0));
        let r = [t("A", 50), t("B", 100), t("A", 60), t("B", 104), t("A", 70)];
        let sd = Statistic::PooledSd(m("rescued_total")).value(&r);
        assert!(close(sd, (108.0f64 / 2.0).sqrt()), "{sd}");
        // A method with one trial: undefined.
        assert!(
            Statistic::PooledSd(m("rescued_total"))
                .value(&r[..4])
                .is_finite()
        );
        assert!(
            Statistic::PooledSd(m("rescued_total"))
                .value(&r[..3])
                .is_nan()
        );
        assert!(Statistic::PooledSd(m("rescued_total")).value(&[]).is_nan());
    }

    /// Three methods of three trials each; the expected values are those of
    /// `shared/tools/structure.py` on the same numbers (Python's `statistics`, by hand).
    #[test]
    fn structure_statistics_match_hand_computed_values() {
        // (trial, hard, easy, energy_total)
        let data = [
            (
                "A",
                [(0, 60, 90, 400.0), (1, 50, 100, 420.0), (2, 40, 115, 380.0)],
            ),
            (
                "B",
                [(0, 10, 20, 300.0), (1, 20, 30, 330.0), (2, 30, 50, 310.0)],
            ),
            (
                "C",
                [(0, 30, 35, 500.0), (1, 25, 45, 480.0), (2, 35, 30, 520.0)],
            ),
        ];
        let mut r = Vec::new();
        for (method, trials) in data {
            for (k, hard, easy, energy) in trials {
                let mut t = trial(
                    method,
                    6,
                    (easy, hard),
                    (energy / 2.0, energy / 2.0),
                    (1.0, 1.0),
                );
                t.trial = k;
                r.push(t);
            }
        }
        // Per method: A -0.99340, B 0.98198, C -0.98198 (hard against easy).
        let within = Statistic::WithinMethodCorrelation(m("rescued_hard"), m("rescued_easy"));
        assert!(
            close(within.value(&r), -0.33113308926626095),
            "{}",
            within.value(&r)
        );
        // Totals A 150 150 155, B 30 50 80, C 65 70 65: the three pairs' mean.
        let cross = Statistic::CrossMethodCorrelation(m("rescued_total"));
        assert!(
            close(cross.value(&r), 0.1009850228489886),
            "{}",
            cross.value(&r)
        );
        // 100 x 18.5592 / 404.444.
        let cv = Statistic::PooledCv(m("energy_total_pct"));
        assert!(close(cv.value(&r), 4.5888167825522155), "{}", cv.value(&r));
        // In any order of the trials.
        let mut shuffled = r.clone();
        shuffled.reverse();
        assert!(close(cross.value(&shuffled), cross.value(&r)));
        assert!(close(within.value(&shuffled), within.value(&r)));
        // A constant side counts as no correlation; one method has no pair; too few trials.
        let constant: Vec<TrialResult> = r.iter().filter(|t| t.method == "A").cloned().collect();
        let flat = Statistic::WithinMethodCorrelation(m("rounds"), m("rescued_easy"));
        assert_eq!(flat.value(&constant), 0.0);
        assert!(cross.value(&constant).is_nan());
        assert!(within.value(&constant[..1]).is_nan());
    }

    #[test]
    fn statistics_print_as_written_without_quotes() {
        assert_eq!(
            Statistic::RatioOfMeans(m("rescued_easy"), m("rescued_hard")).to_string(),
            "RatioOfMeans(rescued_easy, rescued_hard)"
        );
        assert_eq!(
            Statistic::PooledSd(m("rescued_total")).to_string(),
            "PooledSd(rescued_total)"
        );
        assert_eq!(
            Statistic::WithinMethodCorrelation(m("rescued_hard"), m("rescued_easy")).to_string(),
            "WithinMethodCorrelation(rescued_hard, rescued_easy)"
        );
        assert_eq!(
            Statistic::CrossMethodCorrelation(m("rescued_total")).to_string(),
            "CrossMethodCorrelation(rescued_total)"
        );
    }
}
