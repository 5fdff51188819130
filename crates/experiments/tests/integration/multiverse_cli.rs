//! `usar multiverse`: tiny multiverses over scenarios/corridor.ron (the axes and targets of
//! `tests/data/`: 2 x 2 universes, one invalid, one not admissible; two methods, 2 trials of
//! 60 s, calibrations of 1 trial per method and at most 3 evaluations) write consistent files,
//! continue after kills with the same files as an uninterrupted run on another thread count,
//! record failing trials in their universes and retry them on a rerun, give the same files
//! sharded and merged, write Slurm scripts, and refuse bad input in one line.

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::{STOPPED, ok, read, read_text, stderr, usar_in};

const CORRIDOR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/corridor.ron");
const AXES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/multiverse-axes.ron"
);
const TARGETS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/multiverse-targets.ron"
);

const CLAIMS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenarios/paper-claims.ron"
);

/// The options of every multiverse here after the scenario, but `--out`.
const OPTIONS: [&str; 19] = [
    "--axes",
    AXES,
    "--targets",
    TARGETS,
    "--claims",
    CLAIMS,
    "--free",
    "mission.pickup_s=0.5..2",
    "--methods",
    "rne,dis",
    "--trials",
    "2",
    "--duration",
    "60",
    "--calibration-trials",
    "1",
    "--max-evals",
    "3",
    "--quiet",
];

/// The files at the top of a multiverse's folder.
const TOP_FILES: [&str; 12] = [
    "multiverse.csv",
    "multiverse.md",
    "spec_curve_1.svg",
    "spec_curve_2.svg",
    "spec_curve_3.svg",
    "spec_curve_4a.svg",
    "spec_curve_4b.svg",
    "sensitivity_1.svg",
    "sensitivity_2.svg",
    "sensitivity_3.svg",
    "sensitivity_4a.svg",
    "sensitivity_4b.svg",
];

/// Two empty working folders `names` under `root`, for two runs to compare.
fn working_dirs(root: &Path, names: [&str; 2]) -> [PathBuf; 2] {
    names.map(|n| {
        let d = root.join(n);
        std::fs::create_dir_all(&d).unwrap();
        d
    })
}

/// `usar multiverse CORRIDOR OPTIONS --out out EXTRA` in `cwd`.
fn multiverse_in(cwd: &Path, extra: &[&str]) -> Output {
    let mut args = vec!["multiverse", CORRIDOR];
    args.extend(OPTIONS);
    args.extend(["--out", "out"]);
    args.extend(extra);
    usar_in(cwd, args)
}

/// The bytes of every top file of the multiverse in `dir`.
fn top_files(dir: &Path) -> Vec<(&'static str, Vec<u8>)> {
    TOP_FILES.iter().map(|f| (*f, read(&dir.join(f)))).collect()
}

/// Asserts that the top files of `a` and `b` are the same bytes.
fn assert_same_files(a: &Path, b: &Path) {
    for ((name, x), (_, y)) in top_files(a).into_iter().zip(top_files(b)) {
        assert!(
            x == y,
            "{name} differs between {} and {}",
            a.display(),
            b.display()
        );
    }
}

/// Asserts that `o` failed with one line on stderr containing every part of `parts`.
fn one_line_error(o: &Output, parts: &[&str]) {
    let e = stderr(o);
    assert!(!o.status.success(), "succeeded: {e}");
    assert!(e.starts_with("error: "), "{e}");
    assert_eq!(e.trim_end().lines().count(), 1, "not one line: {e}");
    for p in parts {
        assert!(e.contains(p), "no {p:?} in {e}");
    }
}

