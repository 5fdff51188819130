//! Reports that fit the scenario: `report.md`, `grid.md` and the terminal summary compare with
//! calibration targets only with `--targets FILE` and check the paper's claims only with
//! `--claims`, for `scenarios/three-tasks.ron` and for a user's own scenario whose tasks
//! happen to be named `easy` and `hard`. The options are outputs, not inputs: changing them
//! on a journaled sweep re-renders its reports without running a trial again; a sharded
//! sweep records them for `usar merge`.

use crate::common;

use std::path::Path;

use common::{journal_trials, ok, read_text, stderr, text, usar};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// A user's own scenario written from the docs: five robots, two tasks named `easy` and
/// `hard` (so the paper's claims and targets could be computed for it, but nobody asked).
const USER_SCENARIO: &str = r#"Scenario(
    name: "my-site",
    description: "Five robots, two rooms.",
    arena: (width_m: 30.0, height_m: 20.0),
    kinds: [
        (name: "ugv", role: Carrier, locomotion: Ground, count: 3, quota: (easy: 2, hard: 1),
         body_radius_m: 0.4, max_speed_m_per_s: 1.5, sensing_range_m: 3.0,
         observing_range_m: 0.5, carrying_capacity: 2, rescuing_resources: 2,
         hp_needs_full: 2.0, energy_needs_full: 1.5,
         starts: Row(first_m: (12.0, 2.0), step_m: (2.0, 0.0))),
        (name: "drone", role: Observer, locomotion: Aerial, count: 2, quota: (easy: 1, hard: 1),
         body_radius_m: 0.3, max_speed_m_per_s: 2.0, sensing_range_m: 8.0,
         observing_range_m: 10.0, carrying_capacity: 0, rescuing_resources: 0,
         hp_needs_full: 1.0, energy_needs_full: 1.0,
         starts: Row(first_m: (13.0, 4.0), step_m: (2.0, 0.0))),
    ],
    rest_station: (center_m: (25.0, 3.0), radius_m: 1.5),
    tasks: [
        (name: "easy", search_area: (min_m: (18.0, 12.0), max_m: (26.0, 18.0)),
         goal_m: (22.0, 15.0), drop_off: (center_m: (20.0, 8.0), radius_m: 2.0),
         rescuees: Grid(spacing_m: 2.0, margin_m: 0.5)),
        (name: "hard", search_area: (min_m: (3.0, 12.0), max_m: (11.0, 18.0)),
         goal_m: (7.0, 15.0), drop_off: (center_m: (8.0, 8.0), radius_m: 2.0),
         rescuees: Grid(spacing_m: 2.0, margin_m: 0.5)),
    ],
    radiation_zones: [(center_m: (7.0, 11.0), radius_m: 2.0)],
    mission: (duration_s: 60.0),
)
"#;

fn paper_targets() -> String {
    format!("{ROOT}/scenarios/paper-targets.ron")
}

fn paper_claims() -> String {
    format!("{ROOT}/scenarios/paper-claims.ron")
}

/// Claims of a user's own for [`USER_SCENARIO`]: nothing of the paper's.
const USER_CLAIMS: &str = r#"Claims(claims: [
    (id: "dis-easy", sentence: "DIS rescues more in room easy than RNE", subject: "DIS",
     rivals: Only(["rne"]), metric: "rescued_easy", direction: More),
])
"#;

/// `usar sweep SCENARIO` of rne,dis x 2 trials x 4 s into `out`, then `extra`; succeeds.
fn sweep(scenario: &str, out: &Path, extra: &[&str]) -> String {
    let mut args = vec![
        "sweep",
        scenario,
        "--methods",
        "rne,dis",
        "--trials",
        "2",
        "--duration",
        "4",
        "--quiet",
        "--threads",
        "2",
        "--out",
        text(out),
    ];
    args.extend_from_slice(extra);
    ok(&usar(&args))
}

/// Whether a report (or summary) `text` has the pooled statistics and the claims.
fn sections(text: &str) -> (bool, bool) {
    let pooled = text.contains("# Pooled statistics") || text.contains("pooled statistics against");
    let claims = text.contains("## Claims") || text.contains("\nclaims of ");
    (pooled, claims)
}

