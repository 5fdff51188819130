//! `usar sweep`: 1 and 2 threads write byte-identical trials.csv and summary.csv; a thread
//! count past the cap is capped with a warning.

use crate::common;

use std::path::Path;
use std::process::Command;

use common::PAPER;

fn sweep(out: &Path, threads: &str) {
    let o = Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "eng,hp_dis", "--trials", "2"])
        .args([
            "--duration",
            "60",
            "--seed",
            "5",
            "--quiet",
            "--threads",
            threads,
        ])
        .arg("--out")
        .arg(out)
        .output()
        .expect("run usar");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

#[test]
fn one_and_two_threads_write_the_same_files() {
    let tmp = tempfile::tempdir().unwrap();
    let (a, b) = (tmp.path().join("t1"), tmp.path().join("t2"));
    sweep(&a, "1");
    sweep(&b, "2");
    for name in ["trials.csv", "summary.csv"] {
        let (x, y) = (
            std::fs::read(a.join(name)).unwrap(),
            std::fs::read(b.join(name)).unwrap(),
        );
        assert!(x == y, "{name} differs between 1 and 2 threads");
    }
    let trials = std::fs::read_to_string(a.join("trials.csv")).unwrap();
    assert_eq!(trials.lines().count(), 5);
    // --seed 5 is the base seed: trial k's seed is trial_seed(5, k).
    let seeds: Vec<u64> = trials
        .lines()
        .skip(1)
        .map(|l| l.split(',').nth(3).unwrap().parse().unwrap())
        .collect();
    let want: Vec<u64> = (0..2)
        .map(|k| usar_sim::mission::trial_seed(5, k))
        .collect();
    assert_eq!(seeds, [want[0], want[1], want[0], want[1]]);
}

#[test]
fn too_many_threads_are_capped_with_a_warning() {
    let tmp = tempfile::tempdir().unwrap();
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    // Just past the cap (4 x the cores), so that a regression starts few threads.
    let asked = (4 * cores + 1).to_string();
    let run = |methods: &str, trials: &str| {
        Command::new(env!("CARGO_BIN_EXE_usar"))
            .args(["sweep", PAPER, "--methods", methods, "--trials", trials])
            .args(["--duration", "2", "--quiet", "--threads", &asked, "--out"])
            .arg(tmp.path().join(format!("{methods}-{trials}")))
            .output()
            .expect("run usar")
    };
    // 4 x 2 = 8 jobs: the cap, or the job count if that is less.
    let o = run("rne,dis,eng,hp_dis", "2");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let err = String::from_utf8_lossy(&o.stderr);
    let warning = format!(
        "warning: --threads {asked} is more than 4 x the {cores} available cores: using {}",
        4 * cores
    );
    assert!(err.contains(&warning), "{err}");
    assert_eq!(err.lines().filter(|l| l.contains("--threads")).count(), 1);
    let out = String::from_utf8_lossy(&o.stdout);
    let used = (4 * cores).min(8);
    assert!(out.contains(&format!("on {used} thread(s)")), "{out}");
    // One job: one thread.
    let o = run("rne", "1");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("ran 1 trials in"));
    assert!(String::from_utf8_lossy(&o.stdout).contains("on 1 thread(s)"));
}