/// Checks `multiverse.csv` in `out`: a universe row each, then per method x metric and per
/// claim for every universe whose comparison ran (not the invalid one).
fn check_csv(out: &Path) {
    let mut csv = csv::Reader::from_path(out.join("multiverse.csv")).unwrap();
    let header: Vec<String> = csv.headers().unwrap().iter().map(String::from).collect();
    assert_eq!(
        &header[..6],
        [
            "universe",
            "team",
            "pace",
            "admissible",
            "loss",
            "mission.pickup_s"
        ]
    );
    let rows: Vec<csv::StringRecord> = csv.records().map(Result::unwrap).collect();
    let col = |name: &str| header.iter().position(|h| h == name).unwrap();
    let metrics = usar_sweep::metrics::Metric::all(2).len();
    // A universe row, 2 methods x the metrics, the one target and the 5 claims.
    let compared = 1 + 2 * metrics + 1 + 5;
    for (id, admissible, status, count) in [
        ("u000", "true", "ok", compared),
        ("u001", "false", "ok", compared),
        ("u002", "true", "ok", compared),
        ("u003", "false", "invalid", 1),
    ] {
        let own: Vec<_> = rows.iter().filter(|r| &r[0] == id).collect();
        assert_eq!(own.len(), count, "{id}");
        assert!(
            own.iter()
                .all(|r| &r[col("admissible")] == admissible && &r[col("status")] == status),
            "{id}"
        );
    }
    let invalid = rows.iter().find(|r| &r[0] == "u003").unwrap();
    assert!(
        invalid[col("message")]
            .contains("kinds[0].starts: 2 start position(s) listed but count is 3")
    );
    let claims: Vec<_> = rows.iter().filter(|r| &r[col("row")] == "claim").collect();
    assert_eq!(claims.len(), 15);
    assert!(claims.iter().all(|r| {
        ["holds", "not significant", "does not hold", "not tested"].contains(&&r[col("verdict")])
    }));
}

#[test]
fn a_multiverse_writes_consistent_files_and_a_rerun_changes_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let summary = ok(&multiverse_in(tmp.path(), &[]));
    assert!(
        summary.contains("4 of 4 universes (4 run now, 0 from earlier runs)"),
        "{summary}"
    );
    assert!(
        summary.contains("admissible: 2/4 (50 %); invalid 1, failed 0"),
        "{summary}"
    );
    let out = tmp.path().join("out");
    for f in TOP_FILES.iter().filter(|f| f.ends_with(".svg")) {
        assert!(read_text(&out.join(f)).starts_with("<svg"), "{f}");
    }
    check_csv(&out);
    let md = read_text(&out.join("multiverse.md"));
    assert!(md.contains("2/4 (50 %) admissible"), "{md}");
    assert!(
        md.contains("of the universes are admissible: the whole factorial ran"),
        "{md}"
    );
    assert!(
        md.contains(
            "| [u003](universes/u003/) | three east-bound | crawl | no |  |  |  | invalid |"
        ),
        "{md}"
    );
    // Each universe's folder: its scenario (which loads), calibration, comparison, record.
    let u0 = out.join("universes/u000");
    for f in [
        "scenario.ron",
        "calibration/calibrated.ron",
        "comparison/trials.csv",
        "universe.json",
    ] {
        assert!(u0.join(f).is_file(), "u000/{f}");
    }
    let s = usar_sim::scenario::load(out.join("universes/u002/scenario.ron")).unwrap();
    assert_eq!(s.kinds()[0].count, 3);
    assert!(!out.join("universes/u003/calibration").exists());
    // The same command again runs nothing and writes the same bytes.
    let before = top_files(&out);
    let again = ok(&multiverse_in(tmp.path(), &[]));
    assert!(
        again.contains("(0 run now, 4 from earlier runs)"),
        "{again}"
    );
    assert_eq!(top_files(&out), before);
    // Which choices decide each claim, and a sensitivity figure per claim.
    assert!(md.contains("## Which choices decide each claim"), "{md}");
    assert!(
        md.contains("![Claim 4b: what decides it](sensitivity_4b.svg)"),
        "{md}"
    );
    // --near-loss is a report option: the same universes, one more section.
    let near = ok(&multiverse_in(tmp.path(), &["--near-loss", "1e9"]));
    assert!(near.contains("(0 run now, 4 from earlier runs)"), "{near}");
    let md = read_text(&out.join("multiverse.md"));
    assert!(
        md.contains("## Sensitivity: near-admissible universes (loss <= 1000000000)"),
        "{md}"
    );
    assert!(
        md.contains("counted as admissible (`--near-loss 1000000000`): 3/4 (75 %)"),
        "{md}"
    );
}

