//! Writing a sweep's files from its outcome and analysis, every file atomically
//! ([`crate::atomic`]).
//!
//! Without a grid, the output folder gets `trials.csv`, `summary.csv`, the three figures and
//! `report.md` (beside the journal). With a grid, each cell's folder (see
//! [`crate::grid::names`]) gets those files plus `scenario.ron`, and the top of the output
//! folder gets `grid.csv`, `grid.md` and one `grid_<metric>.svg` per chosen metric (for one or
//! two varied fields). Nothing written depends on thread count or interruptions except the
//! timings in `report.md`.

use std::path::{Path, PathBuf};

use anyhow::Result;

use crate::analysis::Analysis;
use crate::atomic::{check_writable, write_atomic};
use crate::figures::{FIGURES, figure_svg};
use crate::grid::{Grid, GridCell};
use crate::grid_outputs::csv::grid_csv;
use crate::grid_outputs::figures::{figure_file, grid_figure_svg};
use crate::grid_outputs::report::{GridReportInput, grid_md};
use crate::metrics::Metric;
use crate::report::{ReportInput, report_md};
use crate::spec_ron::spec_to_ron;
use crate::summary::{summary_csv, trials_csv, trials_long_csv};
use crate::sweep::{SweepConfig, SweepOutcome};

/// Writes every output file of the sweep into `cfg.out_dir`; returns their paths in the order
/// written. `grid_metrics` chooses the metrics of `grid.md` and its figures (ignored without
/// a grid).
///
/// Every file is made twice: a first pass makes each one and checks that its path can be
/// written ([`check_writable`]: not a folder, a socket, ...) without writing anything, the
/// second writes them, each atomically ([`write_atomic`]). So a file that cannot be made or
/// whose path cannot be written fails the call before any file changes, and the set is never
/// half old and half new for those reasons; an I/O error during the writes (a full disk) can
/// still leave the files before it new and the rest old.
///
/// # Errors
/// An I/O error, a path that cannot be written, or a figure plotters fails to draw.
pub fn write_outputs(
    cfg: &SweepConfig,
    outcome: &SweepOutcome,
    analysis: &Analysis,
    grid_metrics: &[Metric],
) -> Result<Vec<PathBuf>> {
    let mut check = Staged::Check;
    make_outputs(cfg, outcome, analysis, grid_metrics, &mut check)?;
    let mut write = Staged::Write(Vec::new());
    make_outputs(cfg, outcome, analysis, grid_metrics, &mut write)?;
    Ok(match write {
        Staged::Write(files) => files,
        Staged::Check => Vec::new(),
    })
}

/// Makes every output file of the sweep and hands each to `staged`.
fn make_outputs(
    cfg: &SweepConfig,
    outcome: &SweepOutcome,
    analysis: &Analysis,
    grid_metrics: &[Metric],
    staged: &mut Staged,
) -> Result<()> {
    let Some(grid) = &cfg.grid else {
        return write_cell(&cfg.out_dir, cfg, outcome, analysis, 0, None, staged);
    };
    for cell in &grid.cells {
        let dir = cfg.out_dir.join(&cell.dir);
        write_cell(&dir, cfg, outcome, analysis, cell.index, Some(cell), staged)?;
        let ron = spec_to_ron(&cell.spec, &scenario_comments(cfg, outcome, cell))?;
        put(&dir, "scenario.ron", ron.as_bytes(), staged)?;
    }
    write_grid(cfg, grid, outcome, analysis, grid_metrics, staged)
}

/// What [`write_outputs`]' passes do with each file made.
enum Staged {
    /// Check that its path can be written; write nothing.
    Check,
    /// Write it; the paths written so far.
    Write(Vec<PathBuf>),
}

fn put(dir: &Path, name: &str, bytes: &[u8], files: &mut Staged) -> Result<()> {
    let p = dir.join(name);
    match files {
        Staged::Check => check_writable(&p),
        Staged::Write(written) => {
            write_atomic(&p, bytes)?;
            written.push(p);
            Ok(())
        }
    }
}

/// One cell's `trials.csv`, `summary.csv`, figures and `report.md` into `dir`.
fn write_cell(
    dir: &Path,
    cfg: &SweepConfig,
    outcome: &SweepOutcome,
    analysis: &Analysis,
    cell: usize,
    grid_cell: Option<&GridCell>,
    files: &mut Staged,
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
        put(dir, spec.file, figure_svg(spec, a)?.as_bytes(), files)?;
    }
    let report = report_md(&ReportInput {
        scenario: grid_cell.map_or(&cfg.scenario, |g| &g.scenario),
        scenario_path: &cfg.scenario_path,
        outcome,
        cell,
        analysis: a,
        grid_cell,
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
    files: &mut Staged,
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
        if let Some(svg) = grid_figure_svg(&outcome.header, analysis, *m)? {
            let tasks = analysis.cells.first().map_or(&[][..], |c| &c.tasks[..]);
            let name = figure_file(*m, tasks);
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
