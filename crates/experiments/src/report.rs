//! `report.md`: a sweep's parameters, results table, the paper's claims checked one by one
//! with significance tests, failed trials and timings.

use std::fmt::Write as _;
use std::path::Path;

use usar_sim::mission::{TrialResult, trial_seed};
use usar_sim::scenario::Scenario;

use crate::figures::FIGURES;
use crate::stats::{Summary, TestResult, mann_whitney_greater, welch_greater};
use crate::summary::{METRICS, metric, rows_of, values};
use crate::sweep::SweepOutcome;

/// Significance level of the claim checks (one-sided).
pub const ALPHA: f64 = 0.05;

/// Software version written into reports: the crate version, plus the commit
/// (`git describe --always --dirty`, recorded by `build.rs` at build time, or taken from
/// `USAR_GIT_DESCRIBE` in the build environment).
pub fn software_version() -> String {
    match option_env!("USAR_GIT_DESCRIBE") {
        Some(g) if !g.is_empty() => format!("usar {} ({g})", env!("CARGO_PKG_VERSION")),
        _ => format!(
            "usar {} (commit not recorded: built outside a git checkout)",
            env!("CARGO_PKG_VERSION")
        ),
    }
}

/// Which way a claim says a metric should go for its subject.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// The subject has the highest mean.
    Highest,
    /// The subject has the lowest mean.
    Lowest,
}

/// One claim of the paper: `subject` has the highest (or lowest) mean `metric` of all methods.
#[derive(Debug, Clone, Copy)]
pub struct Claim {
    /// Short id, e.g. `1` or `4a`.
    pub id: &'static str,
    /// The claim in words.
    pub text: &'static str,
    /// Method the claim is about, upper case.
    pub subject: &'static str,
    /// Metric name (see [`METRICS`]).
    pub metric: &'static str,
    /// Highest or lowest.
    pub direction: Direction,
}

/// The paper's claims from section VI (Fig. 3).
pub const CLAIMS: [Claim; 5] = [
    Claim {
        id: "1",
        text: "RNE rescues the most in total",
        subject: "RNE",
        metric: "rescued_total",
        direction: Direction::Highest,
    },
    Claim {
        id: "2",
        text: "RNE rescues more in the hard task than every baseline",
        subject: "RNE",
        metric: "rescued_hard",
        direction: Direction::Highest,
    },
    Claim {
        id: "3",
        text: "DIS rescues the most in the easy task",
        subject: "DIS",
        metric: "rescued_easy",
        direction: Direction::Highest,
    },
    Claim {
        id: "4a",
        text: "RNE has the lowest energy cost per rescuee in the hard task",
        subject: "RNE",
        metric: "energy_per_hard_rescuee_pct",
        direction: Direction::Lowest,
    },
    Claim {
        id: "4b",
        text: "RNE has the lowest HP cost per rescuee in the hard task",
        subject: "RNE",
        metric: "hp_per_hard_rescuee_pct",
        direction: Direction::Lowest,
    },
];

/// Verdict on a claim.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Verdict {
    /// Subject's mean is better than every other method's and every one-sided Welch test has
    /// p < [`ALPHA`].
    Holds,
    /// Subject's mean is better than every other's but some test has p >= [`ALPHA`] (or
    /// cannot be computed).
    NotSignificant,
    /// Some other method's mean is as good or better.
    DoesNotHold,
    /// The subject or every other method is missing from the sweep.
    NotTested,
}

impl Verdict {
    /// Words for the report.
    pub fn words(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::NotSignificant => "not significant",
            Verdict::DoesNotHold => "does not hold",
            Verdict::NotTested => "not tested",
        }
    }
}

/// One pairwise comparison of a claim: subject against `other`.
#[derive(Debug, Clone)]
pub struct Comparison {
    /// The other method.
    pub other: String,
    /// Summary of the other method's values.
    pub other_summary: Summary,
    /// Welch's t-test of "subject better than other" (one-sided).
    pub welch: TestResult,
    /// Mann-Whitney U test of the same (one-sided).
    pub mann_whitney: TestResult,
    /// Welch's test of the opposite ("other better than subject").
    pub welch_reverse: TestResult,
}

/// A checked claim.
#[derive(Debug, Clone)]
pub struct ClaimCheck {
    /// The claim.
    pub claim: Claim,
    /// Summary of the subject's values.
    pub subject_summary: Summary,
    /// Comparison with every other method, in sweep order.
    pub comparisons: Vec<Comparison>,
    /// The verdict.
    pub verdict: Verdict,
}

