//! A claim checked against a sweep's results: each rival compared with the subject by the
//! one-sided tests, paired (trial k with trial k) and unpaired, the claim's own test (after
//! its correction) deciding the [`Verdict`].

use usar_sim::mission::TrialResult;

use super::claim::{Claim, Correction, Direction, Rivals, Test};
use crate::paired::{differences, paired_t_greater, wilcoxon_greater};
use crate::stats::{Summary, TestResult, mann_whitney_greater, welch_greater};
use crate::targets::metric_ref::MetricRef;
use usar_sweep::metrics::Metric;

/// Verdict on a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// The subject's mean is better than every rival's and every rival's (corrected) p of the
    /// claim's test is below its alpha.
    Holds,
    /// The subject's mean is better than every rival's but some (corrected) p is at least
    /// alpha, or cannot be computed (Welch's test with fewer than 2 trials of a method).
    /// For a paired test "better" is the mean of the paired differences.
    NotSignificant,
    /// Some rival's mean is as good or better.
    DoesNotHold,
    /// The claim cannot be tested on this sweep: its subject, or a rival it names, has no
    /// trials in it, or no rival has, or (a paired test) a rival shares fewer than 2 trials
    /// with the subject ([`ClaimCheck::reason`] says which).
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
    /// Pairs of trials: trials of the subject and of the rival with the same trial index and
    /// seed (the same draws) that both have a value of the metric.
    pub pairs: usize,
    /// Trials of the subject or of the rival with a value but no partner (a failed trial, a
    /// cost per rescuee with no rescuee), left out of the paired tests.
    pub unpaired: usize,
    /// Mean of the paired differences, subject minus rival (NaN without a pair).
    pub paired_diff: f64,
    /// The paired t-test of "subject better than rival" over the pairs (one-sided).
    pub paired_t: TestResult,
    /// The Wilcoxon signed-rank test of the same over the pairs (one-sided).
    pub wilcoxon: TestResult,
    /// The claim's test of the opposite ("rival better than subject"): the paired t-test for
    /// a paired claim, Welch's for an unpaired one ([`Comparison::welch_reverse`]).
    pub reverse: TestResult,
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

/// One trial's defined value of a claim's metric, as [`check_claim_on`] reads a sweep: the
/// trial's method (as the sweep spells it), trial index, seed and value (a `trials.csv` row's
/// `method`, `trial`, `seed` and metric column). A trial whose value is undefined (a cost per
/// rescuee without rescuees) has no observation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Observation<'a> {
    /// The method's name, as the sweep spells it (`RNE`, `HP_DIS`, a Python method's name).
    pub method: &'a str,
    /// Trial index within the sweep, 0-based.
    pub trial: u32,
    /// Seed of the trial's starting team: with the index, what pairs two methods' trials.
    pub seed: u64,
    /// The metric's value.
    pub value: f64,
}

/// The observations of `metric` in `results`, in their order (undefined values left out).
pub fn observations(results: &[TrialResult], metric: Metric) -> Vec<Observation<'_>> {
    results
        .iter()
        .filter_map(|r| {
            Some(Observation {
                method: &r.method,
                trial: r.trial,
                seed: r.seed,
                value: metric.value(r)?,
            })
        })
        .collect()
}

/// The claim's subject as `methods` spell it (the claim's own spelling when it is not there).
fn subject_in(claim: &Claim, methods: &[String]) -> String {
    methods
        .iter()
        .find(|m| claim.is_subject(m))
        .cloned()
        .unwrap_or_else(|| claim.subject.clone())
}

/// Checks `claim` against `results` of a sweep with `methods` (names as the results spell
/// them, in sweep order) and task names `tasks`. A claim whose metric names a task `tasks`
/// lack is [`Verdict::NotTested`], saying so (a claims file is checked against the
/// scenario's tasks before a sweep runs, [`super::Claims::check_tasks`]; a grid cell may
/// still lack one). The same as [`check_claim_on`] over the results' [`observations`].
pub fn check_claim(
    claim: &Claim,
    results: &[TrialResult],
    methods: &[String],
    tasks: &[String],
) -> ClaimCheck {
    match claim.metric.resolve(tasks) {
        Ok(metric) => check_claim_on(claim, metric, &observations(results, metric), methods),
        Err(e) => ClaimCheck {
            claim: claim.clone(),
            metric: None,
            subject_summary: Summary::of(&[]),
            subject: subject_in(claim, methods),
            comparisons: Vec::new(),
            verdict: Verdict::NotTested,
            reason: Some(e),
        },
    }
}