#[test]
fn a_killed_multiverse_resumes_to_the_files_of_an_uninterrupted_run_on_another_thread_count() {
    let tmp = tempfile::tempdir().unwrap();
    let [whole, killed] = working_dirs(tmp.path(), ["whole", "killed"]);
    ok(&multiverse_in(&whole, &["--threads", "2"]));
    // Calibration evaluations and comparison trials count together: 3 stops in u000's
    // comparison; 4 more (7) at u001's last calibration evaluation, before its outputs.
    for stop in ["3", "4"] {
        let o = multiverse_in(&killed, &["--threads", "1", "--stop-after", stop]);
        assert_eq!(o.status.code(), Some(STOPPED), "{}", stderr(&o));
    }
    let k = killed.join("out");
    assert!(k.join("universes/u000/universe.json").is_file());
    assert!(k.join("universes/u001/calibration/trace.jsonl").is_file());
    assert!(!k.join("universes/u001/calibration/calibrated.ron").exists());
    assert!(!k.join("multiverse.csv").exists());
    let summary = ok(&multiverse_in(&killed, &["--threads", "1"]));
    assert!(
        summary.contains("(3 run now, 1 from earlier runs)"),
        "{summary}"
    );
    assert_same_files(&whole.join("out"), &k);
}

#[test]
fn failing_trials_fail_their_universes_only_and_a_rerun_retries_them() {
    let tmp = tempfile::tempdir().unwrap();
    let [whole, failing] = working_dirs(tmp.path(), ["whole", "failing"]);
    ok(&multiverse_in(&whole, &[]));
    let o = multiverse_in(&failing, &["--fail-trial", "dis:1"]);
    let e = stderr(&o);
    assert!(!o.status.success());
    assert!(
        e.contains(
            "error: 3 of 4 universes failed: u000 (comparison: 1 of 4 trials failed: DIS trial 1: "
        ),
        "{e}"
    );
    assert!(
        e.contains("run the same command again to retry them"),
        "{e}"
    );
    // The files are written, with the failures: the invalid universe is not one of them.
    let csv = read_text(&failing.join("out/multiverse.csv"));
    let failed = csv
        .lines()
        .filter(|l| l.contains(",failed,universe,"))
        .count();
    assert_eq!(failed, 3, "{csv}");
    assert!(csv.contains(",invalid,universe,"));
    let summary = ok(&multiverse_in(&failing, &[]));
    assert!(
        summary.contains("(3 run now, 1 from earlier runs)"),
        "{summary}"
    );
    assert_same_files(&whole.join("out"), &failing.join("out"));
}

#[test]
fn shards_merged_give_the_files_of_one_run() {
    let tmp = tempfile::tempdir().unwrap();
    let [one, split] = working_dirs(tmp.path(), ["one", "split"]);
    ok(&multiverse_in(&one, &[]));
    let shard = ok(&multiverse_in(&split, &["--shard", "1/2"]));
    assert!(
        shard.contains("shard 1/2 of multiverse corridor: 2 of 4 universes"),
        "{shard}"
    );
    assert!(
        shard.contains("when every shard is done: usar merge out"),
        "{shard}"
    );
    assert!(!split.join("out/multiverse.csv").exists());
    // The merge names what is missing and the shard that runs it.
    let early = usar_in(&split, ["merge", "out"]);
    let e = stderr(&early);
    assert!(!early.status.success());
    assert!(
        e.contains("2 of 4 universes are not done, so nothing was merged"),
        "{e}"
    );
    assert!(
        e.contains("u000: not run yet (shard 0/2)") && e.contains("u002: not run yet (shard 0/2)"),
        "{e}"
    );
    assert!(e.contains(" --shard 0/2 --out out"), "{e}");
    ok(&multiverse_in(&split, &["--shard", "0/2"]));
    let merged = ok(&usar_in(&split, ["merge", "out"]));
    assert!(
        merged.contains("multiverse corridor: 4 of 4 universes"),
        "{merged}"
    );
    assert_same_files(&one.join("out"), &split.join("out"));
}

