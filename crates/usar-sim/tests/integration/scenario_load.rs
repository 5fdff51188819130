//! Scenario loading: every shipped scenario loads, and broken scenarios get precise errors.

use std::path::PathBuf;

use usar_sim::scenario::{self, Locomotion, Role, ScenarioError};

fn scenarios_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenarios")
}

fn broken_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("tests/data/broken")
}

/// The name of the top-level RON struct of `src` (`Scenario`, `Axes`, `Targets`, ...): the
/// identifier before the first `(` outside line comments.
fn top_level_struct(src: &str) -> String {
    src.lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with("//"))
        .and_then(|l| l.split('(').next())
        .unwrap_or("")
        .trim()
        .to_string()
}

#[test]
fn every_shipped_scenario_loads() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(scenarios_dir())
        .expect("scenarios/ exists")
        .map(|e| e.expect("dir entry").path())
        .filter(|p| p.extension().is_some_and(|e| e == "ron"))
        .collect();
    files.sort();
    // scenarios/ also holds the calibration targets (`Targets`, loaded by experiments'
    // calibration module), the multiverse axes (`Axes`) and the claims files (`Claims`);
    // tests/tests/integration/calibration.rs checks those. Every other file must be a scenario.
    files.retain(|f| {
        let src = std::fs::read_to_string(f).expect("readable");
        match top_level_struct(&src).as_str() {
            "Targets" | "Axes" | "Claims" => false,
            "Scenario" => true,
            other => panic!("{}: unknown top-level struct {other:?}", f.display()),
        }
    });
    assert!(
        files.len() >= 2,
        "expected paper.ron and corridor.ron, found {files:?}"
    );
    for f in &files {
        let s = scenario::load(f).unwrap_or_else(|e| panic!("{e}"));
        assert!(!s.robots().is_empty(), "{}", f.display());
        assert_eq!(
            s.robots().len(),
            s.kinds().iter().map(|k| k.count).sum::<usize>(),
            "{}",
            f.display()
        );
        for t in s.tasks() {
            assert!(!t.rescuees.is_empty());
            assert!(t.rescuees.iter().all(|p| t.search_area.contains(p)));
        }
    }
}

/// A small valid scenario; tests break one thing at a time.
const BASE: &str = r#"Scenario(
    name: "base",
    arena: (width_m: 30.0, height_m: 20.0),
    kinds: [
        (
            name: "rover",
            role: Carrier,
            locomotion: Ground,
            count: 2,
            quota: (easy: 1, hard: 1),
            body_radius_m: 0.4,
            max_speed_m_per_s: 1.5,
            sensing_range_m: 2.0,
            observing_range_m: 1.0,
            carrying_capacity: 2,
            rescuing_resources: 2,
            hp_needs_full: 2.0,
            energy_needs_full: 1.5,
            starts: List([(14.0, 2.0), (16.0, 2.0)]),
        ),
    ],
    rest_station: (center_m: (25.0, 2.0), radius_m: 1.0),
    tasks: [
        (
            name: "hard",
            difficulty: 1,
            search_area: (min_m: (2.0, 14.0), max_m: (10.0, 18.0)),
            goal_m: (6.0, 16.0),
            drop_off: (center_m: (3.0, 5.0), radius_m: 1.0),
            rescuees: List([(3.0, 15.0), (4.0, 15.0)]),
        ),
        (
            name: "easy",
            search_area: (min_m: (20.0, 14.0), max_m: (28.0, 18.0)),
            goal_m: (24.0, 16.0),
            drop_off: (center_m: (27.0, 5.0), radius_m: 1.0),
            rescuees: Grid(spacing_m: 1.0),
        ),
    ],
    debris: [
        Circle(center_m: (15.0, 10.0), radius_m: 1.0),
    ],
)
"#;

/// 1-based line of the first line of `src` containing `needle`.
fn line_of(src: &str, needle: &str) -> usize {
    src.lines()
        .position(|l| l.contains(needle))
        .unwrap_or_else(|| panic!("{needle:?} not in source"))
        + 1
}

fn broken(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "{from:?} not in BASE");
    BASE.replacen(from, to, 1)
}