/// Checks `claim` against `results` (methods in `methods` order).
pub fn check_claim(claim: Claim, results: &[TrialResult], methods: &[String]) -> ClaimCheck {
    let m = metric(claim.metric);
    let vals = |method: &str| values(&rows_of(results, method), m);
    let subject_vals = vals(claim.subject);
    let subject_summary = Summary::of(&subject_vals);
    let present = methods.iter().any(|x| x == claim.subject) && subject_summary.n > 0;
    let mut comparisons = Vec::new();
    for other in methods.iter().filter(|x| *x != claim.subject) {
        let ov = vals(other);
        // Orient each test so that "greater" means "better for the claim".
        let (better, worse) = match claim.direction {
            Direction::Highest => (subject_vals.clone(), ov.clone()),
            Direction::Lowest => (
                subject_vals.iter().map(|x| -x).collect(),
                ov.iter().map(|x| -x).collect(),
            ),
        };
        comparisons.push(Comparison {
            other: other.clone(),
            other_summary: Summary::of(&ov),
            welch: welch_greater(&better, &worse),
            mann_whitney: mann_whitney_greater(&better, &worse),
            welch_reverse: welch_greater(&worse, &better),
        });
    }
    let verdict = if !present || comparisons.iter().all(|c| c.other_summary.n == 0) {
        Verdict::NotTested
    } else {
        let better = |c: &Comparison| match claim.direction {
            Direction::Highest => subject_summary.mean > c.other_summary.mean,
            Direction::Lowest => subject_summary.mean < c.other_summary.mean,
        };
        let compared: Vec<&Comparison> = comparisons
            .iter()
            .filter(|c| c.other_summary.n > 0)
            .collect();
        if !compared.iter().all(|c| better(c)) {
            Verdict::DoesNotHold
        } else if compared.iter().all(|c| c.welch.p < ALPHA) {
            Verdict::Holds
        } else {
            Verdict::NotSignificant
        }
    };
    ClaimCheck {
        claim,
        subject_summary,
        comparisons,
        verdict,
    }
}

/// Formats a number for tables: 3 significant decimals for small values, fewer for large.
pub fn num(x: f64) -> String {
    if !x.is_finite() {
        return "n/a".to_string();
    }
    let a = x.abs();
    if a >= 100.0 {
        format!("{x:.1}")
    } else if a >= 1.0 {
        format!("{x:.2}")
    } else if a >= 0.01 || a == 0.0 {
        format!("{x:.3}")
    } else {
        format!("{x:.2e}")
    }
}

/// Formats a p-value.
pub fn pval(p: f64) -> String {
    if !p.is_finite() {
        "n/a".to_string()
    } else if p < 0.001 {
        format!("{p:.1e}")
    } else {
        format!("{p:.3}")
    }
}

/// `mean ± sd` of a summary, the mean alone when the sd is undefined (n = 1), `n/a` for no
/// values.
pub(crate) fn mean_sd(s: &Summary) -> String {
    if s.n == 0 {
        "n/a".to_string()
    } else if s.sd.is_finite() {
        format!("{} ± {}", num(s.mean), num(s.sd))
    } else {
        num(s.mean)
    }
}

/// What [`report_md`] needs.
#[derive(Debug)]
pub struct ReportInput<'a> {
    /// The scenario.
    pub scenario: &'a Scenario,
    /// Where it was loaded from.
    pub scenario_path: &'a Path,
    /// The sweep.
    pub outcome: &'a SweepOutcome,
}