#[test]
fn a_shared_design_starts_the_calibrations_and_gives_the_same_files_resumed_and_sharded() {
    let tmp = tempfile::tempdir().unwrap();
    let [one, split] = working_dirs(tmp.path(), ["one", "split"]);
    // 16 points, 12 of them in the three valid universes (the emulator fits at least 10).
    let design = ["--design", "16", "--check-trials", "1"];
    ok(&multiverse_in(
        &one,
        &[&design[..], &["--threads", "2"]].concat(),
    ));
    let out = one.join("out");
    let points = |d: &Path| std::fs::read_dir(d.join("design")).unwrap().count();
    assert_eq!(points(&out), 16);
    // Every calibrated universe started at the emulator's point, recorded with its
    // predicted loss; the report says so and gives the emulator's error.
    let record = read_text(&out.join("universes/u000/universe.json"));
    assert!(record.contains("\"predicted_loss\":"), "{record}");
    let trace = read_text(&out.join("universes/u000/calibration/trace.jsonl"));
    assert!(trace.contains("; start: "), "{trace}");
    let md = read_text(&out.join("multiverse.md"));
    for part in [
        "--design 16 --check-trials 1 --check-seed 7",
        "starting where an emulator fitted to 16 shared design evaluations predicts",
        "checked on 1 unseen trials per method",
        "## The design shared by the universes",
        "| rescuees | 4 in [3, 100] |",
    ] {
        assert!(md.contains(part), "no {part:?} in {md}");
    }
    let again = ok(&multiverse_in(&one, &design));
    assert!(
        again.contains("(0 run now, 4 from earlier runs)"),
        "{again}"
    );
    // A design point removed runs again, to the same files.
    std::fs::remove_file(out.join("design/d0005.json")).unwrap();
    std::fs::remove_file(out.join("multiverse.md")).unwrap();
    ok(&multiverse_in(&one, &design));
    assert_eq!(points(&out), 16);
    // Shard 1 of 4 alone runs the whole design (its own points first), then its universe;
    // the others find the design done; merged, the files are the one run's.
    let shard = |s: &str| {
        multiverse_in(
            &split,
            &[&design[..], &["--shard", s, "--threads", "1"]].concat(),
        )
    };
    ok(&shard("1/4"));
    assert_eq!(points(&split.join("out")), 16);
    for s in ["3/4", "0/4", "2/4"] {
        let o = ok(&shard(s));
        assert!(o.contains("1 of 4 universes"), "{o}");
    }
    ok(&usar_in(&split, ["merge", "out"]));
    assert_same_files(&out, &split.join("out"));
    let md_split = read(&split.join("out/multiverse.md"));
    assert_eq!(read(&out.join("multiverse.md")), md_split);
    // Another design is another multiverse; too large a design is refused in one line.
    let other = multiverse_in(&one, &["--design", "17"]);
    one_line_error(&other, &["holds another multiverse", "design 16 vs 17"]);
    let huge = multiverse_in(&split, &["--design", "100001"]);
    one_line_error(&huge, &["--design 100001 is more than the limit of 100000"]);
    let few = multiverse_in(&split, &["--design", "5"]);
    one_line_error(
        &few,
        &["--design 5 is too few: a design needs at least 10 points"],
    );
    // --overwrite removes the design with the rest; a design is then another multiverse.
    ok(&multiverse_in(&one, &["--overwrite"]));
    assert!(!out.join("design").exists());
    let added = multiverse_in(&one, &design);
    one_line_error(&added, &["holds another multiverse", "design none vs 16"]);
}

/// Writes `text` as the axes file `name` in `dir`; returns its path.
fn axes_with(dir: &Path, name: &str, text: &str) -> String {
    let path = dir.join(name);
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

#[test]
fn bad_input_is_one_line_and_nothing_runs() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    let syntax = axes_with(
        d,
        "syntax.ron",
        "Axes(\n    axes: [\n        (name: \"a\" alternatives: []),\n    ],\n)\n",
    );
    let unknown = axes_with(
        d,
        "unknown.ron",
        "Axes(axes: [\n    (name: \"x\", alternatives: [(name: \"base\"), (name: \"y\", set: [\"mission.pickup_sec=1\"])]),\n])\n",
    );
    let free = axes_with(
        d,
        "free.ron",
        "Axes(axes: [(name: \"pickup\", alternatives: [(name: \"slow\", set: [\"mission.pickup_s=2\"])])])\n",
    );
    let cases: Vec<(Vec<&str>, Vec<&str>)> = vec![
        (
            vec!["--axes", &syntax],
            vec!["syntax.ron:3:20: axes[0]: Expected comma"],
        ),
        (
            vec!["--axes", &unknown],
            vec![
                "unknown.ron:2:66: axes[0].alternatives[1].set[0]: axis \"x\", alternative \"y\": no field \"pickup_sec\" in mission",
            ],
        ),
        (
            vec!["--axes", &free],
            vec![
                "free.ron:1:",
                "mission.pickup_s is also --free mission.pickup_s=0.5..2: a calibrated field cannot be a choice too",
            ],
        ),
        (
            vec!["--sample", "5"],
            vec!["--sample 5: the axes make only 4 universes (the full factorial); give at most 4"],
        ),
        (
            vec!["--shard", "0/5"],
            vec!["--shard 0/5: the multiverse runs 4 universe(s), so at most 4 shards have work"],
        ),
        (vec!["--sample", "0"], vec!["--sample must be at least 1"]),
        (
            vec!["--near-loss", "0"],
            vec!["--near-loss must be a finite loss above 0 (0 is admissibility itself), not 0"],
        ),
    ];
    for (extra, parts) in cases {
        // `--axes FILE` in `extra` stands for the good axes file.
        let mut options: Vec<&str> = OPTIONS.to_vec();
        let mut rest: Vec<&str> = extra.clone();
        if let Some(i) = rest.iter().position(|a| *a == "--axes") {
            options[1] = rest[i + 1];
            rest.drain(i..i + 2);
        }
        let mut args = vec!["multiverse", CORRIDOR];
        args.extend(options);
        args.extend(rest);
        args.extend(["--out", "out"]);
        let o = usar_in(d, &args);
        one_line_error(&o, &parts);
        assert!(!d.join("out").exists(), "{extra:?} made the output folder");
    }
}

