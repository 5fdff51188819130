//! End-to-end tests of `usar replay` and `usar sweep --replay` (runs the built binary).

use crate::common;

use std::path::{Path, PathBuf};
use std::process::Output;

use common::{PAPER, stderr, text, usar};

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn sweep(out: &Path, extra: &[&str]) -> Output {
    let mut args = vec![
        "sweep",
        "--methods",
        "rne,dis",
        "--trials",
        "2",
        "--duration",
        "8",
        "--quiet",
        "--out",
        text(out),
    ];
    args.insert(1, PAPER);
    args.extend_from_slice(extra);
    usar(&args)
}

fn replay(method: &str, trial: &str, out: &Path) -> Vec<u8> {
    let o = usar([
        "replay",
        PAPER,
        "--method",
        method,
        "--trial",
        trial,
        "--duration",
        "8",
        "--out",
        text(out),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    std::fs::read(out).expect("replay written")
}

/// The sweep's replays are of the sweep's own trials: byte for byte the pages `usar replay`
/// writes for the same trials. Run again (the journal has every trial), the trials are run
/// once more for their replays, with the same bytes.
#[test]
fn sweep_replays_are_the_sweeps_trials_and_survive_a_rerun() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("sweep");
    let o = sweep(&out, &["--replay", "rne:0,DIS:1"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let printed = stdout(&o);
    for f in ["replay-rne-0.html", "replay-dis-1.html"] {
        assert!(printed.contains(f), "{printed}");
    }
    assert!(!printed.contains("run again"), "{printed}");
    let sweep_rne = std::fs::read(out.join("replay-rne-0.html")).expect("rne replay");
    let sweep_dis = std::fs::read(out.join("replay-dis-1.html")).expect("dis replay");
    assert_eq!(sweep_rne, replay("rne", "0", &dir.path().join("rne.html")));
    assert_eq!(sweep_dis, replay("dis", "1", &dir.path().join("dis.html")));
    assert!(!out.join("replay-rne-1.html").exists());

    let again = sweep(&out, &["--replay", "rne:0"]);
    assert!(again.status.success(), "{}", stderr(&again));
    assert!(
        stdout(&again).contains("trial run again for it: it was in the journal"),
        "{}",
        stdout(&again)
    );
    assert_eq!(
        std::fs::read(out.join("replay-rne-0.html")).expect("rne"),
        sweep_rne
    );
}

/// A `--replay` naming no trial of the sweep is a one-line error before any trial runs (no
/// journal is written).
#[test]
fn bad_replay_lists_are_refused_before_any_trial_runs() {
    let dir = tempfile::tempdir().expect("temp dir");
    for (arg, says) in [
        ("eng:0", "the sweep runs no method \"eng\""),
        (
            "rne:2",
            "trial 2 is out of range (the sweep runs trials 0 to 1)",
        ),
        ("rne", "expected METHOD:TRIAL"),
    ] {
        let out = dir.path().join(arg.replace(':', "_"));
        let o = sweep(&out, &["--replay", arg]);
        assert!(!o.status.success(), "--replay {arg} accepted");
        let err = stderr(&o);
        assert!(err.contains(says), "--replay {arg}: {err}");
        assert_eq!(err.trim().lines().count(), 1, "{err}");
        assert!(
            !out.join("journal.jsonl").exists(),
            "--replay {arg} ran trials"
        );
    }
    let o = sweep(
        &dir.path().join("shard"),
        &["--replay", "rne:0", "--shard", "0/2"],
    );
    assert!(!o.status.success());
    assert!(stderr(&o).contains("--shard"), "{}", stderr(&o));
}

#[test]
fn usar_replay_refuses_bad_options_with_one_line() {
    let dir = tempfile::tempdir().expect("temp dir");
    let page = dir.path().join("r.html");
    for (args, says) in [
        (vec!["--hz", "0"], "--hz: sampling rate 0 Hz"),
        (vec!["--method", "nope"], "nope"),
        (vec!["--duration", "-1"], "duration"),
        // A seed is used as is: a trial index with it would label the page wrongly.
        (vec!["--seed", "3", "--trial", "2"], "cannot be used with"),
    ] {
        let mut all = vec!["replay", "--out", text(&page)];
        all.insert(1, PAPER);
        all.extend(args.iter().copied());
        let o = usar(&all);
        assert!(!o.status.success(), "{args:?} accepted");
        assert!(stderr(&o).contains(says), "{args:?}: {}", stderr(&o));
        assert!(!page.exists());
    }
    let o = usar(["replay", "no-such.ron", "--out", text(&page)]);
    assert!(!o.status.success());
    assert!(stderr(&o).contains("no-such.ron"));
    // The sweep's option is named as the sweep spells it.
    let o = sweep(
        &dir.path().join("s"),
        &["--replay", "rne:0", "--replay-hz", "0"],
    );
    assert!(!o.status.success());
    let err = stderr(&o);
    assert!(err.contains("--replay-hz: sampling rate 0 Hz"), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
}

#[test]
fn grid_sweeps_write_a_replay_in_every_cell() {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = dir.path().join("grid");
    let o = sweep(
        &out,
        &[
            "--vary",
            "mission.hp_pct_per_step_in_radiation=0.0003,0.003",
            "--replay",
            "dis:0",
        ],
    );
    assert!(o.status.success(), "{}", stderr(&o));
    let cells: Vec<PathBuf> = std::fs::read_dir(&out)
        .expect("grid folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.is_dir()
                && p.file_name()
                    .is_some_and(|n| n.to_string_lossy().starts_with('c'))
        })
        .collect();
    assert_eq!(cells.len(), 2, "{cells:?}");
    for c in cells {
        assert!(c.join("replay-dis-0.html").is_file(), "{}", c.display());
    }
}

/// The summary gives the rate used with three significant digits (it printed
/// `2.941176470588235 samples/s` for `--hz 3`, which samples every 17th step of 0.02 s).
#[test]
fn the_summary_rounds_the_rate_used() {
    let dir = tempfile::tempdir().expect("temp dir");
    let page = dir.path().join("r.html");
    let o = usar([
        "replay",
        PAPER,
        "--duration",
        "4",
        "--hz",
        "3",
        "--out",
        text(&page),
    ]);
    assert!(o.status.success(), "{}", stderr(&o));
    assert!(
        stdout(&o).contains(", 4.0 s at 2.94 samples/s, "),
        "{}",
        stdout(&o)
    );
}