/// A report without targets or claims: nothing about the paper but one line on how to ask.
fn assert_plain(report: &str) {
    assert_eq!(sections(report), (false, false), "{report}");
    for absent in [
        "n/a **out**",
        "Not applicable",
        "**out**",
        "calibrated against",
    ] {
        assert!(!report.contains(absent), "{absent:?} in\n{report}");
    }
    let asks: Vec<&str> = report
        .lines()
        .filter(|l| l.contains("--targets FILE"))
        .collect();
    assert_eq!(asks.len(), 1, "{report}");
    assert!(asks[0].contains("`--claims FILE`"), "{}", asks[0]);
}

/// Default, then both options on the same folder (all trials from the journal), then
/// without them again: the sections come and go, the journal keeps its trials.
fn sections_follow_the_options(scenario: &str) {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let summary = sweep(scenario, &out, &[]);
    assert_eq!(sections(&summary), (false, false), "{summary}");
    assert_plain(&read_text(&out.join("report.md")));

    let (targets, claims) = (paper_targets(), paper_claims());
    let summary = sweep(
        scenario,
        &out,
        &["--targets", &targets, "--claims", &claims],
    );
    assert!(
        summary.contains("all 4 trials came from the journal"),
        "{summary}"
    );
    assert_eq!(journal_trials(&out), 4);
    assert!(
        summary.contains(&format!("pooled statistics against {targets}: ")),
        "{summary}"
    );
    assert_eq!(sections(&summary), (true, true), "{summary}");
    let report = read_text(&out.join("report.md"));
    assert_eq!(sections(&report), (true, true), "{report}");
    assert!(
        report.contains(&format!("the targets of `{targets}`")),
        "{report}"
    );
    assert!(!report.contains("n/a **out**"), "{report}");
    assert!(!report.contains("--targets FILE"), "{report}");

    // Only the claims: the line asks for the targets alone.
    let summary = sweep(scenario, &out, &["--claims", &claims]);
    assert!(summary.contains("all 4 trials came from the journal"));
    let report = read_text(&out.join("report.md"));
    assert_eq!(sections(&report), (false, true), "{report}");
    assert!(report.contains("--targets FILE") && !report.contains("`--claims FILE`"));

    sweep(scenario, &out, &[]);
    assert_plain(&read_text(&out.join("report.md")));
    assert_eq!(journal_trials(&out), 4);
}

#[test]
fn three_tasks_reports_say_nothing_of_the_paper_unless_asked() {
    sections_follow_the_options(&format!("{ROOT}/scenarios/three-tasks.ron"));
}

#[test]
fn a_user_scenario_with_easy_and_hard_tasks_is_not_held_to_the_paper() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("my-site.ron");
    std::fs::write(&path, USER_SCENARIO).unwrap();
    sections_follow_the_options(text(&path));
}

#[test]
fn grid_reports_show_the_sections_only_when_asked() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("my-site.ron");
    std::fs::write(&path, USER_SCENARIO).unwrap();
    let out = tmp.path().join("grid");
    let vary = ["--vary", "mission.pickup_s=0,1"];
    let summary = sweep(text(&path), &out, &vary);
    assert_eq!(sections(&summary), (false, false), "{summary}");
    let grid = read_text(&out.join("grid.md"));
    assert_eq!(sections(&grid), (false, false), "{grid}");
    assert!(!grid.contains("n/a !"), "{grid}");
    assert_eq!(grid.matches("--targets FILE").count(), 1, "{grid}");
    let cell = out.join("c00_pickup_s=0").join("report.md");
    assert_plain(&read_text(&cell));

    let targets = paper_targets();
    let mut asked = vary.to_vec();
    let claims = paper_claims();
    asked.extend(["--targets", &targets, "--claims", &claims]);
    let summary = sweep(text(&path), &out, &asked);
    assert!(
        summary.contains("all 8 trials came from the journal"),
        "{summary}"
    );
    assert!(
        summary.contains("(grid.md): cell 0: ") && summary.contains("; cell 1: "),
        "{summary}"
    );
    let grid = read_text(&out.join("grid.md"));
    assert_eq!(sections(&grid), (true, true), "{grid}");
    assert!(!grid.contains("--targets FILE"), "{grid}");
    assert_eq!(sections(&read_text(&cell)), (true, true));
}

