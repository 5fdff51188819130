//! `usar sweep --vary`: a grid killed part-way and resumed writes the same files as an
//! uninterrupted one, 1 and 2 threads write the same files, running the same command twice
//! reuses the journal, and a failing trial of one cell stops nothing else.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::{PAPER, STOPPED, journal_trials, ok, read};

const VARY: [&str; 4] = [
    "--vary",
    "mission.hp_pct_per_step_in_radiation=0.0003,0.003",
    "--vary",
    "kinds[0].max_speed_m_per_s=1.0,2.0",
];
const CELLS: [&str; 4] = [
    "c00_hp_pct_per_step_in_radiation=0.0003_max_speed_m_per_s=1.0",
    "c01_hp_pct_per_step_in_radiation=0.0003_max_speed_m_per_s=2.0",
    "c02_hp_pct_per_step_in_radiation=0.003_max_speed_m_per_s=1.0",
    "c03_hp_pct_per_step_in_radiation=0.003_max_speed_m_per_s=2.0",
];

/// The 2 x 2 grid of paper.ron, rne,dis x 2 trials x 8 s, into `out`, then `extra`.
fn grid(out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", "2"])
        .args(["--duration", "8", "--quiet"])
        .args(VARY)
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .expect("run usar")
}

/// The files that must not depend on threads or interruptions.
fn assert_same_outputs(a: &Path, b: &Path) {
    for name in ["grid.csv", "grid.md", "grid_rescued_total.svg"] {
        assert!(read(&a.join(name)) == read(&b.join(name)), "{name} differs");
    }
    for cell in CELLS {
        for name in ["trials.csv", "summary.csv", "scenario.ron"] {
            let (x, y) = (a.join(cell).join(name), b.join(cell).join(name));
            assert!(read(&x) == read(&y), "{cell}/{name} differs");
        }
    }
}

#[test]
fn a_killed_grid_resumes_to_the_same_files() {
    let tmp = tempfile::tempdir().unwrap();
    let (whole, parts) = (tmp.path().join("whole"), tmp.path().join("parts"));
    ok(&grid(&whole, &["--threads", "2"]));
    assert_eq!(journal_trials(&whole), 16);

    let o = grid(&parts, &["--threads", "2", "--stop-after", "5"]);
    assert_eq!(
        o.status.code(),
        Some(STOPPED),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    assert_eq!(journal_trials(&parts), 5);
    assert!(!parts.join("grid.csv").exists());

    let out = ok(&grid(&parts, &["--threads", "1", "--resume"]));
    assert!(out.contains("ran 11 trials"), "{out}");
    assert_eq!(journal_trials(&parts), 16);
    assert_same_outputs(&whole, &parts);
}

#[test]
fn one_and_two_threads_write_the_same_grid() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("t1"), tmp.path().join("t2"));
    ok(&grid(&a, &["--threads", "1"]));
    ok(&grid(&b, &["--threads", "2"]));
    assert_same_outputs(&a, &b);
    // Common random numbers: trial k has the same seed in every cell.
    let seeds = |cell: &str| -> Vec<String> {
        String::from_utf8(read(&a.join(cell).join("trials.csv")))
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').nth(3).unwrap().to_string())
            .collect()
    };
    assert_eq!(seeds(CELLS[0]), seeds(CELLS[3]));
    // ... and the cells do run different scenarios (carriers at 1 or 2 m/s; 8 s are too short
    // for the HP rate to show).
    let trials = |cell: &str| read(&a.join(cell).join("trials.csv"));
    assert!(trials(CELLS[0]) != trials(CELLS[1]));
}

#[test]
fn the_same_command_twice_reuses_the_journal() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("g");
    ok(&grid(&dir, &[]));
    let first = read(&dir.join("grid.csv"));
    let out = ok(&grid(&dir, &[]));
    assert!(out.contains("holds this very sweep"), "{out}");
    assert!(out.contains("all 16 trials came from the journal"), "{out}");
    assert!(read(&dir.join("grid.csv")) == first);
    assert_eq!(journal_trials(&dir), 16);

    // An interrupted run is continued by the same command, without --resume.
    let part = tmp.path().join("p");
    let o = grid(&part, &["--stop-after", "3"]);
    assert_eq!(o.status.code(), Some(STOPPED));
    let out = ok(&grid(&part, &[]));
    assert!(
        out.contains("holds this very sweep") && out.contains("ran 13 trials"),
        "{out}"
    );
    assert!(read(&part.join("grid.csv")) == first);

    // Other parameters are refused, naming the ways out; the journal is left alone.
    let o = grid(&dir, &["--vary", "sim.dt_s=0.02,0.025"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    for needle in ["--resume", "--overwrite", "--out", "varied fields"] {
        assert!(err.contains(needle), "{needle}: {err}");
    }
    assert_eq!(journal_trials(&dir), 16);
}

#[test]
fn a_failing_trial_stops_nothing_else_in_the_grid() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("f");
    let o = grid(&dir, &["--fail-trial", "dis:1"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("4 of 16 trials failed"), "{err}");
    assert!(
        err.contains(&format!("DIS trial 1 in cell {}", CELLS[2])),
        "{err}"
    );
    for cell in CELLS {
        let trials = String::from_utf8(read(&dir.join(cell).join("trials.csv"))).unwrap();
        assert_eq!(trials.lines().count(), 1 + 3, "{cell}: {trials}");
    }
    let md = String::from_utf8(read(&dir.join("grid.md"))).unwrap();
    assert!(md.contains("## Failed trials") && md.contains("Trials finished: 12 of 16"));
    // --resume reruns only the failed ones.
    let out = ok(&grid(&dir, &["--resume"]));
    assert!(out.contains("ran 4 trials"), "{out}");
}

#[test]
fn overwrite_leaves_nothing_of_the_earlier_grid() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("o");
    ok(&grid(&dir, &[]));
    std::fs::write(dir.join(CELLS[1]).join("notes.txt"), "mine").unwrap();
    // The same folder, no grid, --overwrite: the grid's files and cells go, other files stay.
    let o = Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "dis", "--trials", "1"])
        .args(["--duration", "4", "--quiet", "--overwrite", "--out"])
        .arg(&dir)
        .output()
        .expect("run usar");
    ok(&o);
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let expected = [
        CELLS[1],
        "fig3a_rescuees.svg",
        "fig3b_energy_per_rescuee.svg",
        "fig3c_hp_per_rescuee.svg",
        "journal.jsonl",
        "report.md",
        "summary.csv",
        "sweep.lock",
        "trials.csv",
        "trials_long.csv",
        "usar-owner.json",
    ];
    assert_eq!(names, expected);
    // The folder is the sweep's now.
    let owner = std::fs::read_to_string(dir.join("usar-owner.json")).unwrap();
    assert!(owner.contains("\"kind\":\"sweep\""), "{owner}");
    let kept: Vec<_> = std::fs::read_dir(dir.join(CELLS[1])).unwrap().collect();
    assert_eq!(kept.len(), 1, "only notes.txt stays in its cell");
    assert_eq!(journal_trials(&dir), 1);
}
