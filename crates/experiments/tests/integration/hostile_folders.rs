//! Output folders tampered with (issue 70): a shard's `plan.json` or a multiverse's
//! `multiverse.json` that is a link to `/dev/zero`, a FIFO or a huge file is refused in one
//! line naming it (`usar merge` once read `/dev/zero` until 8 GB); a manifest
//! (`usar-owner.json`) edited to name another kind of run is refused with what contradicts
//! it, and nothing is removed (`--overwrite` once deleted a merged sweep's tables); a shard
//! folder with an invalid name is refused with the valid form; an OS error is printed once.

use crate::common;

use std::path::Path;
use std::process::Output;

use common::{
    CORRIDOR, merge, multiverse_args, ok, sharded_sweep, snapshot, stderr, text, usar, usar_within,
};
use usar_sweep::bounded_file::{MAX_MULTIVERSE_PLAN_BYTES, MAX_SHARD_PLAN_BYTES};

/// `usar sweep --vary --overwrite` of corridor.ron into `out` (refused in every test here).
fn grid_overwrite(out: &Path) -> Output {
    usar([
        "sweep",
        CORRIDOR,
        "--vary",
        "mission.pickup_s=1,2",
        "--methods",
        "rne",
        "--trials",
        "1",
        "--duration",
        "2",
        "--quiet",
        "--overwrite",
        "--out",
        text(out),
    ])
}

/// `usar multiverse` of corridor.ron into `out`, with `--overwrite` if `overwrite` (a tiny
/// one: every test here expects it refused before it runs).
fn multiverse(out: &Path, overwrite: bool) -> Output {
    let mut args = multiverse_args(out);
    if overwrite {
        args.push("--overwrite");
    }
    usar_within(60, args)
}

/// The one-line error of the failed `o`.
fn one_line_error(o: &Output) -> String {
    let e = stderr(o);
    assert!(!o.status.success(), "accepted: {e}");
    assert_eq!(e.trim_end().lines().count(), 1, "{e}");
    e
}

/// Replaces the file at `path` by a link to `/dev/zero`, a FIFO, then a sparse file of
/// `limit + 1` bytes, and asserts that `run` refuses each in one line naming `path`.
#[cfg(unix)]
fn refused_in_every_form(path: &Path, limit: u64, run: &dyn Fn() -> Output) {
    let name = text(path);
    let fifo = common::make_fifo;
    let zero = |p: &Path| std::os::unix::fs::symlink("/dev/zero", p).unwrap();
    let huge = |p: &Path| {
        std::fs::File::create(p)
            .unwrap()
            .set_len(limit + 1)
            .unwrap()
    };
    for (make, says) in [
        (&zero as &dyn Fn(&Path), "not a regular file".to_string()),
        (&fifo, "not a regular file".to_string()),
        (&huge, format!("longer than the limit of {limit} bytes")),
    ] {
        let _ = std::fs::remove_file(path);
        make(path);
        let e = one_line_error(&run());
        assert!(
            e.contains(&format!("cannot read {name}: ")) && e.contains(&says),
            "{e}"
        );
    }
}

#[cfg(unix)]
#[test]
fn a_shard_plan_that_is_no_small_file_is_refused_by_name() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("S");
    sharded_sweep(&dir);
    let plan = dir.join("shards/0-of-2/plan.json");
    refused_in_every_form(&plan, MAX_SHARD_PLAN_BYTES, &|| {
        usar_within(30, ["merge", text(&dir)])
    });
}

#[cfg(unix)]
#[test]
fn a_multiverse_plan_that_is_no_small_file_is_refused_by_name() {
    let tmp = tempfile::tempdir().unwrap();
    let owner = "{\"tool\":\"usar\",\"kind\":\"multiverse\",\"format\":1}\n";
    // At the top: a merge, and a run into the folder.
    let top = tmp.path().join("M");
    std::fs::create_dir(&top).unwrap();
    std::fs::write(top.join("usar-owner.json"), owner).unwrap();
    let plan = top.join("multiverse.json");
    refused_in_every_form(&plan, MAX_MULTIVERSE_PLAN_BYTES, &|| {
        usar_within(30, ["merge", text(&top)])
    });
    refused_in_every_form(&plan, MAX_MULTIVERSE_PLAN_BYTES, &|| {
        multiverse(&top, false)
    });
    // In a shard's folder.
    let sharded = tmp.path().join("N");
    let shard = sharded.join("shards/1-of-2");
    std::fs::create_dir_all(&shard).unwrap();
    std::fs::write(sharded.join("usar-owner.json"), owner).unwrap();
    std::fs::write(shard.join("usar-owner.json"), owner).unwrap();
    refused_in_every_form(
        &shard.join("multiverse.json"),
        MAX_MULTIVERSE_PLAN_BYTES,
        &|| usar_within(30, ["merge", text(&sharded)]),
    );
}

