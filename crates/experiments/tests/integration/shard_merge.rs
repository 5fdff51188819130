//! Sharded sweeps: any split of a sweep covers every job once; shards run in any order (one of
//! them killed and resumed) merge into the same CSV files as the sweep on one machine; a
//! missing shard and a failed trial are named with the command that runs the shard again.

use crate::common;

use std::collections::HashSet;
use std::path::Path;
use std::process::{Command, Output};

use usar_sim::scenario;
use usar_sweep::grid::build_grid;
use usar_sweep::shard::Shard;
use usar_sweep::sweep::{SweepConfig, header_of, job_list};

use common::{PAPER, STOPPED, merge, ok, read, read_lines, write_lines};

const CELLS: [&str; 2] = [
    "c00_hp_pct_per_step_in_radiation=0.0003",
    "c01_hp_pct_per_step_in_radiation=0.003",
];

/// `usar sweep` of a 2-cell grid, rne,dis x 3 trials x 8 s, into `out`, then `extra`.
fn sweep(out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", "3"])
        .args(["--duration", "8", "--quiet", "--threads", "2"])
        .args([
            "--vary",
            "mission.hp_pct_per_step_in_radiation=0.0003,0.003",
        ])
        .arg("--out")
        .arg(out)
        .args(extra)
        .output()
        .expect("run usar")
}

fn assert_same_csv(a: &Path, b: &Path) {
    assert!(
        read(&a.join("grid.csv")) == read(&b.join("grid.csv")),
        "grid.csv differs"
    );
    for cell in CELLS {
        for name in [
            "trials.csv",
            "trials_long.csv",
            "summary.csv",
            "scenario.ron",
        ] {
            let (x, y) = (a.join(cell).join(name), b.join(cell).join(name));
            assert!(read(&x) == read(&y), "{cell}/{name} differs");
        }
    }
}

#[test]
fn every_split_covers_every_job_exactly_once() {
    let spec = scenario::parse_spec(&std::fs::read_to_string(PAPER).unwrap(), PAPER).unwrap();
    let scenario = scenario::load(PAPER).unwrap();
    // Cells of different trial lengths: the split balances simulated time.
    let grid = build_grid(&spec, &["mission.duration_s=30,60,90".to_string()]).unwrap();
    let cfg = SweepConfig {
        grid: Some(grid),
        methods: vec!["rne".into(), "dis".into(), "eng".into()],
        trials: 7,
        ..SweepConfig::new(scenario, PAPER)
    };
    let header = header_of(&cfg).unwrap();
    let all = job_list(3, 3, 7);
    for count in 1..=12 {
        let mut seen = HashSet::new();
        let mut sizes = Vec::new();
        for index in 0..count {
            let jobs = Shard::new(index, count).unwrap().jobs(&header);
            sizes.push(jobs.len());
            for j in jobs {
                assert!(seen.insert(j), "{j:?} is in two shards of {count}");
            }
        }
        assert_eq!(seen.len(), all.len(), "a split into {count} misses jobs");
        assert!(all.iter().all(|j| seen.contains(j)));
        assert!(sizes.iter().all(|&s| s > 0 || count > all.len()));
    }
}

#[test]
fn shards_in_any_order_merge_into_the_files_of_one_sweep() {
    let tmp = tempfile::tempdir().unwrap();
    let local = tmp.path().join("local");
    ok(&sweep(&local, &[]));

    // Three shards, out of order; shard 0 is killed after one trial and run again.
    let three = tmp.path().join("three");
    ok(&sweep(&three, &["--shard", "2/3"]));
    let killed = sweep(&three, &["--shard", "0/3", "--stop-after", "1"]);
    assert_eq!(killed.status.code(), Some(STOPPED));
    let out = ok(&sweep(&three, &["--shard", "0/3"]));
    assert!(out.contains("1 from the shard's journal"), "{out}");
    ok(&sweep(&three, &["--shard", "1/3"]));
    // A shard writes no tables: only its journal and plan.
    assert!(!three.join("grid.csv").exists());
    assert!(three.join("shards/0-of-3/plan.json").exists());
    let merged = ok(&merge(&three));
    assert!(merged.contains("merged 3 shards"), "{merged}");
    assert_same_csv(&local, &three);

    // Two shards, in reverse order.
    let two = tmp.path().join("two");
    ok(&sweep(&two, &["--shard", "1/2"]));
    ok(&sweep(&two, &["--shard", "0/2"]));
    ok(&merge(&two));
    assert_same_csv(&local, &two);
}