/// A list of rest stations loads in the file's order, and a robot leaving to recharge is
/// sent to the nearest (straight-line, ties to the one listed first).
#[test]
fn several_rest_stations_load_and_the_nearest_is_chosen() {
    let src = broken(
        "rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)",
        "rest_station: [(center_m: (25.0, 2.0), radius_m: 1.0), (center_m: (5.0, 2.0), radius_m: 1.5)]",
    );
    let s = scenario::from_str(&src, "stations.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.rest_stations().len(), 2);
    assert_eq!(s.rest_stations()[1].radius_m, 1.5);
    let p = |x, y| scenario::PointM::new(x, y);
    assert_eq!(s.nearest_rest_station(&p(24.0, 10.0)), 0);
    assert_eq!(s.nearest_rest_station(&p(6.0, 10.0)), 1);
    assert_eq!(
        s.nearest_rest_station(&p(15.0, 2.0)),
        0,
        "a tie goes to the first"
    );
    assert!(s.in_rest_station(&p(5.0, 3.4)) && !s.in_rest_station(&p(15.0, 2.0)));
    // One circle is a list of one.
    let one = scenario::from_str(BASE, "base.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(one.rest_stations().len(), 1);
    assert_eq!(one.nearest_rest_station(&p(0.0, 0.0)), 0);
}

/// A syntax error outside every field (a file cut short at its start, no `Scenario(`) names
/// the scenario as its field, so every error reads `file:line:col: field: message`.
#[test]
fn a_syntax_error_outside_every_field_names_the_scenario() {
    for src in ["(", "", "Scenario", "Foo(name: \"x\")"] {
        let e = scenario::from_str(src, "t.ron").expect_err(src);
        assert_eq!(e.field(), Some("Scenario"), "{src:?}: {e}");
        assert!(e.to_string().starts_with("t.ron:1:"), "{src:?}: {e}");
        assert!(e.to_string().contains(": Scenario: "), "{src:?}: {e}");
    }
    // Inside a field, the field is named as before.
    let e = scenario::from_str("Scenario(kinds: [", "t.ron").expect_err("cut short");
    assert_eq!(e.field(), Some("kinds"), "{e}");
    // A byte that is not UTF-8 names the field whose value it is in, else the scenario.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.ron");
    for (bytes, field) in [
        (&b"Scenario(\xff"[..], "Scenario"),
        (b"\xff", "Scenario"),
        (b"Scenario(name: \"a\xffb\")", "Scenario"),
        (b"Scenario(kinds: [(name: \"a\xff", "kinds[0]"),
        (b"Scenario(mission: (duration_s: 6\xff", "mission"),
    ] {
        std::fs::write(&path, bytes).unwrap();
        let e = scenario::load(&path).expect_err("not UTF-8");
        assert_eq!(e.field(), Some(field), "{bytes:?}: {e}");
        assert!(
            e.to_string()
                .contains(&format!(": {field}: byte 0xff is not UTF-8")),
            "{e}"
        );
    }
}

#[test]
fn base_is_valid_and_defaults_apply() {
    let s = scenario::from_str(BASE, "base.ron").unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.sim().dt_s, 0.02);
    assert_eq!(s.sim().seed, 0);
    assert_eq!(s.mission().duration_s, 600.0);
    assert_eq!(s.mission().energy_pct_per_moving_step, 0.0045);
    assert_eq!(s.mission().hp_pct_per_step_in_radiation, 0.0003);
    assert_eq!(s.mission().no_observer_speed_factor, 0.7);
    assert_eq!(s.mission().initial_energy.mean_pct, 80.0);
    assert_eq!(s.mission().initial_hp.std_dev_pct, 10.0);
    assert_eq!(s.navigation().grid_cell_m, 0.25);
    assert_eq!(s.navigation().clearance_m, 0.1);
    assert_eq!(s.navigation().waypoint_tolerance_m, 0.3);
    assert!(s.collision().enabled);
    assert_eq!(s.collision().lookahead_s, 1.0);
    assert_eq!(s.collision().safety_margin_m, 0.2);
    assert_eq!(s.collision().deadlock_after_s, 2.0);
    assert_eq!(s.arena().wall_thickness_m, 0.5);
    assert_eq!(s.needs_weights().to_array(), [1.0; 7]);
    // Tasks in the file's order; the hard one first by difficulty, the easy one's default 0.
    assert_eq!(s.task_names(), ["hard", "easy"]);
    assert_eq!((s.tasks()[0].difficulty, s.tasks()[1].difficulty), (1, 0));
    assert_eq!(s.hardest_first(), [0, 1]);
    assert_eq!(s.kinds()[0].quota, [1, 1]);
    // 8 x 4 m area, spacing 1: 9 x 5 grid.
    assert_eq!(s.tasks()[1].rescuees.len(), 45);
    assert_eq!(s.tasks()[0].rescuees.len(), 2);
    assert_eq!(s.steps_per_trial(), 30_000);
}

/// (case, source, expected field path, line of this needle (None: no position), message part)
type Case = (
    &'static str,
    String,
    &'static str,
    Option<&'static str>,
    &'static str,
);

fn inline_cases() -> Vec<Case> {
    vec![
        (
            "an empty quota is named by its brackets, not as a RON unit",
            broken("quota: (easy: 1, hard: 1)", "quota: ()"),
            "kinds[0].quota",
            Some("quota: ()"),
            "but found `()` (an empty value) instead",
        ),
        (
            "quota sum",
            broken("quota: (easy: 1, hard: 1)", "quota: (easy: 1, hard: 2)"),
            "kinds[0].quota",
            Some("quota: (easy: 1, hard: 2)"),
            "hard 2 + easy 1 = 3 but count is 2",
        ),
        (
            "start count",
            broken("starts: List([(14.0, 2.0), (16.0, 2.0)])", "starts: List([(14.0, 2.0)])"),
            "kinds[0].starts",
            Some("starts: List([(14.0, 2.0)])"),
            "1 start position(s) listed but count is 2",
        ),
        (
            "unknown field",
            broken("max_speed_m_per_s: 1.5", "max_speed: 1.5"),
            "kinds[0].max_speed",
            Some("max_speed: 1.5"),
            "Unexpected field named `max_speed`",
        ),
        (
            "misspelt field",
            broken("max_speed_m_per_s: 1.5", "max_sped_m_per_s: 1.5"),
            "kinds[0].max_sped_m_per_s",
            Some("max_sped_m_per_s: 1.5"),
            "`starts` instead; did you mean `max_speed_m_per_s`?",
        ),
        (
            "misspelt task in a quota",
            broken("quota: (easy: 1, hard: 1)", "quota: (easy: 1, hrad: 1)"),
            "kinds[0].quota",
            Some("quota: (easy: 1, hrad: 1)"),
            "no task is called \"hrad\" (tasks: \"hard\", \"easy\"); did you mean `hard`?",
        ),
        (
            "missing field",
            broken("            sensing_range_m: 2.0,\n", ""),
            "kinds[0].sensing_range_m",
            // ron reports missing fields at the struct's closing parenthesis.
            Some("        ),"),
            "missing field named `sensing_range_m`",
        ),
        (
            // No comma after the struct's last field: the error is still the struct's.
            "missing field, no trailing comma",
            broken(
                "arena: (width_m: 30.0, height_m: 20.0)",
                "arena: (height_m: 20.0)",
            ),
            "arena.width_m",
            Some("arena: (height_m: 20.0)"),
            "missing field named `width_m`",
        ),
        (
            "missing field in a nested struct, no trailing comma",
            broken(
                "    debris: [",
                "    mission: (initial_energy: (std_dev_pct: 1.0)),\n    debris: [",
            ),
            "mission.initial_energy.mean_pct",
            Some("initial_energy: (std_dev_pct: 1.0)"),
            "missing field named `mean_pct`",
        ),
        (
            "missing field of the one rest station",
            broken(
                "rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)",
                "rest_station: (radius_m: 1.0)",
            ),
            "rest_station.center_m",
            Some("rest_station: (radius_m: 1.0)"),
            "missing field named `center_m`",
        ),
        (
            "missing field of a listed rest station",
            broken(
                "rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)",
                "rest_station: [(center_m: (25.0, 2.0), radius_m: 1.0), (center_m: (25.0, 5.0))]",
            ),
            "rest_station[1].radius_m",
            Some("rest_station: ["),
            "missing field named `radius_m`",
        ),
        (
            // No `sim` block: the default step is positioned at the scenario itself.
            "a default that breaks a rule",
            broken("    debris: [", "    mission: (duration_s: 0.01),\n    debris: ["),
            "sim.dt_s",
            Some("Scenario("),
            "longer than the trial",
        ),
        (
            "wrong type",
            broken("count: 2", "count: \"two\""),
            "kinds[0].count",
            Some("count: \"two\""),
            "Expected",
        ),
        (
            "unknown variant",
            broken("locomotion: Ground", "locomotion: Wheels"),
            "kinds[0].locomotion",
            Some("locomotion: Wheels"),
            "Wheels",
        ),
        (
            "negative radius",
            broken("body_radius_m: 0.4", "body_radius_m: -0.4"),
            "kinds[0].body_radius_m",
            Some("body_radius_m: -0.4"),
            "expected a finite number > 0, found -0.4",
        ),
        (
            "search area outside arena",
            broken("max_m: (10.0, 18.0)", "max_m: (10.0, 21.0)"),
            "tasks[0].search_area",
            Some("search_area: (min_m: (2.0, 14.0), max_m: (10.0, 21.0))"),
            "not inside the arena",
        ),
        (
            "rescuee outside search area",
            broken("List([(3.0, 15.0), (4.0, 15.0)])", "List([(3.0, 15.0),\n (11.0, 15.0)])"),
            "tasks[0].rescuees[1]",
            Some(" (11.0, 15.0)])"),
            "outside the search area",
        ),
        (
            "start inside debris",
            broken("(16.0, 2.0)]", "(15.0, 10.5)]"),
            "kinds[0].starts[1]",
            Some("starts: List"),
            "overlaps debris[0]",
        ),
        (
            "starts overlap",
            broken("(16.0, 2.0)]", "(14.5, 2.0)]"),
            "kinds[0].starts[1]",
            Some("starts: List"),
            "need at least 0.8 m",
        ),
        (
            "threshold out of range",
            broken("    debris: [", "    mission: (low_hp_pct: 130.0),\n    debris: ["),
            "mission.low_hp_pct",
            Some("low_hp_pct: 130.0"),
            "expected a number in [0, 100], found 130",
        ),
        (
            "weight zero",
            broken("    debris: [", "    needs_weights: (cap: 0.0),\n    debris: ["),
            "needs_weights.cap",
            Some("needs_weights: (cap: 0.0)"),
            "expected a finite number > 0, found 0",
        ),
        (
            "goal inside debris",
            broken("goal_m: (6.0, 16.0)", "goal_m: (15.0, 10.0)"),
            "tasks[0].goal_m",
            Some("goal_m: (15.0, 10.0)"),
            "debris[0]",
        ),
        (
            "debris outside arena",
            broken("Circle(center_m: (15.0, 10.0), radius_m: 1.0)", "Circle(center_m: (29.5, 10.0), radius_m: 1.0)"),
            "debris[0]",
            Some("Circle(center_m: (29.5"),
            "not inside the arena",
        ),
        (
            "duplicate kind name",
            broken(
                "    rest_station:",
                "    rest_station:",
            )
            .replace(
                "    ],\n    rest_station",
                "        (name: \"rover\", role: Observer, locomotion: Aerial, count: 1, quota: (easy: 1), body_radius_m: 0.3, max_speed_m_per_s: 1.0, sensing_range_m: 12.0, observing_range_m: 50.0, carrying_capacity: 0, rescuing_resources: 0, hp_needs_full: 1.0, energy_needs_full: 1.0, starts: List([(15.0, 2.0)])),\n    ],\n    rest_station",
            ),
            "kinds[1].name",
            Some("(name: \"rover\", role: Observer"),
            "duplicate kind name \"rover\"",
        ),
        (
            "debris field cannot fit",
            broken(
                "    debris: [",
                "    debris_fields: [(region: (min_m: (1.0, 8.0), max_m: (5.0, 12.0)), count: 30, shape: Circles(radius_m: (0.5, 1.0)))],\n    debris: [",
            ),
            "debris_fields[0].count",
            Some("count: 30"),
            "placed only",
        ),
        (
            "dt longer than trial",
            broken("    debris: [", "    sim: (dt_s: 5.0),\n    mission: (duration_s: 1.0),\n    debris: ["),
            "sim.dt_s",
            Some("sim: (dt_s: 5.0)"),
            "longer than the trial",
        ),
        (
            "empty rest station list",
            broken("rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)", "rest_station: []"),
            "rest_station",
            Some("rest_station: []"),
            "give at least one rest station",
        ),
        (
            "second rest station outside the arena",
            broken(
                "rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)",
                "rest_station: [\n        (center_m: (25.0, 2.0), radius_m: 1.0),\n        (center_m: (29.8, 2.0), radius_m: 1.0),\n    ]",
            ),
            "rest_station[1]",
            Some("(center_m: (29.8, 2.0)"),
            "not inside the arena",
        ),
        (
            "rest station list item with a bad radius",
            broken(
                "rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)",
                "rest_station: [\n        (center_m: (25.0, 2.0), radius_m: 1.0),\n        (center_m: (5.0, 2.0), radius_m: -1.0),\n    ]",
            ),
            "rest_station[1].radius_m",
            Some("(center_m: (5.0, 2.0), radius_m: -1.0)"),
            "-1",
        ),
        (
            "rest station that is neither a circle nor a list",
            broken("rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)", "rest_station: 3.0"),
            "rest_station",
            Some("rest_station: 3.0"),
            "a circle (center_m: (x, y), radius_m: r) or a list of circles",
        ),
        (
            "RON whitespace beyond ASCII's before the field",
            broken("count: 2,\n", "count: 2,\u{0b}\u{2028}\u{85}")
                .replace("rest_station: (center_m: (25.0, 2.0)", "rest_station: (center_m: (29.8, 2.0)"),
            "rest_station",
            Some("rest_station: (center_m: (29.8"),
            "not inside the arena",
        ),
        (
            "syntax error",
            broken("count: 2,", "count: 2"),
            "kinds[0]",
            Some("quota: (easy: 1, hard: 1)"),
            "Expected",
        ),
        (
            // ron stops reading the integer at the `.` and asks for a comma.
            "fraction in an integer field",
            broken("count: 2,", "count: 2.0,"),
            "kinds[0].count",
            Some("count: 2.0,"),
            "expected an integer, found `2.0`",
        ),
        (
            "a longer fraction in another integer field",
            broken("carrying_capacity: 2,", "carrying_capacity: 2.50,"),
            "kinds[0].carrying_capacity",
            Some("carrying_capacity: 2.50,"),
            "expected an integer, found `2.50`",
        ),
    ]
}

fn check(name: &str, err: &ScenarioError, src: &str, field: &str, needle: Option<&str>, msg: &str) {
    let text = err.to_string();
    assert_eq!(err.field(), Some(field), "{name}: {text}");
    assert!(text.contains(&format!("{field}: ")), "{name}: {text}");
    assert!(text.contains(msg), "{name}: message {msg:?} not in {text}");
    match needle {
        Some(n) => {
            let line = line_of(src, n);
            let (l, _) = err
                .line_col()
                .unwrap_or_else(|| panic!("{name}: no position: {text}"));
            assert_eq!(l, line, "{name}: {text}");
            assert!(text.contains(&format!(":{line}:")), "{name}: {text}");
        }
        None => assert_eq!(err.line_col(), None, "{name}: {text}"),
    }
}

#[test]
fn broken_inline_sources_get_precise_errors() {
    for (name, src, field, needle, msg) in inline_cases() {
        let err = scenario::from_str(&src, "inline.ron").expect_err(name);
        println!("{name}: {err}");
        assert_eq!(err.origin(), "inline.ron");
        assert!(err.to_string().starts_with("inline.ron:"), "{name}: {err}");
        check(name, &err, &src, field, needle, msg);
    }
}

/// Fixture files: (file, field, line, message part).
const FIXTURES: &[(&str, &str, usize, &str)] = &[
    (
        "quota_mismatch.ron",
        "kinds[1].quota",
        0,
        "hard 2 + easy 2 = 4 but count is 3",
    ),
    (
        "unknown_field.ron",
        "tasks[1].goal",
        0,
        "Unexpected field named `goal`",
    ),
    (
        "rescuee_outside.ron",
        "tasks[1].rescuees[2]",
        0,
        "outside the search area",
    ),
    (
        "radiation_outside.ron",
        "radiation_zones[1]",
        0,
        "not inside the arena",
    ),
    (
        "row_overlap.ron",
        "kinds[0].starts",
        0,
        "need at least 0.8 m",
    ),
];

#[test]
fn broken_fixture_files_get_precise_errors() {
    for &(file, field, _, msg) in FIXTURES {
        let path = broken_dir().join(file);
        let src = std::fs::read_to_string(&path).expect("fixture exists");
        // Each fixture marks the offending line with a `// <- error` comment.
        let needle = "// <- error";
        let err = scenario::load(&path).expect_err(file);
        println!("{err}");
        assert!(
            err.to_string().starts_with(&path.display().to_string()),
            "{file}: {err}"
        );
        check(file, &err, &src, field, Some(needle), msg);
    }
}

#[test]
fn missing_file_is_an_io_error_that_says_its_cause_once() {
    let err = scenario::load("/nonexistent/none.ron").expect_err("missing");
    assert!(matches!(err, ScenarioError::Io { .. }));
    let msg = err.to_string();
    assert!(
        msg.starts_with("/nonexistent/none.ron: cannot read"),
        "{msg}"
    );
    assert_eq!(msg.matches("No such file").count(), 1, "{msg}");
    // Printed with its chain (as `usar` does), the cause still appears once.
    let chained = rne_core::error_line(&err);
    assert_eq!(chained.matches("No such file").count(), 1, "{chained}");
}

#[test]
fn a_byte_that_is_not_utf8_is_reported_at_its_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.ron");
    let mut bytes = BASE.as_bytes().to_vec();
    // Third line, after its first four characters.
    let third = bytes
        .iter()
        .enumerate()
        .filter(|(_, b)| **b == b'\n')
        .nth(1)
        .map(|(i, _)| i + 1)
        .unwrap();
    bytes.insert(third + 4, 0xff);
    std::fs::write(&path, &bytes).unwrap();
    let err = scenario::load(&path).expect_err("not UTF-8");
    assert_eq!(err.line_col(), Some((3, 5)), "{err}");
    assert!(err.to_string().contains("0xff is not UTF-8"), "{err}");
    // After a byte-order mark, a bad byte on the first line: columns count from after it.
    let mut first = b"\xEF\xBB\xBF".to_vec();
    first.extend_from_slice(b"Scen\xffario(");
    std::fs::write(&path, &first).unwrap();
    let err = scenario::load(&path).expect_err("not UTF-8");
    assert_eq!(err.line_col(), Some((1, 5)), "{err}");
}