#[test]
fn a_merge_renders_with_the_options_its_shards_were_given() {
    let tmp = tempfile::tempdir().unwrap();
    let path = tmp.path().join("my-site.ron");
    std::fs::write(&path, USER_SCENARIO).unwrap();
    let (targets, claims) = (paper_targets(), paper_claims());
    let out = tmp.path().join("big");
    for shard in ["0/2", "1/2"] {
        sweep(
            text(&path),
            &out,
            &["--claims", &claims, "--targets", &targets, "--shard", shard],
        );
    }
    let merged = ok(&common::merge(&out));
    assert_eq!(sections(&merged), (true, true), "{merged}");
    assert_eq!(sections(&read_text(&out.join("report.md"))), (true, true));

    // Shards without options; the merge's own --claims adds the claims only.
    let plain = tmp.path().join("plain");
    for shard in ["0/2", "1/2"] {
        sweep(text(&path), &plain, &["--shard", shard]);
    }
    ok(&common::merge(&plain));
    assert_plain(&read_text(&plain.join("report.md")));
    ok(&usar(["merge", text(&plain), "--claims", &claims]));
    assert_eq!(
        sections(&read_text(&plain.join("report.md"))),
        (false, true)
    );
}

#[test]
fn targets_for_tasks_the_scenario_lacks_are_refused_before_any_trial() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("out");
    let o = usar([
        "sweep",
        &format!("{ROOT}/tests/data/one-task.ron"),
        "--trials",
        "1",
        "--duration",
        "1",
        "--quiet",
        "--out",
        text(&out),
        "--targets",
        &paper_targets(),
    ]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("error: --targets: ")
            && err.contains("paper-targets.ron:")
            && err.contains("one-task.ron"),
        "{err}"
    );
    assert!(!out.join("journal.jsonl").exists());
}

/// A scenario's `report` section asks for the sections itself: paper.ron names its targets
/// and claims files (relative to its folder), so its plain sweep checks both; a user's
/// scenario that names a claims file of its own gets those claims only, nothing of the
/// paper's.
#[test]
fn the_scenarios_report_section_asks_for_the_sections() {
    let tmp = tempfile::tempdir().unwrap();
    let paper = format!("{ROOT}/scenarios/paper.ron");
    let out = tmp.path().join("paper");
    sweep(&paper, &out, &[]);
    let report = read_text(&out.join("report.md"));
    assert_eq!(sections(&report), (true, true), "{report}");

    let file = tmp.path().join("claims-only.ron");
    let asked = USER_SCENARIO.replace(
        "    mission: (duration_s: 60.0),\n",
        "    mission: (duration_s: 60.0),\n    report: (claims: \"mine.ron\"),\n",
    );
    assert_ne!(asked, USER_SCENARIO);
    std::fs::write(&file, asked).unwrap();
    std::fs::write(tmp.path().join("mine.ron"), USER_CLAIMS).unwrap();
    let out = tmp.path().join("mine");
    let summary = sweep(text(&file), &out, &[]);
    let report = read_text(&out.join("report.md"));
    assert_eq!(sections(&report), (false, true), "{report}");
    for text in [&report, &summary] {
        assert!(
            text.contains("(dis-easy) DIS rescues more in room easy than RNE"),
            "{text}"
        );
        assert!(
            !text.contains("(4b)") && !text.contains("hard task"),
            "{text}"
        );
    }
    let section = &report[report.find("### (dis-easy)").expect("its section")..];
    assert!(section.contains("| vs | other's mean"), "{report}");
    assert_eq!(section.matches("\n| RNE | ").count(), 1, "{section}");
}

/// A copy of paper.ron in a folder without `paper-targets.ron` and `paper-claims.ron` still
/// sweeps: a one-line warning names each missing file, and the reports leave out the bands
/// and the claims (`--claims FILE` brings the claims back).
#[test]
fn a_copy_of_the_paper_elsewhere_sweeps_without_its_targets_file() {
    let tmp = tempfile::tempdir().unwrap();
    let copy = tmp.path().join("paper.ron");
    std::fs::copy(format!("{ROOT}/scenarios/paper.ron"), &copy).unwrap();
    let out = tmp.path().join("out");
    let run = usar([
        "sweep",
        text(&copy),
        "--methods",
        "rne",
        "--trials",
        "1",
        "--duration",
        "4",
        "--quiet",
        "--out",
        text(&out),
    ]);
    let warning = stderr(&run);
    ok(&run);
    assert!(
        warning.contains("report.targets:") && warning.contains("paper-targets.ron not found"),
        "{warning}"
    );
    assert!(
        warning.contains("report.claims:") && warning.contains("paper-claims.ron not found"),
        "{warning}"
    );
    assert_eq!(warning.lines().count(), 2, "{warning}");
    let report = read_text(&out.join("report.md"));
    assert_eq!(sections(&report), (false, false), "{report}");
}
