//! `usar sweep`: 1 and 2 threads write byte-identical trials.csv and summary.csv.

use std::path::Path;
use std::process::Command;

const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");

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
