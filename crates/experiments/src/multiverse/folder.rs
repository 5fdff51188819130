//! A multiverse's output folder: the plans it holds (at the top, written by a run without
//! `--shard`, and in each shard folder `shards/<I>-of-<N>/`), the refusal of a multiverse of
//! another identity, and `--overwrite`'s clean-up.
//!
//! ```text
//! DIR/
//!   multiverse.json   the plan (super::plan)      sweep.lock   the lock (crate::lock)
//!   multiverse.csv  multiverse.md  spec_curve_<claim>.svg      (super::outputs)
//!   universes/u000/ ...                                        (super::universe_run)
//!   shards/0-of-4/multiverse.json, sweep.lock                  (a shard's plan and lock)
//! ```

use std::path::Path;

use anyhow::{Context, Result, bail};
use usar_sim::scenario::path_text;

use super::outputs::output_files;
use super::plan::{MultiversePlan, identity_diff};
use super::universe_run::UNIVERSES_DIR;
use crate::shard::{SHARDS_DIR, Shard, shard_folders};

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

/// Whether `dir` holds a multiverse: a plan at its top or in a shard folder.
pub fn is_multiverse_dir(dir: &Path) -> bool {
    MultiversePlan::path_in(dir).is_file()
        || shard_folders(dir)
            .is_ok_and(|s| s.iter().any(|(_, f)| MultiversePlan::path_in(f).is_file()))
}

/// Where a plan lies, for messages.
fn plan_path(dir: &Path, shard: Option<Shard>) -> String {
    let folder = match shard {
        Some(s) => crate::shard::shard_dir(dir, s),
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
            bail!(
                "{} holds another multiverse ({}): pass --overwrite to start afresh (its \
                 universes go), or choose another --out",
                plan_path(dir, shard),
                identity_diff(&other.identity, &plan.identity)
            );
        }
    }
    Ok(())
}

/// `--overwrite`: removes from `dir` what a multiverse wrote there (the plan, the top files,
/// `universes/` and `shards/`); other files stay.
///
/// # Errors
/// An I/O error removing something.
pub fn clear(dir: &Path) -> Result<()> {
    let mut files = output_files();
    files.push(super::plan::PLAN_FILE.to_string());
    for name in files {
        let p = dir.join(name);
        if p.symlink_metadata()
            .is_ok_and(|m| m.is_file() || m.is_symlink())
        {
            std::fs::remove_file(&p).with_context(|| format!("removing {}", path_text(&p)))?;
        }
    }
    for name in [UNIVERSES_DIR, SHARDS_DIR] {
        let p = dir.join(name);
        match p.symlink_metadata() {
            Ok(m) if m.is_dir() => std::fs::remove_dir_all(&p),
            Ok(_) => std::fs::remove_file(&p),
            Err(_) => continue,
        }
        .with_context(|| format!("removing {}", path_text(&p)))?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;

    #[test]
    fn another_identity_is_refused_and_overwrite_clears_what_is_ours() {
        let dir = tempfile::tempdir().unwrap();
        let d = dir.path();
        assert!(!is_multiverse_dir(d));
        let p = plan();
        let shard = crate::shard::shard_dir(d, Shard::new(1, 2).unwrap());
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
        std::fs::create_dir_all(d.join("universes/u000")).unwrap();
        std::fs::write(d.join("multiverse.csv"), "x").unwrap();
        std::fs::write(d.join("notes.txt"), "mine").unwrap();
        p.write(d).unwrap();
        clear(d).unwrap();
        assert!(!is_multiverse_dir(d));
        assert!(!d.join("universes").exists() && !d.join("multiverse.csv").exists());
        assert_eq!(
            std::fs::read_to_string(d.join("notes.txt")).unwrap(),
            "mine"
        );
    }
}
