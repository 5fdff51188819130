//! `usar calibrate`: short calibrations of scenarios/paper.ron (one method, 2 trials of 60 s
//! per evaluation, a few evaluations) write their files, continue after a kill with the same
//! result as an uninterrupted run, do not depend on --threads, and refuse bad input in one
//! line.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::{PAPER, STOPPED, ok, read, read_text, stderr, text};

/// Test targets over paper.ron's tasks: rounds and the easy / hard ratio reachable at 60 s,
/// rescuees far out of reach, so that the search runs until its simplex is flat.
const TARGETS: &str = "\
// Targets of the calibrate_cli tests.
Targets(
    targets: [
        (name: \"rounds\", statistic: Mean(\"rounds\"), value: 1.0, band: PlusMinus(0.5)),
        (name: \"rescuees\", statistic: Mean(\"rescued_total\"), value: 500.0, band: PlusMinus(10.0)),
        (name: \"easy / hard\", statistic: RatioOfMeans(\"rescued_easy\", \"rescued_hard\"),
         value: 1.3, band: PlusMinus(0.2)),
        (name: \"sd\", statistic: PooledSd(\"rescued_total\"), value: 3.0, band: Between(1.0, 6.0)),
    ],
)
";

/// The free fields of every run here.
const FREE: [&str; 4] = [
    "--free",
    "mission.pickup_s=0.5..2",
    "--free",
    "mission.search_time_budget_s=8..30",
];

/// `--trials 2`, `--max-evals 6` and `--check-trials 1`, each unless `extra` gives it.
fn defaults(extra: &[&str]) -> Vec<&'static str> {
    let mut out = Vec::new();
    for (flag, value) in [
        ("--trials", "2"),
        ("--max-evals", "6"),
        ("--check-trials", "1"),
    ] {
        if !extra.contains(&flag) {
            out.extend([flag, value]);
        }
    }
    out
}

/// `usar calibrate PAPER --targets t.ron --free ... --methods rne --duration 60 --out out
/// ARGS` in the folder `cwd` (which holds t.ron), with a fixed date and [`defaults`].
fn calibrate_in(cwd: &Path, extra: &[&str]) -> Output {
    std::fs::write(cwd.join("t.ron"), TARGETS).unwrap();
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .current_dir(cwd)
        .env("SOURCE_DATE_EPOCH", "1700000000")
        .args(["calibrate", PAPER, "--targets", "t.ron"])
        .args(FREE)
        .args([
            "--methods",
            "rne",
            "--duration",
            "60",
            "--quiet",
            "--out",
            "out",
        ])
        .args(extra)
        .args(defaults(extra))
        .output()
        .expect("run usar")
}

/// The rows of `trace.csv` in `dir`, split into cells (no cell here holds a comma).
fn rows(dir: &Path) -> Vec<Vec<String>> {
    read_text(&dir.join("trace.csv"))
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(String::from).collect())
        .collect()
}

/// `calibrated.ron` in `dir` without its header comment: the scenario alone.
fn scenario_part(dir: &Path) -> String {
    read_text(&dir.join("calibrated.ron"))
        .lines()
        .filter(|l| !l.starts_with("//"))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Evaluation lines in the trace of `dir`.
fn traced(dir: &Path) -> usize {
    read_text(&dir.join("trace.jsonl"))
        .lines()
        .filter(|l| l.starts_with("{\"eval\""))
        .count()
}

#[test]
fn a_calibration_writes_its_files_and_the_best_values_reproduce_its_statistics() {
    let tmp = tempfile::tempdir().unwrap();
    let summary = ok(&calibrate_in(tmp.path(), &[]));
    let out = tmp.path().join("out");
    for f in [
        "trace.jsonl",
        "calibrated.ron",
        "trace.csv",
        "calibration.md",
        "convergence.svg",
        "statistics.svg",
    ] {
        assert!(out.join(f).is_file(), "{f} missing");
    }
    assert!(summary.contains("run now, 0 from the trace"), "{summary}");
    assert!(
        summary.contains("best values: mission.pickup_s="),
        "{summary}"
    );
    let rows = rows(&out);
    assert!((3..=6).contains(&rows.len()), "{rows:?}");
    assert_eq!(traced(&out), rows.len());
    // The best row: the lowest loss, the earliest of equals.
    let loss = |r: &Vec<String>| r[7].parse::<f64>().unwrap();
    let best = rows
        .iter()
        .fold(&rows[0], |b, r| if loss(r) < loss(b) { r } else { b });
    // calibrated.ron passes `usar check` and holds the best values.
    ok(&common::usar(["check", text(&out.join("calibrated.ron"))]));
    let spec = usar_sim::scenario::parse_spec(&scenario_part(&out), "calibrated.ron").unwrap();
    assert_eq!(spec.mission.pickup_s.to_string(), best[1]);
    assert_eq!(
        spec.mission.search_time_budget_s.map(|x| x.to_string()),
        Some(best[2].clone())
    );
    let ron = read_text(&out.join("calibrated.ron"));
    assert!(ron.starts_with("// Calibrated by usar calibrate on 2023-11-14T22:13:20Z (UTC):\n"));
    assert!(
        ron.contains(&format!("best: evaluation #{}, loss {}", best[0], best[7])),
        "{ron}"
    );
    // A sweep of calibrated.ron with the same trials gives the best evaluation's statistics.
    let sweep = tmp.path().join("sweep");
    ok(&common::usar([
        "sweep",
        text(&out.join("calibrated.ron")),
        "--methods",
        "rne",
        "--trials",
        "2",
        "--duration",
        "60",
        "--quiet",
        "--out",
        text(&sweep),
    ]));
    let csv = read_text(&sweep.join("trials.csv"));
    let head: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    let column = |name: &str| -> Vec<f64> {
        let i = head.iter().position(|h| *h == name).unwrap();
        csv.lines()
            .skip(1)
            .map(|l| l.split(',').nth(i).unwrap().parse().unwrap())
            .collect()
    };
    let mean = |xs: &[f64]| xs.iter().sum::<f64>() / xs.len() as f64;
    let close = |a: f64, b: &str| (a - b.parse::<f64>().unwrap()).abs() <= 1e-12 * a.abs().max(1.0);
    assert!(close(mean(&column("rounds")), &best[3]), "{best:?}");
    assert!(close(mean(&column("rescued_total")), &best[4]), "{best:?}");
    let ratio = mean(&column("rescued_easy")) / mean(&column("rescued_hard"));
    assert!(close(ratio, &best[5]), "{best:?}");
    let md = read_text(&out.join("calibration.md"));
    for part in [
        "## Result",
        "## Best values",
        "## Unseen trials",
        "convergence.svg",
        "statistics.svg",
    ] {
        assert!(md.contains(part), "{part} missing from calibration.md");
    }
    assert!(read_text(&out.join("convergence.svg")).starts_with("<svg"));

    // The same command again runs nothing and writes the same files.
    let again = ok(&calibrate_in(tmp.path(), &[]));
    assert!(
        again.contains(&format!("(0 run now, {} from the trace)", rows_len(&out))),
        "{again}"
    );
    assert_eq!(traced(&out), rows_len(&out));
}

fn rows_len(dir: &Path) -> usize {
    rows(dir).len()
}

#[test]
fn a_killed_calibration_resumes_to_the_same_result_on_any_thread_count() {
    let tmp = tempfile::tempdir().unwrap();
    let (whole, parts, one) = (
        tmp.path().join("whole"),
        tmp.path().join("parts"),
        tmp.path().join("one"),
    );
    for d in [&whole, &parts, &one] {
        std::fs::create_dir(d).unwrap();
    }
    ok(&calibrate_in(&whole, &["--threads", "2"]));

    // Killed after two evaluations: no output but the trace, whose last line a kill cut.
    let o = calibrate_in(&parts, &["--threads", "2", "--stop-after", "2"]);
    assert_eq!(o.status.code(), Some(STOPPED), "{}", stderr(&o));
    let out = parts.join("out");
    assert_eq!(traced(&out), 2);
    assert!(!out.join("calibrated.ron").exists());
    let mut trace = read(&out.join("trace.jsonl"));
    trace.extend_from_slice(b"{\"eval\":{\"index\":2,\"values\":[0.97");
    std::fs::write(out.join("trace.jsonl"), &trace).unwrap();

    // The same command continues: two evaluations from the trace, the rest run.
    let resumed = ok(&calibrate_in(&parts, &["--threads", "2"]));
    let n = rows_len(&whole.join("out"));
    assert!(
        resumed.contains(&format!("({} run now, 2 from the trace)", n - 2)),
        "{resumed}"
    );
    for f in ["trace.csv", "calibrated.ron"] {
        assert!(
            read(&whole.join("out").join(f)) == read(&out.join(f)),
            "{f} differs after a resume"
        );
    }
    // The cut line is gone: every line of the trace is whole.
    assert_eq!(traced(&out), n);
    assert!(read(&out.join("trace.jsonl")).ends_with(b"}\n"));

    // One thread: the same evaluations and scenario (only the command line differs).
    ok(&calibrate_in(&one, &["--threads", "1"]));
    assert!(read(&whole.join("out/trace.csv")) == read(&one.join("out/trace.csv")));
    assert_eq!(
        scenario_part(&whole.join("out")),
        scenario_part(&one.join("out"))
    );
}

#[test]
fn another_calibration_in_the_folder_is_refused_and_overwrite_starts_afresh() {
    let tmp = tempfile::tempdir().unwrap();
    let quick = ["--max-evals", "1", "--check-trials", "0"];
    ok(&calibrate_in(tmp.path(), &quick));
    let o = calibrate_in(tmp.path(), &[&quick[..], &["--trials", "3"]].concat());
    assert!(!o.status.success());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("out/trace.jsonl holds another calibration (trace has trials 2 vs 3)")
            && err.contains("--overwrite")
            && err.contains("another --out"),
        "{err}"
    );
    let fresh = ok(&calibrate_in(
        tmp.path(),
        &[&quick[..], &["--trials", "3", "--overwrite"]].concat(),
    ));
    assert!(
        fresh.contains("1 evaluations (1 run now, 0 from the trace)"),
        "{fresh}"
    );
}

#[test]
fn bad_input_gives_one_line_errors() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path();
    let bad_targets = TARGETS.replace("Mean(\"rounds\")", "Mean(\"roundz\")");
    let missing_task = TARGETS.replace("\"rescued_easy\"", "\"rescued_medium\"");
    let syntax = TARGETS.replace("value: 1.0,", "value: 1.0");
    std::fs::write(dir.join("bad.ron"), &bad_targets).unwrap();
    std::fs::write(dir.join("task.ron"), &missing_task).unwrap();
    std::fs::write(dir.join("syntax.ron"), &syntax).unwrap();
    let run = |targets: &str, free: &[&str]| -> String {
        let mut args = vec!["calibrate", PAPER, "--targets", targets, "--out"];
        let out = dir.join("never");
        args.push(text(&out));
        for f in free {
            args.extend(["--free", f]);
        }
        let o = Command::new(env!("CARGO_BIN_EXE_usar"))
            .current_dir(dir)
            .args(&args)
            .output()
            .unwrap();
        assert!(!o.status.success(), "{args:?} succeeded");
        assert!(!out.exists(), "{args:?} made the output folder");
        let err = stderr(&o);
        assert_eq!(err.lines().count(), 1, "{err}");
        err
    };
    let good = ["mission.pickup_s=0.5..2"];
    for (targets, free, says) in [
        (
            "bad.ron",
            &good[..],
            "error: --targets: bad.ron:4:26: targets[0].statistic: unknown metric \"roundz\" (metrics: ",
        ),
        (
            "syntax.ron",
            &good[..],
            "error: --targets: syntax.ron:4:64: targets[0]: Expected comma",
        ),
        (
            "task.ron",
            &good[..],
            "error: --targets: task.ron:6:31: targets[2].statistic: target \"easy / hard\": \
             metric \"rescued_medium\" is about task \"medium\", which the scenario does not \
             have (its tasks: hard, easy); scenario: ",
        ),
        (
            "t.ron",
            &["mission.pickup_s=1..1"][..],
            "error: --free mission.pickup_s=1..1: the range 1..1 is empty or reversed",
        ),
        (
            "t.ron",
            &["mission.pickup_s=0..2:log"][..],
            "error: --free mission.pickup_s=0..2:log: a log range needs LO > 0, found 0",
        ),
        (
            "t.ron",
            &["mission.pick_s=0.5..2"][..],
            "error: --free mission.pick_s=0.5..2: no field \"pick_s\" in mission (fields: ",
        ),
        (
            "t.ron",
            &["mission.pickup_s=0.5..2", "mission.pickup_s=1..3"][..],
            "error: --free mission.pickup_s=1..3: the field is given twice",
        ),
        (
            "t.ron",
            &["mission.round_start=0..1"][..],
            "error: --free mission.round_start=0..1: mission.round_start: is not a number",
        ),
    ] {
        std::fs::write(dir.join("t.ron"), TARGETS).unwrap();
        let err = run(targets, free);
        assert!(err.starts_with(says), "{err}\nshould start with\n{says}");
    }
}

