//! `trials.csv` and `summary.csv`: the per-trial rows and the per-method statistics of a sweep.
//!
//! Both files hold only simulated results (no wall-clock times, no dates) in a fixed order
//! (methods in sweep order, then trials), so two sweeps with the same parameters write the
//! same bytes whatever the thread count.

use anyhow::{Context, Result};
use usar_sim::mission::{TrialResult, TrialRow};

use crate::analysis::CellAnalysis;

/// A metric of [`TrialRow`]: its CSV column name, a short label and how to read it
/// (`None` when undefined for the trial, e.g. a cost per rescuee when nobody was rescued).
#[derive(Clone, Copy)]
pub struct Metric {
    /// Column name in `trials.csv` (and `metric` value in `summary.csv`).
    pub name: &'static str,
    /// Label for tables and figures.
    pub label: &'static str,
    /// Reads the metric from a row.
    pub get: fn(&TrialRow) -> Option<f64>,
}

impl std::fmt::Debug for Metric {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

macro_rules! metric {
    ($field:ident, $label:expr, some) => {
        Metric {
            name: stringify!($field),
            label: $label,
            get: |r| Some(f64::from(r.$field)),
        }
    };
    ($field:ident, $label:expr, float) => {
        Metric {
            name: stringify!($field),
            label: $label,
            get: |r| Some(r.$field),
        }
    };
    ($field:ident, $label:expr, opt) => {
        Metric {
            name: stringify!($field),
            label: $label,
            get: |r| r.$field,
        }
    };
}

/// Every numeric metric of a trial row, in `trials.csv` column order.
pub const METRICS: [Metric; 17] = [
    metric!(rescued_total, "rescuees, total", some),
    metric!(rescued_hard, "rescuees, hard", some),
    metric!(rescued_easy, "rescuees, easy", some),
    metric!(energy_hard_pct, "energy cost hard (%)", float),
    metric!(energy_easy_pct, "energy cost easy (%)", float),
    metric!(energy_total_pct, "energy cost total (%)", float),
    metric!(hp_hard_pct, "HP cost hard (%)", float),
    metric!(hp_easy_pct, "HP cost easy (%)", float),
    metric!(hp_total_pct, "HP cost total (%)", float),
    metric!(rounds, "rounds", some),
    metric!(
        energy_per_hard_rescuee_pct,
        "energy / hard rescuee (%)",
        opt
    ),
    metric!(
        energy_per_easy_rescuee_pct,
        "energy / easy rescuee (%)",
        opt
    ),
    metric!(energy_per_rescuee_pct, "energy / rescuee (%)", opt),
    metric!(hp_per_hard_rescuee_pct, "HP / hard rescuee (%)", opt),
    metric!(hp_per_easy_rescuee_pct, "HP / easy rescuee (%)", opt),
    metric!(hp_per_rescuee_pct, "HP / rescuee (%)", opt),
    metric!(mean_round_s, "mean round time (s)", opt),
];

/// The metric called `name`, if there is one.
pub fn find_metric(name: &str) -> Option<Metric> {
    METRICS.iter().find(|m| m.name == name).copied()
}

/// The metric called `name`.
///
/// # Panics
/// If no metric has that name (a programming error).
pub fn metric(name: &str) -> Metric {
    *METRICS
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("unknown metric {name}"))
}

/// The defined values of `metric` over `rows` of one method, in row order.
pub fn values(rows: &[TrialRow], metric: Metric) -> Vec<f64> {
    rows.iter().filter_map(|r| (metric.get)(r)).collect()
}

/// The rows of `method` among `results`.
pub fn rows_of(results: &[TrialResult], method: &str) -> Vec<TrialRow> {
    results
        .iter()
        .filter(|r| r.method == method)
        .map(TrialResult::row)
        .collect()
}

/// `trials.csv`: one [`TrialRow`] per result, in the given order.
///
/// # Errors
/// A CSV serialisation error (not expected).
pub fn trials_csv(results: &[TrialResult]) -> Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    for r in results {
        w.serialize(r.row()).context("writing a trials.csv row")?;
    }
    w.into_inner().context("finishing trials.csv")
}

/// Formats a statistic for `summary.csv` and `grid.csv`: shortest round-trip form, empty when
/// undefined.
pub fn stat_cell(x: f64) -> String {
    if x.is_finite() {
        format!("{x}")
    } else {
        String::new()
    }
}

/// `summary.csv`: per method (in sweep order) and metric (in [`METRICS`] order): `n`, mean,
/// standard deviation and the 95 % t confidence interval of the mean, from the cell's
/// analysis. Undefined statistics (fewer than two values) are empty cells.
///
/// # Errors
/// A CSV serialisation error (not expected).
pub fn summary_csv(cell: &CellAnalysis) -> Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "method",
        "metric",
        "n",
        "mean",
        "sd",
        "ci95_half_width",
        "ci95_low",
        "ci95_high",
    ])?;
    for m in &cell.methods {
        for (metric, s) in METRICS.iter().zip(&m.metrics) {
            w.write_record([
                m.method.clone(),
                metric.name.to_string(),
                s.n.to_string(),
                stat_cell(s.mean),
                stat_cell(s.sd),
                stat_cell(s.ci95),
                stat_cell(s.ci_low()),
                stat_cell(s.ci_high()),
            ])?;
        }
    }
    w.into_inner().context("finishing summary.csv")
}