#[test]
fn deep_nesting_is_a_positioned_error_not_a_stack_overflow() {
    for open in ["(", "[", "{"] {
        let close = match open {
            "(" => ")",
            "[" => "]",
            _ => "}",
        };
        let depth = 200_000;
        let src = BASE.replacen(
            "width_m: 30.0",
            &format!("width_m: {}{}", open.repeat(depth), close.repeat(depth)),
            1,
        );
        assert_ne!(src, BASE);
        let err = scenario::from_str(&src, "deep.ron").expect_err("nested");
        assert!(err.line_col().is_some(), "{err}");
        assert_eq!(err.to_string().lines().count(), 1, "{err}");
    }
}

#[test]
fn a_byte_order_mark_is_skipped_and_columns_count_after_it() {
    let plain = scenario::from_str(BASE, "base.ron").expect("loads");
    let with_bom = format!("\u{feff}{BASE}");
    assert_eq!(
        scenario::from_str(&with_bom, "bom.ron").expect("loads"),
        plain
    );
    let spec = scenario::parse_spec(&with_bom, "bom.ron").expect("parses");
    assert_eq!(spec, scenario::parse_spec(BASE, "base.ron").unwrap());
    let bad = format!("\u{feff}{}", broken("Scenario(", "Scenario( x: 1,"));
    let err = scenario::from_str(&bad, "bom.ron").expect_err("unknown field");
    assert_eq!(err.line_col(), Some((1, 11)), "{err}");
}

