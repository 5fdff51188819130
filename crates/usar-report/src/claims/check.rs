//! A claim checked against a sweep's results: each rival compared with the subject by both
//! one-sided tests, the claim's own test (after its correction) deciding the [`Verdict`].

use usar_sim::mission::TrialResult;

use super::claim::{Claim, Correction, Direction, Rivals, Test};
use crate::stats::{Summary, TestResult, mann_whitney_greater, welch_greater};
use usar_sweep::metrics::{Metric, values_of};

/// Verdict on a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The subject's mean is better than every rival's and every rival's (corrected) p of the
    /// claim's test is below its alpha.
    Holds,
    /// The subject's mean is better than every rival's but some (corrected) p is at least
    /// alpha, or cannot be computed (Welch's test with fewer than 2 trials of a method).
    NotSignificant,
    /// Some rival's mean is as good or better.
    DoesNotHold,
    /// The claim cannot be tested on this sweep: its subject, or a rival it names, has no
    /// trials in it, or no rival has ([`ClaimCheck::reason`] says which).
    NotTested,
}

impl Verdict {
    /// Words for the reports: `holds`, `not significant`, `does not hold`, `not tested`.
    pub fn words(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::NotSignificant => "not significant",
            Verdict::DoesNotHold => "does not hold",
            Verdict::NotTested => "not tested",
        }
    }
}

/// One pairwise comparison of a claim: its subject against the rival `other`.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// The rival.
    pub other: String,
    /// Summary of the rival's values.
    pub other_summary: Summary,
    /// Welch's t-test of "subject better than rival" (one-sided).
    pub welch: TestResult,
    /// Mann-Whitney U test of the same (one-sided).
    pub mann_whitney: TestResult,
    /// Welch's test of the opposite ("rival better than subject").
    pub welch_reverse: TestResult,
    /// The claim's test's p after the claim's correction over the rivals compared (the raw
    /// p without one); NaN when the test is undefined.
    pub p_adjusted: f64,
}

/// A checked claim.
#[derive(Debug, Clone)]
pub struct ClaimCheck {
    /// The claim.
    pub claim: Claim,
    /// Its metric for the sweep's tasks (`None`: the tasks lack the one it names, and the
    /// claim is [`Verdict::NotTested`]).
    pub metric: Option<Metric>,
    /// Summary of the subject's values.
    pub subject_summary: Summary,
    /// The subject's name as the sweep spells it (the claim's own when it is not in it).
    pub subject: String,
    /// Comparison with every rival that has trials, in sweep order.
    pub comparisons: Vec<Comparison>,
    /// The verdict.
    pub verdict: Verdict,
    /// Why the claim was not tested ([`Verdict::NotTested`]); `None` otherwise.
    pub reason: Option<String>,
}

/// Checks `claim` against `results` of a sweep with `methods` (names as the results spell
/// them, in sweep order) and task names `tasks`. A claim whose metric names a task `tasks`
/// lack is [`Verdict::NotTested`], saying so (a claims file is checked against the
/// scenario's tasks before a sweep runs, [`super::Claims::check_tasks`]; a grid cell may
/// still lack one).
pub fn check_claim(
    claim: &Claim,
    results: &[TrialResult],
    methods: &[String],
    tasks: &[String],
) -> ClaimCheck {
    let subject = methods
        .iter()
        .find(|m| claim.is_subject(m))
        .cloned()
        .unwrap_or_else(|| claim.subject.clone());
    let metric = match claim.metric.resolve(tasks) {
        Ok(m) => m,
        Err(e) => {
            return ClaimCheck {
                claim: claim.clone(),
                metric: None,
                subject_summary: Summary::of(&[]),
                subject,
                comparisons: Vec::new(),
                verdict: Verdict::NotTested,
                reason: Some(e),
            };
        }
    };
    let subject_vals = values_of(results, &subject, metric);
    let subject_summary = Summary::of(&subject_vals);
    let (rivals, missing) = claim.rivals_in(methods);
    let mut comparisons: Vec<Comparison> = rivals
        .iter()
        .map(|other| compare(claim.direction, &subject_vals, other, results, metric))
        .filter(|c| c.other_summary.n > 0)
        .collect();
    let ps: Vec<f64> = comparisons
        .iter()
        .map(|c| match claim.test {
            Test::Welch => c.welch.p,
            Test::MannWhitney => c.mann_whitney.p,
        })
        .collect();
    let adjusted = match claim.correction {
        Correction::None => ps,
        Correction::Holm => holm_adjusted(&ps),
    };
    for (c, p) in comparisons.iter_mut().zip(adjusted) {
        c.p_adjusted = p;
    }
    let in_sweep = methods.iter().any(|m| claim.is_subject(m));
    let column = &claim.metric;
    // A rival the claim names must have values: without them it was not compared.
    let named_without_values = match &claim.rivals {
        Rivals::Only(_) => rivals
            .iter()
            .find(|r| !comparisons.iter().any(|c| &c.other == **r)),
        Rivals::Every => None,
    };
    let reason = if !in_sweep {
        Some(format!(
            "{} is not among the sweep's methods",
            claim.subject
        ))
    } else if subject_summary.n == 0 {
        Some(format!("no trial of {subject} has a value of {column}"))
    } else if let Some(m) = missing.first() {
        Some(format!("its rival {m} is not among the sweep's methods"))
    } else if let Some(r) = named_without_values {
        Some(format!("no trial of its rival {r} has a value of {column}"))
    } else if comparisons.is_empty() {
        Some(format!(
            "no rival of {subject} has a trial with a value of {column}"
        ))
    } else {
        None
    };
    let verdict = if reason.is_some() {
        Verdict::NotTested
    } else if !comparisons.iter().all(|c| match claim.direction {
        Direction::More => subject_summary.mean > c.other_summary.mean,
        Direction::Less => subject_summary.mean < c.other_summary.mean,
    }) {
        Verdict::DoesNotHold
    } else if comparisons.iter().all(|c| c.p_adjusted < claim.alpha) {
        Verdict::Holds
    } else {
        Verdict::NotSignificant
    };
    ClaimCheck {
        claim: claim.clone(),
        metric: Some(metric),
        subject_summary,
        subject,
        comparisons,
        verdict,
        reason,
    }
}

