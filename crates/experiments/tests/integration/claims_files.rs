//! Claims files (`--claims FILE`, a scenario's `report: (claims: ...)`): the paper's file
//! gives the verdicts the built-in claims gave; a user's three-task scenario with claims of its
//! own gets those verdicts, specification curves and shares and nothing of the paper's; bad
//! files get one line naming the file, line, column and field.

use crate::common;

use std::path::Path;

use common::{ok, read_text, stderr, text, usar, usar_in};

const ROOT: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../..");

/// The claim lines of paper.ron's report (4 methods x 4 trials x 200 s) as the built-in claims
/// wrote them, before claims became a file: headers with verdicts, the subject's mean and every
/// comparison row.
const BEFORE: &str = include_str!("../data/paper-claims-verdicts-4x200s.txt");

/// The lines of `report` that [`BEFORE`] holds.
fn claim_lines(report: &str) -> Vec<&str> {
    let start = report.find("## Claims").expect("a claims section");
    let end = report[start..]
        .find("\n## Figures")
        .expect("figures after it")
        + start;
    report[start..end]
        .lines()
        .filter(|l| {
            l.starts_with("### (")
                || ["| RNE |", "| DIS |", "| ENG |", "| HP_DIS |"]
                    .iter()
                    .any(|p| l.starts_with(p))
                || (l.starts_with("RNE ") || l.starts_with("DIS ")) && l.ends_with(").")
        })
        .collect()
}

#[test]
fn the_paper_claims_file_gives_the_verdicts_of_the_built_in_claims() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("paper");
    // The built-in claims ran on paper.ron of then: paper-v1.ron's model (its steering,
    // `collision.steering: Memoryless`, the default before issue 70; its rules before the
    // authors' clock of issue 71) stepped near contacts, and the paper's claims file.
    let paper = std::fs::read_to_string(format!("{ROOT}/scenarios/paper-v1.ron")).unwrap();
    let before = "sim: (dt_s: 0.02, seed: 2021)";
    assert!(paper.contains(before), "paper-v1.ron's sim section moved");
    let then = paper.replacen(
        before,
        "sim: (dt_s: 0.02, seed: 2021, physics: NearContacts)",
        1,
    );
    let scenario = tmp.path().join("paper.ron");
    std::fs::write(&scenario, then).unwrap();
    // The built-in claims were judged by Welch's test, unpaired: the paper's claims file with
    // `test: Welch` (its claims are paired since issue 71).
    let paired = std::fs::read_to_string(format!("{ROOT}/scenarios/paper-claims.ron")).unwrap();
    assert_eq!(paired.matches("test: PairedT,").count(), 5);
    let claims = tmp.path().join("paper-claims-welch.ron");
    std::fs::write(&claims, paired.replace("test: PairedT,", "test: Welch,")).unwrap();
    ok(&usar([
        "sweep",
        text(&scenario),
        "--claims",
        text(&claims),
        "--trials",
        "4",
        "--duration",
        "200",
        "--quiet",
        "--out",
        text(&out),
    ]));
    let report = read_text(&out.join("report.md"));
    let want: Vec<&str> = BEFORE.lines().collect();
    assert_eq!(want.len(), 25);
    assert_eq!(claim_lines(&report), want);
}

/// paper.ron's claims are paired (issue 71): the terminal and report.md name the paired
/// t-test and its pairs, and each claim's table has the pairs and the unpaired Welch p.
#[test]
fn the_paper_claims_are_judged_paired_and_say_so() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("paper");
    let printed = ok(&usar([
        "sweep",
        common::PAPER,
        "--trials",
        "3",
        "--duration",
        "200",
        "--out",
        text(&out),
    ]));
    let lines: Vec<&str> = printed.lines().filter(|l| l.starts_with("  (")).collect();
    assert_eq!(lines.len(), 5, "{printed}");
    for line in &lines {
        assert!(
            line.contains(" (paired t-test over 3 pairs of trials, max p = ")
                || line.contains("not tested ("),
            "{line}"
        );
    }
    assert!(lines[0].contains("paired t-test over 3 pairs"), "{printed}");
    let report = read_text(&out.join("report.md"));
    assert!(
        report.contains(
            "| (1) RNE rescues the most in total | one-sided paired t-test over 3 pairs of \
             trials, alpha 0.05 | **"
        ),
        "{report}"
    );
    assert!(report.contains(
        "Paired (paired t-test over 3 pairs of trials): trial k of RNE against trial k of each \
         rival, on the same draws."
    ));
    assert!(report.contains(
        "| vs | other's mean ± sd (n) | pairs | mean paired difference | paired t (dof) | p | \
         Wilcoxon W+ | p | p(reverse) | Welch p (unpaired) |"
    ));
    assert!(report.contains("| DIS | "), "{report}");
}

/// A user's three-task scenario (scenarios/three-tasks.ron: tasks hard, medium, easy).
const THREE_TASKS: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/../../scenarios/three-tasks.ron"
);

