//! What `usar sweep --overwrite` removes besides the journal: the output files the journaled
//! sweep wrote into the folder, so no table, figure or grid cell of it stays next to the new
//! sweep's (a grid of other values, or a run killed before its files were written, left them
//! mixed).
//!
//! Only a folder with a journal (its own, or a shard's under `shards/`, whose merge wrote
//! there) is touched, and in it only names a sweep writes
//! (`usar_report::output::write_outputs`, the grid's files and replays, `usar_report::replay`): at the
//! top the tables, figures, reports, replays and grid files (never a `scenario.ron`, which a
//! sweep writes only into grid cells), and the cell folders the journals' headers name, each
//! emptied of its outputs and removed only once empty. Anything else stays, the shards'
//! folders too.

use std::collections::BTreeSet;
use std::fs;
use std::io::ErrorKind;
use std::path::{Path, PathBuf};

use usar_sim::scenario::path_text;

use crate::atomic::{FileError, remove_files_where, remove_named, remove_stale_temps};
use crate::data::figure_list::FIGURES;
use crate::data::shard_folders::shard_folders;
use crate::grid::names::{cell_dir, field_labels};
use crate::journal::{GridHeader, Journal, read_header_unverified};
use crate::vary::FieldPath;

/// What the functions of this module return.
type Result<T> = std::result::Result<T, FileError>;

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
        .collect::<std::result::Result<Vec<_>, _>>()
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

/// The journals whose sweeps wrote into `dir`: `journal` (the folder's own) and those of the
/// shards under `dir/shards/`, whose merge (`usar merge`) wrote there; only regular files.
fn journals_of(dir: &Path, journal: &Path) -> Result<Vec<PathBuf>> {
    let mut journals = vec![journal.to_path_buf()];
    for (_, shard) in shard_folders(dir)? {
        journals.push(Journal::path_in(&shard));
    }
    journals.retain(|j| j.is_file());
    Ok(journals)
}

/// Removes from `dir` the output files of the sweeps journaled in `journal` (a file in `dir`)
/// and in the journals of its shards (`dir/shards/<I>-of-<N>/journal.jsonl`, whose merge
/// wrote into `dir`): the top-level tables, figures, reports, replays and grid files, and in
/// each cell folder a header names, that cell's files and temporary files a kill left
/// ([`crate::atomic::is_temp_name`]), then the folder if that left it empty. A header is read
/// for its names only, without verifying it ([`read_header_unverified`]): an edited header
/// still names its sweep's cells. Nothing when no such journal exists. Call it only while
/// holding the folder's lock ([`crate::lock`]). Returns the files removed.
///
/// # Errors
/// An I/O error listing a folder or removing a file or an emptied cell folder.
pub fn remove_previous_outputs(dir: &Path, journal: &Path) -> Result<Vec<PathBuf>> {
    let journals = journals_of(dir, journal)?;
    if journals.is_empty() {
        return Ok(Vec::new());
    }
    let mut removed = remove_files_where(dir, is_top_output)?;
    let cells: BTreeSet<String> = journals
        .iter()
        .filter_map(|j| read_header_unverified(j))
        .flat_map(|h| cell_dirs(&h.grid))
        .collect();
    for name in cells {
        let cell = dir.join(name);
        if !cell.is_dir() {
            continue;
        }
        removed.extend(remove_files_where(&cell, is_cell_output)?);
        removed.extend(remove_stale_temps(&cell)?);
        match fs::remove_dir(&cell) {
            Ok(()) => {}
            Err(e) if e.kind() == ErrorKind::DirectoryNotEmpty => {}
            Err(e) => return Err(FileError::io(format!("removing {}", path_text(&cell)))(e)),
        }
    }
    Ok(removed)
}

/// `--overwrite` of a sweep's folder whose journal is `dir/journal.jsonl`: removes that
/// journal, the outputs of its sweep and its shards' merge ([`remove_previous_outputs`]) and
/// the temporary files killed runs left; the shards' folders, the lock, the owner manifest
/// and every file a sweep does not write stay. Call it only while holding the folder's lock.
///
/// # Errors
/// An I/O error listing a folder or removing a file.
pub fn clear_sweep(dir: &Path) -> Result<()> {
    let journal = Journal::path_in(dir);
    remove_previous_outputs(dir, &journal)?;
    remove_named(dir, &[crate::journal::JOURNAL_FILE])?;
    remove_stale_temps(dir)?;
    Ok(())
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

    /// Files in the cell folders of the test header's grid (`mission.duration_s` = 10, 20).
    fn old_cells(d: &Path, files: &[&str]) {
        for cell in ["c00_duration_s=10", "c01_duration_s=20"] {
            fs::create_dir_all(d.join(cell)).unwrap();
            for f in files {
                fs::write(d.join(cell).join(f), "x").unwrap();
            }
        }
    }

    #[test]
    fn an_edited_header_still_names_its_cells_and_their_temp_files_go() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        drop(Journal::create(d, &header()).unwrap());
        let j = Journal::path_in(d);
        let edited = fs::read_to_string(&j)
            .unwrap()
            .replace("\"sum\":\"", "\"sum\":\"0");
        fs::write(&j, edited).unwrap();
        assert!(crate::journal::read_header(&j).is_err());
        // A kill left a temporary file next to a cell's table.
        old_cells(d, &["trials.csv", ".summary.csv.tmp-99999-1"]);
        let removed = remove_previous_outputs(d, &j).unwrap();
        assert_eq!(removed.len(), 4, "{removed:?}");
        assert_eq!(names(d), ["journal.jsonl"]);
    }

    #[test]
    fn the_cells_a_merge_of_shards_wrote_go_and_the_shards_stay() {
        let tmp = tempfile::tempdir().unwrap();
        let d = tmp.path();
        let shard = d.join("shards/0-of-2");
        drop(Journal::create(&shard, &header()).unwrap());
        fs::write(d.join("grid.csv"), "x").unwrap();
        old_cells(d, &["trials.csv", "scenario.ron"]);
        // The folder has no journal of its own: a merge wrote its files.
        let removed = remove_previous_outputs(d, &Journal::path_in(d)).unwrap();
        assert_eq!(removed.len(), 5, "{removed:?}");
        assert_eq!(names(d), ["shards"]);
        assert_eq!(names(&shard), ["journal.jsonl"]);
    }
}
