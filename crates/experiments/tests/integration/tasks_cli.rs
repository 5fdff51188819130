//! Tasks as data through the command line: scenarios with K = 1, 2, 3 and 4 tasks go through
//! `usar check`, `run`, `sweep` and `render`, and every output names each task; a sweep's
//! per-task counts equal those of `usar run` for the same trial.

use crate::common;

use std::process::Output;

use usar_sim::mission::TrialResult;

use common::read_text;

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// (scenario file under the workspace root, its task names in file order).
const SCENARIOS: &[(&str, &[&str])] = &[
    ("tests/data/one-task.ron", &["rubble"]),
    ("scenarios/paper.ron", &["hard", "easy"]),
    ("scenarios/three-tasks.ron", &["hard", "medium", "easy"]),
    (
        "tests/data/four-tasks.ron",
        &["hard", "medium", "easy", "far"],
    ),
];

/// `usar ARGS`, which must succeed.
fn usar(args: &[&str]) -> Output {
    let o = common::usar(args);
    assert!(
        o.status.success(),
        "usar {}: {}",
        args.join(" "),
        String::from_utf8_lossy(&o.stderr)
    );
    o
}

/// The `rescued_<task>` values of `method`'s trial 0 in a trials.csv text.
fn sweep_counts(trials_csv: &str, method: &str, tasks: &[&str]) -> Vec<u32> {
    let mut lines = trials_csv.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let row: Vec<&str> = lines
        .map(|l| l.split(',').collect::<Vec<_>>())
        .find(|r| r[1] == method && r[2] == "0")
        .unwrap_or_else(|| panic!("no {method} trial 0 in trials.csv"));
    tasks
        .iter()
        .map(|t| {
            let col = header
                .iter()
                .position(|h| *h == format!("rescued_{t}"))
                .unwrap_or_else(|| panic!("no column rescued_{t}"));
            row[col].parse().unwrap()
        })
        .collect()
}

fn end_to_end(file: &str, tasks: &[&str]) {
    let path = format!("{ROOT}/{file}");
    let tmp = tempfile::tempdir().unwrap();

    let check = String::from_utf8(usar(&["check", &path]).stdout).unwrap();
    for (i, t) in tasks.iter().enumerate() {
        assert!(
            check.contains(&format!("task {t} (")),
            "check lists task {i} {t}:\n{check}"
        );
    }

    let json = tmp.path().join("run.json");
    let run = usar(&[
        "run",
        &path,
        "--method",
        "rne",
        "--duration",
        "60",
        "--json",
        json.to_str().unwrap(),
    ]);
    let run_out = String::from_utf8(run.stdout).unwrap();
    let r: TrialResult = serde_json::from_str(&read_text(&json)).unwrap();
    assert_eq!(r.tasks, tasks);
    assert_eq!(r.rescued.len(), tasks.len());
    for t in tasks {
        assert!(
            run_out.lines().any(|l| l.starts_with(t)),
            "run prints a row for {t}:\n{run_out}"
        );
    }

    let out = tmp.path().join("sweep");
    usar(&[
        "sweep",
        &path,
        "--methods",
        "rne,dis",
        "--trials",
        "2",
        "--duration",
        "60",
        "--quiet",
        "--out",
        out.to_str().unwrap(),
    ]);
    let trials = read_text(&out.join("trials.csv"));
    assert_eq!(sweep_counts(&trials, "RNE", tasks), r.rescued);
    let long = read_text(&out.join("trials_long.csv"));
    let summary = read_text(&out.join("summary.csv"));
    let report = read_text(&out.join("report.md"));
    for t in tasks {
        // 2 methods x 2 trials x (rescued, energy, hp, and the two costs per rescuee).
        let rows = long
            .lines()
            .filter(|l| l.split(',').nth(4) == Some(t))
            .count();
        assert_eq!(rows, 2 * 2 * 5, "trials_long.csv rows of task {t}");
        assert!(
            summary.contains(&format!("RNE,rescued_{t},2,")),
            "{summary}"
        );
        assert!(report.contains(&format!("rescued_{t}")) || report.contains(t));
    }
    // Every metric is a count, a cost or a time: no confidence interval goes below 0, although
    // two 60 s trials give wide ones (a regression: `rescued_easy 0.500 [-5.85, 6.85]`).
    let lows: Vec<f64> = report
        .lines()
        .filter(|l| l.starts_with("| "))
        .flat_map(|l| l.split(" [").skip(1))
        .map(|c| c.split(',').next().unwrap().parse().unwrap())
        .collect();
    assert!(!lows.is_empty(), "report.md has intervals:\n{report}");
    assert!(lows.iter().all(|&x| x >= 0.0), "{lows:?}\n{report}");
    for row in summary.lines().skip(1) {
        let low = row.split(',').nth(6).unwrap();
        assert!(
            low.is_empty() || low.parse::<f64>().unwrap() >= 0.0,
            "{row}"
        );
    }
    // Without --targets only a scenario whose `report` section names targets (paper.ron)
    // compares with them (it marked nine n/a values **out** for a scenario without tasks named
    // easy and hard; see report_sections.rs).
    let asks = usar_sim::scenario::load(&path)
        .expect("valid")
        .report()
        .targets
        .is_some();
    assert_eq!(report.contains("Pooled statistics"), asks, "{report}");
    assert!(!report.contains("n/a **out**"), "{report}");
    let fig = read_text(&out.join("fig3a_rescuees.svg"));
    for t in tasks {
        assert!(fig.contains(t), "fig3a names task {t}");
    }

    let svg = tmp.path().join("trace.svg");
    usar(&[
        "render",
        &path,
        "--out",
        svg.to_str().unwrap(),
        "--trace",
        "--duration",
        "20",
    ]);
    let svg = read_text(&svg);
    for t in tasks {
        assert!(
            svg.contains(&format!("{t} search area")),
            "render labels task {t}"
        );
    }
}

#[test]
fn one_task_end_to_end() {
    let (file, tasks) = SCENARIOS[0];
    end_to_end(file, tasks);
}

#[test]
fn two_tasks_end_to_end() {
    let (file, tasks) = SCENARIOS[1];
    end_to_end(file, tasks);
}

#[test]
fn three_tasks_end_to_end() {
    let (file, tasks) = SCENARIOS[2];
    end_to_end(file, tasks);
}

#[test]
fn four_tasks_end_to_end() {
    let (file, tasks) = SCENARIOS[3];
    end_to_end(file, tasks);
}

/// A grid over a scenario without tasks named `easy` and `hard`: `grid.md` has no
/// calibration table (it showed a row of `n/a !`, marking every undefined value as outside
/// its band; targets are compared only with `--targets`, see `report_sections.rs`).
#[test]
fn a_grid_without_easy_and_hard_has_no_pooled_table() {
    let path = format!("{ROOT}/tests/data/one-task.ron");
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g");
    usar(&[
        "sweep",
        &path,
        "--methods",
        "rne,dis",
        "--trials",
        "1",
        "--duration",
        "4",
        "--quiet",
        "--threads",
        "1",
        "--vary",
        "mission.pickup_s=0,1",
        "--out",
        out.to_str().unwrap(),
    ]);
    let md = read_text(&out.join("grid.md"));
    assert!(!md.contains("## Pooled statistics"), "{md}");
    assert!(!md.contains("n/a !"), "{md}");
}
