//! `trials.csv` and `summary.csv`: the per-trial rows and the per-method statistics of a sweep.
//!
//! Both files hold only simulated results (no wall-clock times, no dates) in a fixed order
//! (methods in sweep order, then trials), so two sweeps with the same parameters write the
//! same bytes whatever the thread count.

use anyhow::{Context, Result};
use usar_sim::mission::TrialResult;

use crate::analysis::CellAnalysis;
pub use crate::metrics::{METRICS, Metric, find_metric, metric, rows_of, values};

/// `trials.csv`: one [`TrialRow`](usar_sim::mission::TrialRow) per result, in the given order.
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