/// Asserts that `o` was refused because the manifest of `dir` says `said` while `evidence`
/// (under `dir`) shows `found`.
fn contradicted(o: &Output, dir: &Path, said: &str, evidence: &str, found: &str) {
    let e = one_line_error(o);
    let manifest = text(&dir.join("usar-owner.json")).to_owned();
    let evidence = text(&dir.join(evidence)).to_owned();
    assert!(
        e.contains(&format!(
            "{manifest} says the folder holds a {said}, but {evidence} shows a {found}"
        )) && e.contains("nothing was changed"),
        "{e}"
    );
}

#[test]
fn a_manifest_forged_to_another_kind_is_refused_and_nothing_is_removed() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("S");
    sharded_sweep(&dir);
    let manifest = dir.join("usar-owner.json");
    for forged in ["grid", "multiverse", "sweep", "calibration"] {
        std::fs::write(
            &manifest,
            format!("{{\"tool\":\"usar\",\"kind\":\"{forged}\",\"format\":1}}\n"),
        )
        .unwrap();
        let before = snapshot(&dir);
        for f in ["trials.csv", "summary.csv", "report.md", "trials_long.csv"] {
            assert!(before.contains_key(Path::new(f)), "no {f}");
        }
        let grid = grid_overwrite(&dir);
        let shard_manifest = "shards/0-of-2/usar-owner.json";
        contradicted(&grid, &dir, forged, shard_manifest, "sharded sweep");
        assert_eq!(snapshot(&dir), before, "forged to {forged}");
        contradicted(
            &multiverse(&dir, true),
            &dir,
            forged,
            shard_manifest,
            "sharded sweep",
        );
        assert_eq!(snapshot(&dir), before, "forged to {forged}");
    }
    // A multiverse's folder whose manifest is forged to a grid: its plan contradicts it.
    let m = tmp.path().join("M");
    std::fs::create_dir(&m).unwrap();
    std::fs::write(m.join("multiverse.json"), "{}").unwrap();
    std::fs::write(m.join("multiverse.md"), "mine").unwrap();
    std::fs::write(
        m.join("usar-owner.json"),
        "{\"tool\":\"usar\",\"kind\":\"grid\",\"format\":1}\n",
    )
    .unwrap();
    let before = snapshot(&m);
    let grid = grid_overwrite(&m);
    contradicted(&grid, &m, "grid", "multiverse.json", "multiverse");
    assert_eq!(snapshot(&m), before);
}

#[test]
fn a_misnamed_shard_folder_is_refused_with_the_valid_form() {
    let tmp = tempfile::tempdir().unwrap();
    let dir = tmp.path().join("S");
    sharded_sweep(&dir);
    for bad in ["2-of-2", "0-of-0", "1-of-02", "shard-1"] {
        let folder = dir.join("shards").join(bad);
        std::fs::create_dir(&folder).unwrap();
        let before = snapshot(&dir);
        for o in [merge(&dir), multiverse(&dir, true)] {
            let e = one_line_error(&o);
            assert!(
                e.contains(&format!("{}: not a shard's folder name", text(&folder)))
                    && e.contains("a shard's folder is named <I>-of-<N>"),
                "{bad}: {e}"
            );
        }
        assert_eq!(snapshot(&dir), before, "{bad}");
        std::fs::remove_dir(&folder).unwrap();
    }
    // A user's file there, or a hidden one, is no shard and no error.
    std::fs::write(dir.join("shards/notes.txt"), "mine").unwrap();
    std::fs::create_dir(dir.join("shards/.cache")).unwrap();
    ok(&merge(&dir));
}

/// Whether a part of the error line (between `: `) comes twice in a row.
fn repeats_a_part(e: &str) -> bool {
    let parts: Vec<&str> = e.trim_end().split(": ").collect();
    parts.windows(2).any(|w| w[0] == w[1])
}

/// Regression (issue 70): an error that formatted its cause into its message and also
/// returned it as its source printed the system's text twice ("stream did not contain valid
/// UTF-8: stream did not contain valid UTF-8").
#[test]
fn an_os_error_is_printed_once() {
    let tmp = tempfile::tempdir().unwrap();
    let bytes: &[u8] = b"\xff\xfe(";
    let out = tmp.path().join("O");
    std::fs::create_dir(&out).unwrap();
    std::fs::write(out.join("usar-owner.json"), bytes).unwrap();
    let e = one_line_error(&usar([
        "sweep",
        CORRIDOR,
        "--trials",
        "1",
        "--duration",
        "1",
        "--quiet",
        "--out",
        text(&out),
    ]));
    assert_eq!(e.matches("did not contain valid UTF-8").count(), 1, "{e}");
    assert!(e.contains("usar-owner.json"), "{e}");
    let bad = tmp.path().join("bad.ron");
    std::fs::write(&bad, bytes).unwrap();
    let out = tmp.path().join("P");
    for args in [
        &["run", text(&bad)][..],
        &["check", text(&bad)],
        &[
            "sweep",
            CORRIDOR,
            "--claims",
            text(&bad),
            "--out",
            text(&out),
        ],
        &[
            "sweep",
            CORRIDOR,
            "--targets",
            text(&bad),
            "--out",
            text(&out),
        ],
    ] {
        let e = one_line_error(&usar(args));
        assert!(
            e.contains("bad.ron") && !repeats_a_part(&e),
            "{args:?}: {e}"
        );
    }
}