#[test]
fn validate_spec_without_source_has_field_but_no_position() {
    let mut spec = scenario::parse_spec(BASE, "base.ron").expect("parses");
    spec.kinds[0].count = 3;
    let err = spec.validate("edited").expect_err("count changed");
    assert_eq!(err.field(), Some("kinds[0].quota"));
    assert_eq!(err.line_col(), None);
    assert_eq!(
        err.to_string(),
        "edited: kinds[0].quota: hard 1 + easy 1 = 2 but count is 3"
    );
}

#[test]
fn paper_scenario_matches_the_paper() {
    let s = scenario::load(scenarios_dir().join("paper.ron")).unwrap_or_else(|e| panic!("{e}"));
    let by_role = |r: Role| {
        s.kinds()
            .iter()
            .find(|k| k.role == r)
            .expect("role present")
    };
    let (c, sup, o) = (
        by_role(Role::Carrier),
        by_role(Role::Supplier),
        by_role(Role::Observer),
    );
    assert_eq!((c.count, sup.count, o.count), (6, 4, 2));
    assert_eq!(
        (c.quota.clone(), sup.quota.clone(), o.quota.clone()),
        (vec![3, 3], vec![2, 2], vec![1, 1])
    );
    assert_eq!(o.locomotion, Locomotion::Aerial);
    // Section VI.B ratios.
    let close = |a: f64, b: f64| (a - b).abs() < 1e-9 * b.abs().max(1.0);
    assert!(close(c.max_speed_m_per_s, 1.5 * o.max_speed_m_per_s));
    assert!(close(sup.max_speed_m_per_s, c.max_speed_m_per_s));
    assert!(close(o.sensing_range_m, 6.0 * c.sensing_range_m));
    assert!(close(sup.sensing_range_m, c.sensing_range_m));
    assert_eq!(c.carrying_capacity, 6 * sup.carrying_capacity);
    assert_eq!(o.carrying_capacity, 0);
    assert_eq!(sup.rescuing_resources, 10 * c.rescuing_resources);
    assert_eq!(o.rescuing_resources, 0);
    assert!(close(o.observing_range_m, 1000.0 * c.observing_range_m));
    assert!(close(sup.observing_range_m, c.observing_range_m));
    assert!(close(c.hp_needs_full, 2.0 * o.hp_needs_full));
    assert!(close(sup.hp_needs_full, c.hp_needs_full));
    assert!(close(c.energy_needs_full, 1.5 * o.energy_needs_full));
    assert!(close(sup.energy_needs_full, c.energy_needs_full));

    // Geometry: hard goal about 1.25 times as far from the team as the easy goal.
    let n = s.robots().len() as f64;
    let centroid = s
        .robots()
        .iter()
        .fold(nalgebra::Vector2::zeros(), |acc, r| {
            acc + r.start_in_world.coords
        })
        / n;
    let task = |name: &str| &s.tasks()[s.task_id(name).expect("paper.ron has easy and hard")];
    let d = |name: &str| (task(name).goal.coords - centroid).norm();
    let ratio = d("hard") / d("easy");
    assert!((1.2..=1.3).contains(&ratio), "ratio {ratio}");
    assert!(task("hard").goal.x < s.arena().width_m.get() / 2.0);
    assert!(task("easy").goal.x > s.arena().width_m.get() / 2.0);
    // Dense grids: hundreds of rescuees per task.
    for t in s.tasks() {
        assert!(t.rescuees.len() >= 200, "{} rescuees", t.rescuees.len());
    }
    // The hard side (left of the team) holds far more debris and radiation than the easy
    // side (right of it); the cluster in front of the team lies between the two.
    let (hard_side, easy_side) = (|x: f64| x < 33.0, |x: f64| x > 47.0);
    let debris_x: Vec<f64> = s
        .debris()
        .iter()
        .map(|d| match d {
            usar_sim::scenario::Debris::Rect { center, .. } => center.x,
            usar_sim::scenario::Debris::Circle(c) => c.center.x,
        })
        .collect();
    let debris_hard = debris_x.iter().filter(|x| hard_side(**x)).count();
    let debris_easy = debris_x.iter().filter(|x| easy_side(**x)).count();
    assert_eq!((debris_hard, debris_easy), (16, 3));
    let rad = |side: fn(f64) -> bool| {
        s.radiation_zones()
            .iter()
            .filter(|z| side(z.area.center.x))
            .count()
    };
    assert_eq!((rad(hard_side), rad(easy_side)), (6, 1));
}