#[test]
fn report_only_names_a_target_of_the_file() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("never");
    let o = Command::new(env!("CARGO_BIN_EXE_usar"))
        .current_dir(tmp.path())
        .args(["calibrate", PAPER, "--free", "mission.pickup_s=0.5..2"])
        .args([
            "--report-only",
            "pooled SD of all rescuees",
            "--out",
            text(&out),
        ])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(!out.exists());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with(
            "error: scenarios/paper-targets.ron (built in): --report-only \"pooled SD of all \
             rescuees\": no target has that name (targets: \"rounds per trial\""
        ),
        "{err}"
    );
}

#[test]
fn cma_es_resumes_its_own_trace_and_refuses_one_of_nelder_mead() {
    let tmp = tempfile::tempdir().unwrap();
    let cma = ["--optimizer", "cma-es", "--check-trials", "0"];
    // A short CMA-ES run, then the same command with a larger budget: the first evaluations
    // come from the trace, in the same order.
    let first = ok(&calibrate_in(
        tmp.path(),
        &[&cma[..], &["--max-evals", "3"]].concat(),
    ));
    assert!(
        first.contains("3 evaluations (3 run now, 0 from the trace)"),
        "{first}"
    );
    let before = rows(&tmp.path().join("out"));
    let more = ok(&calibrate_in(
        tmp.path(),
        &[&cma[..], &["--max-evals", "5"]].concat(),
    ));
    assert!(
        more.contains("5 evaluations (2 run now, 3 from the trace)"),
        "{more}"
    );
    let after = rows(&tmp.path().join("out"));
    assert_eq!(before[..], after[..3]);
    let md = read_text(&tmp.path().join("out/calibration.md"));
    assert!(md.contains("CMA-ES (fcmaes-core, active)"), "{md}");
    // The same folder under Nelder-Mead is another calibration.
    let o = calibrate_in(tmp.path(), &["--max-evals", "5", "--check-trials", "0"]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("holds another calibration") && err.contains("search"),
        "{err}"
    );
}

