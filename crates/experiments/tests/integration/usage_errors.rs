//! Usage errors (an unknown flag, a bad value, a missing argument) are one line on stderr with
//! exit code 2, like every other error of `usar`; `--help` and a bare `usar` still print help.

use crate::common;

use common::usar;

#[test]
fn usage_errors_are_one_line_with_the_tip_and_the_usage() {
    let cases: [(&[&str], &[&str]); 4] = [
        (
            &["sweep", "--trial", "3", "x.ron"],
            &[
                "error: unexpected argument '--trial' found",
                "'--trials'",
                "usar sweep",
            ],
        ),
        (
            &["run", "--trial", "x", "x.ron"],
            &["error: invalid value 'x' for '--trial <N>'", "--help"],
        ),
        (
            &["run"],
            &["error: the following required arguments were not provided: <SCENARIO>"],
        ),
        (&["frob"], &["error: unrecognized subcommand 'frob'"]),
    ];
    for (args, needles) in cases {
        let o = usar(args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        for n in needles {
            assert!(err.contains(n), "{args:?}: {n:?} not in {err}");
        }
    }
}

#[test]
fn help_is_still_printed_whole() {
    let o = usar(["run", "--help"]);
    assert!(o.status.success());
    assert!(String::from_utf8_lossy(&o.stdout).lines().count() > 5);
    let bare = usar([] as [&str; 0]);
    let text = String::from_utf8_lossy(&bare.stderr);
    assert!(
        text.contains("Commands:") && text.lines().count() > 5,
        "{text}"
    );
}

/// A scenario with a bad arena width, written to `dir` under `name`.
fn bad_scenario(dir: &std::path::Path, name: &str) -> std::path::PathBuf {
    let p = dir.join(name);
    std::fs::write(
        &p,
        "Scenario(\n  name: \"x\",\n  arena: (width_m: -1.0, height_m: 5.0),\n)\n",
    )
    .expect("write");
    p
}

#[test]
fn every_command_gives_a_bad_scenario_as_file_line_col_field() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let p = bad_scenario(tmp.path(), "bad.ron");
    let path = p.to_str().expect("utf-8");
    let out = tmp.path().join("out").to_str().expect("utf-8").to_string();
    let commands: [&[&str]; 5] = [
        &["check", path],
        &["run", path],
        &["render", path, "--out", &out],
        &["replay", path, "--out", &out],
        &["sweep", path, "--out", &out],
    ];
    for args in commands {
        let o = usar(args);
        assert!(!o.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(
            err,
            format!("error: {path}:3:20: arena.width_m: expected a finite number > 0, found -1\n"),
            "{args:?}"
        );
    }
}

#[test]
fn a_path_with_a_line_break_is_escaped_in_a_one_line_error() {
    let tmp = tempfile::tempdir().expect("temp dir");
    let p = bad_scenario(tmp.path(), "a\nb.ron");
    let shown = p.to_str().expect("utf-8").replace('\n', "\\n");
    for args in [vec!["check"], vec!["run"]] {
        let o = common::usar(args.iter().map(std::ffi::OsStr::new).chain([p.as_os_str()]));
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with(&format!("error: {shown}:3:20: arena.width_m:")),
            "{err}"
        );
    }
    let missing = tmp.path().join("no\nsuch.ron");
    let o = common::usar([std::ffi::OsStr::new("run"), missing.as_os_str()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("no\\nsuch.ron: cannot read scenario file"),
        "{err}"
    );
}

#[test]
fn an_output_that_cannot_be_written_names_its_flag() {
    let tmp = tempfile::tempdir().unwrap();
    let paper = common::PAPER;
    // A regular file where a folder should be, and a folder where a file should be.
    let file = tmp.path().join("a-file");
    std::fs::write(&file, "x").unwrap();
    let at = |name: &str| file.join(name).to_str().unwrap().to_owned();
    let (svg, html, under) = (at("map.svg"), at("page.html"), at("sub"));
    let folder = tmp.path().to_str().unwrap();
    let sweep = |more: &[&'static str]| {
        let mut args = vec!["sweep", paper, "--trials", "1", "--duration", "1", "-q"];
        args.extend_from_slice(more);
        args
    };
    let mut to_sub = sweep(&["--out"]);
    to_sub.push(&under);
    let cases: Vec<(Vec<&str>, &str)> = vec![
        (
            vec!["run", paper, "--duration", "1", "--json", folder],
            "error: --json: ",
        ),
        (vec!["render", paper, "--out", &svg], "error: --out: "),
        (
            vec!["replay", paper, "--duration", "1", "--out", &html],
            "error: --out: ",
        ),
        (to_sub, "error: --out: "),
        (sweep(&["--methods", "rne,,dis"]), "error: --methods: "),
        (
            vec!["run", paper, "--duration", "1", "--rounds-csv", folder],
            "error: --rounds-csv: ",
        ),
    ];
    for (args, start) in cases {
        let o = usar(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(!o.status.success(), "{args:?}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(
            err.starts_with(start),
            "{args:?}: want {start:?}, got {err}"
        );
        // A file flag's path is named once, by the error itself, not again by the flag's
        // context.
        if ["--json", "--rounds-csv"].iter().any(|f| args.contains(f)) {
            assert_eq!(err.matches(folder).count(), 1, "{args:?}: {err}");
        }
    }
}
