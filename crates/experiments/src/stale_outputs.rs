//! What `usar sweep --overwrite` removes besides the journal: the output files the journaled
//! sweep wrote into the folder, so no table, figure or grid cell of it stays next to the new
//! sweep's (a grid of other values, or a run killed before its files were written, left them
//! mixed).
//!
//! Only a folder with a journal is touched, and in it only names a sweep writes
//! ([`crate::output::write_outputs`], the grid's files and replays, [`crate::replay`]): at the
//! top the tables, figures, reports, replays and grid files (never a `scenario.ron`, which a
//! sweep writes only into grid cells), and the cell folders the journal's header names, each
//! emptied of its outputs and removed only once empty. Anything else stays.

use std::fs;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use crate::atomic::remove_files_where;
use crate::figures::FIGURES;
use crate::grid::names::{cell_dir, field_labels};
use crate::journal::{GridHeader, read_header};
use crate::vary::FieldPath;

/// Tables and the report of one cell (or of the output folder without a grid).
const TABLES: [&str; 4] = ["trials.csv", "trials_long.csv", "summary.csv", "report.md"];

/// Whether a sweep writes a file of this name at the top of its output folder: [`TABLES`],
/// the figures of [`FIGURES`], `replay-*.html`, `grid.csv`, `grid.md` and `grid_*.svg`.
fn is_top_output(name: &str) -> bool {
    TABLES.contains(&name)
        || FIGURES.iter().any(|f| f.file == name)
        || (name.starts_with("replay-") && name.ends_with(".html"))
        || name == "grid.csv"
        || name == "grid.md"
        || (name.starts_with("grid_") && name.ends_with(".svg"))
}

/// Whether a sweep writes a file of this name into a grid cell's folder: [`TABLES`], the
/// figures, replays and the cell's `scenario.ron`.
fn is_cell_output(name: &str) -> bool {
    name == "scenario.ron" || (!name.starts_with("grid") && is_top_output(name))
}

/// The cell folder names of a journaled grid ([`crate::grid::names::cell_dir`] of its fields
/// and values); none without a grid or when a field no longer parses.
fn cell_dirs(grid: &GridHeader) -> Vec<String> {
    if grid.fields.is_empty() {
        return Vec::new();
    }
    let Ok(paths) = grid
        .fields
        .iter()
        .map(|f| FieldPath::parse(f))
        .collect::<Result<Vec<_>, _>>()
    else {
        return Vec::new();
    };
    let labels = field_labels(&paths.iter().collect::<Vec<_>>());
    let n = grid.cells.len();
    grid.cells
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let values: Vec<&str> = c.values.iter().map(String::as_str).collect();
            cell_dir(i, n, &labels, &values)
        })
        .collect()
}

/// Removes from `dir` the output files of the sweep journaled in `journal` (a file in `dir`):
/// the top-level tables, figures, reports, replays and grid files, and in each cell folder
/// its header names, that cell's files, then the folder if that left it empty. Nothing when
/// `journal` does not exist; only the top-level files when its header cannot be read. Call
/// it only while holding the folder's lock ([`crate::lock`]). Returns the files removed.
///
/// # Errors
/// An I/O error listing a folder or removing a file or an emptied cell folder.
pub fn remove_previous_outputs(dir: &Path, journal: &Path) -> Result<Vec<PathBuf>> {
    if !journal.is_file() {
        return Ok(Vec::new());
    }
    let mut removed = remove_files_where(dir, is_top_output)?;
    let cells = read_header(journal).map_or_else(|_| Vec::new(), |h| cell_dirs(&h.grid));
    for name in cells {
        let cell = dir.join(name);
        if !cell.is_dir() {
            continue;
        }
        removed.extend(remove_files_where(&cell, is_cell_output)?);
        match fs::remove_dir(&cell) {
            Ok(()) => {}
            Err(e) if e.kind() == ErrorKind::DirectoryNotEmpty => {}
            Err(e) => return Err(e).with_context(|| format!("removing {}", cell.display())),
        }
    }
    Ok(removed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atomic::tests::names;
    use crate::journal::Journal;
    use crate::journal::tests::header;

    #[test]
    fn removes_the_journaled_sweeps_files_and_keeps_everything_else() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        for f in [
            "trials.csv",
            "summary.csv",
            "report.md",
            "fig3a_rescuees.svg",
            "grid.csv",
            "grid.md",
            "grid_rescued_total.svg",
            "replay-rne-0.html",
            "scenario.ron",
            "sweep.lock",
            "notes.txt",
        ] {
            fs::write(d.join(f), "x").unwrap();
        }
        for cell in [
            "c00_duration_s=10",
            "c01_duration_s=20",
            "c02_duration_s=30",
            "c2024_backup",
        ] {
            fs::create_dir(d.join(cell)).unwrap();
            fs::write(d.join(cell).join("trials.csv"), "x").unwrap();
            fs::write(d.join(cell).join("scenario.ron"), "x").unwrap();
        }
        fs::write(d.join("c01_duration_s=20/mine.txt"), "x").unwrap();
        // The journal of a grid over mission.duration_s = 10, 20.
        drop(Journal::create(d, &header()).unwrap());
        let j = Journal::path_in(d);
        // A folder without a journal is not touched.
        assert!(
            remove_previous_outputs(d, &d.join("none.jsonl"))
                .unwrap()
                .is_empty()
        );
        let removed = remove_previous_outputs(d, &j).unwrap();
        assert_eq!(removed.len(), 8 + 2 * 2, "{removed:?}");
        assert_eq!(
            names(d),
            [
                "c01_duration_s=20",
                "c02_duration_s=30",
                "c2024_backup",
                "journal.jsonl",
                "notes.txt",
                "scenario.ron",
                "sweep.lock"
            ]
        );
        assert_eq!(names(&d.join("c01_duration_s=20")), ["mine.txt"]);
        assert_eq!(
            names(&d.join("c2024_backup")),
            ["scenario.ron", "trials.csv"]
        );
    }
}
