//! `usar sweep`: one writer per output folder. A second sweep, `--resume` or `--overwrite`
//! into a folder in use fails at once naming the holder's pid and touches nothing; the lock
//! of a killed sweep does not block the next one.

use crate::common;

use std::path::Path;
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

use usar_sweep::journal::read_journal;
use usar_sweep::lock::{LOCK_FILE, OutputLock};

use common::{PAPER, read};

fn sweep_cmd(out: &Path, trials: &str, duration: &str, extra: &[&str]) -> Command {
    let mut c = Command::new(env!("CARGO_BIN_EXE_usar"));
    c.args(["sweep", PAPER, "--methods", "rne,dis", "--trials", trials])
        .args(["--duration", duration, "--quiet", "--out"])
        .arg(out)
        .args(extra);
    c
}

fn sweep(out: &Path, extra: &[&str]) -> Output {
    sweep_cmd(out, "2", "10", extra).output().expect("run usar")
}

/// Asserts `o` failed because the folder is locked by `pid`, in one line, quickly.
fn assert_refused_by(o: &Output, took: Duration, pid: u32) {
    assert!(!o.status.success(), "the second sweep ran");
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("is in use by another sweep") && err.contains(&format!("(pid {pid})")),
        "{err}"
    );
    assert_eq!(err.trim_end().lines().count(), 1, "{err}");
    assert!(took < Duration::from_secs(20), "took {took:?} to refuse");
}

#[test]
fn a_locked_folder_is_refused_at_once_and_left_as_it_was() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    let o = sweep(&out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let files = ["journal.jsonl", "trials.csv", "summary.csv", "report.md"];
    let before: Vec<Vec<u8>> = files.iter().map(|f| read(&out.join(f))).collect();

    // This test process holds the lock, as a running sweep would.
    let held = OutputLock::acquire(&out).unwrap();
    for extra in [
        &[][..],
        &["--resume"],
        &["--overwrite"],
        &["--seed", "9", "--overwrite"],
    ] {
        let t0 = Instant::now();
        let o = sweep(&out, extra);
        assert_refused_by(&o, t0.elapsed(), std::process::id());
    }
    for (f, b) in files.iter().zip(&before) {
        assert!(&read(&out.join(f)) == b, "{f} changed");
    }
    drop(held);
    // Released: the same command runs again (from the journal).
    let o = sweep(&out, &[]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).contains("all 4 trials came from the journal"));
    assert!(read(&out.join("trials.csv")) == before[1]);
}

/// A child process killed when dropped, so that a failing test leaves no long sweep running.
struct KillOnDrop(Child);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

#[test]
fn two_sweeps_into_one_folder_and_a_killed_holder() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("s");
    // A long first sweep (400 trials of 600 s on one thread, minutes): still running below.
    let mut first = KillOnDrop(
        sweep_cmd(&out, "200", "600", &["--threads", "1"])
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("start usar"),
    );
    let pid = first.0.id();
    let lock = out.join(LOCK_FILE);
    let t0 = Instant::now();
    // The lock is taken before the journal's header is written: wait for both.
    let journal_path = out.join("journal.jsonl");
    while std::fs::read_to_string(&lock).ok().as_deref() != Some(&format!("{pid}\n"))
        || read_journal(&journal_path).is_err()
    {
        assert!(
            first.0.try_wait().unwrap().is_none(),
            "the first sweep ended early"
        );
        assert!(
            t0.elapsed() < Duration::from_secs(60),
            "no lock or no journal"
        );
        std::thread::sleep(Duration::from_millis(20));
    }

    // The second, even with --overwrite, is refused at once; the first's journal is intact.
    let t0 = Instant::now();
    let o = sweep(&out, &["--overwrite"]);
    assert_refused_by(&o, t0.elapsed(), pid);
    assert!(
        first.0.try_wait().unwrap().is_none(),
        "the first sweep ended before the check: test inconclusive"
    );
    let journal = read_journal(&journal_path).unwrap();
    assert_eq!(journal.header.trials, 200);
    assert!(journal.rejected.is_empty());

    // Killed, the first leaves its lock file with its pid; the next sweep is not blocked.
    first.0.kill().unwrap();
    first.0.wait().unwrap();
    assert_eq!(std::fs::read_to_string(&lock).unwrap(), format!("{pid}\n"));
    let o = sweep(&out, &["--overwrite"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let trials = String::from_utf8(read(&out.join("trials.csv"))).unwrap();
    assert_eq!(trials.lines().count(), 1 + 4);
}
