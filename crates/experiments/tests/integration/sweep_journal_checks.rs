//! `usar sweep`: a journal record edited so that it stays valid JSON is reported by line and
//! its trial runs again (the files equal an untampered run's); an edited header is refused;
//! a damaged journal names the flag that helps, `--overwrite`.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use common::{PAPER, STOPPED, ok, read, read_lines, set_journal_build, write_lines};

/// rne,dis x `trials` trials x 20 s into `out`, then `extra`.
fn sweep_of(trials: &str, out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", trials])
        .args(["--duration", "20", "--quiet", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("run usar")
}

fn sweep(out: &Path, extra: &[&str]) -> Output {
    sweep_of("2", out, extra)
}

fn err(o: &Output) -> String {
    assert!(
        !o.status.success(),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// The string or number after the first `pattern` (`"key":` with what precedes it) in a
/// journal line.
fn field<'a>(line: &'a str, pattern: &str) -> &'a str {
    let rest = &line[line.find(pattern).unwrap() + pattern.len()..];
    let end = rest.find([',', '}']).unwrap();
    rest[..end].trim_matches('"')
}

#[test]
fn an_edited_record_is_reported_and_run_again() {
    let tmp = tempfile::tempdir().unwrap();
    let (whole, parts) = (tmp.path().join("whole"), tmp.path().join("parts"));
    ok(&sweep(&whole, &["--threads", "2"]));

    let o = sweep(&parts, &["--threads", "1", "--stop-after", "3"]);
    assert_eq!(o.status.code(), Some(STOPPED));
    // Line 3 (the second record): more rescuees in the first task than it had, still valid
    // JSON.
    let journal = parts.join("journal.jsonl");
    let mut ls = read_lines(&journal);
    assert_eq!(ls.len(), 4);
    let first: u32 = field(&ls[2], "\"rescued\":[").parse().unwrap();
    let from = format!("\"rescued\":[{first},");
    assert!(ls[2].contains(&from), "{}", ls[2]);
    ls[2] = ls[2].replacen(&from, &format!("\"rescued\":[{},", first + 7), 1);
    serde_json::from_str::<serde_json::Value>(&ls[2]).expect("still valid JSON");
    let (method, trial) = (
        field(&ls[2], ",\"method\":").to_string(),
        field(&ls[2], ",\"trial\":").to_string(),
    );
    write_lines(&journal, &ls);

    let o = sweep(&parts, &["--resume"]);
    let stdout = ok(&o);
    let stderr = String::from_utf8_lossy(&o.stderr);
    assert!(
        stderr.contains(&format!(
            "journal.jsonl:3: record does not verify (edited?); trial {method} #{trial} of cell \
             0 will run again"
        )),
        "{stderr}"
    );
    assert!(stdout.contains("ran 2 trials"), "{stdout}");
    for name in ["trials.csv", "summary.csv"] {
        assert!(
            read(&whole.join(name)) == read(&parts.join(name)),
            "{name} differs from the untampered run"
        );
    }
    // The rerun's record verifies: nothing is reported or run the next time.
    let o = sweep(&parts, &["--resume"]);
    assert!(ok(&o).contains("all 4 trials came from the journal"));
    assert!(!String::from_utf8_lossy(&o.stderr).contains("does not verify"));
}

#[test]
fn an_edited_header_is_refused() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &[]));
    let journal = dir.join("journal.jsonl");
    let mut ls = read_lines(&journal);
    // Claim the journal was a 3-trial sweep, so that `--trials 3 --resume` would reuse it.
    assert!(ls[0].contains("\"trials\":2,"), "{}", ls[0]);
    ls[0] = ls[0].replace("\"trials\":2,", "\"trials\":3,");
    write_lines(&journal, &ls);
    let before = read(&journal);
    for extra in [&["--resume"][..], &[]] {
        let e = err(&sweep_of("3", &dir, extra));
        assert!(
            e.contains("journal.jsonl:1: the header does not verify (edited?)")
                && e.contains("--overwrite"),
            "{extra:?}: {e}"
        );
    }
    assert!(read(&journal) == before, "the journal was changed");
}

#[test]
fn a_damaged_journal_names_overwrite_and_overwrite_helps() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &[]));
    let journal = dir.join("journal.jsonl");
    let mut ls = read_lines(&journal);
    let half = ls[2].len() / 2;
    ls[2].truncate(half);
    write_lines(&journal, &ls);
    for extra in [&["--resume"][..], &[]] {
        let e = err(&sweep(&dir, extra));
        assert!(
            e.contains("journal.jsonl:3: not a valid journal line")
                && e.contains("--overwrite (in place of --resume)"),
            "{extra:?}: {e}"
        );
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    }
    ok(&sweep(&dir, &["--overwrite"]));
    assert_eq!(read_lines(&journal).len(), 1 + 4);
}

