//! `usar check`: a summary of a valid scenario; the loader's error and a non-zero exit status
//! for an invalid one.

use crate::common;

use std::process::Command;

use common::{PAPER, usar};

/// A scenario whose hard task's goal and drop-off no robot can reach: every command warns.
const SPLIT_ARENA: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../usar-sim/tests/data/split-arena.ron"
);

/// `check` and a 1 s `run` of [`SPLIT_ARENA`]: each prints the two reachability warnings.
fn warning_commands() -> [Vec<&'static str>; 2] {
    [
        vec!["check", SPLIT_ARENA],
        vec!["run", SPLIT_ARENA, "--method", "dis", "--duration", "1"],
    ]
}

#[test]
fn check_summarises_the_paper_scenario() {
    let o = usar(["check", PAPER]);
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
    // Every goal of the paper's scenario is reachable: no warning.
    assert_eq!(String::from_utf8_lossy(&o.stderr), "");
}

#[test]
fn a_large_team_is_summarised_per_kind_and_listed_with_robots() {
    let swarm = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../scenarios/swarm-1000.ron"
    );
    let o = usar(["check", swarm]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(out.contains("starts by kind (1000 robots"), "{out}");
    // A few lines per kind, not a thousand robot rows before the verdict.
    assert!(
        out.lines().count() < 80,
        "{} lines:\n{out}",
        out.lines().count()
    );
    let carriers = out
        .lines()
        .skip_while(|l| !l.starts_with("starts by kind"))
        .find(|l| l.starts_with("carrier "))
        .expect("a carrier row under the starts by kind");
    assert_eq!(
        carriers.split_whitespace().nth(1),
        Some("500"),
        "{carriers}"
    );
    assert!(carriers.contains(".."), "ranges in {carriers}");
    let o = usar(["check", swarm, "--robots"]);
    let listed = String::from_utf8_lossy(&o.stdout);
    assert!(listed.lines().count() > 1000 && !listed.contains("starts by kind"));
    // The paper's 12 robots keep their table.
    let paper = String::from_utf8_lossy(&usar(["check", PAPER]).stdout).to_string();
    assert!(
        paper.contains(" 11 observer") && !paper.contains("starts by kind"),
        "{paper}"
    );
}

#[test]
fn check_gives_the_control_period_where_the_scenario_has_one() {
    let second_line = |args: &[&str]| {
        let o = usar(args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout)
            .unwrap()
            .lines()
            .nth(1)
            .unwrap()
            .to_string()
    };
    let line = second_line(&[
        "check",
        PAPER,
        "--set",
        "sim.control_period_s=Some(0.1)",
        "--set",
        "sim.physics=EveryStep",
    ]);
    assert!(
        line.ends_with("; robots decide every 0.1 s (5 steps)"),
        "{line}"
    );
    // paper.ron steps Rapier near contacts only, and says so.
    let line = second_line(&["check", PAPER]);
    assert!(!line.contains("decide"), "{line}");
    assert!(
        line.ends_with("; Rapier steps near contacts only"),
        "{line}"
    );
}

