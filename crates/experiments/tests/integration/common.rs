//! Helpers shared by the `usar` command-line tests: the paper scenario, running the built
//! binary, and reading what it wrote.

#![allow(dead_code)] // each test file uses a subset

use std::ffi::OsStr;
use std::path::Path;
use std::process::{Command, Output};

/// `scenarios/paper.ron`.
pub const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");

/// `scenarios/corridor.ron`.
pub const CORRIDOR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/corridor.ron");

/// The axes file of the tiny multiverses of the tests.
pub const AXES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/multiverse-axes.ron"
);

/// The targets file of the tiny multiverses of the tests.
pub const TARGETS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/data/multiverse-targets.ron"
);

/// Exit status of a sweep stopped by `--stop-after` (`STOP_EXIT_CODE` in the binary's
/// `commands/test_hooks.rs`).
pub const STOPPED: i32 = 75;

/// `usar ARGS`: runs the built binary and returns what it wrote and its status.
pub fn usar<I, S>(args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(args)
        .output()
        .expect("run usar")
}

/// `usar ARGS`, run in the folder `cwd`.
pub fn usar_in<I, S>(cwd: &Path, args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("run usar")
}

/// `usar merge DIR`.
pub fn merge(dir: &Path) -> Output {
    usar([OsStr::new("merge"), dir.as_os_str()])
}

/// Asserts that `o` succeeded (else panics with its stderr) and returns its stdout.
pub fn ok(o: &Output) -> String {
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The stderr of `o` as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// `p` as a command-line argument; panics unless it is UTF-8.
pub fn text(p: &Path) -> &str {
    p.to_str().expect("utf-8 path")
}

/// The bytes of the file at `path`; panics naming the path.
pub fn read(path: &Path) -> Vec<u8> {
    std::fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The text of the file at `path`; panics naming the path.
pub fn read_text(path: &Path) -> String {
    std::fs::read_to_string(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

/// The lines of the UTF-8 file at `path` (a journal), without their line breaks.
pub fn read_lines(path: &Path) -> Vec<String> {
    String::from_utf8(read(path))
        .unwrap()
        .lines()
        .map(String::from)
        .collect()
}

/// Writes `lines` to `path`, each ended by a line break.
pub fn write_lines(path: &Path, lines: &[String]) {
    std::fs::write(path, lines.join("\n") + "\n").unwrap();
}

/// How many trial records the journal of the sweep folder `dir` holds.
pub fn journal_trials(dir: &Path) -> usize {
    std::fs::read_to_string(dir.join("journal.jsonl"))
        .unwrap()
        .lines()
        .filter(|l| l.starts_with("{\"trial\""))
        .count()
}

/// Rewrites the journal at `path` as if the build `build` had written it: the header's build,
/// and every line's checksum recomputed so that the journal verifies.
pub fn set_journal_build(path: &Path, build: &str) {
    use usar_sweep::checked_log::{header_sum, record_sum};
    let text = std::fs::read_to_string(path).unwrap();
    let body = |line: &str, kind: &str| -> String {
        let prefix = format!("{{\"{kind}\":");
        let (json, _) = line
            .strip_prefix(&prefix)
            .unwrap()
            .rsplit_once(",\"sum\":")
            .unwrap();
        json.to_owned()
    };
    let mut lines = text.lines();
    let json = body(lines.next().unwrap(), "header");
    let at = json.find("\"build\":\"").unwrap() + "\"build\":\"".len();
    let end = at + json[at..].find('"').unwrap();
    let json = format!("{}{build}{}", &json[..at], &json[end..]);
    let sum = header_sum(&json);
    let mut out = format!("{{\"header\":{json},\"sum\":\"{sum}\"}}\n");
    for line in lines {
        let record = body(line, "trial");
        let record_sum = record_sum(&sum, &record);
        out.push_str(&format!(
            "{{\"trial\":{record},\"sum\":\"{record_sum}\"}}\n"
        ));
    }
    std::fs::write(path, out).unwrap();
}

/// Every file under `dir` (relative path, bytes; a symbolic link as the path it names).
pub fn snapshot(dir: &Path) -> std::collections::BTreeMap<std::path::PathBuf, Vec<u8>> {
    fn walk(
        root: &Path,
        dir: &Path,
        out: &mut std::collections::BTreeMap<std::path::PathBuf, Vec<u8>>,
    ) {
        for e in std::fs::read_dir(dir).unwrap() {
            let p = e.unwrap().path();
            let rel = p.strip_prefix(root).unwrap().to_path_buf();
            if p.is_symlink() {
                let to = std::fs::read_link(&p).unwrap();
                out.insert(rel, to.to_string_lossy().as_bytes().to_vec());
            } else if p.is_dir() {
                walk(root, &p, out);
            } else {
                out.insert(rel, std::fs::read(&p).unwrap());
            }
        }
    }
    let mut out = std::collections::BTreeMap::new();
    walk(dir, dir, &mut out);
    out
}

/// `usar ARGS`, killed (and the test failed, naming the command) unless it ends within
/// `secs` seconds: for inputs that once made `usar` wait or read for ever.
pub fn usar_within<I, S>(secs: u64, args: I) -> Output
where
    I: IntoIterator<Item = S>,
    S: AsRef<OsStr>,
{
    use std::process::Stdio;
    use std::time::{Duration, Instant};
    let args: Vec<_> = args.into_iter().map(|a| a.as_ref().to_owned()).collect();
    let mut child = Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(&args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("run usar");
    let t0 = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t0.elapsed() > Duration::from_secs(secs) {
            child.kill().unwrap();
            let _ = child.wait();
            panic!("usar {args:?} did not end within {secs} s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    child.wait_with_output().unwrap()
}

/// Makes a FIFO (named pipe) at `path` with `mkfifo`; panics when it cannot.
#[cfg(unix)]
pub fn make_fifo(path: &Path) {
    let made = Command::new("mkfifo").arg(path).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo {}", path.display());
}

/// One shard (`"i/n"`) of a sweep of paper.ron (rne and dis, 1 trial of 10 s) into `dir`.
pub fn sweep_shard(dir: &Path, shard: &str) -> Output {
    usar([
        "sweep",
        PAPER,
        "--methods",
        "rne,dis",
        "--trials",
        "1",
        "--duration",
        "10",
        "--quiet",
        "--shard",
        shard,
        "--out",
        text(dir),
    ])
}

/// A sharded sweep of paper.ron ([`sweep_shard`], 2 shards) in `dir`, merged.
pub fn sharded_sweep(dir: &Path) {
    for shard in ["0/2", "1/2"] {
        ok(&sweep_shard(dir, shard));
    }
    ok(&merge(dir));
}

/// A tiny multiverse of corridor.ron (the axes and targets of `tests/data/`, 1 trial of 10 s,
/// 1 evaluation) into `out`.
pub fn multiverse_args(out: &Path) -> Vec<&str> {
    vec![
        "multiverse",
        CORRIDOR,
        "--axes",
        AXES,
        "--targets",
        TARGETS,
        "--free",
        "mission.pickup_s=0.5..2",
        "--trials",
        "1",
        "--calibration-trials",
        "1",
        "--max-evals",
        "1",
        "--duration",
        "10",
        "--quiet",
        "--out",
        text(out),
    ]
}