#[test]
fn a_missing_shard_is_named_with_its_command_and_nothing_is_merged() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &["--shard", "0/3"]));
    ok(&sweep(&dir, &["--shard", "2/3"]));
    let o = merge(&dir);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("1 of 3 shards are not done"), "{err}");
    assert!(err.contains("shard 1/3: no journal"), "{err}");
    assert!(err.contains("--shard 1/3 --out"), "{err}");
    assert!(!dir.join("grid.csv").exists());

    // A shard killed before its journal's header was whole: named as not run, as a sweep
    // treats such a journal as none.
    std::fs::create_dir_all(dir.join("shards/1-of-3")).unwrap();
    std::fs::write(dir.join("shards/1-of-3/journal.jsonl"), "{\"header\":{\"fo").unwrap();
    let o = merge(&dir);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("shard 1/3: its journal holds no trial"),
        "{err}"
    );
    assert!(err.contains("--shard 1/3 --out"), "{err}");
    ok(&sweep(&dir, &["--shard", "1/3"]));
    ok(&merge(&dir));

    // A folder with no shard at all.
    let o = merge(&tmp.path().join("empty"));
    assert!(String::from_utf8_lossy(&o.stderr).contains("no shards to merge"));
}

#[test]
fn a_failed_trial_names_its_shard_and_rerunning_the_shard_fixes_the_merge() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &["--shard", "0/2"]));
    // Trial 0 of DIS is job 1 of the job list: shard 1 of 2.
    let failed = sweep(&dir, &["--shard", "1/2", "--fail-trial", "dis:0"]);
    assert!(!failed.status.success());
    let o = merge(&dir);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("trials failed"), "{err}");
    assert!(err.contains("--shard 1/2 --out"), "{err}");
    assert!(!err.contains("--shard 0/2"), "{err}");
    // The files are written without the failed trials, as a sweep writes them.
    assert!(dir.join("grid.csv").exists());
    ok(&sweep(&dir, &["--shard", "1/2"]));
    ok(&merge(&dir));
}

#[test]
fn shards_of_a_different_sweep_are_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &["--shard", "0/2"]));
    // Shard 1 of the same folder with another seed: its header differs.
    ok(&sweep(&dir, &["--shard", "1/2", "--seed", "7"]));
    let o = merge(&dir);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!o.status.success());
    assert!(err.contains("shard 1/2") && err.contains("seed"), "{err}");
}

#[test]
fn the_shard_that_ran_another_sweep_is_named_and_its_command_mends_the_split() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    // Shard 0 of 3 ran with another seed than shards 1 and 2.
    ok(&sweep(&dir, &["--shard", "0/3", "--seed", "7"]));
    ok(&sweep(&dir, &["--shard", "1/3"]));
    ok(&sweep(&dir, &["--shard", "2/3"]));
    let o = merge(&dir);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("1 of 3 shards ran another sweep"), "{err}");
    assert!(
        err.contains("shard 0/3") && err.contains("seed 7 vs"),
        "{err}"
    );
    assert!(
        !err.contains("shard 1/3") && !err.contains("shard 2/3"),
        "{err}"
    );
    let command = err
        .lines()
        .map(str::trim)
        .find(|l| l.starts_with("usar sweep"))
        .unwrap_or_else(|| panic!("no command in: {err}"));
    assert!(
        command.contains("--shard 0/3 --out") && command.ends_with(" --overwrite"),
        "{command}"
    );
    let usar_bin = env!("CARGO_BIN_EXE_usar");
    let mended = Command::new("sh")
        .arg("-c")
        .arg(command.replacen("usar", &format!("'{usar_bin}'"), 1))
        .output()
        .unwrap();
    ok(&mended);
    ok(&merge(&dir));
}

#[test]
fn an_edited_plan_is_named_as_such() {
    let (_tmp, dir) = swept_in_two_shards();
    let plan = dir.join("shards/0-of-2/plan.json");
    let text = std::fs::read_to_string(&plan).unwrap();
    assert!(text.contains("\"trials\": 3"), "{text}");
    std::fs::write(&plan, text.replace("\"trials\": 3", "\"trials\": 4")).unwrap();
    let o = merge(&dir);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("shard 0/2") && err.contains("plan.json: the plan does not match"),
        "{err}"
    );
    assert!(err.contains("trials 3 vs 4"), "{err}");
}

#[test]
fn a_bad_shard_argument_is_one_line() {
    let tmp = tempfile::tempdir().unwrap();
    let o = sweep(&tmp.path().join("s"), &["--shard", "3/3"]);
    assert!(!o.status.success());
    assert_eq!(
        String::from_utf8_lossy(&o.stderr).trim(),
        "error: --shard 3/3: the shard index must be from 0 to 2"
    );
    // 2 cells x 2 methods x 3 trials: a 13th shard would have nothing to run.
    let o = sweep(&tmp.path().join("s"), &["--shard", "0/13"]);
    assert!(!o.status.success());
    assert_eq!(
        String::from_utf8_lossy(&o.stderr).trim(),
        "error: --shard 0/13: the sweep has 12 trial(s), so at most 12 shards have work; split \
         it into at most 12"
    );
    assert!(!tmp.path().join("s").exists());
}

