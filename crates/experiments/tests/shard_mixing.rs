//! One output folder never holds the files of two sweeps through a merge: `usar merge`
//! refuses a folder whose own journal is another sweep's, a sweep refuses a folder whose
//! shards are another sweep's, and `--overwrite` removes what the shards' merge wrote.

mod common;

use std::path::Path;
use std::process::{Command, Output};

use common::{PAPER, merge, ok, set_journal_build};

/// The cell folders of the sharded sweep's grid.
const CELLS: [&str; 2] = [
    "c00_hp_pct_per_step_in_radiation=0.0003",
    "c01_hp_pct_per_step_in_radiation=0.003",
];

/// `usar sweep` of rne,dis x 2 trials x 8 s into `out`, then `extra`.
fn sweep(out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", "2"])
        .args(["--duration", "8", "--quiet", "--threads", "2", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("run usar")
}

/// Shard `shard` of the sweep over a 2-cell grid ([`CELLS`]) into `out`.
fn grid_shard(out: &Path, shard: &str) -> Output {
    let vary = "mission.hp_pct_per_step_in_radiation=0.0003,0.003";
    sweep(out, &["--vary", vary, "--shard", shard])
}

fn refused(o: &Output) -> String {
    assert!(!o.status.success(), "ran, but should have been refused");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_merge_refuses_a_folder_whose_journal_is_another_sweeps() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &[]));
    let plain = std::fs::read(dir.join("trials.csv")).unwrap();
    ok(&grid_shard(&dir, "0/2"));
    ok(&grid_shard(&dir, "1/2"));
    let err = refused(&merge(&dir));
    assert!(
        err.contains("journal.jsonl is the journal of another sweep than the shards'")
            && err.contains("varied fields"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    // Nothing of the shards' sweep was written next to the plain sweep's files.
    assert!(!dir.join("grid.csv").exists());
    assert!(CELLS.iter().all(|c| !dir.join(c).exists()));
    assert_eq!(std::fs::read(dir.join("trials.csv")).unwrap(), plain);
}

#[test]
fn a_sweep_refuses_a_folder_whose_shards_are_another_sweeps_and_overwrite_clears_it() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&grid_shard(&dir, "0/2"));
    ok(&grid_shard(&dir, "1/2"));
    ok(&merge(&dir));
    assert!(dir.join("grid.csv").exists() && dir.join(CELLS[0]).exists());
    // Another sweep (no grid) run plainly into the folder is refused.
    let err = refused(&sweep(&dir, &[]));
    assert!(
        err.contains("is a shard's journal of another sweep") && err.contains("--overwrite"),
        "{err}"
    );
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    assert!(!dir.join("journal.jsonl").exists());
    // --overwrite removes the merged grid (its top files and cell folders) and keeps the
    // shards, whose merge is then refused.
    ok(&sweep(&dir, &["--overwrite"]));
    assert!(!dir.join("grid.csv").exists());
    assert!(CELLS.iter().all(|c| !dir.join(c).exists()), "a cell stayed");
    assert!(dir.join("shards/0-of-2/journal.jsonl").exists());
    assert!(dir.join("trials.csv").exists());
    refused(&merge(&dir));
}

#[test]
fn the_shards_own_sweep_runs_plainly_in_their_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &["--shard", "0/2"]));
    ok(&sweep(&dir, &["--shard", "1/2"]));
    ok(&merge(&dir));
    let merged = std::fs::read(dir.join("trials.csv")).unwrap();
    ok(&sweep(&dir, &[]));
    assert_eq!(std::fs::read(dir.join("trials.csv")).unwrap(), merged);
    // And a merge after it: the folder's journal is the shards' sweep.
    ok(&merge(&dir));
    assert_eq!(std::fs::read(dir.join("trials.csv")).unwrap(), merged);
}

/// Shards run by two builds of usar are not merged (the second may simulate differently);
/// shards of one build are, whichever build merges them.
#[test]
fn shards_of_two_builds_are_not_merged() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &["--shard", "0/2"]));
    ok(&sweep(&dir, &["--shard", "1/2"]));
    let journal = |i: usize| {
        dir.join("shards")
            .join(format!("{i}-of-2"))
            .join("journal.jsonl")
    };
    set_journal_build(&journal(1), "0000000-other");
    let err = refused(&merge(&dir));
    assert!(
        err.contains("build ") && err.contains("0000000-other") && err.contains("--overwrite"),
        "{err}"
    );
    assert!(!dir.join("trials.csv").exists());
    // Both shards of that other build: merged by this one.
    set_journal_build(&journal(0), "0000000-other");
    ok(&merge(&dir));
    assert!(dir.join("trials.csv").exists());
}
