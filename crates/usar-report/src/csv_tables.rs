//! `trials.csv` and `summary.csv`: the per-trial rows and the per-method statistics of a sweep.
//!
//! Both files hold only simulated results (no wall-clock times, no dates) in a fixed order
//! (methods in sweep order, then trials), so two sweeps with the same parameters write the
//! same bytes whatever the thread count.

use crate::error::{ReportError, Result};
use serde::Serialize;
use usar_sim::mission::TrialResult;

use crate::analysis::CellAnalysis;
use usar_sweep::metrics::{Cell, Metric};

/// One field of a CSV row: the identifying text and integers, then metric cells (serialised by
/// type, as serde writes struct fields: integers plainly, floats in ryu's shortest form,
/// undefined values as empty cells).
#[derive(Serialize)]
#[serde(untagged)]
enum Field<'a> {
    Text(&'a str),
    Int(u64),
    Metric(Cell),
}

fn writer() -> csv::Writer<Vec<u8>> {
    csv::WriterBuilder::new()
        .has_headers(false)
        .from_writer(Vec::new())
}

/// `trials.csv`: one row per result, in the given order: `scenario, method, trial, seed`, then
/// every metric of [`Metric::all`] for the tasks `tasks` (the columns of the paper's experiment
/// sheet for tasks `[hard, easy]`).
///
/// # Errors
/// A CSV serialisation error (not expected).
pub fn trials_csv(results: &[TrialResult], tasks: &[String]) -> Result<Vec<u8>> {
    let metrics = Metric::all(tasks.len());
    let mut w = writer();
    let mut header = vec![
        "scenario".to_string(),
        "method".into(),
        "trial".into(),
        "seed".into(),
    ];
    header.extend(metrics.iter().map(|m| m.name(tasks)));
    w.write_record(&header)?;
    for r in results {
        let mut row = vec![
            Field::Text(&r.scenario),
            Field::Text(&r.method),
            Field::Int(u64::from(r.trial)),
            Field::Int(r.seed),
        ];
        row.extend(metrics.iter().map(|m| Field::Metric(m.cell(r))));
        w.serialize(&row)
            .map_err(ReportError::csv("writing a trials.csv row"))?;
    }
    w.into_inner()
        .map_err(ReportError::finish("finishing trials.csv"))
}

/// `trials_long.csv`: the same numbers in long ("tidy") form, one row per trial and metric:
/// `scenario, method, trial, seed, task, metric, value`, where `task` is a task's name, `total`
/// for all tasks together, or empty for a per-trial quantity (`rounds`, `mean_round_s`), and
/// `metric` is the quantity's name ([`Metric::quantity_name`]); an undefined value (a cost per
/// rescuee without rescuees) is an empty cell. pandas, R and seaborn read it directly.
///
/// # Errors
/// A CSV serialisation error (not expected).
pub fn trials_long_csv(results: &[TrialResult], tasks: &[String]) -> Result<Vec<u8>> {
    let metrics = Metric::all(tasks.len());
    let mut w = writer();
    w.write_record([
        "scenario", "method", "trial", "seed", "task", "metric", "value",
    ])?;
    for r in results {
        for m in &metrics {
            let row = [
                Field::Text(&r.scenario),
                Field::Text(&r.method),
                Field::Int(u64::from(r.trial)),
                Field::Int(r.seed),
                Field::Text(m.task_name(tasks)),
                Field::Text(m.quantity_name()),
                Field::Metric(m.cell(r)),
            ];
            w.serialize(row)
                .map_err(ReportError::csv("writing a trials_long.csv row"))?;
        }
    }
    w.into_inner()
        .map_err(ReportError::finish("finishing trials_long.csv"))
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

/// `summary.csv`: per method (in sweep order) and metric (in [`Metric::all`] order): `n`, mean,
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
        for (metric, s) in cell.metrics.iter().zip(&m.metrics) {
            w.write_record([
                m.method.clone(),
                metric.name(&cell.tasks),
                s.n.to_string(),
                stat_cell(s.mean),
                stat_cell(s.sd),
                stat_cell(s.ci95),
                stat_cell(s.ci_low()),
                stat_cell(s.ci_high()),
            ])?;
        }
    }
    w.into_inner()
        .map_err(ReportError::finish("finishing summary.csv"))
}
