//! Every output folder has an owner (`usar-owner.json`, `usar_sweep::data::owner`): a run of
//! another kind is refused with and without `--overwrite` and the folder's files stay
//! byte for byte; `usar merge` refuses shards of another kind; and a calibration against a
//! band reaching 1.7e308 ends (its targets figure once spun forever).

use crate::common;

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

use common::{
    PAPER, merge, multiverse_args, ok, sharded_sweep, snapshot, stderr, sweep_shard, text, usar,
    usar_in,
};

/// Asserts `o` failed with a one-line error naming the folder's owner and the refused kind.
fn refused(o: &Output, owner: &str, kind: &str) {
    let e = stderr(o);
    assert!(!o.status.success(), "accepted: {e}");
    assert!(
        e.contains(&format!("holds a {owner} (")) && e.contains(&format!("a {kind} never writes")),
        "{e}"
    );
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
}

#[test]
fn no_other_kind_writes_into_a_sharded_sweeps_folder() {
    let tmp = tempfile::tempdir().unwrap();
    let s = tmp.path().join("S");
    sharded_sweep(&s);
    std::fs::create_dir_all(s.join("universes")).unwrap();
    std::fs::write(s.join("universes/notes.txt"), "mine").unwrap();
    std::fs::write(s.join("notes.txt"), "mine").unwrap();
    let before = snapshot(&s);
    assert!(before.contains_key(Path::new("shards/0-of-2/journal.jsonl")));
    assert!(before.contains_key(Path::new("usar-owner.json")));
    for overwrite in [false, true] {
        let mut multiverse = multiverse_args(&s);
        let mut calibrate = vec![
            "calibrate",
            PAPER,
            "--free",
            "mission.pickup_s=0.5..2",
            "--methods",
            "rne",
            "--trials",
            "2",
            "--duration",
            "10",
            "--max-evals",
            "1",
            "--check-trials",
            "0",
            "--quiet",
            "--out",
            text(&s),
        ];
        let mut grid = vec![
            "sweep",
            PAPER,
            "--vary",
            "mission.pickup_s=1,2",
            "--methods",
            "rne",
            "--trials",
            "1",
            "--duration",
            "10",
            "--quiet",
            "--out",
            text(&s),
        ];
        let mut sweep = vec![
            "sweep",
            PAPER,
            "--methods",
            "rne",
            "--trials",
            "1",
            "--duration",
            "10",
            "--quiet",
            "--out",
            text(&s),
        ];
        for args in [&mut multiverse, &mut calibrate, &mut grid, &mut sweep] {
            if overwrite {
                args.push("--overwrite");
            }
        }
        refused(&usar(&multiverse), "sharded sweep", "multiverse");
        refused(&usar(&calibrate), "sharded sweep", "calibration");
        refused(&usar(&grid), "sharded sweep", "grid");
        refused(&usar(&sweep), "sharded sweep", "sweep");
        assert!(
            snapshot(&s) == before,
            "the sweep's folder changed (overwrite {overwrite})"
        );
    }
    // Its own kind still merges, and another shard of it still runs.
    ok(&merge(&s));
}

/// Regression: a folder of the user's own files (no run's) was used by any run, whose
/// `report.md` and `trials.csv` then replaced theirs. Every kind, and `usar slurm` before it
/// writes its scripts, now refuses it in one line naming `--out` and the first such file, with
/// or without `--overwrite`, and the folder stays byte for byte.
#[test]
fn a_folder_of_the_users_own_files_is_refused_by_every_kind_of_run() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path().join("mine");
    std::fs::create_dir_all(&d).unwrap();
    std::fs::write(d.join("report.md"), "my notes").unwrap();
    std::fs::write(d.join("trials.csv"), "my,data").unwrap();
    let before = snapshot(&d);
    let run = [
        "--trials",
        "2",
        "--duration",
        "10",
        "--quiet",
        "--out",
        text(&d),
    ];
    let sweep = [&["sweep", PAPER, "--methods", "rne"][..], &run].concat();
    let grid = [&sweep[..], &["--vary", "mission.pickup_s=1,2"]].concat();
    let shard = [&sweep[..], &["--shard", "0/2"]].concat();
    let free = ["--free", "mission.pickup_s=0.5..2", "--max-evals", "1"];
    let calibrate = [&["calibrate", PAPER, "--methods", "rne"][..], &free, &run].concat();
    let slurm = [
        &["slurm", PAPER, "--methods", "rne"][..],
        &run[..4],
        &["--shards", "2", "--out", text(&d)],
    ]
    .concat();
    let multiverse = multiverse_args(&d);
    for overwrite in [false, true] {
        for args in [&sweep, &grid, &shard, &calibrate, &multiverse, &slurm] {
            let mut args = args.clone();
            if overwrite && args[0] != "slurm" {
                args.push("--overwrite");
            }
            let o = usar(&args);
            let e = stderr(&o);
            assert!(!o.status.success(), "{args:?} accepted: {e}");
            let want = format!(
                "error: --out: {} holds report.md, which no usar run wrote",
                text(&d)
            );
            assert!(e.starts_with(&want), "{args:?}: {e}");
            assert_eq!(e.trim_end().lines().count(), 1, "{e}");
            assert!(snapshot(&d) == before, "{args:?} changed the folder");
        }
    }
    // Without --out, the default folder (results/paper) is blamed as such.
    let cwd = tmp.path();
    let default = cwd.join("results/paper");
    std::fs::create_dir_all(&default).unwrap();
    std::fs::write(default.join("report.md"), "my notes").unwrap();
    let run = ["--methods", "rne", "--trials", "2", "--duration", "10"];
    for command in ["sweep", "slurm"] {
        let mut args = [&[command, PAPER][..], &run].concat();
        if command == "slurm" {
            args.extend(["--shards", "2"]);
        }
        let e = stderr(&usar_in(cwd, &args));
        assert!(
            e.starts_with("error: the default output folder (--out DIR sets another): ")
                && e.contains("results/paper holds report.md, which no usar run wrote"),
            "{command}: {e}"
        );
    }
    assert_eq!(std::fs::read_dir(&default).unwrap().count(), 1);
    // A folder of the user's inside a run's folder is theirs too.
    let (top, inside) = (tmp.path().join("run"), tmp.path().join("run/mine"));
    let sweep_into = |d: &Path| usar([&sweep[..sweep.len() - 1], &[text(d)]].concat());
    ok(&sweep_into(&top));
    std::fs::create_dir_all(&inside).unwrap();
    std::fs::write(inside.join("report.md"), "my notes").unwrap();
    let e = stderr(&sweep_into(&inside));
    assert!(
        e.contains("mine holds report.md, which no usar run wrote"),
        "{e}"
    );
    assert_eq!(std::fs::read_dir(&inside).unwrap().count(), 1);
}