#[test]
fn check_gives_the_trial_length_a_trial_runs() {
    let summary = |duration: &str| {
        let o = usar(["check", PAPER, "--set", duration]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let out = String::from_utf8(o.stdout).unwrap();
        out.lines().nth(1).unwrap().to_string()
    };
    let line = summary("mission.duration_s=0.03");
    assert!(
        line.contains(
            "trial 0.04 s (2 steps; mission.duration_s 0.03 s rounded up to whole steps)"
        ),
        "{line}"
    );
    let line = summary("mission.duration_s=0.04");
    assert!(line.contains("trial 0.04 s (2 steps), seed"), "{line}");
}

#[test]
fn check_and_run_warn_about_goals_no_path_reaches() {
    let split = SPLIT_ARENA;
    for args in warning_commands() {
        let o = usar(&args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{args:?}: {err}");
        let lines: Vec<&str> = err.lines().collect();
        assert_eq!(lines.len(), 2, "{args:?}: {err}");
        for (line, field) in lines
            .iter()
            .zip(["tasks.hard.goal_m", "tasks.hard.drop_off"])
        {
            let head = format!("warning: {split}: {field} (");
            assert!(line.starts_with(&head), "{line}");
            assert!(
                line.contains("no path from the start of 2 robot(s) (id 0, 1)"),
                "{line}"
            );
        }
    }
    // A grid warns once per goal, naming the cells.
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g");
    let o = usar([
        "sweep",
        split,
        "--methods",
        "dis",
        "--trials",
        "1",
        "--duration",
        "1",
        "--quiet",
        "--vary",
        "mission.recharge_s=10,20",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 2, "{err}");
    let head = format!("warning: {split} (every cell): tasks.hard.goal_m");
    assert!(lines[0].starts_with(&head), "{err}");
}

#[test]
fn check_reports_the_loader_error_with_its_position() {
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad.ron");
    let text = std::fs::read_to_string(PAPER).unwrap();
    // An unknown field: ron reports it with line and column.
    let broken = text.replacen("name:", "nmae:", 1);
    std::fs::write(&bad, broken).unwrap();
    let o = usar(["check", bad.to_str().unwrap()]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    let prefix = format!("error: {}:", bad.display());
    assert!(err.starts_with(&prefix), "{err}");
    // file:line:col
    let rest = &err[prefix.len()..];
    let mut parts = rest.splitn(3, ':');
    assert!(parts.next().unwrap().parse::<usize>().is_ok(), "{err}");
    assert!(parts.next().unwrap().parse::<usize>().is_ok(), "{err}");

    let o = usar(["check", "/nonexistent/x.ron"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("/nonexistent/x.ron"));
}

#[test]
fn every_subcommand_help_has_examples() {
    for sub in ["check", "run", "sweep"] {
        let o = usar([sub, "--help"]);
        assert!(o.status.success());
        assert!(
            String::from_utf8_lossy(&o.stdout).contains("Examples:"),
            "{sub}"
        );
    }
    let o = usar(["--help"]);
    assert!(String::from_utf8_lossy(&o.stdout).contains("usar sweep scenarios/paper.ron"));
}

#[test]
fn check_set_print_and_hash_reproduce_an_overridden_scenario() {
    let tmp = tempfile::tempdir().unwrap();
    let set = [
        "--set",
        "mission.hp_pct_per_step_in_radiation=0.003",
        "--set",
        "kinds[0].starts.first_m=(31.5, 3.0)",
    ];
    let o = usar([&["check", PAPER][..], &set, &["--print"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed = String::from_utf8(o.stdout).unwrap();
    assert!(
        printed.contains("hp_pct_per_step_in_radiation: 0.003,"),
        "{printed}"
    );
    assert!(printed.contains("first_m: (31.5, 3.0)"), "{printed}");
    let file = tmp.path().join("hot.ron");
    std::fs::write(&file, &printed).unwrap();
    let file = file.to_str().unwrap();

    // The printed file validates to the same scenario: same hash as the overrides give.
    let hash_of = |args: &[&str]| {
        let o = usar(args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap().trim().to_string()
    };
    let h = hash_of(&[&["check", PAPER][..], &set, &["--hash"]].concat());
    assert_eq!(h.len(), 16, "{h}");
    assert_eq!(hash_of(&["check", file, "--hash"]), h);
    assert_ne!(hash_of(&["check", PAPER, "--hash"]), h);
    // The summary shows it too.
    let o = usar(["check", file]);
    assert!(String::from_utf8_lossy(&o.stdout).contains(&format!("scenario hash {h}")));
}

#[test]
fn check_set_errors_name_the_override() {
    for (set, want) in [
        (
            "mission.duration_s=-5",
            "error: --set mission.duration_s=-5: mission.duration_s: expected a finite number > \
             0, found -5\n",
        ),
        (
            "kinds[9].count=1",
            "error: --set kinds[9].count=1: no element [9] in kinds: it has 3 (indices 0 to 2)\n",
        ),
        (
            "collision.enabled=maybe",
            "error: --set collision.enabled=maybe: collision.enabled: expected true or false, \
             found maybe\n",
        ),
    ] {
        let o = usar(["check", PAPER, "--set", set]);
        assert!(!o.status.success(), "{set}");
        assert_eq!(String::from_utf8_lossy(&o.stderr), want);
        assert!(o.stdout.is_empty());
    }
}

#[test]
fn an_error_with_stderr_closed_still_exits_with_status_1() {
    use std::process::Stdio;
    let mut child = Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["check", "no-such-scenario.ron"])
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run usar");
    // Close both read ends before usar writes: its error message meets a closed pipe.
    drop(child.stdout.take());
    drop(child.stderr.take());
    let status = child.wait().expect("wait for usar");
    assert_eq!(status.code(), Some(1), "{status:?}");
}

#[test]
fn warnings_meeting_a_closed_stderr_leave_the_exit_status_0() {
    use std::process::Stdio;
    for args in warning_commands() {
        let mut child = Command::new(env!("CARGO_BIN_EXE_usar"))
            .args(&args)
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("run usar");
        // The reader goes before usar warns: its warnings meet a closed pipe (EPIPE).
        drop(child.stderr.take());
        let status = child.wait().expect("wait for usar");
        assert_eq!(status.code(), Some(0), "{args:?}: {status:?}");
    }
}

#[test]
fn check_warns_about_tasks_no_group_can_rescue_from() {
    let o = usar([
        "check",
        PAPER,
        "--set",
        "kinds[0].locomotion=Aerial",
        "--set",
        "kinds[1].carrying_capacity=0",
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 2, "{err}");
    for (line, task) in lines.iter().zip(["hard", "easy"]) {
        let head =
            format!("warning: {PAPER}: tasks.{task}: no ground robot with carrying_capacity > 0");
        assert!(line.starts_with(&head), "{line}");
    }
    // The shipped scenario itself gets no warning.
    let o = usar(["check", PAPER]);
    assert!(o.status.success() && o.stderr.is_empty());
}

#[cfg(unix)]
#[test]
fn check_refuses_an_endless_device_as_no_regular_file() {
    let o = usar(["check", "/dev/zero"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(
        err,
        "error: /dev/zero: cannot read scenario file: not a regular file (a folder, FIFO or device)\n"
    );
}

#[test]
fn set_repairs_a_rule_the_file_breaks_and_the_files_own_error_keeps_its_position() {
    let dir = tempfile::tempdir().expect("temp dir");
    let src = std::fs::read_to_string(PAPER).expect("paper.ron");
    let broken = src.replacen("max_speed_m_per_s: 4.0", "max_speed_m_per_s: 1000.0", 1);
    assert_ne!(src, broken, "paper.ron's speed line moved");
    let path = dir.path().join("fast.ron");
    std::fs::write(&path, broken).expect("write");
    let file = path.to_str().expect("utf-8 path");
    // The speed's line in paper.ron, 1-based.
    let speed_line = 1 + std::fs::read_to_string(&path)
        .unwrap()
        .lines()
        .position(|l| l.contains("max_speed_m_per_s: 1000.0"))
        .unwrap();
    let own = format!(
        "error: {file}:{speed_line}:13: kinds[0].max_speed_m_per_s: 1000 m/s is faster than the \
         limit of 100 m/s"
    );
    // The file alone, and with an override of another field: the file's own error, positioned.
    for set in [&[][..], &["--set", "mission.duration_s=30.0"]] {
        let o = usar([&["check", file][..], set].concat());
        assert_eq!(o.status.code(), Some(1));
        assert_eq!(String::from_utf8_lossy(&o.stderr).trim_end(), own);
    }
    // "Set a field before validating": the override repairs the rule.
    let o = usar(["check", file, "--set", "kinds[0].max_speed_m_per_s=2.5"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    // A second rule the file breaks, found once the override repairs the first: at its line
    // and column, with the override it was found with.
    let both = std::fs::read_to_string(&path).unwrap().replacen(
        "waypoint_tolerance_m: 0.3",
        "waypoint_tolerance_m: 100.0",
        1,
    );
    // Its line in paper.ron, 1-based.
    let line = 1 + both
        .lines()
        .position(|l| l.contains("waypoint_tolerance_m: 100.0"))
        .unwrap();
    std::fs::write(&path, both).expect("write");
    let o = usar(["check", file, "--set", "kinds[0].max_speed_m_per_s=2.5"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.starts_with(&format!("error: {file}:{line}:"))
            && err
                .contains(": navigation.waypoint_tolerance_m: 100 m is more than the limit of 5 m")
            && err
                .trim_end()
                .ends_with("(with --set kinds[0].max_speed_m_per_s=2.5)"),
        "{err}"
    );
    // An override that breaks the rule otherwise is named.
    let o = usar(["check", file, "--set", "kinds[0].max_speed_m_per_s=500.0"]);
    assert_eq!(
        String::from_utf8_lossy(&o.stderr).trim_end(),
        "error: --set kinds[0].max_speed_m_per_s=500.0: kinds[0].max_speed_m_per_s: 500 m/s is \
         faster than the limit of 100 m/s"
    );
}

#[test]
fn a_rejected_long_set_value_is_quoted_by_its_start() {
    let stations: Vec<String> = (0..257)
        .map(|i| format!("(center_m: ({}.0, 4.0), radius_m: 1.0)", 1 + i % 70))
        .collect();
    let set = format!("rest_station=[{}]", stations.join(", "));
    let o = usar(["check", PAPER, "--set", &set]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    let n = set.chars().count();
    assert!(
        err.trim_end().ends_with(&format!(
            "... ({n} characters): rest_station: 257 rest stations, more than the limit of 256"
        )),
        "{err}"
    );
    assert!(err.len() < 200, "{} bytes: {err}", err.len());
}

#[test]
fn an_index_reaches_a_single_rest_station_as_element_0() {
    let hash_line = |set: &str| {
        let o = usar(["check", PAPER, "--set", set]);
        assert!(
            o.status.success(),
            "{set}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let out = String::from_utf8(o.stdout).unwrap();
        let line = out.lines().find(|l| l.starts_with("scenario hash"));
        line.expect("a scenario hash line").to_string()
    };
    let single = hash_line("rest_station.radius_m=3");
    assert_eq!(hash_line("rest_station[0].radius_m=3"), single);
    assert_eq!(hash_line("rest_station[*].radius_m=3"), single);
    assert_ne!(hash_line("rest_station.radius_m=2.5"), single);
    let o = usar(["check", PAPER, "--set", "rest_station[1].radius_m=3"]);
    assert!(!o.status.success());
    assert!(
        String::from_utf8_lossy(&o.stderr).contains("no element [1] in rest_station: it has 1"),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
}

/// The line every subcommand that reads a scenario prints for `bad` and the folder `dir`
/// (outputs go there), by subcommand.
fn load_errors(bad: &std::path::Path, dir: &std::path::Path) -> Vec<(&'static str, String)> {
    let (file, out) = (bad.to_str().unwrap(), dir.join("out"));
    let out = out.to_str().unwrap();
    let runs: [(&str, Vec<&str>); 6] = [
        ("check", vec!["check", file]),
        ("run", vec!["run", file]),
        ("sweep", vec!["sweep", file, "--trials", "1", "--out", out]),
        ("render", vec!["render", file, "--out", out]),
        ("replay", vec!["replay", file, "--out", out]),
        (
            "slurm",
            vec![
                "slurm", file, "--trials", "1", "--shards", "1", "--out", out,
            ],
        ),
    ];
    runs.into_iter()
        .map(|(name, args)| {
            let o = usar(&args);
            assert!(!o.status.success(), "{name}");
            (name, String::from_utf8_lossy(&o.stderr).into_owned())
        })
        .collect()
}

#[test]
fn every_subcommand_prints_a_load_error_as_the_loader_writes_it() {
    let tmp = tempfile::tempdir().unwrap();
    let bad = tmp.path().join("bad.ron");
    let text = std::fs::read_to_string(PAPER).unwrap();
    std::fs::write(
        &bad,
        text.replacen("duration_s: 600.0", "duration_s: -1.0", 1),
    )
    .unwrap();
    let line = text
        .lines()
        .position(|l| l.contains("duration_s: 600.0"))
        .unwrap()
        + 1;
    let col = text.lines().nth(line - 1).unwrap().find("600.0").unwrap() + 1;
    let want = format!(
        "error: {}:{line}:{col}: mission.duration_s: expected a finite number > 0, found -1\n",
        bad.display()
    );
    for (name, err) in load_errors(&bad, tmp.path()) {
        assert_eq!(err, want, "usar {name}");
    }
    let missing = tmp.path().join("missing.ron");
    let want = format!(
        "error: {}: cannot read scenario file: No such file or directory (os error 2)\n",
        missing.display()
    );
    for (name, err) in load_errors(&missing, tmp.path()) {
        assert_eq!(err, want, "usar {name}");
    }
}

/// The stderr of `usar ARGS`, which must fail.
fn failure(args: &[&str]) -> String {
    let o = usar(args);
    assert!(!o.status.success(), "{args:?}");
    String::from_utf8_lossy(&o.stderr).into_owned()
}

#[test]
fn a_line_break_in_a_path_is_escaped_in_every_message() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().display().to_string();
    let text = std::fs::read_to_string(PAPER).unwrap();
    let bad = tmp.path().join("a\nb.ron");
    std::fs::write(
        &bad,
        text.replacen("duration_s: 600.0", "duration_s: -1.0", 1),
    )
    .unwrap();
    let file = bad.to_str().unwrap();
    let svg = tmp.path().join("x.svg");
    for args in [
        vec!["check", file],
        vec!["run", file],
        vec!["render", file, "--out", svg.to_str().unwrap()],
    ] {
        let err = failure(&args);
        let head = format!("error: {dir}/a\\nb.ron:");
        assert!(err.starts_with(&head), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
    let err = failure(&["check", &format!("{dir}/no\nsuch.ron")]);
    assert_eq!(
        err,
        format!(
            "error: {dir}/no\\nsuch.ron: cannot read scenario file: No such file or directory \
             (os error 2)\n"
        )
    );
    // Outputs: a folder that is a file, a file in it.
    let taken = tmp.path().join("o\nut");
    std::fs::write(&taken, "").unwrap();
    let taken = taken.to_str().unwrap();
    let json = format!("{taken}/x.json");
    for args in [
        vec![
            "sweep",
            PAPER,
            "--trials",
            "1",
            "--duration",
            "1",
            "--out",
            taken,
        ],
        vec!["run", PAPER, "--duration", "1", "--json", &json],
    ] {
        let err = failure(&args);
        assert!(err.contains(&format!("{dir}/o\\nut")), "{args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
    }
    // Warnings name the scenario on one line too.
    let split = tmp.path().join("split\narena.ron");
    std::fs::copy(SPLIT_ARENA, &split).unwrap();
    let o = usar(["check", split.to_str().unwrap()]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(o.status.success(), "{err}");
    let head = format!("warning: {dir}/split\\narena.ron: tasks.hard.");
    assert_eq!(err.lines().count(), 2, "{err}");
    assert!(err.lines().all(|l| l.starts_with(&head)), "{err}");
}

#[test]
fn check_print_shows_the_authors_clock_switches_and_their_defaults_keep_the_hash() {
    let set = [
        "--set",
        "mission.round_clock=Timer(length_s: 90.0)",
        "--set",
        "mission.cost_clock=Frames(steps_per_s: 120.0)",
        "--set",
        "mission.rest_timing=InSlack",
        "--set",
        "mission.costs_count=Every",
    ];
    let o = usar([&["check", PAPER][..], &set, &["--print"]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let printed = String::from_utf8(o.stdout).unwrap();
    for want in [
        "round_clock: Timer(",
        "length_s: 90.0",
        "rest_timing: InSlack,",
        "cost_clock: Frames(",
        "steps_per_s: 120.0",
        "costs_count: Every,",
    ] {
        assert!(printed.contains(want), "{want} in {printed}");
    }
    // A scenario that does not use them keeps its hash when they are written out at their
    // defaults (`usar_sim::scenario::ADDED_FIELDS`).
    let v1 = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper-v1.ron");
    let hash_of = |args: &[&str]| {
        let o = usar(args);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        String::from_utf8(o.stdout).unwrap().trim().to_string()
    };
    let defaults = [
        "--set",
        "mission.round_clock=AllBack",
        "--set",
        "mission.cost_clock=PaperStep",
        "--set",
        "mission.rest_timing=OutOfRound",
        "--set",
        "mission.costs_count=InGroup",
    ];
    let plain = hash_of(&["check", v1, "--hash"]);
    assert_eq!(
        hash_of(&[&["check", v1][..], &defaults, &["--hash"]].concat()),
        plain
    );
    assert_ne!(
        hash_of(&[&["check", v1][..], &set, &["--hash"]].concat()),
        plain
    );
}
