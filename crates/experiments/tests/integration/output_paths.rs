//! Output paths given on the command line (`run --json`, `render --out`, a sweep's files) are
//! written, not replaced: a symlink is followed and stays a symlink, a FIFO gets the bytes, a
//! folder is refused without a temporary file left next to it, and a sweep clears the
//! temporary files of killed runs from its folder when it resumes.
#![cfg(unix)]

use crate::common;

use std::ffi::OsStr;
use std::fs;
use std::os::unix::fs::{FileTypeExt, symlink};
use std::path::Path;
use std::process::{Command, Output};
use std::time::Duration;

use common::{PAPER, STOPPED, ok};

/// `usar ARGS PATHS`.
fn usar(args: &[&str], paths: &[&Path]) -> Output {
    let paths = paths.iter().map(|p| p.as_os_str());
    common::usar(args.iter().map(OsStr::new).chain(paths))
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn is_symlink(p: &Path) -> bool {
    fs::symlink_metadata(p).unwrap().file_type().is_symlink()
}

#[test]
fn run_json_through_a_symlink_writes_its_target() {
    let tmp = tempfile::tempdir().unwrap();
    fs::create_dir(tmp.path().join("real")).unwrap();
    let target = tmp.path().join("real/t.json");
    fs::write(&target, "old").unwrap();
    let link = tmp.path().join("t.json");
    symlink("real/t.json", &link).unwrap();
    let args = ["run", PAPER, "--method", "rne", "--duration", "2", "--json"];
    ok(&usar(&args, &[&link]));
    assert!(is_symlink(&link), "the link was replaced");
    let r: usar_sim::mission::TrialResult =
        serde_json::from_str(&fs::read_to_string(&target).unwrap()).unwrap();
    assert_eq!(r.method, "RNE");
    assert_eq!(names(tmp.path()), ["real", "t.json"]);
    assert_eq!(names(&tmp.path().join("real")), ["t.json"]);

    // /dev/null through a link: written (to nothing), neither it nor the link replaced.
    let null = tmp.path().join("null.json");
    symlink("/dev/null", &null).unwrap();
    ok(&usar(&args, &[&null]));
    assert!(is_symlink(&null));
    assert!(
        fs::metadata("/dev/null")
            .unwrap()
            .file_type()
            .is_char_device()
    );
}

#[test]
fn render_out_to_a_fifo_feeds_its_reader() {
    let tmp = tempfile::tempdir().unwrap();
    let fifo = tmp.path().join("arena.svg");
    if !Command::new("mkfifo")
        .arg(&fifo)
        .status()
        .is_ok_and(|s| s.success())
    {
        eprintln!("no mkfifo here: skipped");
        return;
    }
    let (tx, rx) = std::sync::mpsc::channel();
    let reader = fifo.clone();
    std::thread::spawn(move || {
        let _ = tx.send(fs::read_to_string(reader));
    });
    ok(&usar(&["render", PAPER, "--out"], &[&fifo]));
    let svg = rx
        .recv_timeout(Duration::from_secs(60))
        .expect("the FIFO's reader got nothing: it was replaced")
        .unwrap();
    assert!(svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"));
    assert!(fs::symlink_metadata(&fifo).unwrap().file_type().is_fifo());
    assert_eq!(names(tmp.path()), ["arena.svg"]);
}

#[test]
fn a_folder_as_output_is_refused_and_no_temporary_file_is_left() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("arena.svg");
    fs::create_dir(&dir).unwrap();
    let o = usar(&["render", PAPER, "--out"], &[&dir]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("is a folder"), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    let json = tmp.path().join("t.json");
    fs::create_dir(&json).unwrap();
    let o = usar(
        &["run", PAPER, "--duration", "1", "--json"],
        &[json.as_path()],
    );
    assert!(!o.status.success());
    assert_eq!(names(tmp.path()), ["arena.svg", "t.json"]);
    assert!(names(&dir).is_empty() && names(&json).is_empty());
}

#[test]
fn a_resumed_sweep_clears_stale_temporary_files_and_writes_through_links() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    let sweep = |extra: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_usar"))
            .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", "2"])
            .args(["--duration", "10", "--quiet", "--out"])
            .arg(&out)
            .args(extra)
            .output()
            .expect("run usar")
    };
    let o = sweep(&["--stop-after", "1"]);
    assert_eq!(o.status.code(), Some(STOPPED));
    // What killed runs of this and of earlier versions leave, and files that only look alike.
    let stale = [".trials.csv.tmp-4000000", ".report.md.tmp-4000000-3"];
    let kept = ["notes.tmp-1", ".hidden", "trials.csv.tmp-5"];
    for n in stale.iter().chain(&kept) {
        fs::write(out.join(n), "x").unwrap();
    }
    // trials.csv is a link to a file elsewhere: it gets the table and stays a link.
    fs::create_dir(tmp.path().join("kept")).unwrap();
    symlink("../kept/trials.csv", out.join("trials.csv")).unwrap();

    ok(&sweep(&["--resume"]));
    let left = names(&out);
    for n in stale {
        assert!(!left.contains(&n.to_string()), "{n} left in {left:?}");
    }
    for n in kept {
        assert!(left.contains(&n.to_string()), "{n} removed");
    }
    assert!(
        !left
            .iter()
            .any(|n| n.contains(".tmp-") && n.starts_with('.'))
    );
    assert!(is_symlink(&out.join("trials.csv")));
    let table = fs::read_to_string(tmp.path().join("kept/trials.csv")).unwrap();
    assert!(table.starts_with("scenario,method,trial,seed,"), "{table}");
    assert_eq!(table.lines().count(), 1 + 4);
}