/// Claims of the user's own about the three tasks, one with a list of rivals, a
/// Mann-Whitney test and Holm's correction.
const USER_CLAIMS: &str = r#"// My claims about three-tasks.ron.
Claims(
    claims: [
        (
            id: "medium-rne",
            sentence: "RNE rescues more in the medium task than DIS",
            subject: "rne",
            rivals: Only(["DIS"]),
            metric: "rescued_medium",
            direction: More,
        ),
        (
            id: "cheap-dis",
            sentence: "DIS spends the least energy per rescuee in total",
            subject: "DIS",
            metric: "energy_per_rescuee_pct",
            direction: Less,
            test: MannWhitney,
            alpha: 0.1,
            correction: Holm,
        ),
    ],
)
"#;

/// Axes of a tiny multiverse over three-tasks.ron: two universes.
const USER_AXES: &str = r#"Axes(axes: [(name: "pickup", alternatives: [
    (name: "as given"),
    (name: "slow", set: ["mission.pickup_s=3"]),
])])"#;

/// A target every universe reaches.
const USER_TARGETS: &str = r#"Targets(targets: [
    (name: "rescuees", statistic: Mean("rescued_total"), value: 10.0, band: Between(0.0, 1000.0)),
])"#;

#[test]
fn a_users_three_task_claims_get_their_verdicts_curves_and_shares_and_nothing_of_the_paper() {
    let tmp = tempfile::tempdir().unwrap();
    let d = tmp.path();
    for (name, body) in [
        ("mine.ron", USER_CLAIMS),
        ("axes.ron", USER_AXES),
        ("targets.ron", USER_TARGETS),
    ] {
        std::fs::write(d.join(name), body).unwrap();
    }
    let short = [
        "--methods",
        "rne,dis,eng",
        "--trials",
        "3",
        "--duration",
        "30",
    ];
    let mut args = vec![
        "sweep",
        THREE_TASKS,
        "--claims",
        "mine.ron",
        "--out",
        "sweep",
    ];
    args.extend(short);
    let summary = ok(&usar_in(d, &args));
    let report = read_text(&d.join("sweep/report.md"));
    for text in [&summary, &report] {
        assert!(text.contains("(medium-rne) RNE rescues more in the medium task than DIS"));
        assert!(text.contains("(cheap-dis) DIS spends the least energy per rescuee in total"));
        for paper in ["(1) RNE", "(4b)", "hard task", "easy task"] {
            assert!(!text.contains(paper), "{paper:?} in\n{text}");
        }
    }
    assert!(
        report.contains("| one-sided Mann-Whitney U, alpha 0.1, Holm-corrected |"),
        "{report}"
    );
    // Only DIS is medium-rne's rival; cheap-dis compares with RNE and ENG, Holm-corrected.
    let medium = &report[report.find("### (medium-rne)").unwrap()..];
    let medium = &medium[..medium.find("### (cheap-dis)").unwrap()];
    assert_eq!(medium.matches("\n| DIS |").count(), 1, "{medium}");
    assert!(!medium.contains("\n| ENG |"), "{medium}");
    let cheap = &report[report.find("### (cheap-dis)").unwrap()..];
    assert!(cheap.contains("| p (Holm) |"), "{cheap}");
    assert!(cheap.contains("\n| RNE |") && cheap.contains("\n| ENG |"));

    let mut args = vec![
        "multiverse",
        THREE_TASKS,
        "--axes",
        "axes.ron",
        "--targets",
        "targets.ron",
        "--claims",
        "mine.ron",
        "--free",
        "mission.search_time_budget_s=6..30",
        "--calibration-trials",
        "1",
        "--max-evals",
        "2",
        "--quiet",
        "--out",
        "mv",
    ];
    args.extend(short);
    ok(&usar_in(d, &args));
    let mv = d.join("mv");
    let mut svgs: Vec<String> = std::fs::read_dir(&mv)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with("spec_curve_"))
        .collect();
    svgs.sort();
    assert_eq!(
        svgs,
        ["spec_curve_cheap-dis.svg", "spec_curve_medium-rne.svg"]
    );
    let md = read_text(&mv.join("multiverse.md"));
    assert!(md.contains("| (medium-rne) RNE rescues more in the medium task than DIS"));
    assert!(
        md.contains("(medium-rne) holds | (cheap-dis) holds"),
        "{md}"
    );
    assert!(!md.contains("(4b)") && !md.contains("hard task"), "{md}");
    let csv = read_text(&mv.join("multiverse.csv"));
    let claim_rows: Vec<&str> = csv
        .lines()
        .filter(|l| l.split(',').nth(6) == Some("claim"))
        .collect();
    assert_eq!(claim_rows.len(), 4, "{csv}");
    assert!(
        claim_rows
            .iter()
            .all(|r| r.contains("medium-rne") || r.contains("cheap-dis"))
    );
}

