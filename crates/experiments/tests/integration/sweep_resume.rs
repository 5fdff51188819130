//! `usar sweep`: a sweep killed part-way and resumed writes the same trials.csv and
//! summary.csv as an uninterrupted one; --resume refuses a journal of other parameters.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::{PAPER, STOPPED, journal_trials, read};

fn sweep(out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", "2"])
        .args(["--duration", "40", "--quiet", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("run usar")
}

#[test]
fn resumed_sweep_matches_uninterrupted_one() {
    let tmp = tempfile::tempdir().unwrap();
    let whole = tmp.path().join("whole");
    let parts = tmp.path().join("parts");

    let o = sweep(&whole, &["--threads", "2"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert_eq!(journal_trials(&whole), 4);

    // Killed after the first trial is journaled: no tables yet, one trial in the journal.
    let o = sweep(&parts, &["--threads", "2", "--stop-after", "1"]);
    assert_eq!(
        o.status.code(),
        Some(STOPPED),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert!(!parts.join("trials.csv").exists());
    assert_eq!(journal_trials(&parts), 1);

    // Running again with other parameters and without --resume refuses to touch the journal,
    // and suggests what works: not `--resume` with these parameters (it would be refused too).
    let o = sweep(&parts, &["--seed", "9"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("run it with its own parameters (and --resume)")
            && err.contains("pass --overwrite")
            && err.contains("seed 2021 vs 9")
            && !err.contains("pass --resume"),
        "{err}"
    );
    assert_eq!(journal_trials(&parts), 1);

    // Resume runs only the three missing trials.
    let o = sweep(&parts, &["--threads", "1", "--resume"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("ran 3 trials"), "{stdout}");
    assert_eq!(journal_trials(&parts), 4);

    for name in ["trials.csv", "summary.csv"] {
        assert!(
            read(&whole.join(name)) == read(&parts.join(name)),
            "{name} differs"
        );
    }
    let rows = String::from_utf8(read(&whole.join("trials.csv"))).unwrap();
    let methods: Vec<&str> = rows
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(1).unwrap())
        .collect();
    assert_eq!(methods, ["RNE", "RNE", "DIS", "DIS"]);
    for f in [
        "report.md",
        "fig3a_rescuees.svg",
        "fig3b_energy_per_rescuee.svg",
        "fig3c_hp_per_rescuee.svg",
    ] {
        assert!(parts.join(f).exists(), "{f} missing");
    }

    // A resume of a finished sweep runs nothing and rewrites the same files.
    let o = sweep(&parts, &["--resume"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).contains("all 4 trials came from the journal"));
    assert!(read(&whole.join("trials.csv")) == read(&parts.join("trials.csv")));
}

#[test]
fn resume_refuses_a_journal_of_other_parameters() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    let o = sweep(&dir, &["--stop-after", "1"]);
    assert_eq!(o.status.code(), Some(STOPPED));
    let o = sweep(&dir, &["--resume", "--seed", "7"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("other parameters") && err.contains("seed 2021 vs 7"),
        "{err}"
    );
    // The journal is left as it was.
    assert_eq!(journal_trials(&dir), 1);
}

#[test]
fn an_empty_journal_is_started_afresh_with_or_without_resume() {
    let tmp = tempfile::tempdir().unwrap();
    for extra in [&[][..], &["--resume"][..]] {
        let dir = tmp.path().join(format!("e{}", extra.len()));
        std::fs::create_dir(&dir).unwrap();
        std::fs::write(dir.join("journal.jsonl"), "").unwrap();
        let o = sweep(&dir, extra);
        assert!(
            o.status.success(),
            "{extra:?}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        assert_eq!(journal_trials(&dir), 4, "{extra:?}");
    }
}