/// Checks `claim`, whose metric is `metric`, against `observed`, the metric's defined values
/// in a sweep's trials with `methods` (names as the observations spell them, in sweep order):
/// what [`check_claim`] does with a sweep's results, for trials known only by their values
/// (a table of trials read back, the Python package's DataFrames). The observations' order is
/// the sweep's trial order (sums run in it, so the same order gives the same bits).
pub fn check_claim_on(
    claim: &Claim,
    metric: Metric,
    observed: &[Observation<'_>],
    methods: &[String],
) -> ClaimCheck {
    let subject = subject_in(claim, methods);
    let subject_vals = values_in(observed, &subject);
    let subject_summary = Summary::of(&subject_vals);
    let (rivals, missing) = claim.rivals_in(methods);
    let mut comparisons: Vec<Comparison> = rivals
        .iter()
        .map(|other| compare(claim, (&subject, &subject_vals), other, observed))
        .filter(|c| c.other_summary.n > 0)
        .collect();
    let ps: Vec<f64> = comparisons.iter().map(|c| c.p_of(claim.test)).collect();
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
        too_few_pairs(claim.test, &subject, column, &comparisons)
    };
    let verdict = if reason.is_some() {
        Verdict::NotTested
    } else if !comparisons.iter().all(|c| {
        let diff = if claim.test.is_paired() {
            c.paired_diff
        } else {
            subject_summary.mean - c.other_summary.mean
        };
        match claim.direction {
            Direction::More => diff > 0.0,
            Direction::Less => diff < 0.0,
        }
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

/// Why a paired claim cannot be tested: a rival shares fewer than 2 trials with the subject.
fn too_few_pairs(
    test: Test,
    subject: &str,
    column: &MetricRef,
    comparisons: &[Comparison],
) -> Option<String> {
    let c = comparisons.iter().find(|c| c.pairs < 2)?;
    test.is_paired().then(|| {
        format!(
            "{subject} and {} have {} trial(s) in common with a value of {column}: the {} \
             needs at least 2 pairs of trials",
            c.other,
            c.pairs,
            test.words(),
        )
    })
}

/// The metric's values of `a` and `b` on the trials both have one, matched by trial index
/// and seed (the same draws), in trial order; and how many trials of either have a value but
/// no partner.
pub fn paired_values(
    results: &[TrialResult],
    a: &str,
    b: &str,
    metric: Metric,
) -> (Vec<f64>, Vec<f64>, usize) {
    paired_in(&observations(results, metric), a, b)
}

/// The values of `method` among `observed`, in their order.
fn values_in(observed: &[Observation<'_>], method: &str) -> Vec<f64> {
    observed
        .iter()
        .filter(|o| o.method == method)
        .map(|o| o.value)
        .collect()
}

/// [`paired_values`] over observations.
fn paired_in(observed: &[Observation<'_>], a: &str, b: &str) -> (Vec<f64>, Vec<f64>, usize) {
    let keyed = |method: &str| -> std::collections::BTreeMap<(u32, u64), f64> {
        observed
            .iter()
            .filter(|o| o.method == method)
            .map(|o| ((o.trial, o.seed), o.value))
            .collect()
    };
    let (ka, kb) = (keyed(a), keyed(b));
    let (mut xa, mut xb) = (Vec::new(), Vec::new());
    for (key, va) in &ka {
        if let Some(vb) = kb.get(key) {
            xa.push(*va);
            xb.push(*vb);
        }
    }
    let unpaired = ka.len() + kb.len() - 2 * xa.len();
    (xa, xb, unpaired)
}

/// `values` oriented so that "greater" means "better for the claim".
fn oriented(direction: Direction, values: &[f64]) -> Vec<f64> {
    match direction {
        Direction::More => values.to_vec(),
        Direction::Less => values.iter().map(|x| -x).collect(),
    }
}

/// The claim's subject (its name and its values of the metric) against `other`, each test
/// oriented so that "greater" means "better for the claim".
fn compare(
    claim: &Claim,
    (subject, sv): (&str, &[f64]),
    other: &str,
    observed: &[Observation<'_>],
) -> Comparison {
    let dir = claim.direction;
    let ov = values_in(observed, other);
    let (better, worse) = (oriented(dir, sv), oriented(dir, &ov));
    let (ps, po, unpaired) = paired_in(observed, subject, other);
    let (pb, pw) = (oriented(dir, &ps), oriented(dir, &po));
    let paired_diff = Summary::of(&differences(&ps, &po)).mean;
    let welch_reverse = welch_greater(&worse, &better);
    let paired_t = paired_t_greater(&pb, &pw);
    Comparison {
        other: other.to_owned(),
        other_summary: Summary::of(&ov),
        welch: welch_greater(&better, &worse),
        mann_whitney: mann_whitney_greater(&better, &worse),
        welch_reverse,
        pairs: ps.len(),
        unpaired,
        paired_diff,
        paired_t,
        wilcoxon: wilcoxon_greater(&pb, &pw),
        reverse: if claim.test.is_paired() {
            paired_t_greater(&pw, &pb)
        } else {
            welch_reverse
        },
        p_adjusted: f64::NAN,
    }
}

impl Comparison {
    /// The raw one-sided p of `test` in this comparison.
    pub fn p_of(&self, test: Test) -> f64 {
        match test {
            Test::PairedT => self.paired_t.p,
            Test::Wilcoxon => self.wilcoxon.p,
            Test::Welch => self.welch.p,
            Test::MannWhitney => self.mann_whitney.p,
        }
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
    /// The test that decided the claim, in words for the terminal and the reports: `paired
    /// t-test over 10 pairs of trials` (`over 7 to 10 pairs` when rivals share different
    /// numbers of trials with the subject), `Wilcoxon signed-rank test over ...`, `unpaired
    /// Welch t-test` or `unpaired Mann-Whitney U test`.
    pub fn test_run_words(&self) -> String {
        let test = self.claim.test;
        if !test.is_paired() {
            return match test {
                Test::MannWhitney => "unpaired Mann-Whitney U test".to_owned(),
                _ => "unpaired Welch t-test".to_owned(),
            };
        }
        let name = test.words();
        let pairs = self.comparisons.iter().map(|c| c.pairs);
        match (pairs.clone().min(), pairs.max()) {
            (Some(lo), Some(hi)) if lo < hi => format!("{name} over {lo} to {hi} pairs of trials"),
            (Some(n), _) => format!("{name} over {n} pairs of trials"),
            _ => name.to_owned(),
        }
    }

    /// The standardized effect of the comparison `c` (one of [`ClaimCheck::comparisons`]),
    /// oriented as the tests are (positive points the claimed way): for a paired test
    /// (paired t or Wilcoxon) Cohen's `d_z`, the mean paired difference over the sd of the
    /// differences (the paired t over `sqrt(pairs)`); for an unpaired one (Welch or
    /// Mann-Whitney) Cohen's `d` with the unweighted root mean square of the two sample sds,
    /// `(mean_s - mean_r) / sqrt((sd_s² + sd_r²) / 2)`. ±infinity when the spread is 0 and
    /// the means differ; NaN with fewer than 2 pairs (2 values a side) or no spread at all.
    ///
    /// # Reference
    /// J. Cohen, *Statistical Power Analysis for the Behavioral Sciences*, 2nd ed., 1988,
    /// sections 2.2 (`d`) and 2.3.5 (`d_z`, paired samples).
    pub fn effect_size(&self, c: &Comparison) -> f64 {
        if self.claim.test.is_paired() {
            return c.paired_t.statistic / (c.pairs as f64).sqrt();
        }
        let (s, r) = (&self.subject_summary, &c.other_summary);
        let diff = match self.claim.direction {
            Direction::More => s.mean - r.mean,
            Direction::Less => r.mean - s.mean,
        };
        diff / ((s.sd.powi(2) + r.sd.powi(2)) / 2.0).sqrt()
    }

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

    /// Trial `k` of `method` (seed `100 + k`) with `total` rescuees, all in the easy task.
    fn trial(method: &str, k: u32, total: u32) -> TrialResult {
        let mut t = crate::testing::trial(method, 6, (total, 0), (1.0, 1.0), (1.0, 1.0));
        t.trial = k;
        t.seed = 100 + u64::from(k);
        t
    }

    fn claim(test: Test) -> Claim {
        Claim {
            id: "1".into(),
            sentence: "RNE rescues the most".into(),
            subject: "RNE".into(),
            rivals: Rivals::Every,
            metric: MetricRef("rescued_total".into()),
            direction: Direction::More,
            test,
            alpha: 0.05,
            correction: Correction::None,
        }
    }

    /// Ten trials whose draws give levels 100 apart; RNE rescues 1 or 2 more than DIS in each.
    fn steady_edge() -> Vec<TrialResult> {
        (0..10u32)
            .flat_map(|k| {
                let level = 100 * ((k * 7) % 10);
                [trial("RNE", k, level + 1 + k % 2), trial("DIS", k, level)]
            })
            .collect()
    }

    fn check(test: Test, results: &[TrialResult]) -> ClaimCheck {
        let methods = ["RNE".to_string(), "DIS".to_string()];
        let tasks = ["hard".to_string(), "easy".to_string()];
        check_claim(&claim(test), results, &methods, &tasks)
    }

    #[test]
    fn a_small_edge_in_every_paired_trial_holds_paired_and_not_unpaired() {
        let results = steady_edge();
        for test in [Test::PairedT, Test::Wilcoxon] {
            let c = check(test, &results);
            assert_eq!(c.verdict, Verdict::Holds, "{test:?}: {:?}", c.comparisons);
            assert_eq!((c.comparisons[0].pairs, c.comparisons[0].unpaired), (10, 0));
            assert!(c.worst_p() < 0.01, "{test:?}: p = {}", c.worst_p());
        }
        for test in [Test::Welch, Test::MannWhitney] {
            let c = check(test, &results);
            assert_eq!(c.verdict, Verdict::NotSignificant, "{test:?}");
            assert!(c.worst_p() > 0.3, "{test:?}: p = {}", c.worst_p());
        }
        // The default claim is paired.
        assert_eq!(Test::default(), Test::PairedT);
    }

    #[test]
    fn only_common_trials_are_paired_and_fewer_than_two_pairs_are_not_tested() {
        // RNE's trials 0 and 1 failed, DIS's trial 9: trials 2..=8 are paired, 3 are not.
        let mut results: Vec<TrialResult> = steady_edge()
            .into_iter()
            .filter(|t| !(t.method == "RNE" && t.trial < 2 || t.method == "DIS" && t.trial == 9))
            .collect();
        let c = check(Test::PairedT, &results);
        assert_eq!((c.comparisons[0].pairs, c.comparisons[0].unpaired), (7, 3));
        assert_eq!(c.verdict, Verdict::Holds);
        // A trial of the same index on other draws (another seed) is no pair.
        results.retain(|t| t.method == "DIS" || t.trial == 2);
        results.retain(|t| t.method == "RNE" || t.trial >= 2);
        results
            .iter_mut()
            .filter(|t| t.method == "DIS" && t.trial == 3)
            .for_each(|t| t.seed = 7);
        let c = check(Test::PairedT, &results);
        assert_eq!(c.comparisons[0].pairs, 1);
        assert_eq!(c.verdict, Verdict::NotTested);
        let why = c.reason.expect("a reason");
        assert!(
            why.contains("have 1 trial(s) in common with a value of rescued_total"),
            "{why}"
        );
        // Unpaired, the same trials are tested.
        assert_ne!(check(Test::Welch, &results).verdict, Verdict::NotTested);
    }

    #[test]
    fn observations_check_as_results_do_and_give_the_effect_size() {
        let results = steady_edge();
        let methods = ["RNE".to_string(), "DIS".to_string()];
        let tasks = ["hard".to_string(), "easy".to_string()];
        let metric = claim(Test::PairedT)
            .metric
            .resolve(&tasks)
            .expect("a metric");
        let observed = observations(&results, metric);
        assert_eq!(observed.len(), 20);
        for test in [
            Test::PairedT,
            Test::Wilcoxon,
            Test::Welch,
            Test::MannWhitney,
        ] {
            let a = check_claim(&claim(test), &results, &methods, &tasks);
            let b = check_claim_on(&claim(test), metric, &observed, &methods);
            assert_eq!(a.verdict, b.verdict);
            let (x, y) = (&a.comparisons[0], &b.comparisons[0]);
            // Debug text: the rank tests' NaN dof equal as text.
            let tests = |c: &Comparison| format!("{:?}", (c.paired_t, c.welch, c.wilcoxon));
            assert_eq!(tests(x), tests(y));
            assert_eq!(x.p_adjusted.to_bits(), y.p_adjusted.to_bits());
        }
        // Paired: differences 1, 2, 1, 2, ... (mean 1.5, sd 0.527): d_z = 2.846.
        let paired = check_claim_on(&claim(Test::PairedT), metric, &observed, &methods);
        let d_z = paired.effect_size(&paired.comparisons[0]);
        assert_abs_diff_eq!(d_z, 1.5 / (2.5f64 / 9.0).sqrt(), epsilon = 1e-12);
        // Unpaired: the same 1.5 against a spread of about 300 between trials: d is small.
        let welch = check_claim_on(&claim(Test::Welch), metric, &observed, &methods);
        let d = welch.effect_size(&welch.comparisons[0]);
        assert!(d > 0.0 && d < 0.01, "d = {d}");
        // A lower-is-better claim turns the sign; too few pairs give NaN.
        let mut less = claim(Test::PairedT);
        less.direction = Direction::Less;
        let c = check_claim_on(&less, metric, &observed, &methods);
        assert_abs_diff_eq!(c.effect_size(&c.comparisons[0]), -d_z, epsilon = 1e-12);
        let one: Vec<Observation<'_>> = observed.iter().filter(|o| o.trial == 0).copied().collect();
        let c = check_claim_on(&claim(Test::PairedT), metric, &one, &methods);
        assert_eq!(c.verdict, Verdict::NotTested);
        assert!(c.effect_size(&c.comparisons[0]).is_nan());
    }

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
