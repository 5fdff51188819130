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
    common::make_fifo(&d.join("fifo.ron"));
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

/// `usar calibrate PAPER --targets t.ron` (t.ron holding `targets`) of one evaluation of RNE's
/// trials of 10 s, no check, in `d`, with `extra`.
fn calibrate(d: &Path, targets: &str, extra: &[&str]) -> Output {
    std::fs::write(d.join("t.ron"), targets).unwrap();
    let short = "--free mission.pickup_s=0.5..2 --methods rne --duration 10 --max-evals 1 \
                 --check-trials 0 --quiet --out out";
    let mut args = vec!["calibrate", PAPER, "--targets", "t.ron"];
    args.extend(short.split_whitespace());
    args.extend(extra);
    usar_within_a_minute(d, &args)
}

/// Regression (issue 70): a target name of 65,536 characters made `usar calibrate` panic
/// ("Formatting argument out of range") after it wrote its files. Names are bounded when the
/// file is read.
#[test]
fn a_target_name_past_the_limit_is_refused_before_anything_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let name = "n".repeat(65_536);
    let targets = format!(
        "Targets(targets: [\n  (name: \"{name}\", statistic: Mean(\"rounds\"), value: 1.0, \
         band: PlusMinus(0.5)),\n])"
    );
    let err = one_line_error(&calibrate(tmp.path(), &targets, &["--trials", "2"]));
    assert_eq!(
        err,
        "error: --targets: t.ron:2:4: targets[0].name: target name of 65536 characters, longer than the \
         limit of 200\n"
    );
    assert!(!tmp.path().join("out").exists());
}

/// Regression (issue 70): `--max-time=18446744073709551615s` panicked ("overflow when
/// adding duration to instant"); a budget whose end cannot be represented is no limit.
#[test]
fn an_endless_max_time_is_no_limit() {
    let tmp = tempfile::tempdir().unwrap();
    let targets = r#"Targets(targets: [
  (name: "rounds", statistic: Mean("rounds"), value: 9.0, band: PlusMinus(0.5)),
])"#;
    let o = calibrate(
        tmp.path(),
        targets,
        &["--trials", "2", "--max-time=18446744073709551615s"],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let summary = String::from_utf8_lossy(&o.stdout);
    assert!(summary.contains("1 evaluations (1 run now"), "{summary}");
}

/// Regression (issue 70): `--trials 1` with a spread among the targets gave a loss of inf,
/// NaN spreads and an empty message; it is refused naming the flag, the target and why.
#[test]
fn one_trial_for_a_spread_target_is_refused_naming_the_flag() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let targets = r#"Targets(targets: [
  (name: "rounds", statistic: Mean("rounds"), value: 1.0, band: PlusMinus(0.5)),
  (name: "sd", statistic: PooledSd("rescued_total"), value: 3.0, band: PlusMinus(1.0)),
])"#;
    let err = one_line_error(&calibrate(d, targets, &["--trials", "1"]));
    assert_eq!(
        err,
        "error: --trials must be at least 2: target \"sd\" (PooledSd(rescued_total)): it needs \
         at least 2 trials per method defining rescued_total\n"
    );
    assert!(!d.join("out").exists());
    std::fs::write(d.join("a.ron"), AXES).unwrap();
    let o = usar_within_a_minute(
        d,
        &[
            "multiverse",
            PAPER,
            "--axes",
            "a.ron",
            "--targets",
            "t.ron",
            "--free",
            "mission.pickup_s=0.5..2",
            "--calibration-trials",
            "1",
            "--out",
            "mv",
        ],
    );
    let err = one_line_error(&o);
    assert!(
        err.starts_with("error: --calibration-trials must be at least 2: target \"sd\""),
        "{err}"
    );
    assert!(!d.join("mv").exists());
}

/// Regression (issue 70): claims files' errors. A missing field was reported at the claim's
/// last field (`claims[0].correction: Unexpected missing field named id`); ids that differ
/// only by case, which name the same file where case is ignored, were accepted; an alpha of
/// 1e308 was written in 309 digits.
#[test]
fn claims_files_name_a_missing_field_ids_equal_but_for_case_and_numbers_short() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let claim = |id: &str, extra: &str| {
        format!(
            "  (id: \"{id}\", sentence: \"s\", subject: \"rne\", metric: \"rounds\", \
             direction: Less{extra}),\n"
        )
    };
    let no_id = "  (sentence: \"s\", subject: \"rne\", metric: \"rounds\",\n   direction: Less, \
                 correction: Holm),\n";
    let cases = [
        (
            format!("Claims(claims: [\n{no_id}])"),
            "c.ron:2:3: claims[0]: missing field `id`",
        ),
        (
            format!(
                "Claims(claims: [\n{}{}])",
                claim("Hard", ""),
                claim("hard", "")
            ),
            "c.ron:3:4: claims[1].id: ids \"hard\" and \"Hard\" (claims[0]) differ only by \
             case: they name files (spec_curve_<id>.svg), which would be one file where case \
             is ignored",
        ),
        (
            format!("Claims(claims: [\n{}])", claim("a", ", alpha: 1e308")),
            "c.ron:2:79: claims[0].alpha: expected a one-sided level in (0, 0.5], found 1e308",
        ),
    ];
    for (body, want) in cases {
        std::fs::write(d.join("c.ron"), &body).unwrap();
        let o = usar_within_a_minute(d, &["sweep", PAPER, "--claims", "c.ron", "--out", "out"]);
        let err = one_line_error(&o);
        assert_eq!(err, format!("error: --claims: {want}\n"), "{body}");
        assert!(!d.join("out").exists());
    }
}

