//! `usar run`: one trial's metrics on the terminal and as JSON.

use crate::common;

use std::process::Command;

use common::{PAPER, usar};

#[test]
fn run_prints_metrics_and_writes_json() {
    let tmp = tempfile::tempdir().unwrap();
    let json = tmp.path().join("t.json");
    let o = usar([
        "run",
        PAPER,
        "--method",
        "hp_dis",
        "--trial",
        "1",
        "--duration",
        "30",
        "--json",
        json.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    for needle in [
        "trial 1 with HP_DIS",
        "rescuees",
        "hard",
        "easy",
        "total",
        "rounds:",
        "deadl.",
    ] {
        assert!(out.contains(needle), "{needle} missing in\n{out}");
    }
    let text = std::fs::read_to_string(&json).unwrap();
    let r: usar_sim::mission::TrialResult = serde_json::from_str(&text).unwrap();
    // Each task's figures by name, and the totals, beside the TrialResult's vectors.
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    for (t, name) in r.tasks.iter().enumerate() {
        let task = &v["by_task"][name.as_str()];
        assert_eq!(task["rescued"], r.rescued[t], "{name}");
        assert_eq!(task["energy_spent_pct"], r.energy_spent_pct[t], "{name}");
        assert_eq!(task["hp_lost_pct"], r.hp_lost_pct[t], "{name}");
    }
    assert_eq!(v["total"]["rescued"], r.rescued_total());
    assert_eq!(v["total"]["hp_lost_pct"], r.hp_total_pct());
    assert_eq!(r.method, "HP_DIS");
    assert_eq!(r.trial, 1);
    assert_eq!(r.seed, usar_sim::mission::trial_seed(2021, 1));
    assert_eq!(r.robots.len(), 12);
    assert!((r.duration_s - 30.0).abs() < 1e-9);
    // The round table numbers rounds from 1, as the replay page does ("Round 1 of n").
    let header = out.lines().position(|l| l.contains("start s")).unwrap();
    let first = out.lines().nth(header + 1).unwrap();
    assert!(!r.rounds.is_empty());
    assert_eq!(first.split_whitespace().next(), Some("1"), "{out}");
}

#[test]
fn run_with_a_seed_reproduces_the_trial_with_that_seed() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("a.json"), tmp.path().join("b.json"));
    let seed = usar_sim::mission::trial_seed(2021, 0).to_string();
    let headers = [
        format!("paper trial 0 with RNE (seed {seed}), 10 s"),
        // A seed given as is belongs to no trial index.
        format!("paper a trial with RNE (seed {seed}), 10 s"),
    ];
    let runs = [(["--trial", "0"], &a), (["--seed", seed.as_str()], &b)];
    for ((args, path), header) in runs.into_iter().zip(headers) {
        let o = usar([
            "run",
            PAPER,
            "--method",
            "rne",
            args[0],
            args[1],
            "--duration",
            "10",
            "--json",
            path.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let stdout = String::from_utf8(o.stdout).unwrap();
        assert_eq!(stdout.lines().next(), Some(header.as_str()), "{stdout}");
    }
    let read = |p: &std::path::Path| -> usar_sim::mission::TrialResult {
        serde_json::from_str(&std::fs::read_to_string(p).unwrap()).unwrap()
    };
    assert_eq!(read(&a), read(&b));
}

#[test]
fn run_refuses_bad_options() {
    let o = usar(["run", PAPER, "--method", "nope", "--duration", "1"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("nope"), "{err}");
    // The error names the one flag it is about.
    assert!(err.starts_with("error: --method: "), "{err}");
    let o = usar(["run", PAPER, "--method", "rne", "--duration", "-1"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.starts_with("error: --duration: trial length"), "{err}");
    let o = usar(["run", PAPER, "--trial", "1", "--seed", "3"]);
    assert!(!o.status.success());
}

#[test]
fn a_huge_or_tiny_duration_is_named_in_a_short_line() {
    let o = usar(["run", PAPER, "--method", "dis", "--duration", "-1e300"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        err.trim_end(),
        "error: --duration: trial length: expected a number of seconds > 0, found -1e300"
    );
    // Shorter than one step: one step is run, and the warning writes the request as given.
    let o = usar(["run", PAPER, "--method", "dis", "--duration", "1e-300"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        err.trim_end(),
        "warning: --duration 1e-300 s is shorter than one step of 0.02 s (sim.dt_s): the trial \
         runs 0.02 s (1 step)"
    );
}

/// Runs `usar` with `args` and closes its standard output at once, before it writes (the
/// reader of a pipe gone); returns how it ended.
fn with_reader_gone(args: &[&std::ffi::OsStr]) -> std::process::Output {
    let mut child = Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(args)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("run usar");
    drop(child.stdout.take());
    child.wait_with_output().unwrap()
}

/// Regression: `usar run ... | head` ended with `error: Broken pipe (os error 32)` once `head`
/// had gone. A closed pipe now ends the command quietly with 141 (128 + SIGPIPE), as a shell
/// reports a program killed by that signal.
#[test]
fn a_reader_that_goes_away_ends_the_command_quietly() {
    let args = ["run", PAPER, "--method", "dis", "--duration", "2"];
    let o = with_reader_gone(&args.map(std::ffi::OsStr::new));
    assert_eq!(o.status.code(), Some(141));
    assert_eq!(String::from_utf8_lossy(&o.stderr), "");
}

/// Regression: the sweep's summary on standard output is written by the report library,
/// whose typed error holds the broken pipe inside it; a reader that goes away still ends the
/// command quietly with 141.
#[test]
fn a_reader_that_goes_away_ends_a_sweep_quietly() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    let args = [
        "sweep",
        PAPER,
        "--methods",
        "dis",
        "--trials",
        "1",
        "--duration",
        "2",
    ];
    let mut args: Vec<&std::ffi::OsStr> = args.iter().map(std::ffi::OsStr::new).collect();
    args.extend([
        "--threads".as_ref(),
        "1".as_ref(),
        "--out".as_ref(),
        out.as_os_str(),
    ]);
    let o = with_reader_gone(&args);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(141), "{stderr}");
    assert_eq!(stderr, "");
    assert!(
        out.join("trials.csv").is_file(),
        "the files are written before the summary"
    );
}

/// `--threads 0` is a one-line error on every command that simulates one trial.
#[test]
fn zero_threads_is_a_one_line_error() {
    let tmp = tempfile::tempdir().unwrap();
    let page = tmp.path().join("r.html");
    let svg = tmp.path().join("r.svg");
    for args in [
        vec!["run", PAPER, "--duration", "1", "--threads", "0"],
        vec!["replay", PAPER, "--duration", "1", "--threads", "0"],
        vec![
            "render",
            PAPER,
            "--trace",
            "--duration",
            "1",
            "--threads",
            "0",
        ],
    ] {
        let mut args: Vec<&str> = args;
        match args[0] {
            "replay" => args.extend(["--out", page.to_str().unwrap()]),
            "render" => args.extend(["--out", svg.to_str().unwrap()]),
            _ => {}
        }
        let o = usar(&args);
        assert!(!o.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(
            err.trim_end(),
            "error: --threads must be at least 1",
            "{args:?}"
        );
    }
}

/// A team above the parallel threshold (`swarm-1000.ron`, 1,000 robots) writes the same
/// result, byte for byte, on one and on two threads.
#[test]
fn a_large_team_runs_the_same_on_one_and_two_threads() {
    let swarm = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/swarm-1000.ron"
    );
    let tmp = tempfile::tempdir().unwrap();
    let json = |threads: &str| {
        let path = tmp.path().join(format!("t{threads}.json"));
        let o = usar([
            "run",
            swarm,
            "--method",
            "dis",
            "--duration",
            "6",
            "--threads",
            threads,
            "--json",
            path.to_str().unwrap(),
        ]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        std::fs::read(&path).unwrap()
    };
    assert!(
        json("1") == json("2"),
        "1 and 2 threads wrote different results"
    );
}

#[test]
fn rounds_csv_of_run_and_sweep_has_a_row_per_round_and_task_and_a_summary() {
    let tmp = tempfile::tempdir().unwrap();
    let csv = tmp.path().join("rounds.csv");
    let json = tmp.path().join("t.json");
    let o = usar([
        "run",
        PAPER,
        "--method",
        "rne",
        "--duration",
        "200",
        "--json",
        json.to_str().unwrap(),
        "--rounds-csv",
        csv.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("per-round yields"), "{out}");
    let r: usar_sim::mission::TrialResult =
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap();
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[0], "cell");
    assert_eq!(*header.last().unwrap(), "wait_s");
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert!(r.rounds.len() >= 2, "a 200 s trial has rounds");
    assert_eq!(rows.len(), r.rounds.len() * r.tasks.len());
    let col = |name: &str| header.iter().position(|h| *h == name).unwrap();
    for (i, row) in rows.iter().enumerate() {
        let (round, t) = (&r.rounds[i / 2], i % 2);
        assert_eq!(row[col("task")], r.tasks[t]);
        assert_eq!(row[col("rescued")], round.rescued[t].to_string());
        assert_eq!(row[col("deliveries")], round.deliveries[t].to_string());
    }

    let swept = tmp.path().join("swept.csv");
    let o = usar([
        "sweep",
        PAPER,
        "--methods",
        "rne,dis",
        "--trials",
        "2",
        "--duration",
        "60",
        "--quiet",
        "--out",
        tmp.path().join("s").to_str().unwrap(),
        "--rounds-csv",
        swept.to_str().unwrap(),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let text = std::fs::read_to_string(&swept).unwrap();
    for (method, trial) in [("RNE", 0), ("RNE", 1), ("DIS", 0), ("DIS", 1)] {
        let prefix = format!("0,{method},{trial},");
        assert!(
            text.lines().any(|l| l.starts_with(&prefix)),
            "{prefix} missing in\n{text}"
        );
    }
}