/// The text of `report.md`.
pub fn report_md(input: &ReportInput<'_>) -> String {
    let o = input.outcome;
    let h = &o.header;
    let s = input.scenario;
    let methods = &h.methods;
    let mut r = String::new();
    let _ = writeln!(r, "# Sweep report: {}\n", h.scenario);
    let _ = writeln!(r, "## Set-up\n");
    let _ = writeln!(
        r,
        "- Scenario: `{}` from `{}` (scenario hash `{}`): {}",
        h.scenario,
        input.scenario_path.display(),
        h.scenario_hash,
        s.description
    );
    let _ = writeln!(
        r,
        "- Team: {} robots ({}); step {} s.",
        s.robots.len(),
        s.kinds
            .iter()
            .map(|k| format!("{} {}", k.count, k.name))
            .collect::<Vec<_>>()
            .join(", "),
        s.sim.dt_s
    );
    let _ = writeln!(r, "- Methods: {}.", methods.join(", "));
    let _ = writeln!(
        r,
        "- Trials: {} per method, {} s of simulated time each.",
        h.trials, h.duration_s
    );
    let _ = writeln!(
        r,
        "- Seeds: base seed {}; trial k starts from the team drawn with seed \
         `trial_seed({}, k)`, the same for every method (common random numbers): {}.",
        h.base_seed,
        h.base_seed,
        (0..h.trials)
            .map(|k| format!("{k}: {}", trial_seed(h.base_seed, k)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(r, "- Software: {}.", software_version());
    let expected = methods.len() * h.trials as usize;
    let _ = writeln!(
        r,
        "- Trials finished: {} of {}{}.\n",
        o.results.len(),
        expected,
        if o.failures.is_empty() {
            String::new()
        } else {
            format!(", {} failed (see below)", o.failures.len())
        }
    );

    // Results table.
    let _ = writeln!(r, "## Results\n");
    let _ = writeln!(
        r,
        "Mean ± standard deviation over trials, then the 95 % confidence interval of the mean \
         (Student's t). Costs are in percent points summed over the robots of a task's group; \
         per-rescuee costs average over the trials that rescued at least one (n shown when \
         fewer than all). The same numbers are in `summary.csv`, every trial in `trials.csv`.\n"
    );
    let _ = write!(r, "| metric |");
    for m in methods {
        let _ = write!(r, " {m} |");
    }
    let _ = write!(r, "\n|---|");
    for _ in methods {
        let _ = write!(r, "---|");
    }
    r.push('\n');
    let rows: Vec<_> = methods.iter().map(|m| rows_of(&o.results, m)).collect();
    for metric in METRICS {
        let _ = write!(r, "| {} |", metric.label);
        for mrows in &rows {
            let sm = Summary::of(&values(mrows, metric));
            let mut cell = mean_sd(&sm);
            if sm.ci95.is_finite() {
                let _ = write!(cell, " [{}, {}]", num(sm.ci_low()), num(sm.ci_high()));
            }
            if sm.n != mrows.len() {
                let _ = write!(cell, " (n = {})", sm.n);
            }
            let _ = write!(r, " {cell} |");
        }
        r.push('\n');
    }
    r.push('\n');
    round_lengths(&mut r, methods, &o.results);

    // Claims.
    let _ = writeln!(r, "## The paper's claims (section VI, Fig. 3)\n");
    let _ = writeln!(
        r,
        "Each claim says one method has the best mean of all methods. It **holds** when that \
         method's mean is better than every other method's and each pairwise one-sided Welch \
         t-test (unequal variances) has p < {ALPHA}; it is **not significant** when the means \
         point the claimed way but some p >= {ALPHA}; it **does not hold** when another method's \
         mean is as good or better. Requiring every pairwise test to reject is an \
         intersection-union test, so no multiplicity correction is needed for a claim. The \
         Welch statistic and its Welch-Satterthwaite degrees of freedom are computed here and \
         the p-value comes from statrs's Student's t CDF (statrs has no two-sample t-test); the \
         one-sided Mann-Whitney U test (statrs `mannwhitneyu`) is shown as a check that does \
         not assume normality. Both statistics are oriented so that a positive t (a U above \
         n²/2) points the claimed way; `difference` is the subject's mean minus the other's. \
         `p(reverse)` is Welch's p for the opposite direction.\n"
    );
    let checks: Vec<ClaimCheck> = CLAIMS
        .iter()
        .map(|c| check_claim(*c, &o.results, methods))
        .collect();
    let _ = writeln!(r, "| claim | verdict |\n|---|---|");
    for c in &checks {
        let _ = writeln!(
            r,
            "| ({}) {} | **{}** |",
            c.claim.id,
            c.claim.text,
            c.verdict.words()
        );
    }
    r.push('\n');
    for c in &checks {
        let _ = writeln!(
            r,
            "### ({}) {}: **{}**\n",
            c.claim.id,
            c.claim.text,
            c.verdict.words()
        );
        let label = metric(c.claim.metric).label;
        if c.verdict == Verdict::NotTested {
            let _ = writeln!(
                r,
                "Not tested: the sweep has no results for {} or for any other method.\n",
                c.claim.subject
            );
            continue;
        }
        let _ = writeln!(
            r,
            "{} {}: {} (n = {}).\n",
            c.claim.subject,
            label,
            mean_sd(&c.subject_summary),
            c.subject_summary.n
        );
        let _ = writeln!(
            r,
            "| vs | other's mean ± sd (n) | difference | Welch t (dof) | p | Mann-Whitney U | p | p(reverse) |"
        );
        let _ = writeln!(r, "|---|---|---|---|---|---|---|---|");
        for cmp in &c.comparisons {
            let _ = writeln!(
                r,
                "| {} | {} ({}) | {} | {} ({}) | {} | {} | {} | {} |",
                cmp.other,
                mean_sd(&cmp.other_summary),
                cmp.other_summary.n,
                num(c.subject_summary.mean - cmp.other_summary.mean),
                num(cmp.welch.statistic),
                num(cmp.welch.dof),
                pval(cmp.welch.p),
                num(cmp.mann_whitney.statistic),
                pval(cmp.mann_whitney.p),
                pval(cmp.welch_reverse.p),
            );
        }
        r.push('\n');
    }

    // Figures.
    let _ = writeln!(r, "## Figures\n");
    for f in &FIGURES {
        let _ = writeln!(r, "![{}]({})\n", f.title, f.file);
    }

    // Failures.
    if !o.failures.is_empty() {
        let _ = writeln!(r, "## Failed trials\n");
        let _ = writeln!(
            r,
            "These trials are missing from the tables above; `usar sweep --resume` reruns \
             them.\n"
        );
        for f in &o.failures {
            let _ = writeln!(
                r,
                "- {} trial {} (seed {}): {}",
                f.method, f.trial, f.seed, f.message
            );
        }
        r.push('\n');
    }

    // Timings.
    let _ = writeln!(r, "## Timings (this invocation)\n");
    if o.ran == 0 {
        let _ = writeln!(
            r,
            "No trial was run: all {} came from the journal of an earlier run.",
            o.reused
        );
    } else {
        let rate = o.simulated_s() / o.wall_s.max(1e-9);
        let _ = writeln!(
            r,
            "{} trials run in {:.2} s wall-clock on {} thread(s) ({} taken from the journal \
             of an earlier run): {:.0} simulated seconds per wall-clock second, {:.0} per \
             thread; mean wall time per trial {:.3} s.",
            o.ran,
            o.wall_s,
            o.threads,
            o.reused,
            rate,
            rate / o.threads as f64,
            o.trial_wall_sum_s / o.ran as f64
        );
    }
    r
}

/// Appends the "Round lengths" subsection: completed rounds per method and over all methods,
/// with their median, 95th percentile (statrs order statistics) and longest length, seconds,
/// and the mean number of rounds started per trial. A stalled round (robots unable to get
/// back) shows up here long before it moves a mean.
fn round_lengths(r: &mut String, methods: &[String], results: &[TrialResult]) {
    use statrs::statistics::{Data, OrderStatistics};
    let _ = writeln!(
        r,
        "### Round lengths\n\nCompleted rounds (a round cut by the time limit is not \
         counted), seconds.\n\n| method | completed rounds | median | 95th percentile | \
         longest | rounds started per trial |\n|---|---|---|---|---|---|"
    );
    let all = std::iter::once("all").chain(methods.iter().map(String::as_str));
    for m in all {
        let trials: Vec<&TrialResult> = results
            .iter()
            .filter(|t| m == "all" || t.method == m)
            .collect();
        let lengths: Vec<f64> = trials
            .iter()
            .flat_map(|t| t.rounds.iter().filter(|x| x.completed))
            .map(|x| x.end_s - x.start_s)
            .collect();
        if lengths.is_empty() {
            let _ = writeln!(r, "| {m} | 0 | n/a | n/a | n/a | n/a |");
            continue;
        }
        let started =
            trials.iter().map(|t| t.rounds.len()).sum::<usize>() as f64 / trials.len() as f64;
        let longest = lengths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let mut data = Data::new(lengths.clone());
        let _ = writeln!(
            r,
            "| {m} | {} | {} | {} | {} | {} |",
            lengths.len(),
            num(data.median()),
            num(data.percentile(95)),
            num(longest),
            num(started)
        );
    }
    r.push('\n');
}
