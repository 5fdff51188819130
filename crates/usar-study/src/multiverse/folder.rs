//! A multiverse's output folder: the plans it holds (at the top, written by a run without
//! `--shard`, and in each shard folder `shards/<I>-of-<N>/`), the refusal of a multiverse of
//! another identity, and `--overwrite`'s clean-up.
//!
//! ```text
//! DIR/
//!   usar-owner.json   its owner, a multiverse (usar_sweep::data::owner)
//!   multiverse.json   the plan (super::plan)      sweep.lock   the lock (usar_sweep::lock)
//!   multiverse.csv  multiverse.md  spec_curve_<claim>.svg      (super::outputs)
//!   universes/u000/ ...                                        (super::universe_run)
//!   shards/0-of-4/multiverse.json, sweep.lock                  (a shard's plan and lock)
//! ```

use std::fs;
use std::path::Path;

use usar_sim::scenario::path_text;

use super::design::DESIGN_DIR;
use super::error::MultiverseError;
use super::outputs::output_files;
use super::plan::{MultiversePlan, identity_diff};
use super::record::RECORD_FILE;
use super::universe_run::{CALIBRATION_DIR, COMPARISON_DIR, SCENARIO_FILE, UNIVERSES_DIR};
use usar_sweep::atomic::{FileError, remove_dir_if_empty, remove_named, remove_stale_temps};
use usar_sweep::data::owner::{OWNER_FILE, RunKind, check_owner};
use usar_sweep::journal::something_at;
use usar_sweep::lock::LOCK_FILE;
use usar_sweep::shard::{SHARDS_DIR, Shard, shard_folders};
use usar_sweep::stale_outputs::clear_sweep;

/// What the functions of this module return.
type Result<T> = std::result::Result<T, MultiverseError>;

/// Every plan in `dir`: the top one (`None`), then each shard folder's, by shard.
///
/// # Errors
/// A plan that cannot be read, or an I/O error listing the shard folders.
pub fn plans_in(dir: &Path) -> Result<Vec<(Option<Shard>, MultiversePlan)>> {
    let mut out = Vec::new();
    if let Some(p) = MultiversePlan::read(dir)? {
        out.push((None, p));
    }
    for (shard, folder) in shard_folders(dir)? {
        if let Some(p) = MultiversePlan::read(&folder)? {
            out.push((Some(shard), p));
        }
    }
    Ok(out)
}

/// Whether `dir` holds a multiverse: a plan at its top or in a shard folder (anything by the
/// plan's name, even a link to `/dev/zero`, which reading the plan then refuses by name).
pub fn is_multiverse_dir(dir: &Path) -> bool {
    let plan_at = |d: &Path| something_at(&MultiversePlan::path_in(d));
    plan_at(dir) || shard_folders(dir).is_ok_and(|s| s.iter().any(|(_, f)| plan_at(f)))
}

/// Where a plan lies, for messages.
fn plan_path(dir: &Path, shard: Option<Shard>) -> String {
    let folder = match shard {
        Some(s) => usar_sweep::shard::shard_dir(dir, s),
        None => dir.to_path_buf(),
    };
    path_text(&MultiversePlan::path_in(&folder))
}

/// Refuses to run `plan` in `dir` when a plan of another identity is there.
///
/// # Errors
/// The first such plan, with what differs, suggesting `--overwrite` or another `--out`.
pub fn refuse_others(dir: &Path, plan: &MultiversePlan) -> Result<()> {
    for (shard, other) in plans_in(dir)? {
        if other.identity != plan.identity {
            return Err(MultiverseError::OtherMultiverse {
                plan: plan_path(dir, shard),
                diff: identity_diff(&other.identity, &plan.identity),
            });
        }
    }
    Ok(())
}

