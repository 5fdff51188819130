//! `usar sweep`: a trial that fails (panics) is journaled with its error, the other trials
//! finish and are written, and the exit status is non-zero naming the failed trial.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::PAPER;

fn sweep(out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", "2"])
        .args(["--duration", "30", "--quiet", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("run usar")
}

#[test]
fn failing_trial_is_recorded_and_the_rest_finish() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("f");
    let o = sweep(&dir, &["--fail-trial", "dis:1"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("1 of 4 trials failed"), "{err}");
    assert!(err.contains("DIS trial 1"), "{err}");
    assert!(err.contains("failing on purpose"), "{err}");

    let journal = std::fs::read_to_string(dir.join("journal.jsonl")).unwrap();
    let failed: Vec<&str> = journal
        .lines()
        .filter(|l| l.contains("\"failed\""))
        .collect();
    assert_eq!(failed.len(), 1, "{journal}");
    assert!(failed[0].contains("\"method\":\"DIS\"") && failed[0].contains("\"trial\":1"));

    let trials = std::fs::read_to_string(dir.join("trials.csv")).unwrap();
    assert_eq!(trials.lines().count(), 1 + 3, "{trials}");
    let report = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(report.contains("## Failed trials") && report.contains("DIS trial 1"));

    // --resume retries only the failed trial.
    let o = sweep(&dir, &["--resume"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("ran 1 trials"));
    let trials = std::fs::read_to_string(dir.join("trials.csv")).unwrap();
    assert_eq!(trials.lines().count(), 1 + 4);
}

#[test]
fn bad_options_are_refused_before_running() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("b");
    for (args, needle) in [
        (&["--methods", "rne,xyz"][..], "xyz"),
        (&["--fail-trial", "eng:0"][..], "names no trial"),
        (&["--threads", "0"][..], "--threads"),
        (&["--duration", "-1"][..], "--duration"),
    ] {
        let o = sweep(&dir, args);
        assert!(!o.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.contains(needle), "{args:?}: {err}");
    }
}