#[test]
fn corridor_scales_to_2_4_8_robots() {
    let path = scenarios_dir().join("corridor.ron");
    let src = std::fs::read_to_string(&path).expect("corridor.ron");
    for per_end in [1usize, 2, 4] {
        let mut spec = scenario::parse_spec(&src, "corridor.ron").expect("parses");
        spec.kinds[0].count = per_end;
        spec.kinds[0].quota.0.insert("easy".into(), per_end);
        spec.kinds[1].count = per_end;
        spec.kinds[1].quota.0.insert("hard".into(), per_end);
        let s = spec
            .validate("corridor.ron")
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.robots().len(), 2 * per_end);
        // Everyone is on the corridor's centre line; the groups face each other.
        assert!(
            s.robots()
                .iter()
                .all(|r| (r.start_in_world.y - 1.7).abs() < 1e-12)
        );
        let east_max = s
            .robots()
            .iter()
            .filter(|r| r.kind == 0)
            .map(|r| r.start_in_world.x)
            .fold(f64::MIN, f64::max);
        let west_min = s
            .robots()
            .iter()
            .filter(|r| r.kind == 1)
            .map(|r| r.start_in_world.x)
            .fold(f64::MAX, f64::min);
        assert!(east_max < west_min);
    }
    let s = scenario::load(&path).expect("loads");
    // Wide enough for a moving robot to pass one held on the centre line: the pass offset
    // (two radii plus the safety margin) plus the planner's inflation (radius, clearance and
    // half a grid cell) fits in each half of the corridor.
    let r = s.kinds()[0].body_radius_m;
    let pass_offset = 2.0 * r + s.collision().safety_margin_m.get();
    let inflation = r + s.navigation().clearance_m.get() + s.navigation().grid_cell_m.get() / 2.0;
    assert!(
        s.arena().height_m.get() / 2.0 >= pass_offset + inflation,
        "width {}",
        s.arena().height_m.get()
    );
    // Head-on robots on the centre line still collide: one must yield.
    assert!(
        s.robots()
            .iter()
            .all(|r| r.start_in_world.y == s.arena().height_m.get() / 2.0)
    );
    // Each group's task is at the far end.
    let task = |name: &str| &s.tasks()[s.task_id(name).expect("corridor has easy and hard")];
    assert!(task("easy").goal.x > 20.0);
    assert!(task("hard").goal.x < 4.0);
}

