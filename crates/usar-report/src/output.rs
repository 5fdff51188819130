//! Writing a sweep's files from its outcome and analysis, every file atomically
//! ([`usar_sweep::atomic`]).
//!
//! Without a grid, the output folder gets `trials.csv`, `summary.csv`, the three figures and
//! `report.md` (beside the journal). With a grid, each cell's folder (see
//! [`usar_sweep::grid::names`]) gets those files plus `scenario.ron`, and the top of the output
//! folder gets `grid.csv`, `grid.md` and one `grid_<metric>.svg` per chosen metric (for one or
//! two varied fields). Nothing written depends on thread count or interruptions except the
//! timings in `report.md`.

use std::path::{Path, PathBuf};

use crate::error::Result;

use crate::analysis::Analysis;
use crate::chart::figure_or_warn;
use crate::csv_tables::{summary_csv, trials_csv, trials_long_csv};
use crate::figures::{FIGURES, figure_svg};
use crate::grid_outputs::grid_csv::grid_csv;
use crate::grid_outputs::grid_figures::{figure_file, grid_figure_svg};
use crate::grid_outputs::grid_md::{GridReportInput, grid_md};
use crate::report::{ReportInput, report_md};
use usar_sweep::atomic::FileSet;
use usar_sweep::grid::{Grid, GridCell};
use usar_sweep::metrics::Metric;
use usar_sweep::spec_ron::spec_to_ron;
use usar_sweep::sweep::{SweepConfig, SweepOutcome};

/// Writes every output file of the sweep into `cfg.out_dir`; returns their paths in the order
/// written. `grid_metrics` chooses the metrics of `grid.md` and its figures (ignored without
/// a grid).
///
/// The files are written as one [`FileSet`]: every file is made and staged in a temporary
/// file beside it, then all are renamed into place. So a file that cannot be made, a path
/// that cannot be written (a folder, a socket, a read-only folder) or a full disk fails the
/// call with every file as it was: the set is never half old and half new.
///
/// # Errors
/// An I/O error or a path that cannot be written. A figure that cannot be drawn is left out
/// with a warning ([`figure_or_warn`]); the tables and reports are written.
pub fn write_outputs(
    cfg: &SweepConfig,
    outcome: &SweepOutcome,
    analysis: &Analysis,
    grid_metrics: &[Metric],
) -> Result<Vec<PathBuf>> {
    let mut files = FileSet::new();
    make_outputs(cfg, outcome, analysis, grid_metrics, &mut files)?;
    Ok(files.commit()?)
}

/// Makes every output file of the sweep and stages each in `files`.
fn make_outputs(
    cfg: &SweepConfig,
    outcome: &SweepOutcome,
    analysis: &Analysis,
    grid_metrics: &[Metric],
    files: &mut FileSet,
) -> Result<()> {
    let Some(grid) = &cfg.grid else {
        return write_cell(&cfg.out_dir, cfg, outcome, analysis, 0, None, files);
    };
    for cell in &grid.cells {
        let dir = cfg.out_dir.join(&cell.dir);
        write_cell(&dir, cfg, outcome, analysis, cell.index, Some(cell), files)?;
        let ron = spec_to_ron(&cell.spec, &scenario_comments(cfg, outcome, cell))?;
        put(&dir, "scenario.ron", ron.as_bytes(), files)?;
    }
    write_grid(cfg, grid, outcome, analysis, grid_metrics, files)
}

fn put(dir: &Path, name: &str, bytes: &[u8], files: &mut FileSet) -> Result<()> {
    Ok(files.stage(&dir.join(name), bytes)?)
}

/// One cell's `trials.csv`, `summary.csv`, figures and `report.md` into `dir`.
fn write_cell(
    dir: &Path,
    cfg: &SweepConfig,
    outcome: &SweepOutcome,
    analysis: &Analysis,
    cell: usize,
    grid_cell: Option<&GridCell>,
    files: &mut FileSet,
) -> Result<()> {
    let a = &analysis.cells[cell];
    let results = &outcome.cells[cell].results;
    put(dir, "trials.csv", &trials_csv(results, &a.tasks)?, files)?;
    put(
        dir,
        "trials_long.csv",
        &trials_long_csv(results, &a.tasks)?,
        files,
    )?;
    put(dir, "summary.csv", &summary_csv(a)?, files)?;
    for spec in &FIGURES {
        if let Some(svg) = figure_or_warn(spec.file, || figure_svg(spec, a)) {
            put(dir, spec.file, svg.as_bytes(), files)?;
        }
    }
    let report = report_md(&ReportInput {
        scenario: grid_cell.map_or(&cfg.scenario, |g| &g.scenario),
        scenario_path: &cfg.scenario_path,
        outcome,
        cell,
        analysis: a,
        grid_cell,
        options: &analysis.report,
    });
    put(dir, "report.md", report.as_bytes(), files)
}

/// The comment lines at the top of a cell's `scenario.ron`.
fn scenario_comments(cfg: &SweepConfig, outcome: &SweepOutcome, cell: &GridCell) -> Vec<String> {
    let sets: Vec<String> = cell
        .overrides
        .iter()
        .map(|o| format!("--set '{o}'"))
        .collect();
    vec![
        format!(
            "Cell {} of the grid in ../grid.md: {} with {}.",
            cell.index,
            cfg.scenario_path.display(),
            cell.overrides
                .iter()
                .map(ToString::to_string)
                .collect::<Vec<_>>()
                .join(", ")
        ),
        format!(
            "Scenario hash {} (`usar check scenario.ron` shows it). The same scenario: usar check {} {} --print",
            outcome.header.grid.cells[cell.index].scenario_hash,
            cfg.scenario_path.display(),
            sets.join(" ")
        ),
    ]
}

/// `grid.csv`, the grid figures and `grid.md` at the top of the output folder.
fn write_grid(
    cfg: &SweepConfig,
    grid: &Grid,
    outcome: &SweepOutcome,
    analysis: &Analysis,
    metrics: &[Metric],
    files: &mut FileSet,
) -> Result<()> {
    let dir = &cfg.out_dir;
    put(
        dir,
        "grid.csv",
        &grid_csv(&outcome.header, analysis)?,
        files,
    )?;
    let mut figures = Vec::new();
    for m in metrics {
        let tasks = analysis.cells.first().map_or(&[][..], |c| &c.tasks[..]);
        let name = figure_file(*m, tasks);
        let drawn = figure_or_warn(&name, || grid_figure_svg(&outcome.header, analysis, *m));
        if let Some(svg) = drawn.flatten() {
            put(dir, &name, svg.as_bytes(), files)?;
            figures.push(name);
        }
    }
    let md = grid_md(&GridReportInput {
        scenario_path: &cfg.scenario_path,
        grid,
        outcome,
        analysis,
        metrics,
        figures: &figures,
    });
    put(dir, "grid.md", md.as_bytes(), files)
}
