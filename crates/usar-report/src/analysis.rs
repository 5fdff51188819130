//! One analysis pass over a sweep's results, once per grid cell: per method and metric the
//! summary statistics, the report's claims checked, the round lengths and, when the reports
//! compare with targets, the pooled statistics. Every output (CSV files, figures,
//! `report.md`, `grid.*`, the terminal summary) is rendered from it, so the numbers are
//! computed once and agree everywhere; its [`ReportOptions`] say which sections the reports
//! show.

use statrs::statistics::{Data, OrderStatistics};
use usar_sim::mission::TrialResult;

pub use crate::calibration::ReportOptions;
use crate::calibration::{Target, Targets};
use crate::claims::{ClaimCheck, Claims, check_claim};
use crate::stats::Summary;
use usar_sweep::metrics::{Metric, values_of};
use usar_sweep::sweep::SweepOutcome;

/// The analysis of a whole sweep: one [`CellAnalysis`] per grid cell, in cell order.
#[derive(Debug, Clone)]
pub struct Analysis {
    /// Per cell.
    pub cells: Vec<CellAnalysis>,
    /// What the reports rendered from it show besides the results (default: no targets, no
    /// claims).
    pub report: ReportOptions,
}

impl Analysis {
    /// Analyses every cell of `outcome`, for reports without targets or claims.
    pub fn of(outcome: &SweepOutcome) -> Self {
        Self::with_report(outcome, ReportOptions::default())
    }

    /// Analyses every cell of `outcome` for reports with `report`'s sections: with targets,
    /// each cell's [`CellAnalysis::pooled`] statistics are computed against them.
    pub fn with_report(outcome: &SweepOutcome, report: ReportOptions) -> Self {
        Self {
            cells: outcome
                .cells
                .iter()
                .zip(&outcome.header.grid.cells)
                .map(|(c, h)| {
                    CellAnalysis::of(&c.results, &outcome.header.methods, &h.tasks)
                        .with_difficulty(h.hardest_first.clone())
                        .with_targets(report.targets.as_ref(), &c.results)
                        .with_claims(report.claims.as_ref(), &c.results, &outcome.header.methods)
                })
                .collect(),
            report,
        }
    }
}

/// The analysis of one cell's results.
#[derive(Debug, Clone)]
pub struct CellAnalysis {
    /// The cell's task names, by task id.
    pub tasks: Vec<String>,
    /// Task ids from the hardest to the easiest (the scenario's difficulty order).
    pub hardest_first: Vec<usize>,
    /// Every metric of a trial ([`Metric::all`]), in `trials.csv` column order.
    pub metrics: Vec<Metric>,
    /// Per method, in sweep order.
    pub methods: Vec<MethodStats>,
    /// The report's claims ([`ReportOptions::claims`]) checked, in file order; empty without
    /// claims.
    pub claims: Vec<ClaimCheck>,
    /// Completed-round lengths over all methods (label `all`), then per method.
    pub rounds: Vec<RoundStats>,
    /// The report's targets ([`ReportOptions::targets`]) with this cell's statistics pooled
    /// over all its trials, in the targets' order (see `docs/calibration.md`); empty without
    /// targets.
    pub pooled: Vec<(Target, f64)>,
    /// Per entry of [`CellAnalysis::pooled`], how many trials its statistic left out (a
    /// metric undefined there: [`crate::targets::Statistic::left_out`]), of
    /// [`CellAnalysis::trials`].
    pub pooled_left_out: Vec<usize>,
    /// The cell's trials (every method's).
    pub trials: usize,
}

/// Statistics of one method's trials in one cell.
#[derive(Debug, Clone)]
pub struct MethodStats {
    /// Method, upper case.
    pub method: String,
    /// Successful trials.
    pub trials: usize,
    /// Summary of each metric, in [`CellAnalysis::metrics`] order (a metric undefined for a
    /// trial, such as
    /// a cost per rescuee without rescuees, leaves that trial out).
    pub metrics: Vec<Summary>,
}

/// Lengths of the completed rounds of some trials, seconds (a round cut by the time limit is
/// not counted). Statistics are NaN when no round completed.
#[derive(Debug, Clone, PartialEq)]
pub struct RoundStats {
    /// `all` or the method.
    pub label: String,
    /// Completed rounds.
    pub completed: usize,
    /// Median length, seconds.
    pub median_s: f64,
    /// 95th percentile of the lengths (statrs order statistics), seconds.
    pub p95_s: f64,
    /// Longest, seconds.
    pub longest_s: f64,
    /// Mean number of rounds started per trial.
    pub started_per_trial: f64,
}

