//! `usar slurm`: the job array and merge scripts it writes, and `--submit` with a stand-in
//! `sbatch` that records its arguments (the real Slurm runs in `scripts/slurm-test.sh`).

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::{PAPER, ok, read_text};

fn slurm(out: &Path, extra: &[&str], path_env: Option<&str>) -> Output {
    let mut c = Command::new(env!("CARGO_BIN_EXE_usar"));
    c.args(["slurm", PAPER, "--methods", "rne,dis", "--trials", "2"])
        .args([
            "--duration",
            "60",
            "--vary",
            "mission.duration_s=30,60",
            "--shards",
            "4",
        ])
        .arg("--out")
        .arg(out)
        .args(extra);
    if let Some(p) = path_env {
        c.env("PATH", p);
    }
    c.output().expect("run usar")
}

#[test]
fn writes_an_array_script_a_merge_script_and_a_submit_script() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("big");
    let printed = ok(&slurm(
        &out,
        &[
            "--cpus-per-task",
            "3",
            "--time",
            "01:30:00",
            "--mem",
            "2G",
            "--account",
            "lab",
        ],
        None,
    ));
    assert!(printed.contains("submit.sh"), "{printed}");
    let array = read_text(&out.join("slurm/sweep.sbatch"));
    for line in [
        "#SBATCH --array=0-3",
        "#SBATCH --cpus-per-task=3",
        "#SBATCH --time=01:30:00",
        "#SBATCH --mem=2G",
        "#SBATCH --account=lab",
        "##SBATCH --partition=...",
        "--shard \"${SLURM_ARRAY_TASK_ID}/4\" --threads \"${SLURM_CPUS_PER_TASK:-1}\"",
        "mission.duration_s=30,60",
        "--duration 60",
    ] {
        assert!(array.contains(line), "no {line:?} in\n{array}");
    }
    let merge = read_text(&out.join("slurm/merge.sbatch"));
    assert!(merge.contains(" merge "), "{merge}");
    let submit = read_text(&out.join("slurm/submit.sh"));
    assert!(
        submit.contains("--dependency=afterok:\"$array\""),
        "{submit}"
    );
    assert!(out.join("slurm/logs").is_dir());
    // The array script is valid shell.
    let syntax = Command::new("bash")
        .arg("-n")
        .arg(out.join("slurm/sweep.sbatch"))
        .status()
        .unwrap();
    assert!(syntax.success());
}

#[test]
fn submit_chains_the_merge_to_the_array_with_afterok() {
    let tmp = tempfile::tempdir().unwrap();
    let bin = tmp.path().join("bin");
    std::fs::create_dir(&bin).unwrap();
    let log = tmp.path().join("sbatch.log");
    // A stand-in sbatch: logs its arguments, answers job 41 then 42 (with a cluster name).
    let fake = format!(
        "#!/bin/sh\necho \"$@\" >> '{log}'\nn=$(wc -l < '{log}')\necho \"$((40 + n));cluster\"\n",
        log = log.display()
    );
    let sbatch = bin.join("sbatch");
    std::fs::write(&sbatch, fake).unwrap();
    std::process::Command::new("chmod")
        .arg("+x")
        .arg(&sbatch)
        .status()
        .unwrap();
    let path = format!("{}:/usr/bin:/bin", bin.display());
    let out = tmp.path().join("big");
    let printed = ok(&slurm(&out, &["--submit"], Some(&path)));
    assert!(
        printed.contains("array as job 41 and the merge as job 42"),
        "{printed}"
    );
    let calls = read_text(&log);
    let calls: Vec<&str> = calls.lines().collect();
    assert_eq!(calls.len(), 2, "{calls:?}");
    assert!(calls[0].starts_with("--parsable ") && calls[0].ends_with("sweep.sbatch"));
    assert!(calls[1].contains("--dependency=afterok:41") && calls[1].ends_with("merge.sbatch"));
}

#[test]
fn submit_without_sbatch_fails_with_the_reason() {
    let tmp = tempfile::tempdir().unwrap();
    let o = slurm(&tmp.path().join("big"), &["--submit"], Some("/nonexistent"));
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("--submit") && err.contains("sbatch"), "{err}");
}

#[test]
fn bad_options_are_refused_before_anything_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("big");
    let o = slurm(&out, &["--time", "1 hour"], None);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--time"));
    assert!(!out.join("slurm/sweep.sbatch").exists());
}

#[test]
fn more_shards_than_trials_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    let o = Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["slurm", PAPER, "--methods", "rne,dis", "--trials", "2"])
        .args(["--duration", "60", "--shards", "5", "--out"])
        .arg(&out)
        .output()
        .expect("run usar");
    assert!(!o.status.success());
    assert_eq!(
        String::from_utf8_lossy(&o.stderr).trim(),
        "error: --shards 5: the sweep has 4 trial(s), so at most 4 shards have work; split it \
         into at most 4"
    );
    assert!(!out.join("slurm").exists());
}

/// `usar slurm PAPER --methods rne --shards 1 ARGS --out OUT`.
fn slurm_with(out: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["slurm", PAPER, "--methods", "rne", "--shards", "1"])
        .args(args)
        .arg("--out")
        .arg(out)
        .output()
        .expect("run usar")
}

/// The one-line error of a refused `o`.
fn refused(o: &Output) -> String {
    assert!(!o.status.success(), "accepted");
    let err = String::from_utf8_lossy(&o.stderr).trim().to_string();
    assert_eq!(err.lines().count(), 1, "{err}");
    err
}

#[test]
fn a_sweep_that_usar_sweep_refuses_is_refused_before_anything_is_written() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("o");
    for (args, error) in [
        (
            &["--duration", "nan"][..],
            "error: --duration: trial length",
        ),
        (&["--duration", "0"][..], "error: --duration: trial length"),
        (&["--trials", "0"][..], "error: --trials must be at least 1"),
    ] {
        let err = refused(&slurm_with(&out, args));
        assert!(err.starts_with(error), "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} wrote {}", out.display());
    }
}

#[test]
fn a_path_with_a_line_break_is_refused_and_never_reaches_a_script() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("x\ntouch pwned #");
    let err = refused(&slurm_with(&out, &["--trials", "1"]));
    assert!(
        err.contains("--out") && err.contains("holds a line break"),
        "{err}"
    );
    assert_eq!(std::fs::read_dir(tmp.path()).unwrap().count(), 0);
    let out = tmp.path().join("a \"quoted\" name");
    let err = refused(&slurm_with(&out, &["--trials", "1"]));
    assert!(err.contains("holds a double quote"), "{err}");
}
