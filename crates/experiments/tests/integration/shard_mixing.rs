//! One output folder never holds the files of two sweeps through a merge: a folder belongs to
//! one kind of run (`usar-owner.json`), so shards are refused in a plain sweep's folder and a
//! plain sweep in a sharded sweep's, with or without `--overwrite`; `usar merge` refuses a
//! folder whose own journal is another sweep's.

use crate::common;

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

/// The error of a refused command.
fn refused(o: &Output) -> String {
    assert!(!o.status.success(), "ran, but should have been refused");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The error of a refused command, asserted to be one line.
fn refused_in_a_line(o: &Output) -> String {
    let err = refused(o);
    assert_eq!(err.trim().lines().count(), 1, "{err}");
    err
}

#[test]
fn shards_are_refused_in_a_plain_sweeps_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &[]));
    let plain = std::fs::read(dir.join("trials.csv")).unwrap();
    let err = refused_in_a_line(&grid_shard(&dir, "0/2"));
    assert!(
        err.contains("holds a sweep (") && err.contains("a sharded sweep never writes"),
        "{err}"
    );
    assert!(!dir.join("shards").exists());
    let err = refused_in_a_line(&merge(&dir));
    assert!(err.contains("holds a sweep ("), "{err}");
    assert!(!dir.join("grid.csv").exists());
    assert!(CELLS.iter().all(|c| !dir.join(c).exists()));
    assert_eq!(std::fs::read(dir.join("trials.csv")).unwrap(), plain);
}

#[test]
fn a_merge_refuses_a_folder_whose_journal_is_another_sweeps() {
    let tmp = tempfile::tempdir().unwrap();
    let (plain, dir) = (tmp.path().join("plain"), tmp.path().join("s"));
    ok(&sweep(&plain, &[]));
    ok(&grid_shard(&dir, "0/2"));
    ok(&grid_shard(&dir, "1/2"));
    // A journal of another sweep put at the top of the sharded sweep's folder by hand.
    std::fs::copy(plain.join("journal.jsonl"), dir.join("journal.jsonl")).unwrap();
    let err = refused_in_a_line(&merge(&dir));
    assert!(
        err.contains("journal.jsonl is the journal of another sweep than the shards'")
            && err.contains("varied fields"),
        "{err}"
    );
    assert!(!dir.join("grid.csv").exists());
    assert!(CELLS.iter().all(|c| !dir.join(c).exists()));
}

#[test]
fn a_plain_sweep_is_refused_in_a_sharded_sweeps_folder_even_to_overwrite_it() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&grid_shard(&dir, "0/2"));
    ok(&grid_shard(&dir, "1/2"));
    ok(&merge(&dir));
    let merged = std::fs::read(dir.join("grid.csv")).unwrap();
    for extra in [&[][..], &["--overwrite"][..]] {
        let err = refused_in_a_line(&sweep(&dir, extra));
        assert!(
            err.contains("holds a sharded sweep (") && err.contains("a sweep never writes"),
            "{err}"
        );
    }
    // The same sweep as the shards', run without --shard, is another kind of run too.
    let vary = "mission.hp_pct_per_step_in_radiation=0.0003,0.003";
    refused(&sweep(&dir, &["--vary", vary]));
    assert!(!dir.join("journal.jsonl").exists());
    assert_eq!(std::fs::read(dir.join("grid.csv")).unwrap(), merged);
    assert!(CELLS.iter().all(|c| dir.join(c).exists()));
    ok(&merge(&dir));
    assert_eq!(std::fs::read(dir.join("grid.csv")).unwrap(), merged);
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