#[test]
fn debris_generation_is_deterministic() {
    let path = scenarios_dir().join("paper.ron");
    let a = scenario::load(&path).expect("loads");
    let b = scenario::load(&path).expect("loads");
    assert_eq!(a.debris(), b.debris());
    let src = std::fs::read_to_string(&path).expect("paper.ron");
    let c = scenario::from_str(
        &src.replace("seed: Some(2021)", "seed: Some(7)"),
        "paper7.ron",
    )
    .expect("other seed loads");
    assert_ne!(a.debris(), c.debris());
    assert_eq!(a.debris().len(), c.debris().len());
}

#[test]
fn format_doc_minimal_example_loads() {
    let doc = std::fs::read_to_string(
        PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../docs/scenario-format.md"),
    )
    .expect("docs/scenario-format.md");
    let start = doc.find("## A minimal example").expect("section");
    let block = &doc[start..];
    let open = block.find("```ron\n").expect("ron block") + "```ron\n".len();
    let close = block[open..].find("```").expect("block end") + open;
    let s = scenario::from_str(&block[open..close], "scenario-format.md")
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.name(), "tiny");
    assert_eq!(s.sim().seed, 7);
}

#[test]
fn a_fraction_in_an_integer_field_is_named_at_the_number() {
    let paper = std::fs::read_to_string(scenarios_dir().join("paper.ron")).unwrap();
    for (from, to, field, number) in [
        ("count: 6,", "count: 6.0,", "kinds[0].count", "6.0"),
        // In an `Option`, ron asks for the closing parenthesis instead of a comma.
        (
            "seed: Some(2021),",
            "seed: Some(2021.5),",
            "debris_fields[0].seed",
            "2021.5",
        ),
    ] {
        assert_eq!(paper.matches(from).count(), 1, "{from}");
        let src = paper.replacen(from, to, 1);
        let err = scenario::from_str(&src, "paper.ron").expect_err(to);
        let line = line_of(&src, to);
        let col = src.lines().nth(line - 1).unwrap().find(number).unwrap() + 1;
        assert_eq!(err.line_col(), Some((line, col)), "{err}");
        assert_eq!(err.field(), Some(field), "{err}");
        assert_eq!(
            err.to_string(),
            format!("paper.ron:{line}:{col}: {field}: expected an integer, found `{number}`")
        );
    }
    // A float field keeps ron's own message: no integer was read there.
    let src = paper.replacen("body_radius_m: 0.4,", "body_radius_m: 0.4.5,", 1);
    let err = scenario::from_str(&src, "paper.ron").expect_err("0.4.5");
    assert!(!err.to_string().contains("expected an integer"), "{err}");
}