impl CellAnalysis {
    /// Analyses `results` (the successful trials of one cell) for `methods` (upper case, in
    /// sweep order) and the cell's `tasks`, without targets ([`CellAnalysis::with_targets`]).
    pub fn of(results: &[TrialResult], methods: &[String], tasks: &[String]) -> Self {
        let metrics = Metric::all(tasks.len());
        let stats = methods
            .iter()
            .map(|m| MethodStats {
                method: m.clone(),
                trials: results.iter().filter(|r| &r.method == m).count(),
                metrics: metrics
                    .iter()
                    .map(|metric| {
                        let values = values_of(results, m, *metric);
                        if metric.quantity.is_non_negative() {
                            Summary::of_non_negative(&values)
                        } else {
                            Summary::of(&values)
                        }
                    })
                    .collect(),
            })
            .collect();
        let all = std::iter::once("all").chain(methods.iter().map(String::as_str));
        let rounds = all
            .map(|label| {
                let trials: Vec<&TrialResult> = results
                    .iter()
                    .filter(|t| label == "all" || t.method == label)
                    .collect();
                round_stats(label, &trials)
            })
            .collect();
        Self {
            tasks: tasks.to_vec(),
            hardest_first: (0..tasks.len()).collect(),
            metrics,
            methods: stats,
            claims: Vec::new(),
            rounds,
            pooled: Vec::new(),
            pooled_left_out: Vec::new(),
            trials: 0,
        }
    }

    /// The same analysis with its statistics over `results` (the cell's) pooled against
    /// `targets` ([`CellAnalysis::pooled`]; none without targets).
    pub fn with_targets(mut self, targets: Option<&Targets>, results: &[TrialResult]) -> Self {
        self.pooled = targets.map_or_else(Vec::new, |t| {
            t.targets()
                .iter()
                .map(|t| (t.clone(), t.value_of(results)))
                .collect()
        });
        self.pooled_left_out = self
            .pooled
            .iter()
            .map(|(t, _)| t.statistic.left_out(results))
            .collect();
        self.trials = results.len();
        self
    }

    /// The same analysis with every claim of `claims` checked against `results` (the cell's)
    /// of `methods` ([`check_claim`]; none without claims).
    pub fn with_claims(
        mut self,
        claims: Option<&Claims>,
        results: &[TrialResult],
        methods: &[String],
    ) -> Self {
        self.claims = claims.map_or_else(Vec::new, |c| {
            c.claims()
                .iter()
                .map(|c| check_claim(c, results, methods, &self.tasks))
                .collect()
        });
        self
    }

    /// The same analysis with the tasks' difficulty order `hardest_first` (task ids, hardest
    /// first; default: the tasks' order).
    pub fn with_difficulty(mut self, hardest_first: Vec<usize>) -> Self {
        self.hardest_first = hardest_first;
        self
    }

    /// The summary of `metric` for the method at index `method`, if the cell has that metric.
    ///
    /// # Panics
    /// If `method` is out of range (a programming error).
    pub fn summary(&self, method: usize, metric: Metric) -> Option<Summary> {
        let i = self.metrics.iter().position(|m| *m == metric)?;
        Some(self.methods[method].metrics[i])
    }
}

fn round_stats(label: &str, trials: &[&TrialResult]) -> RoundStats {
    let lengths: Vec<f64> = trials
        .iter()
        .flat_map(|t| t.rounds.iter().filter(|x| x.completed))
        .map(|x| x.end_s - x.start_s)
        .collect();
    if lengths.is_empty() {
        return RoundStats {
            label: label.to_string(),
            completed: 0,
            median_s: f64::NAN,
            p95_s: f64::NAN,
            longest_s: f64::NAN,
            started_per_trial: f64::NAN,
        };
    }
    let started = trials.iter().map(|t| t.rounds.len()).sum::<usize>() as f64 / trials.len() as f64;
    let longest = lengths.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let completed = lengths.len();
    let mut data = Data::new(lengths);
    RoundStats {
        label: label.to_string(),
        completed,
        median_s: data.median(),
        p95_s: data.percentile(95),
        longest_s: longest,
        started_per_trial: started,
    }
}
