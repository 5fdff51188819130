//! `grid.csv`: a grid's statistics in long form, one row per cell x method x metric.

use crate::error::{ReportError, Result};

use crate::analysis::Analysis;
use crate::csv_tables::stat_cell;
use usar_sweep::journal::SweepHeader;

/// `grid.csv`: one column per varied field (named by its path, holding the cell's value as
/// written), then `method, metric, n, mean, sd, ci95_low, ci95_high`; one row per cell (in
/// cell order) x method (in sweep order) x metric (every metric of the cell's tasks,
/// [`usar_sweep::metrics::Metric::all`], in that order). Undefined statistics are empty cells, as in `summary.csv`.
///
/// # Errors
/// A CSV serialisation error (not expected).
pub fn grid_csv(header: &SweepHeader, analysis: &Analysis) -> Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut head: Vec<&str> = header.grid.fields.iter().map(String::as_str).collect();
    head.extend([
        "method",
        "metric",
        "n",
        "mean",
        "sd",
        "ci95_low",
        "ci95_high",
    ]);
    w.write_record(&head)
        .map_err(ReportError::csv("writing the grid.csv header"))?;
    for (cell, a) in header.grid.cells.iter().zip(&analysis.cells) {
        for m in &a.methods {
            for (metric, s) in a.metrics.iter().zip(&m.metrics) {
                let mut row = cell.values.clone();
                row.extend([
                    m.method.clone(),
                    metric.name(&a.tasks),
                    s.n.to_string(),
                    stat_cell(s.mean),
                    stat_cell(s.sd),
                    stat_cell(s.ci_low()),
                    stat_cell(s.ci_high()),
                ]);
                w.write_record(&row)
                    .map_err(ReportError::csv("writing a grid.csv row"))?;
            }
        }
    }
    w.into_inner()
        .map_err(ReportError::finish("finishing grid.csv"))
}
