//! Hostile inputs of the studies' files and flags (issue 70): a FIFO as the scenario,
//! `--claims`, `--targets` or `--axes` is refused at once in one line naming the file.

use crate::common;

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{PAPER, stderr, text};

/// `usar ARGS` in `cwd`, killed (and the test failed) if it runs longer than 60 s: a
/// regression that waits for ever fails instead of hanging the tests.
fn usar_within_a_minute(cwd: &Path, args: &[&str]) -> Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_usar"))
        .current_dir(cwd)
        .args(args)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run usar");
    let start = Instant::now();
    while child.try_wait().expect("wait for usar").is_none() {
        if start.elapsed() > Duration::from_secs(60) {
            child.kill().expect("kill usar");
            child.wait().expect("reap usar");
            panic!("usar {args:?} still running after 60 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().expect("usar's output")
}

/// Its one line of stderr, after asserting that `o` failed with exit status 1.
fn one_line_error(o: &Output) -> String {
    assert_eq!(o.status.code(), Some(1), "{}", stderr(o));
    let err = stderr(o);
    assert_eq!(err.lines().count(), 1, "{err}");
    err
}

const TARGETS: &str = r#"Targets(targets: [
    (name: "rounds", statistic: Mean("rounds"), value: 1.0, band: PlusMinus(0.5)),
])"#;

const AXES: &str = r#"Axes(axes: [(name: "pickup", alternatives: [
    (name: "as given"),
    (name: "slow", set: ["mission.pickup_s=3"]),
])])"#;

/// Regression (issue 70): a FIFO without a writer as the scenario or a study file waited for
/// ever; it is now refused before it is opened, in one line naming it.
#[cfg(unix)]
#[test]
fn a_fifo_as_any_input_file_is_refused_at_once() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let made = Command::new("mkfifo").arg(d.join("fifo.ron")).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    std::fs::write(d.join("t.ron"), TARGETS).unwrap();
    std::fs::write(d.join("a.ron"), AXES).unwrap();
    let no_file = "not a regular file (a folder, FIFO or device)";
    let out = d.join("out");
    let out = text(&out);
    let cases: [(&[&str], String); 5] = [
        (
            &["check", "fifo.ron"],
            format!("fifo.ron: cannot read scenario file: {no_file}"),
        ),
        (
            &["sweep", "fifo.ron", "--out", out],
            format!("fifo.ron: cannot read scenario file: {no_file}"),
        ),
        (
            &["sweep", PAPER, "--claims", "fifo.ron", "--out", out],
            format!("fifo.ron: cannot read claims file: {no_file}"),
        ),
        (
            &[
                "calibrate",
                PAPER,
                "--targets",
                "fifo.ron",
                "--free",
                "mission.pickup_s=0.5..2",
                "--out",
                out,
            ],
            format!("fifo.ron: cannot read targets file: {no_file}"),
        ),
        (
            &[
                "multiverse",
                PAPER,
                "--axes",
                "fifo.ron",
                "--targets",
                "t.ron",
                "--free",
                "mission.pickup_s=0.5..2",
                "--out",
                out,
            ],
            format!("fifo.ron: cannot read axes file: {no_file}"),
        ),
    ];
    for (args, want) in cases {
        let err = one_line_error(&usar_within_a_minute(d, args));
        // The study files' errors may be prefixed by their flag (`error: --claims: ...`).
        assert!(
            err.starts_with("error: ") && err.trim_end().ends_with(&want),
            "{args:?}: {err}"
        );
        assert!(!d.join("out").exists(), "{args:?} made its output folder");
    }
}