/// `line` with the first digit of its first task's rescuee count changed: still JSON, but its
/// checksum no longer verifies.
fn edited(line: &str) -> String {
    let at = line.find("\"rescued\":[").unwrap() + "\"rescued\":[".len();
    let digit = line.as_bytes()[at];
    let other = if digit == b'9' {
        '8'
    } else {
        char::from(digit + 1)
    };
    let mut out = line.to_string();
    out.replace_range(at..=at, &other.to_string());
    out
}

/// Both shards of a 2-way split swept into `<tmp>/s`.
fn swept_in_two_shards() -> (tempfile::TempDir, std::path::PathBuf) {
    swept_in_two_shards_into("s")
}

/// As [`swept_in_two_shards`], into a folder of the temporary folder named `name`.
fn swept_in_two_shards_into(name: &str) -> (tempfile::TempDir, std::path::PathBuf) {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join(name);
    ok(&sweep(&dir, &["--shard", "0/2"]));
    ok(&sweep(&dir, &["--shard", "1/2"]));
    (tmp, dir)
}

/// `usar merge dir` fails with one line that ends in shard 1/2's own command with
/// `--overwrite` and suggests no option merge lacks; returns the message.
fn refused_naming_shard_1s_command(dir: &Path) -> String {
    let o = merge(dir);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    assert!(
        err.contains("run shard 1/2 again from scratch: usar sweep ")
            && err.contains("--shard 1/2")
            && err.trim_end().ends_with("--overwrite"),
        "{err}"
    );
    assert!(
        !err.contains("--resume") && !err.contains("another --out"),
        "usar merge has neither --resume nor --out: {err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    err
}

/// `usar merge dir` succeeds and warns of no journal line.
fn assert_merges_without_warnings(dir: &Path) {
    let o = merge(dir);
    ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(!err.contains("does not verify"), "{err}");
}

#[test]
fn an_edited_shard_record_is_named_and_rerunning_the_shard_clears_it() {
    let (_tmp, dir) = swept_in_two_shards();
    // Line 2 of shard 1's journal (its first record) edited.
    let journal = dir.join("shards/1-of-2/journal.jsonl");
    let mut lines = read_lines(&journal);
    lines[1] = edited(&lines[1]);
    write_lines(&journal, &lines);

    let o = merge(&dir);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("shard 1/2: 1 of its"), "{err}");
    assert!(
        err.contains("trials have no record that verifies (")
            && err.contains(": its record on line 2 does not verify (edited?))"),
        "{err}"
    );
    assert!(!dir.join("grid.csv").exists());

    // The shard runs the trial again; the merge then has nothing to warn about.
    ok(&sweep(&dir, &["--shard", "1/2"]));
    assert_merges_without_warnings(&dir);
}

#[test]
fn an_edited_copy_of_another_shards_record_is_not_run_or_merged() {
    let (_tmp, dir) = swept_in_two_shards();
    // An edited copy of shard 0's first record at the end of shard 1's journal.
    let theirs = read_lines(&dir.join("shards/0-of-2/journal.jsonl"));
    let journal = dir.join("shards/1-of-2/journal.jsonl");
    let mut lines = read_lines(&journal);
    lines.push(edited(&theirs[1]));
    write_lines(&journal, &lines);

    let o = sweep(&dir, &["--shard", "1/2"]);
    let out = ok(&o);
    let err = String::from_utf8_lossy(&o.stderr);
    let line = lines.len();
    assert!(
        err.contains(&format!(
            "journal.jsonl:{line}: record does not verify (edited?)"
        )) && err.contains("is another shard's (the shard that owns it runs it)"),
        "{err}"
    );
    assert!(out.contains("from the shard's journal"), "{out}");
    // Shard 0 holds the trial's record: the merge takes it and says nothing of the copy.
    assert_merges_without_warnings(&dir);
}

#[test]
fn a_damaged_shard_journal_names_the_shards_command_to_run_it_again() {
    let (_tmp, dir) = swept_in_two_shards();
    // Line 2 of shard 1's journal is not a journal line at all (line 3 follows it).
    let journal = dir.join("shards/1-of-2/journal.jsonl");
    let mut lines = read_lines(&journal);
    lines[1] = "not json".to_string();
    write_lines(&journal, &lines);
    let err = refused_naming_shard_1s_command(&dir);
    assert!(
        err.contains("journal.jsonl:2: not a valid journal line"),
        "{err}"
    );
}

#[test]
fn a_shard_journal_of_another_format_names_the_shards_command_on_one_line() {
    // A line break in the output folder's name, which the shard's command holds.
    let (_tmp, dir) = swept_in_two_shards_into("s\nt");
    let journal = dir.join("shards/1-of-2/journal.jsonl");
    let mut lines = read_lines(&journal);
    let format = "{\"header\":{\"format\":";
    assert!(lines[0].starts_with(format), "{}", lines[0]);
    lines[0] = lines[0].replacen(format, "{\"header\":{\"format\":1", 1);
    write_lines(&journal, &lines);
    let err = refused_naming_shard_1s_command(&dir);
    assert!(err.contains("journal format 1"), "{err}");
}
