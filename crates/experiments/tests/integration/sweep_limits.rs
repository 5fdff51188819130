//! Limits of `usar sweep` that a scenario file or a mistyped option must not get past: the
//! default output folder stays inside `results/` whatever the scenario's `name`, and a sweep
//! of more than `MAX_SWEEP_TRIALS` trials is a one-line error before anything is written.

use crate::common;

use std::fs;
use std::path::Path;
use std::process::Output;

use common::{PAPER, usar_in};

/// `paper.ron` with its name replaced, written to `dir/named.ron`.
fn named_copy(dir: &Path, name: &str) -> String {
    let text = fs::read_to_string(PAPER).unwrap();
    let renamed = text.replacen("name: \"paper\"", &format!("name: {name:?}"), 1);
    assert_ne!(text, renamed, "paper.ron's name line moved");
    let path = dir.join("named.ron");
    fs::write(&path, renamed).unwrap();
    path.to_string_lossy().into_owned()
}

#[test]
fn a_scenario_name_cannot_direct_the_default_output_elsewhere() {
    let tmp = tempfile::tempdir().unwrap();
    let cwd = tmp.path().join("work");
    fs::create_dir(&cwd).unwrap();
    let escape = tmp.path().join("escaped");
    for name in ["../escaped", escape.to_str().unwrap()] {
        let file = named_copy(tmp.path(), name);
        let args = ["sweep", &file, "--methods", "dis", "--trials", "1"];
        let o = usar_in(
            &cwd,
            [&args[..], &["--duration", "2", "--threads", "1"]].concat(),
        );
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        assert!(!escape.exists(), "name {name:?} wrote outside results/");
    }
    let mut folders: Vec<String> = fs::read_dir(cwd.join("results"))
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    folders.sort();
    let mut expected = [
        escape.to_string_lossy().replace('/', "_"),
        ".._escaped".into(),
    ];
    expected.sort();
    assert_eq!(folders, expected);
    assert!(cwd.join("results/.._escaped/trials.csv").is_file());
}

#[test]
fn too_many_trials_is_a_one_line_error_before_any_output() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let out_s = out.to_str().unwrap();
    for (trials, extra) in [("4294967295", None), ("300000", Some("--shard=0/100000"))] {
        let mut args = vec!["sweep", PAPER, "--trials", trials, "--out", out_s];
        args.extend(extra);
        let o = usar_in(tmp.path(), &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains("more than the limit of 1000000"), "{err}");
        assert!(!out.exists(), "{trials} trials left {}", out.display());
    }
}

/// Regression: a `--vary` grid was built cell by cell before its size was checked, so nine
/// fields of ten values (1e9 cells) aborted on a 1.17 TB allocation with a backtrace, and
/// 1,001,000 cells took over a minute and 5 GB before the one-line error. The product of the
/// value counts is now checked first, in `usar sweep` and `usar slurm` alike.
#[test]
fn a_grid_over_the_trial_limit_is_refused_before_its_cells_are_built() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let out_s = out.to_str().unwrap();
    let ten = "0,1,2,3,4,5,6,7,8,9";
    let fields = [
        "mission.pickup_s",
        "mission.recharge_s",
        "mission.low_hp_pct",
        "mission.low_energy_pct",
        "mission.energy_pct_per_m",
        "mission.hp_pct_per_step_in_radiation",
        "mission.energy_pct_per_moving_step",
        "collision.safety_margin_m",
        "navigation.clearance_m",
    ];
    let varies: Vec<String> = fields.iter().map(|f| format!("--vary={f}={ten}")).collect();
    for command in [&["sweep"][..], &["slurm", "--shards", "2"]] {
        let mut args = command.to_vec();
        args.extend([PAPER, "--trials", "1", "--methods", "rne"]);
        args.extend(["--out", out_s]);
        args.extend(varies.iter().map(String::as_str));
        let o = usar_in(tmp.path(), &args);
        let err = String::from_utf8_lossy(&o.stderr);
        assert_eq!(o.status.code(), Some(1), "{command:?}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{command:?}: {err}");
        assert!(
            err.contains("1000000000 cell(s)") && err.contains("more than the limit of 1000000"),
            "{command:?}: {err}"
        );
        assert!(!out.exists(), "{command:?} left {}", out.display());
    }
}

/// `usar sweep paper.ron` of one DIS trial of `duration` seconds on one thread into `out`,
/// with `extra` options, run in `cwd`.
fn one_dis_trial(cwd: &Path, duration: &str, extra: &[&str], out: &Path) -> Output {
    let args = [
        "sweep",
        PAPER,
        "--methods",
        "dis",
        "--trials",
        "1",
        "--duration",
        duration,
    ];
    let quiet = ["--threads", "1", "--quiet", "--out", out.to_str().unwrap()];
    let o = usar_in(cwd, [&args[..], extra, &quiet[..]].concat());
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    o
}

#[test]
fn a_duration_between_steps_is_reported_as_the_length_that_ran() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = one_dis_trial(tmp.path(), "0.03", &[], &out);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("DIS x 1 trials x 0.04 s,"), "{stdout}");
    let report = fs::read_to_string(out.join("report.md")).unwrap();
    assert!(
        report.contains("1 per method, 0.04 s of simulated time each."),
        "{report}"
    );
    // A grid whose cells' steps differ: each cell's report gives its own length, and the
    // header does not claim the cells ran their mission.duration_s.
    let grid = tmp.path().join("grid");
    let o = one_dis_trial(tmp.path(), "1", &["--vary", "sim.dt_s=0.02,0.03"], &grid);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        stdout.contains("DIS x 1 trials x --duration 1 s in whole steps of each cell's sim.dt_s,"),
        "{stdout}"
    );
    let cell = fs::read_to_string(grid.join("c01_dt_s=0.03/report.md")).unwrap();
    assert!(
        cell.contains("1 per method, 1.02 s of simulated time each."),
        "{cell}"
    );
}

/// One trial per method: the claims (paper.ron's `report: (claims: ...)`, paired) say why
/// they were not tested (they said `max p = n/a`).
#[test]
fn one_trial_per_method_says_why_claims_have_no_p() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let o = usar_in(
        dir.path(),
        [
            "sweep",
            PAPER,
            "--trials",
            "1",
            "--duration",
            "4",
            "--quiet",
            "--threads",
            "1",
            "--out",
            out.to_str().unwrap(),
        ],
    );
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let claims: Vec<&str> = text.lines().filter(|l| l.starts_with("  (")).collect();
    assert_eq!(claims.len(), 5, "{text}");
    // The paired claims need 2 pairs of trials; in 4 s nobody rescues anyone in the hard
    // task: the costs per hard rescuee have no value, and those claims say so instead.
    for line in claims {
        assert!(
            line.contains(" have 1 trial(s) in common with a value of rescued_")
                && line.ends_with(": the paired t-test needs at least 2 pairs of trials)")
                || line.ends_with(
                    "not tested (no trial of RNE has a value of energy_per_hard_rescuee_pct)"
                )
                || line.ends_with(
                    "not tested (no trial of RNE has a value of hp_per_hard_rescuee_pct)"
                ),
            "{line}"
        );
    }
}