#[test]
fn a_million_character_name_is_cut_in_the_error_line() {
    let paper = std::fs::read_to_string(scenarios_dir().join("paper.ron")).unwrap();
    let long = "c".repeat(1_000_000);
    let cut = format!("{}… (1000000 characters)", &long[..60]);
    for (from, to, field) in [
        // An unknown field: its path and the message.
        (
            "count: 6,",
            format!("count: 6, {long}: 1,"),
            format!("kinds[0].{cut}"),
        ),
        // A fraction in an integer field, a million digits long.
        (
            "count: 6,",
            format!("count: 6.{},", "0".repeat(1_000_000)),
            "kinds[0].count".to_owned(),
        ),
    ] {
        assert_eq!(paper.matches(from).count(), 1, "{from}");
        let src = paper.replacen(from, &to, 1);
        let err = scenario::from_str(&src, "paper.ron").expect_err("a long name");
        let text = err.to_string();
        assert!(text.len() < 1_000, "{} bytes: {text:.1000}", text.len());
        assert_eq!(err.field(), Some(field.as_str()), "{text}");
    }
}

#[test]
fn a_radix_number_in_a_float_field_is_named_as_written() {
    // ron reads `0x1E` in a float field as `0` and stops at the `x`: the range check of a
    // field > 0 refused "0", and a field that takes 0 asked for a comma.
    let paper = std::fs::read_to_string(scenarios_dir().join("paper.ron")).unwrap();
    for (from, to, field, number) in [
        ("width_m: 80.0,", "width_m: 0x1E,", "arena.width_m", "0x1E"),
        (
            "height_m: 60.0,",
            "height_m: -0o17,",
            "arena.height_m",
            "-0o17",
        ),
        ("hp: 1.0,", "hp: 0b101,", "needs_weights.hp", "0b101"),
        (
            "wall_thickness_m: 1.0",
            "wall_thickness_m: 0xFF",
            "arena.wall_thickness_m",
            "0xFF",
        ),
    ] {
        assert_eq!(paper.matches(from).count(), 1, "{from}");
        let src = paper.replacen(from, to, 1);
        let err = scenario::from_str(&src, "paper.ron").expect_err(to);
        let line = line_of(&src, to);
        let col = src.lines().nth(line - 1).unwrap().find(number).unwrap() + 1;
        assert_eq!(err.field(), Some(field), "{err}");
        assert_eq!(
            err.to_string(),
            format!(
                "paper.ron:{line}:{col}: {field}: expected a decimal number, found `{number}` \
                 (hexadecimal, octal and binary numbers are read for integer fields only)"
            )
        );
    }
    // An enum's value written like one is not called a number.
    let src = paper.replacen("role: Carrier", "role: 0x1", 1);
    let err = scenario::from_str(&src, "paper.ron").expect_err("0x1 for a role");
    assert!(!err.to_string().contains("decimal number"), "{err}");
    assert_eq!(err.field(), Some("kinds[0].role"), "{err}");
    // In an integer field ron reads them.
    let src = paper.replacen("count: 6,", "count: 0x6,", 1);
    let s = scenario::from_str(&src, "paper.ron").expect("0x6 in an integer field");
    assert_eq!(s.kinds()[0].count, 6);
}

#[test]
fn old_mac_line_endings_are_counted_as_lines() {
    // A rule error and a syntax error, each at the same line and column whatever the line
    // ending: `\n`, `\r\n` or a bare `\r` (which ron does not count as a line break).
    for (from, to, field) in [
        ("count: 2,", "count: 0,", "kinds[0].count"),
        ("count: 2,", "count: 2,,", "kinds[0]"),
    ] {
        let unix = broken(from, to);
        let want = scenario::from_str(&unix, "t.ron").expect_err(to);
        let rule = matches!(want, ScenarioError::Invalid { .. });
        assert_eq!(
            rule,
            to == "count: 0,",
            "one rule error, one syntax error: {want}"
        );
        assert!(want.line_col().is_some_and(|(line, _)| line > 5), "{want}");
        for ending in ["\r\n", "\r"] {
            let src = unix.replace('\n', ending);
            let e = scenario::from_str(&src, "t.ron").expect_err(to);
            assert_eq!(e.line_col(), want.line_col(), "{ending:?}: {e}");
            assert!(e.field().is_some_and(|f| f.starts_with(field)), "{e}");
        }
    }
    // A shipped file, which starts with `//` comments, loads with bare-CR endings (ron ends
    // a comment only at `\n`), and a bad byte is placed on its line.
    let paper = std::fs::read_to_string(scenarios_dir().join("paper.ron")).unwrap();
    let mac = paper.replace('\n', "\r");
    scenario::from_str(&mac, "paper.ron").expect("paper.ron with bare-CR line endings");
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mac.ron");
    std::fs::write(&path, b"(\r  name: \"a\xFFb\",\r)").unwrap();
    let e = scenario::load(&path).expect_err("not UTF-8");
    assert_eq!(e.line_col(), Some((2, 11)), "{e}");
}