#[test]
fn another_multiverse_in_the_folder_is_refused_and_overwrite_starts_afresh() {
    let tmp = tempfile::tempdir().unwrap();
    ok(&multiverse_in(
        tmp.path(),
        &["--sample", "1", "--sample-seed", "3"],
    ));
    let o = multiverse_in(tmp.path(), &["--sample", "1", "--sample-seed", "4"]);
    one_line_error(
        &o,
        &[
            "out/multiverse.json holds another multiverse (sample",
            "pass --overwrite to start afresh",
        ],
    );
    let before: Vec<_> = std::fs::read_dir(tmp.path().join("out/universes"))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    ok(&multiverse_in(
        tmp.path(),
        &["--sample", "1", "--sample-seed", "4", "--overwrite"],
    ));
    let after: Vec<_> = std::fs::read_dir(tmp.path().join("out/universes"))
        .unwrap()
        .map(|e| e.unwrap().file_name())
        .collect();
    assert_eq!((before.len(), after.len()), (1, 1));
    assert_ne!(before, after, "the first multiverse's universe went");
    // --overwrite with --shard is refused by the command line.
    let o = multiverse_in(tmp.path(), &["--overwrite", "--shard", "0/2"]);
    assert!(
        !o.status.success() && stderr(&o).contains("--overwrite"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn slurm_writes_a_multiverse_array_and_its_merge() {
    let tmp = tempfile::tempdir().unwrap();
    let mut args = vec!["slurm", CORRIDOR];
    args.extend(OPTIONS.iter().filter(|a| **a != "--quiet"));
    args.extend(["--out", "out", "--shards", "2", "--time", "30"]);
    // A shared design needs no other job: each task runs the design's missing points first.
    args.extend([
        "--design",
        "16",
        "--check-trials",
        "2",
        "--optimizer",
        "cma-es",
    ]);
    let printed = ok(&usar_in(tmp.path(), &args));
    assert!(
        printed.contains("multiverse.sbatch (an array of 2 tasks"),
        "{printed}"
    );
    let array = read_text(&tmp.path().join("out/slurm/multiverse.sbatch"));
    for part in [
        "#SBATCH --array=0-1",
        " multiverse ",
        "--axes ",
        "--free 'mission.pickup_s=0.5..2'",
        "--calibration-trials 1",
        "--design 16 --optimizer cma-es --check-trials 2 --check-seed 7",
        "--shard \"${SLURM_ARRAY_TASK_ID}/2\" --threads \"${SLURM_CPUS_PER_TASK:-1}\" --quiet",
        "logs/multiverse-%A_%a.out",
    ] {
        assert!(array.contains(part), "no {part:?} in\n{array}");
    }
    assert!(read_text(&tmp.path().join("out/slurm/merge.sbatch")).contains(" merge "));
    assert!(read_text(&tmp.path().join("out/slurm/submit.sh")).contains("multiverse.sbatch"));
    let mut too_many = args.clone();
    let i = too_many.iter().position(|a| *a == "--shards").unwrap();
    too_many[i + 1] = "5";
    one_line_error(
        &usar_in(tmp.path(), &too_many),
        &["--shards 5", "at most 4 shards"],
    );
}