/// The subject's values `subject_vals` against `other`'s, each test oriented so that
/// "greater" means "better for the claim".
fn compare(
    direction: Direction,
    subject_vals: &[f64],
    other: &str,
    results: &[TrialResult],
    metric: Metric,
) -> Comparison {
    let ov = values_of(results, other, metric);
    let (better, worse) = match direction {
        Direction::More => (subject_vals.to_vec(), ov.clone()),
        Direction::Less => (
            subject_vals.iter().map(|x| -x).collect(),
            ov.iter().map(|x| -x).collect(),
        ),
    };
    Comparison {
        other: other.to_owned(),
        other_summary: Summary::of(&ov),
        welch: welch_greater(&better, &worse),
        mann_whitney: mann_whitney_greater(&better, &worse),
        welch_reverse: welch_greater(&worse, &better),
        p_adjusted: f64::NAN,
    }
}

/// Holm's step-down adjusted p-values of `ps`, in their order: with the `m` p-values sorted
/// ascending, `adj(i) = max over j <= i of min(1, (m - j) p(j))` (0-based). An undefined
/// (NaN) p stays NaN and still counts in `m`, so the others are corrected as if it were there.
///
/// # Reference
/// S. Holm, "A simple sequentially rejective multiple test procedure", Scand. J. Statist.
/// 6(2):65-70, 1979; the adjusted form as R's `p.adjust(method = "holm")`.
pub fn holm_adjusted(ps: &[f64]) -> Vec<f64> {
    let m = ps.len();
    let mut order: Vec<usize> = (0..m).filter(|&i| !ps[i].is_nan()).collect();
    order.sort_by(|&a, &b| ps[a].total_cmp(&ps[b]));
    let mut out = vec![f64::NAN; m];
    let mut running = 0.0f64;
    for (rank, &i) in order.iter().enumerate() {
        running = running.max(((m - rank) as f64 * ps[i]).min(1.0));
        out[i] = running;
    }
    out
}

impl ClaimCheck {
    /// The largest p of the claim's test after its correction over the rivals; NaN ("n/a")
    /// if any comparison could not be tested or there is none.
    pub fn worst_p(&self) -> f64 {
        self.comparisons
            .iter()
            .map(|x| x.p_adjusted)
            .reduce(|a, b| {
                if a.is_nan() || b.is_nan() {
                    f64::NAN
                } else {
                    a.max(b)
                }
            })
            .unwrap_or(f64::NAN)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_abs_diff_eq;

    #[test]
    fn holm_matches_r_p_adjust() {
        // R: p.adjust(c(0.01, 0.04, 0.03, 0.005), "holm") = 0.03 0.06 0.06 0.02
        let adj = holm_adjusted(&[0.01, 0.04, 0.03, 0.005]);
        for (a, want) in adj.iter().zip([0.03, 0.06, 0.06, 0.02]) {
            assert_abs_diff_eq!(*a, want, epsilon = 1e-12);
        }
        // Capped at 1; NaN stays NaN and counts in m.
        let adj = holm_adjusted(&[0.6, f64::NAN, 0.01]);
        assert_abs_diff_eq!(adj[2], 0.03, epsilon = 1e-12);
        assert_abs_diff_eq!(adj[0], 1.0, epsilon = 1e-12);
        assert!(adj[1].is_nan());
        assert!(holm_adjusted(&[]).is_empty());
    }
}