/// `usar sweep paper.ron --claims FILE` with `body` as FILE: one line on stderr, nothing run.
fn refused(dir: &Path, body: &str) -> String {
    let file = dir.join("bad-claims.ron");
    std::fs::write(&file, body).unwrap();
    let out = dir.join("out");
    let o = usar([
        "sweep",
        &format!("{ROOT}/scenarios/paper.ron"),
        "--methods",
        "rne,dis",
        "--trials",
        "1",
        "--duration",
        "1",
        "--quiet",
        "--claims",
        text(&file),
        "--out",
        text(&out),
    ]);
    assert!(!o.status.success());
    assert!(!out.join("journal.jsonl").exists());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    err
}

const GOOD: &str = r#"Claims(claims: [
    (id: "1", sentence: "RNE rescues the most", subject: "RNE", metric: "rescued_total",
     direction: More),
    (id: "2", sentence: "DIS beats HP_DIS in the easy task", subject: "DIS",
     rivals: Only(["HP_DIS"]), metric: "rescued_easy", direction: More),
])
"#;

#[test]
fn bad_claims_files_get_one_line_naming_the_file_line_column_and_field() {
    let tmp = tempfile::tempdir().unwrap();
    let cases = [
        (
            GOOD.replace("subject: \"DIS\"", "subject: \"DIZ\""),
            "bad-claims.ron:4:62: claims[1].subject: unknown method \"DIZ\" (methods: RNE, DIS, \
             ENG, HP_DIS); did you mean `DIS`?",
        ),
        (
            GOOD.replace("rescued_easy", "rescued_north"),
            "bad-claims.ron:5:32: claims[1].metric: metric \"rescued_north\" is about task \
             \"north\", which the scenario does not have (its tasks: hard, easy); scenario: ",
        ),
        (
            GOOD.replace("rescued_total", "rescuees"),
            "bad-claims.ron:2:65: claims[0].metric: unknown metric \"rescuees\" (metrics: ",
        ),
        (
            GOOD.replace("Only([\"HP_DIS\"])", "Only([\"hp_dis\", \"dis\"])"),
            "bad-claims.ron:5:6: claims[1].rivals: the subject \"DIS\" is among its rivals \
             (\"dis\")",
        ),
        (
            GOOD.replace("id: \"2\"", "id: \"1\""),
            "bad-claims.ron:4:6: claims[1].id: duplicate id \"1\" (claims[0] has it too)",
        ),
        (
            GOOD.replace("direction: More),\n])", "direction: More, alpha: 0.9),\n])"),
            "bad-claims.ron:5:73: claims[1].alpha: expected a one-sided level in (0, 0.5], \
             found 0.9",
        ),
        (
            GOOD.replace("direction: More),\n    (", "direction: Most),\n    ("),
            "bad-claims.ron:3:17: claims[0].direction: Unexpected variant named `Most` in enum \
             `Direction`",
        ),
        (
            GOOD.replace("id: \"1\",", "id: \"1\", weight: 2,"),
            "bad-claims.ron:2:15: claims[0].weight: Unexpected field named `weight` in `Claim`",
        ),
        (
            "Claims(claims: [])".to_string(),
            "bad-claims.ron:1:8: claims: no claims: give at least one",
        ),
    ];
    for (body, want) in cases {
        let err = refused(tmp.path(), &body);
        let at = err.find("bad-claims.ron").unwrap_or(0);
        assert!(
            err.starts_with("error: --claims: ") && err[at..].starts_with(want),
            "want {want:?}\n got {err:?}"
        );
    }
}

#[test]
fn a_bad_claims_file_the_scenario_names_is_blamed_on_the_scenarios_field() {
    let tmp = tempfile::tempdir().unwrap();
    let paper = std::fs::read_to_string(format!("{ROOT}/scenarios/paper.ron")).unwrap();
    let from = "claims: \"paper-claims.ron\"";
    assert_eq!(paper.matches(from).count(), 1);
    // A folder where a claims file should be, named by the scenario and not by `--claims`.
    std::fs::create_dir(tmp.path().join("claims-folder")).unwrap();
    let targets = "paper-targets.ron";
    std::fs::copy(
        format!("{ROOT}/scenarios/{targets}"),
        tmp.path().join(targets),
    )
    .unwrap();
    let scenario = tmp.path().join("mine.ron");
    let src = paper.replacen(from, "claims: \"claims-folder\"", 1);
    std::fs::write(&scenario, &src).unwrap();
    let line = src
        .lines()
        .position(|l| l.contains("claims-folder"))
        .unwrap()
        + 1;
    let col = src
        .lines()
        .nth(line - 1)
        .unwrap()
        .find("claims: \"claims-folder\"")
        .unwrap()
        + 1;
    let out = tmp.path().join("out");
    let o = usar([
        "sweep",
        text(&scenario),
        "--trials",
        "1",
        "--duration",
        "1",
        "--quiet",
        "--out",
        text(&out),
    ]);
    assert!(!o.status.success());
    let err = stderr(&o);
    assert_eq!(err.lines().count(), 1, "{err}");
    let want = format!("error: {}:{line}:{col}: report.claims: ", text(&scenario));
    assert!(err.starts_with(&want), "want {want:?}\n got {err:?}");
    assert!(!err.contains("--claims"), "{err}");
    assert!(!out.join("journal.jsonl").exists());
}