/// A study file given by a flag that cannot be parsed is blamed on that flag, then the file,
/// line and field (`--claims` already was; `--targets` and `--axes` named only the file).
#[test]
fn a_bad_targets_or_axes_file_names_its_flag() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    std::fs::write(d.join("t.ron"), TARGETS).unwrap();
    std::fs::write(d.join("a.ron"), AXES).unwrap();
    std::fs::write(d.join("bad.ron"), "(bogus: 1)").unwrap();
    let out = d.join("out");
    let out = text(&out);
    let free = "mission.pickup_s=0.5..2";
    let multiverse = |axes: &'static str, targets: &'static str| {
        let mut args = vec!["multiverse", PAPER, "--axes", axes, "--targets", targets];
        args.extend(["--free", free, "--out", out]);
        args
    };
    let cases: [(Vec<&str>, &str); 3] = [
        (
            vec![
                "calibrate",
                PAPER,
                "--targets",
                "bad.ron",
                "--free",
                free,
                "--out",
                out,
            ],
            "error: --targets: bad.ron:1:2: bogus: ",
        ),
        (
            multiverse("a.ron", "bad.ron"),
            "error: --targets: bad.ron:1:2: bogus: ",
        ),
        (
            multiverse("bad.ron", "t.ron"),
            "error: --axes: bad.ron:1:2: bogus: ",
        ),
    ];
    for (args, start) in cases {
        let err = one_line_error(&usar_within_a_minute(d, &args));
        assert!(
            err.starts_with(start),
            "{args:?}: want {start:?}, got {err}"
        );
        assert!(!d.join("out").exists(), "{args:?} made its output folder");
    }
}

/// The paper's targets file.
const GOOD_TARGETS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenarios/paper-targets.ron"
);

/// A targets or claims file given by a flag that parses but names a task the scenario lacks is
/// blamed on its flag, with the scenario, in `calibrate` and `multiverse` as in `sweep` (the
/// first two named only the file); so is a claims file naming a method neither built in nor
/// run (`multiverse` named only the file).
#[test]
fn a_file_about_a_task_the_scenario_lacks_names_its_flag() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let paper_file = |name: &str| {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name);
        std::fs::read_to_string(path)
            .unwrap()
            .replace("rescued_easy", "rescued_medium")
    };
    std::fs::write(d.join("t.ron"), paper_file("paper-targets.ron")).unwrap();
    std::fs::write(d.join("c.ron"), paper_file("paper-claims.ron")).unwrap();
    let unknown_method = paper_file("paper-claims.ron")
        .replace("rescued_medium", "rescued_easy")
        .replacen("subject: \"RNE\"", "subject: \"RNX\"", 1);
    std::fs::write(d.join("m.ron"), unknown_method).unwrap();
    std::fs::write(d.join("a.ron"), AXES).unwrap();
    let out = d.join("out");
    let out = text(&out);
    // A field the axes do not choose (they choose mission.pickup_s).
    let free = ["--free", "mission.search_time_budget_s=8..30", "--out", out];
    let calibrate = [&["calibrate", PAPER, "--targets", "t.ron"][..], &free].concat();
    let multiverse = |targets: &'static str, claims: Option<&'static str>| {
        let mut args = vec!["multiverse", PAPER, "--axes", "a.ron", "--targets", targets];
        args.extend(claims.map_or(vec![], |c| vec!["--claims", c]));
        [&args[..], &free].concat()
    };
    let sweep = vec!["sweep", PAPER, "--targets", "t.ron", "--out", out];
    let cases: [(Vec<&str>, &str); 4] = [
        (calibrate, "--targets: t.ron:"),
        (multiverse("t.ron", None), "--targets: t.ron:"),
        (multiverse(GOOD_TARGETS, Some("c.ron")), "--claims: c.ron:"),
        (sweep, "--targets: t.ron:"),
    ];
    // A claim naming a method neither built in nor run, as `sweep` reports it.
    for args in [
        multiverse(GOOD_TARGETS, Some("m.ron")),
        vec!["sweep", PAPER, "--claims", "m.ron", "--out", out],
    ] {
        let err = one_line_error(&usar_within_a_minute(d, &args));
        assert!(
            err.starts_with("error: --claims: m.ron:") && err.contains("unknown method \"RNX\""),
            "{args:?}: {err}"
        );
        assert!(!d.join("out").exists(), "{args:?} made its output folder");
    }
    for (args, start) in cases {
        let err = one_line_error(&usar_within_a_minute(d, &args));
        assert!(
            err.starts_with(&format!("error: {start}")),
            "{args:?}: want {start:?}, got {err}"
        );
        assert!(
            err.contains(
                "\"rescued_medium\" is about task \"medium\", which the scenario does not have"
            ) && err.trim_end().ends_with(&format!("; scenario: {PAPER}")),
            "{args:?}: {err}"
        );
        assert!(!d.join("out").exists(), "{args:?} made its output folder");
    }
}