/// The names of the claims' figures in `dir` (`spec_curve_<id>.svg`,
/// `sensitivity_<id>.svg`), whatever the claims were.
fn spec_curve_files(dir: &Path) -> Result<Vec<String>> {
    let mut names = Vec::new();
    let entries = match fs::read_dir(dir) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(names),
        Err(e) => return Err(FileError::io(format!("listing {}", path_text(dir)))(e).into()),
    };
    for entry in entries {
        let entry = entry.map_err(FileError::io(format!("listing {}", path_text(dir))))?;
        if let Some(name) = entry.file_name().to_str()
            && (name.starts_with("spec_curve_") || name.starts_with("sensitivity_"))
            && name.ends_with(".svg")
        {
            names.push(name.to_owned());
        }
    }
    names.sort();
    Ok(names)
}

/// `--overwrite`: removes from `dir` what a multiverse writes there and nothing else: the
/// plan and the top files; in each shard's folder (`shards/<I>-of-<N>/`) its plan, lock and
/// owner manifest; the design's point files (`design/d<digits>.json`); in each universe's folder (`universes/u<digits>/`) its scenario, record,
/// its calibration's files ([`crate::calibrate::outputs::clear`]) and its comparison's
/// ([`usar_sweep::stale_outputs::clear_sweep`]), with their locks and owner manifests. A folder is
/// removed once that leaves it empty; a file the multiverse does not write stays, and so does
/// its folder. Call it only with the folder's exclusive lock held (no shard runs then).
///
/// # Errors
/// An I/O error listing a folder or removing something.
pub fn clear(dir: &Path) -> Result<()> {
    // Every claims file's figures: the plan that named them may be another's.
    let mut files = output_files(&[]);
    files.extend(spec_curve_files(dir)?);
    files.push(super::plan::PLAN_FILE.to_string());
    let names: Vec<&str> = files.iter().map(String::as_str).collect();
    remove_named(dir, &names)?;
    let own = [super::plan::PLAN_FILE, LOCK_FILE, OWNER_FILE];
    for (_, shard) in shard_folders(dir)? {
        remove_named(&shard, &own)?;
        remove_stale_temps(&shard)?;
        remove_dir_if_empty(&shard)?;
    }
    remove_dir_if_empty(&dir.join(SHARDS_DIR))?;
    let universes = dir.join(UNIVERSES_DIR);
    for u in universe_folders(&universes)? {
        clear_universe(&u)?;
    }
    remove_dir_if_empty(&universes)?;
    clear_design(&dir.join(DESIGN_DIR))
}

/// Removes the design's point files (`d` and digits `.json`) from `design` and the folder
/// once empty.
fn clear_design(design: &Path) -> Result<()> {
    let entries = match std::fs::read_dir(design) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(()),
        Err(e) => return Err(FileError::io(format!("listing {}", path_text(design)))(e).into()),
    };
    let mut names = Vec::new();
    for e in entries {
        let e = e.map_err(FileError::io(format!("listing {}", path_text(design))))?;
        if let Some(n) = e.file_name().to_str()
            && let Some(digits) = n.strip_prefix('d').and_then(|n| n.strip_suffix(".json"))
            && !digits.is_empty()
            && digits.bytes().all(|b| b.is_ascii_digit())
        {
            names.push(n.to_owned());
        }
    }
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    remove_named(design, &names)?;
    remove_stale_temps(design)?;
    Ok(remove_dir_if_empty(design)?)
}

/// The universes' folders under `universes` (`u` and digits, as
/// [`super::universe::Universe::id`] names them); none when it does not exist.
fn universe_folders(universes: &Path) -> Result<Vec<std::path::PathBuf>> {
    let entries = match std::fs::read_dir(universes) {
        Ok(e) => e,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Vec::new()),
        Err(e) => return Err(FileError::io(format!("listing {}", path_text(universes)))(e).into()),
    };
    let mut out = Vec::new();
    for e in entries {
        let e = e.map_err(FileError::io(format!("listing {}", path_text(universes))))?;
        let is_dir = e.file_type().is_ok_and(|t| t.is_dir());
        let name = e.file_name();
        let is_id = name.to_str().is_some_and(|n| {
            n.len() > 1 && n.starts_with('u') && n[1..].bytes().all(|b| b.is_ascii_digit())
        });
        if is_dir && is_id {
            out.push(e.path());
        }
    }
    out.sort();
    Ok(out)
}