#[test]
fn require_fits_a_report_only_target_and_names_an_unknown_one() {
    let tmp = tempfile::tempdir().unwrap();
    let o = Command::new(env!("CARGO_BIN_EXE_usar"))
        .current_dir(tmp.path())
        .args(["calibrate", PAPER, "--free", "mission.pickup_s=0.5..2"])
        .args(["--require", "energy per trials", "--out", "never"])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(!tmp.path().join("never").exists());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("--require \"energy per trials\": no target has that name"),
        "{err}"
    );
    let ok_run = ok(&Command::new(env!("CARGO_BIN_EXE_usar"))
        .current_dir(tmp.path())
        .args(["calibrate", PAPER, "--free", "mission.pickup_s=0.5..2"])
        .args([
            "--require",
            "energy per trial",
            "--methods",
            "rne",
            "--trials",
            "2",
        ])
        .args([
            "--duration",
            "30",
            "--max-evals",
            "1",
            "--check-trials",
            "0",
        ])
        .args(["--quiet", "--out", "fit"])
        .output()
        .unwrap());
    assert!(!ok_run.is_empty());
    // Fitted now: the table no longer marks it as reported only.
    let md = read_text(&tmp.path().join("fit/calibration.md"));
    let line = md
        .lines()
        .find(|l| l.contains("energy per trial"))
        .expect("the target is in the table");
    assert!(!line.contains("(reported only)"), "{line}");
    assert!(
        md.lines()
            .any(|l| l.contains("HP lost per trial") && l.contains("(reported only)")),
        "{md}"
    );
}