/// The regular files of `dir` but the lock (which records who held it last), with their
/// bytes, by name.
fn files_of(dir: &Path) -> Vec<(std::ffi::OsString, Vec<u8>)> {
    let mut v: Vec<_> = fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.is_file() && !p.ends_with("sweep.lock"))
        .map(|p| (p.file_name().unwrap().to_owned(), fs::read(&p).unwrap()))
        .collect();
    v.sort();
    v
}

/// A sweep of `out` whose `summary.csv` `block` makes unwritable: the resume fails with an
/// error holding `what`, every other file (trials.csv, written before summary.csv, marked)
/// stays as it was and no temporary file is left; once `unblock` ran, the resume writes them.
fn unwritable_summary_leaves_the_set(block: fn(&Path), what: &str, unblock: fn(&Path)) {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("sweep");
    let sweep = |extra: &[&str]| {
        let mut args = vec![
            "sweep",
            PAPER,
            "--trials",
            "1",
            "--duration",
            "5",
            "--methods",
            "dis",
            "--quiet",
        ];
        args.extend_from_slice(extra);
        args.push("--out");
        usar(&args, &[&out])
    };
    ok(&sweep(&[]));
    fs::write(out.join("trials.csv"), "marked\n").unwrap();
    fs::remove_file(out.join("summary.csv")).unwrap();
    block(&out);
    let before = files_of(&out);
    assert!(before.len() >= 6, "{} files", before.len());
    let o = sweep(&["--resume"]);
    assert!(!o.status.success());
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains(what), "{err}");
    assert_eq!(
        fs::read_to_string(out.join("trials.csv")).unwrap(),
        "marked\n",
        "trials.csv was rewritten before the sweep found it could not write summary.csv"
    );
    let after = files_of(&out);
    let names =
        |v: &[(std::ffi::OsString, Vec<u8>)]| v.iter().map(|f| f.0.clone()).collect::<Vec<_>>();
    assert_eq!(names(&after), names(&before));
    for ((name, a), (_, b)) in after.iter().zip(&before) {
        assert!(a == b, "{name:?} changed although the sweep wrote nothing");
    }
    unblock(&out);
    ok(&sweep(&["--resume"]));
    assert!(
        fs::read_to_string(out.join("trials.csv"))
            .unwrap()
            .starts_with("scenario,")
    );
    assert!(out.join("summary.csv").is_file());
}

#[test]
fn a_sweep_output_that_cannot_be_written_leaves_every_other_file_as_it_was() {
    // A folder where summary.csv goes: refused before any file is made.
    unwritable_summary_leaves_the_set(
        |out| fs::create_dir(out.join("summary.csv")).unwrap(),
        "is a folder",
        |out| fs::remove_dir(out.join("summary.csv")).unwrap(),
    );
    // A link to a file in a folder that cannot be made (procfs refuses it, to root too):
    // found only when the file is written, still before any file changes.
    #[cfg(target_os = "linux")]
    unwritable_summary_leaves_the_set(
        |out| symlink("/proc/usar-no-such/summary.csv", out.join("summary.csv")).unwrap(),
        "/proc/usar-no-such",
        |out| fs::remove_file(out.join("summary.csv")).unwrap(),
    );
}
