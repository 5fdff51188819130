//! The paper's claims (section VI, Fig. 3) and how a sweep's results are judged against them:
//! each claim says one method has the best mean of a metric; it is checked with one-sided
//! Welch t-tests against every other method (plus Mann-Whitney U as a check). The claims name
//! the paper's tasks, `easy` and `hard`: a scenario without a task of that name skips the
//! claims about it ([`Verdict::NotApplicable`]).

use usar_sim::mission::TrialResult;

use crate::metrics::{Metric, Quantity, Scope, values_of};
use crate::stats::{Summary, TestResult, mann_whitney_greater, welch_greater};

/// Significance level of the claim checks (one-sided).
pub const ALPHA: f64 = 0.05;

/// Which way a claim says a metric should go for its subject.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// The subject has the highest mean.
    Highest,
    /// The subject has the lowest mean.
    Lowest,
}

/// One claim of the paper: `subject` has the highest (or lowest) mean of `quantity` in `task`
/// (a task name, or `None` for all tasks together) of all methods.
#[derive(Debug, Clone, Copy)]
pub struct Claim {
    /// Short id, e.g. `1` or `4a`.
    pub id: &'static str,
    /// The claim in words.
    pub text: &'static str,
    /// Method the claim is about, upper case.
    pub subject: &'static str,
    /// The quantity compared.
    pub quantity: Quantity,
    /// The task it is about, by name (`None`: all tasks together).
    pub task: Option<&'static str>,
    /// Highest or lowest.
    pub direction: Direction,
}

impl Claim {
    /// The claim's metric for tasks `tasks`, or `None` if it names a task they lack.
    pub fn metric(&self, tasks: &[String]) -> Option<Metric> {
        let scope = match self.task {
            None => Scope::Total,
            Some(name) => Scope::Task(tasks.iter().position(|t| t == name)?),
        };
        Some(Metric::new(self.quantity, scope))
    }
}

/// The paper's claims from section VI (Fig. 3).
pub const CLAIMS: [Claim; 5] = [
    Claim {
        id: "1",
        text: "RNE rescues the most in total",
        subject: "RNE",
        quantity: Quantity::Rescued,
        task: None,
        direction: Direction::Highest,
    },
    Claim {
        id: "2",
        text: "RNE rescues more in the hard task than every baseline",
        subject: "RNE",
        quantity: Quantity::Rescued,
        task: Some("hard"),
        direction: Direction::Highest,
    },
    Claim {
        id: "3",
        text: "DIS rescues the most in the easy task",
        subject: "DIS",
        quantity: Quantity::Rescued,
        task: Some("easy"),
        direction: Direction::Highest,
    },
    Claim {
        id: "4a",
        text: "RNE has the lowest energy cost per rescuee in the hard task",
        subject: "RNE",
        quantity: Quantity::EnergyPerRescuee,
        task: Some("hard"),
        direction: Direction::Lowest,
    },
    Claim {
        id: "4b",
        text: "RNE has the lowest HP cost per rescuee in the hard task",
        subject: "RNE",
        quantity: Quantity::HpPerRescuee,
        task: Some("hard"),
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
    /// The scenario has no task of the name the claim is about.
    NotApplicable,
}

impl Verdict {
    /// Words for the report.
    pub fn words(self) -> &'static str {
        match self {
            Verdict::Holds => "holds",
            Verdict::NotSignificant => "not significant",
            Verdict::DoesNotHold => "does not hold",
            Verdict::NotTested => "not tested",
            Verdict::NotApplicable => "not applicable",
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
    /// Its metric for the sweep's tasks (`None`: [`Verdict::NotApplicable`]).
    pub metric: Option<Metric>,
    /// Summary of the subject's values.
    pub subject_summary: Summary,
    /// Comparison with every other method, in sweep order.
    pub comparisons: Vec<Comparison>,
    /// The verdict.
    pub verdict: Verdict,
}

/// Checks `claim` against `results` (methods in `methods` order) of a scenario with tasks
/// `tasks`.
pub fn check_claim(
    claim: Claim,
    results: &[TrialResult],
    methods: &[String],
    tasks: &[String],
) -> ClaimCheck {
    let Some(m) = claim.metric(tasks) else {
        return ClaimCheck {
            claim,
            metric: None,
            subject_summary: Summary::of(&[]),
            comparisons: Vec::new(),
            verdict: Verdict::NotApplicable,
        };
    };
    let vals = |method: &str| values_of(results, method, m);
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
        metric: Some(m),
        subject_summary,
        comparisons,
        verdict,
    }
}

impl ClaimCheck {
    /// The largest one-sided Welch p over the comparisons; NaN ("n/a") if any comparison
    /// could not be tested or there is none.
    pub fn worst_p(&self) -> f64 {
        self.comparisons
            .iter()
            .map(|x| x.welch.p)
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
