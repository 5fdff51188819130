//! `usar check`: a summary of a valid scenario; the loader's error and a non-zero exit status
//! for an invalid one.

use std::process::{Command, Output};

const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");

fn usar(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(args)
        .output()
        .expect("run usar")
}

#[test]
fn check_summarises_the_paper_scenario() {
    let o = usar(&["check", PAPER]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "scenario paper",
        "arena",
        "carrier",
        "task easy",
        "task hard",
        "start->goal",
        "debris:",
        "radiation zones:",
        "valid",
    ] {
        assert!(out.contains(needle), "{needle} missing in\n{out}");
    }
}

#[test]
fn check_reports_the_loader_error_with_its_position() {
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad.ron");
    let text = std::fs::read_to_string(PAPER).unwrap();
    // An unknown field: ron reports it with line and column.
    let broken = text.replacen("name:", "nmae:", 1);
    std::fs::write(&bad, broken).unwrap();
    let o = usar(&["check", bad.to_str().unwrap()]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    let prefix = format!("error: {}:", bad.display());
    assert!(err.starts_with(&prefix), "{err}");
    // file:line:col
    let rest = &err[prefix.len()..];
    let mut parts = rest.splitn(3, ':');
    assert!(parts.next().unwrap().parse::<usize>().is_ok(), "{err}");
    assert!(parts.next().unwrap().parse::<usize>().is_ok(), "{err}");

    let o = usar(&["check", "/nonexistent/x.ron"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("/nonexistent/x.ron"));
}

#[test]
fn every_subcommand_help_has_examples() {
    for sub in ["check", "run", "sweep"] {
        let o = usar(&[sub, "--help"]);
        assert!(o.status.success());
        assert!(
            String::from_utf8_lossy(&o.stdout).contains("Examples:"),
            "{sub}"
        );
    }
    let o = usar(&["--help"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("usar sweep scenarios/paper.ron"));
}