/// A journal path holding a FIFO or a link to a missing file: a one-line error naming
/// `--overwrite` (not a wait for a writer, nor "File exists"), and `--overwrite` replaces it.
#[cfg(unix)]
#[test]
fn a_journal_that_is_no_file_is_refused_and_overwrite_replaces_it() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    std::fs::create_dir(&dir).unwrap();
    let journal = dir.join("journal.jsonl");
    let fifo = common::make_fifo;
    let link = |p: &Path| std::os::unix::fs::symlink(tmp.path().join("gone"), p).unwrap();
    for (make, what) in [
        (&fifo as &dyn Fn(&Path), "not a regular file"),
        (&link, "a symbolic link to a missing file"),
    ] {
        make(&journal);
        for extra in [&["--resume"][..], &[]] {
            let e = err(&sweep(&dir, extra));
            assert!(
                e.contains(&format!("journal.jsonl: {what}")) && e.contains("--overwrite"),
                "{extra:?}: {e}"
            );
            assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        }
        ok(&sweep(&dir, &["--overwrite"]));
        assert_eq!(read_lines(&journal).len(), 1 + 4);
        std::fs::remove_file(&journal).unwrap();
    }
}

/// Regression (issue 70): a folder at the journal's path was refused with the advice to pass
/// `--overwrite`, which then failed with "Is a directory". Now the message, with and without
/// `--overwrite` or `--resume`, says what works (remove or move it by hand), on one line, and
/// the folder and what it holds stay.
#[test]
fn a_journal_that_is_a_folder_is_refused_with_advice_that_works() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    let journal = dir.join("journal.jsonl");
    std::fs::create_dir_all(&journal).unwrap();
    std::fs::write(journal.join("mine.txt"), "mine").unwrap();
    for extra in [&[][..], &["--resume"], &["--overwrite"]] {
        let e = err(&sweep(&dir, extra));
        assert!(
            e.contains(
                "journal.jsonl: is a folder, not a journal; move it away or remove it yourself"
            ) && !e.contains("Is a directory")
                && !e.contains("with --overwrite (in place"),
            "{extra:?}: {e}"
        );
        assert_eq!(e.trim_end().lines().count(), 1, "{e}");
        assert_eq!(read(&journal.join("mine.txt")), b"mine");
    }
    std::fs::remove_dir_all(&journal).unwrap();
    ok(&sweep(&dir, &[]));
}

/// A sweep killed while it wrote its header left no trial: the next sweep starts afresh
/// without a word. A journal that cannot be continued is refused by its own message, without
/// the advice to pass --resume, which would fail.
#[test]
fn a_cut_header_starts_afresh_and_an_unusable_journal_does_not_advise_resume() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("s");
    ok(&sweep(&dir, &[]));
    let journal = dir.join("journal.jsonl");
    let whole = read_lines(&journal);
    std::fs::write(&journal, &whole[0][..whole[0].len() / 2]).unwrap();
    ok(&sweep(&dir, &[]));
    let again = read_lines(&journal);
    assert!(
        again[0] == whole[0] && again.len() == whole.len(),
        "a new sweep of 4 trials"
    );
    let mut header = whole[0].clone();
    header.insert(header.len() - 3, '0');
    write_lines(&journal, &[header]);
    let e = err(&sweep(&dir, &[]));
    assert!(
        e.contains("journal.jsonl:1:") && e.contains("--overwrite"),
        "{e}"
    );
    assert!(!e.contains("pass --resume"), "{e}");
}

/// Regression: the journal did not record which build wrote it, so after the simulator's code
/// changed, the same command silently took every trial from the old code's journal ("all 40
/// trials came from the journal"). A journal of another build is now neither continued by the
/// same command nor by --resume; --overwrite starts afresh.
#[test]
fn a_journal_of_another_build_is_not_continued() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    ok(&sweep(&out, &[]));
    let trials = std::fs::read(out.join("trials.csv")).unwrap();
    let journal = out.join("journal.jsonl");
    set_journal_build(&journal, "0000000-other");
    let e = err(&sweep(&out, &[]));
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    assert!(
        e.contains("journal has build 0000000-other vs ")
            && e.contains("pass --overwrite")
            && !e.contains("--resume"),
        "{e}"
    );
    let e = err(&sweep(&out, &["--resume"]));
    assert!(e.contains("journal has build 0000000-other vs "), "{e}");
    let o = ok(&sweep(&out, &["--overwrite"]));
    assert!(!o.contains("came from the journal"), "{o}");
    assert_eq!(std::fs::read(out.join("trials.csv")).unwrap(), trials);
    let header = std::fs::read_to_string(&journal).unwrap();
    assert!(!header.contains("0000000-other"));
}