#[test]
fn a_huge_number_where_ron_wants_another_type_is_written_short() {
    let paper = std::fs::read_to_string(scenarios_dir().join("paper.ron")).unwrap();
    let from = "quota: (easy: 3, hard: 3),";
    assert_eq!(paper.matches(from).count(), 1);
    let src = paper.replacen(from, "quota: -1e63,", 1);
    let err = scenario::from_str(&src, "paper.ron").expect_err("a number for a quota");
    let msg = err.to_string();
    assert!(
        msg.contains("kinds[0].quota") && msg.contains("`-1e63`"),
        "{msg}"
    );
    assert!(!msg.contains("0000000000"), "{msg}");
}

/// An unknown, missing or repeated field of a rest station is the station's, whether
/// `rest_station` is one circle or a list: the field path and the type `CircleSpec` are named
/// alike (ron read the single circle as a map and named the enclosing `Scenario`).
#[test]
fn a_field_error_of_the_one_rest_station_names_its_type_as_the_list_does() {
    let one = "rest_station: (center_m: (25.0, 2.0), radius_m: 1.0)";
    let cases = [
        (
            "radius_m: 1.0, colour: 1",
            "colour",
            "Unexpected field named `colour` in `CircleSpec`",
        ),
        (
            "radius_m: 1.0, radius_m: 2.0",
            "radius_m",
            "duplicate field named `radius_m` in `CircleSpec`",
        ),
    ];
    for (fields, field, msg) in cases {
        for (form, path) in [
            ("(CIRCLE)", "rest_station"),
            ("[(CIRCLE)]", "rest_station[0]"),
        ] {
            let circle = format!("center_m: (25.0, 2.0), {fields}");
            let to = format!("rest_station: {}", form.replace("CIRCLE", &circle));
            let err = scenario::from_str(&broken(one, &to), "inline.ron").expect_err(&to);
            assert_eq!(
                err.field(),
                Some(format!("{path}.{field}").as_str()),
                "{err}"
            );
            assert!(err.to_string().contains(msg), "{err}");
            assert!(!err.to_string().contains("Scenario"), "{err}");
        }
    }
    for (to, path) in [
        (
            "rest_station: (center_m: (25.0, 2.0))",
            "rest_station.radius_m",
        ),
        (
            "rest_station: [(center_m: (25.0, 2.0))]",
            "rest_station[0].radius_m",
        ),
    ] {
        let err = scenario::from_str(&broken(one, to), "inline.ron").expect_err(to);
        assert_eq!(err.field(), Some(path), "{err}");
        let msg = "missing field named `radius_m` in `CircleSpec`";
        assert!(err.to_string().contains(msg), "{err}");
    }
}

/// A file cut short is reported where its text ends, with the bracket it leaves open and the
/// field that bracket (or the value cut off) belongs to; an error before the cut stays ron's.
#[test]
fn a_file_cut_short_names_where_it_ends_and_the_bracket_left_open() {
    let cut_paper = &BASE[..BASE.rfind(')').unwrap()];
    let scenario_open = line_of(BASE, "Scenario(");
    let end = (cut_paper.trim_end().lines().count(), {
        let last = cut_paper.trim_end().lines().last().unwrap();
        last.chars().count() + 1
    });
    let cases = [
        (
            "(",
            "x.ron:1:2: Scenario: the file ends before its `(` at 1:1 is closed".to_string(),
        ),
        (
            "Scenario(kinds: [",
            "x.ron:1:18: kinds: the file ends before `[` at 1:17 is closed".into(),
        ),
        (
            "Scenario(name: \"x\", arena: (width_m: 1",
            "x.ron:1:39: arena.width_m: the file ends before `(` at 1:28 is closed".into(),
        ),
        (
            "Scenario(name: \"x\", arena: ",
            "x.ron:1:27: arena: the file ends before the scenario's `(` at 1:9 is closed".into(),
        ),
        (
            cut_paper,
            format!(
                "x.ron:{}:{}: Scenario: the file ends before its `(` at {scenario_open}:{} is \
                 closed",
                end.0,
                end.1,
                BASE.lines()
                    .nth(scenario_open - 1)
                    .unwrap()
                    .find('(')
                    .unwrap()
                    + 1
            ),
        ),
        // Errors before the cut are ron's, where ron finds them.
        (
            "Scenario(name: \"x\", arena: (width_m: \"a\"",
            "x.ron:1:37: arena.width_m: Expected float".into(),
        ),
        (
            "Scenario(name: \"x), ",
            "x.ron:1:16: name: Expected end of string".into(),
        ),
    ];
    for (src, want) in cases {
        let err = scenario::from_str(src, "x.ron").expect_err(src);
        assert_eq!(err.to_string(), want, "{src:?}");
    }
}