/// Removes what a universe's run writes in its folder `u` (see [`clear`]).
fn clear_universe(u: &Path) -> Result<()> {
    let run_files = [LOCK_FILE, OWNER_FILE];
    let calibration = u.join(CALIBRATION_DIR);
    if check_owner(&calibration, RunKind::Calibration).is_ok() {
        crate::calibrate::outputs::clear(&calibration)?;
        remove_named(&calibration, &run_files)?;
        remove_dir_if_empty(&calibration)?;
    }
    let comparison = u.join(COMPARISON_DIR);
    if check_owner(&comparison, RunKind::Sweep).is_ok() {
        clear_sweep(&comparison)?;
        remove_named(&comparison, &run_files)?;
        remove_dir_if_empty(&comparison)?;
    }
    remove_named(u, &[SCENARIO_FILE, RECORD_FILE])?;
    remove_stale_temps(u)?;
    Ok(remove_dir_if_empty(u)?)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;

    /// The names in `dir`, sorted.
    fn names(dir: &Path) -> Vec<String> {
        let entries = fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name());
        let sorted: std::collections::BTreeSet<String> =
            entries.map(|n| n.into_string().unwrap()).collect();
        sorted.into_iter().collect()
    }

    #[test]
    fn another_identity_is_refused_and_overwrite_clears_what_is_ours() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        assert!(!is_multiverse_dir(d));
        let p = plan();
        let shard = usar_sweep::shard::shard_dir(d, Shard::new(1, 2).unwrap());
        p.write(&shard).unwrap();
        assert!(is_multiverse_dir(d));
        refuse_others(d, &p).unwrap();
        let mut q = p.clone();
        q.identity.trials = 9;
        let e = format!("{:#}", refuse_others(d, &q).unwrap_err());
        assert!(
            e.contains("shards/1-of-2/multiverse.json holds another multiverse (trials 2 vs 9)"),
            "{e}"
        );
        assert!(e.contains("--overwrite") && !e.contains('\n'), "{e}");
        std::fs::create_dir_all(d.join("universes/u000/calibration")).unwrap();
        std::fs::create_dir_all(d.join("universes/u001/comparison")).unwrap();
        for f in [
            "universes/u000/universe.json",
            "universes/u000/scenario.ron",
            "universes/u000/calibration/trace.jsonl",
            "universes/u000/calibration/calibrated.ron",
            "universes/u000/calibration/sweep.lock",
            "universes/u001/comparison/journal.jsonl",
            "universes/u001/comparison/trials.csv",
            "multiverse.csv",
        ] {
            std::fs::write(d.join(f), "x").unwrap();
        }
        // What a multiverse does not write stays, and so do the folders holding it.
        for f in [
            "notes.txt",
            "universes/notes.txt",
            "universes/u001/comparison/mine.txt",
            "shards/1-of-2/mine.txt",
        ] {
            std::fs::write(d.join(f), "mine").unwrap();
        }
        p.write(d).unwrap();
        clear(d).unwrap();
        assert!(!is_multiverse_dir(d));
        assert!(!d.join("multiverse.csv").exists() && !d.join("universes/u000").exists());
        assert_eq!(names(&d.join("universes")), ["notes.txt", "u001"]);
        assert_eq!(names(&d.join("universes/u001")), ["comparison"]);
        assert_eq!(names(&d.join("universes/u001/comparison")), ["mine.txt"]);
        assert_eq!(names(&d.join("shards/1-of-2")), ["mine.txt"]);
        assert_eq!(
            std::fs::read_to_string(d.join("notes.txt")).unwrap(),
            "mine"
        );
        // Nothing left: every folder goes.
        for f in [
            "notes.txt",
            "universes/notes.txt",
            "universes/u001/comparison/mine.txt",
        ] {
            std::fs::remove_file(d.join(f)).unwrap();
        }
        std::fs::remove_file(d.join("shards/1-of-2/mine.txt")).unwrap();
        clear(d).unwrap();
        assert!(names(d).is_empty(), "{:?}", names(d));
    }
}