#[test]
fn a_sharded_sweep_is_refused_in_a_multiverse_folder_and_merge_checks_every_shard() {
    let tmp = tempfile::tempdir().unwrap();
    let m = tmp.path().join("M");
    let mut args = multiverse_args(&m);
    args.extend(["--shard", "0/2"]);
    ok(&usar(&args));
    let before = snapshot(&m);
    let o = sweep_shard(&m, "1/2");
    refused(&o, "multiverse", "sharded sweep");
    assert!(snapshot(&m) == before);

    // Folders written before the manifests, mixing a multiverse's shard and a sweep's: the
    // merge names the odd shard and writes nothing.
    let s = tmp.path().join("S");
    sharded_sweep(&s);
    for dir in [&m, &s] {
        for f in [
            dir.join("usar-owner.json"),
            dir.join("shards/0-of-2/usar-owner.json"),
            dir.join("shards/1-of-2/usar-owner.json"),
        ] {
            let _ = std::fs::remove_file(f);
        }
    }
    std::fs::rename(s.join("shards/1-of-2"), m.join("shards/1-of-2")).unwrap();
    let before = snapshot(&m);
    let o = merge(&m);
    let e = stderr(&o);
    assert!(!o.status.success(), "merged: {e}");
    assert!(
        e.contains("shards/1-of-2 holds a sharded sweep")
            && e.contains("shards/1-of-2/journal.jsonl"),
        "{e}"
    );
    assert!(snapshot(&m) == before, "the merge changed the folder");
}

#[test]
fn a_calibration_against_a_band_reaching_the_largest_number_ends() {
    let tmp = tempfile::tempdir().unwrap();
    let targets = tmp.path().join("t.ron");
    std::fs::write(
        &targets,
        "Targets(targets: [\n\
         (name: \"at least 5\", statistic: Mean(\"rounds\"), value: 6.0, band: Between(5.0, 1.7e308)),\n\
         (name: \"at most 9\", statistic: Mean(\"rounds\"), value: 6.0, band: AtMost(9.0)),\n\
         (name: \"wide\", statistic: Mean(\"rescued_total\"), value: 0.0, band: Between(-1e308, 1e308)),\n\
         ])\n",
    )
    .unwrap();
    let out = tmp.path().join("X");
    let mut child = Command::new(env!("CARGO_BIN_EXE_usar"))
        .args([
            "calibrate",
            PAPER,
            "--targets",
            text(&targets),
            "--free",
            "mission.pickup_s=0.5..2",
            "--methods",
            "rne",
            "--trials",
            "2",
            "--duration",
            "20",
            "--max-evals",
            "2",
            "--check-trials",
            "0",
            "--quiet",
            "--out",
            text(&out),
        ])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let t0 = Instant::now();
    let status = loop {
        if let Some(status) = child.try_wait().unwrap() {
            break status;
        }
        if t0.elapsed() > Duration::from_secs(60) {
            child.kill().unwrap();
            panic!("usar calibrate did not end within 60 s");
        }
        std::thread::sleep(Duration::from_millis(50));
    };
    assert!(status.success());
    let files = snapshot(&out);
    for f in [
        "statistics.svg",
        "convergence.svg",
        "calibration.md",
        "calibrated.ron",
    ] {
        assert!(files.contains_key(Path::new(f)), "no {f}");
    }
    assert!(
        !files.keys().any(|p| p.to_string_lossy().contains(".tmp-")),
        "temporary files left: {:?}",
        files.keys().collect::<Vec<_>>()
    );
    let md = String::from_utf8(files[Path::new("calibration.md")].clone()).unwrap();
    assert!(
        md.contains("[5, 1.7e308]") && md.contains("(-∞, 9]"),
        "{md}"
    );
}
