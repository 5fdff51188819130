//! What `usar sweep --overwrite` removes besides the journal: the output files an earlier sweep
//! wrote into the folder, so no table, figure or grid cell of it stays next to the new sweep's
//! (a grid of other values, or a run killed before its files were written, left them mixed).
//!
//! Only names a sweep writes are removed ([`crate::output::write_outputs`], the grid's files
//! and replays, [`crate::replay`]); anything else in the folder is kept, and a cell folder is
//! removed only once it is empty.

use std::fs;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result};

use crate::atomic::remove_files_where;
use crate::figures::FIGURES;

/// Files of one cell (the output folder itself without a grid): tables, figures, report,
/// the cell's scenario.
const CELL_FILES: [&str; 5] = [
    "trials.csv",
    "trials_long.csv",
    "summary.csv",
    "report.md",
    "scenario.ron",
];

/// Whether a sweep writes a file of this name into a cell's folder (or the output folder
/// without a grid): [`CELL_FILES`], the figures of [`FIGURES`], `replay-*.html`.
fn is_cell_output(name: &str) -> bool {
    CELL_FILES.contains(&name)
        || FIGURES.iter().any(|f| f.file == name)
        || (name.starts_with("replay-") && name.ends_with(".html"))
}

/// Whether a sweep writes a file of this name at the top of its output folder: a cell's
/// files, `grid.csv`, `grid.md` and the grid figures `grid_*.svg`.
fn is_top_output(name: &str) -> bool {
    is_cell_output(name)
        || name == "grid.csv"
        || name == "grid.md"
        || (name.starts_with("grid_") && name.ends_with(".svg"))
}

/// Whether a folder name is a grid cell's ([`crate::grid::names::cell_dir`]): `c`, at least
/// two digits, then the end or `_`.
fn is_cell_dir(name: &str) -> bool {
    let Some(rest) = name.strip_prefix('c') else {
        return false;
    };
    let digits = rest.bytes().take_while(u8::is_ascii_digit).count();
    digits >= 2 && (digits == rest.len() || rest.as_bytes()[digits] == b'_')
}

/// Removes from `dir` the output files of an earlier sweep: the top-level tables, figures,
/// reports and grid files, and in each grid cell folder (`c00_...`) its files, then the folder
/// if that left it empty. Other files and folders stay. A missing folder has nothing to
/// remove. Call it only while holding the folder's lock ([`crate::lock`]). Returns the files
/// removed.
///
/// # Errors
/// An I/O error listing a folder or removing a file or an empty cell folder.
pub fn remove_previous_outputs(dir: &Path) -> Result<Vec<PathBuf>> {
    if !dir.is_dir() {
        return Ok(Vec::new());
    }
    let mut removed = remove_files_where(dir, is_top_output)?;
    for entry in fs::read_dir(dir).with_context(|| format!("listing {}", dir.display()))? {
        let entry = entry.with_context(|| format!("listing {}", dir.display()))?;
        let is_dir = entry.file_type().is_ok_and(|t| t.is_dir());
        if !is_dir || !entry.file_name().to_str().is_some_and(is_cell_dir) {
            continue;
        }
        let cell = entry.path();
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

    #[test]
    fn removes_a_sweeps_files_and_keeps_everything_else() {
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
            "journal.jsonl",
            "sweep.lock",
            "notes.txt",
        ] {
            fs::write(d.join(f), "x").unwrap();
        }
        for cell in [
            "c00_duration_s=30",
            "c01_duration_s=40",
            "c02",
            "cx1",
            "c1_x",
        ] {
            fs::create_dir(d.join(cell)).unwrap();
            fs::write(d.join(cell).join("trials.csv"), "x").unwrap();
            fs::write(d.join(cell).join("scenario.ron"), "x").unwrap();
        }
        fs::write(d.join("c01_duration_s=40/mine.txt"), "x").unwrap();
        let removed = remove_previous_outputs(d).unwrap();
        assert_eq!(removed.len(), 8 + 3 * 2, "{removed:?}");
        assert_eq!(
            names(d),
            [
                "c01_duration_s=40",
                "c1_x",
                "cx1",
                "journal.jsonl",
                "notes.txt",
                "sweep.lock"
            ]
        );
        assert_eq!(names(&d.join("c01_duration_s=40")), ["mine.txt"]);
        assert_eq!(names(&d.join("cx1")), ["scenario.ron", "trials.csv"]);
        assert!(
            remove_previous_outputs(&d.join("missing"))
                .unwrap()
                .is_empty()
        );
    }
}
