//! Regression tests of issue 11 (hardening), one or more per class: what `check` accepts a
//! trial can run, and what it refuses gets one positioned line naming the field that breaks a
//! documented limit (`docs/scenario-format.md`, "Limits").

use std::path::PathBuf;
use std::time::Instant;

use usar_sim::mission::Simulation;
use usar_sim::scenario::{self, Scenario, ScenarioError, limits};
use usar_sim::world::ControlClock;

fn paper() -> String {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/paper.ron");
    std::fs::read_to_string(p).expect("paper.ron")
}

/// paper.ron with the first occurrence of `from` replaced by `to` (which must occur).
fn paper_with(from: &str, to: &str) -> String {
    let src = paper();
    assert!(src.contains(from), "paper.ron has no {from:?}");
    src.replacen(from, to, 1)
}

/// The error of loading `src`, checked to be one positioned line about `field`.
fn rejected(src: &str, field: &str) -> ScenarioError {
    let e = scenario::from_str(src, "t.ron").expect_err("must be rejected");
    let text = e.to_string();
    assert_eq!(e.field(), Some(field), "{text}");
    assert!(e.line_col().is_some(), "no position: {text}");
    assert!(!text.contains('\n'), "not one line: {text}");
    e
}

/// Five steps of `s` with the `rne` method.
fn short_run(s: &Scenario) {
    let mut sim = Simulation::builder(s)
        .method_named("rne")
        .duration_s(5.0 * s.sim().dt_s.get())
        .build()
        .expect("trial builds");
    sim.run_to_end().expect("trial runs");
}

// Class 1: counts near u32::MAX are positioned errors, not allocation aborts.

#[test]
fn a_robot_count_near_u32_max_is_an_error_at_the_count() {
    let src = paper_with("count: 6,", "count: 4294967290,").replacen(
        "quota: (easy: 3, hard: 3)",
        "quota: (easy: 4294967287, hard: 3)",
        1,
    );
    let e = rejected(&src, "kinds[0].count");
    assert!(e.to_string().contains("limit of 10000"), "{e}");
}

#[test]
fn a_debris_field_count_near_u32_max_is_an_error_at_the_count() {
    let e = rejected(
        &paper_with("count: 8,", "count: 4294967295,"),
        "debris_fields[0].count",
    );
    assert!(e.to_string().contains("limit of 10000"), "{e}");
}

// Class 2: derived quantities are validated.

#[test]
fn a_navigation_grid_beyond_the_cell_limit_is_an_error() {
    let e = rejected(
        &paper_with("grid_cell_m: 0.25", "grid_cell_m: 0.0001"),
        "navigation.grid_cell_m",
    );
    assert!(e.to_string().contains("navigation grid"), "{e}");
    // A huge arena: too long a side for the f32 world.
    rejected(
        &paper_with("width_m: 80.0", "width_m: 8000000.0"),
        "arena.width_m",
    );
}

#[test]
fn a_needs_level_that_would_make_a_need_infinite_is_an_error() {
    rejected(
        &paper_with("hp_needs_full: 2.0", "hp_needs_full: 1e308"),
        "kinds[0].hp_needs_full",
    );
    rejected(
        &paper_with("needs_weights: (hp: 1.0", "needs_weights: (hp: 1e300"),
        "needs_weights.hp",
    );
    // The largest accepted level runs.
    let (_, hi) = limits::NEEDS_RANGE;
    let src = paper_with("hp_needs_full: 2.0", &format!("hp_needs_full: {hi:e}"));
    short_run(&scenario::from_str(&src, "t.ron").expect("at the limit"));
}

#[test]
fn a_robot_faster_than_its_body_per_step_is_an_error() {
    let e = rejected(
        &paper_with("dt_s: 0.02", "dt_s: 0.5"),
        "kinds[0].max_speed_m_per_s",
    );
    assert!(e.to_string().contains("per step"), "{e}");
}

/// Two ground robots closing faster than a body radius per step passed through each other
/// (20 m/s, 0.4 m bodies, 0.02 s steps: 0.8 m per step); each alone moves 0.4 m per step,
/// which the per-kind rule allows.
#[test]
fn robots_that_close_more_than_a_body_radius_per_step_are_an_error() {
    let fast = paper_with("max_speed_m_per_s: 4.0,", "max_speed_m_per_s: 20.0,");
    let e = rejected(&fast, "kinds[0].max_speed_m_per_s");
    assert!(
        e.to_string()
            .contains("two carrier robots driving at each other close 0.8 m per step"),
        "{e}"
    );
    // 10 m/s closes 0.4 m per step: exactly the radius, accepted.
    scenario::from_str(
        &paper_with("max_speed_m_per_s: 4.0,", "max_speed_m_per_s: 10.0,"),
        "t.ron",
    )
    .expect("closing one body radius per step is allowed");
}

// Class 3: no endless trial, no endless validation.

#[test]
fn ten_thousand_kinds_are_an_error_at_the_kind_list() {
    let src = paper();
    let start = src.find("    kinds: [\n").expect("kinds") + "    kinds: [\n".len();
    let end = src.find("    rest_station").expect("rest_station");
    let kinds: String = (0..10_000)
        .map(|i| {
            format!(
                "(name: \"k{i}\", role: Observer, locomotion: Aerial, count: 1, \
                 quota: (hard: 1), body_radius_m: 0.01, max_speed_m_per_s: 0.1, \
                 sensing_range_m: 1.0, observing_range_m: 1.0, carrying_capacity: 0, \
                 rescuing_resources: 0, hp_needs_full: 1.0, energy_needs_full: 1.0, \
                 starts: List([({}.0, 1.0)])),\n",
                1 + i % 70
            )
        })
        .collect();
    let src = format!("{}{kinds}    ],\n{}", &src[..start], &src[end..]);
    let e = rejected(&src, "kinds");
    assert!(e.to_string().contains("limit of 256"), "{e}");
}

#[test]
fn a_trial_of_too_many_steps_is_an_error_with_a_short_message() {
    let e = rejected(
        &paper_with("duration_s: 600.0", "duration_s: 1e300"),
        "mission.duration_s",
    );
    assert!(e.to_string().contains("1e300 s"), "{e}");
    assert!(e.to_string().len() < 300, "{e}");
}

#[test]
fn two_thousand_generated_slabs_are_placed_quickly() {
    // One field of 2,000 small slabs over the whole arena, gap 0.3 m (the second field goes).
    let src = paper_with(
        "region: (min_m: (9.0, 26.0), max_m: (28.0, 37.0)),\n            count: 8,",
        "region: (min_m: (0.0, 0.0), max_m: (80.0, 60.0)),\n            count: 2000,",
    )
    .replacen("min_gap_m: 2.0,", "min_gap_m: 0.3,", 1)
    .replacen(
        "shape: Rects(side_m: (0.6, 1.6)",
        "shape: Rects(side_m: (0.2, 0.4)",
        1,
    );
    let start = src
        .find("        (\n            region: (min_m: (33.0")
        .expect("field 1");
    let end = start + src[start..].find("        ),\n").expect("its end") + "        ),\n".len();
    let src = format!("{}{}", &src[..start], &src[end..]);
    let t0 = Instant::now();
    let s = scenario::from_str(&src, "slabs.ron").expect("2,000 slabs fit");
    let took = t0.elapsed().as_secs_f64();
    assert_eq!(s.debris().len(), 11 + 2000);
    // Pairwise tests took 18 s in a release build; the index makes it well under a second.
    assert!(took < 6.0, "placing 2,000 slabs took {took} s");
}

// Class 4: starts exactly one body apart are accepted.

#[test]
fn starts_exactly_one_body_apart_are_accepted() {
    // 20.1 + 0.8 i: the float distances between neighbours are 0.79999999999999716 and the
    // like, one ulp-ish under the 0.8 m the two 0.4 m radii need.
    let src = paper_with(
        "starts: Row(first_m: (32.5, 3.0), step_m: (3.0, 0.0)),",
        "starts: Row(first_m: (20.1, 3.0), step_m: (0.8, 0.0)),",
    );
    let s = scenario::from_str(&src, "t.ron").expect("touching starts are accepted");
    let d = (1..6)
        .map(|i| (s.robots()[i].start_in_world - s.robots()[i - 1].start_in_world).norm())
        .fold(f64::INFINITY, f64::min);
    assert!(d < 0.8 && 0.8 - d < 1e-12, "{d}");
    // Clearly overlapping starts are still refused.
    let src = paper_with(
        "starts: Row(first_m: (32.5, 3.0), step_m: (3.0, 0.0)),",
        "starts: Row(first_m: (20.1, 3.0), step_m: (0.79, 0.0)),",
    );
    rejected(&src, "kinds[0].starts");
}

// Class 5: a huge speed names its field, once.

#[test]
fn a_huge_speed_is_reported_at_its_field_once() {
    let e = rejected(
        &paper_with("max_speed_m_per_s: 4.0", "max_speed_m_per_s: 1e308"),
        "kinds[0].max_speed_m_per_s",
    );
    let text = e.to_string();
    assert!(text.contains("limit of 100 m/s"), "{text}");
    assert!(!text.contains("weighted needs"), "{text}");
}

#[test]
fn a_sweep_spacing_that_makes_endless_waypoints_is_an_error() {
    rejected(
        &paper_with("sweep_spacing_m: None", "sweep_spacing_m: Some(1e-300)"),
        "mission.sweep_spacing_m",
    );
}

#[test]
fn a_step_that_makes_the_default_trial_too_long_is_blamed_on_the_step() {
    let p = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenarios/corridor.ron");
    let src = std::fs::read_to_string(p).expect("corridor.ron");
    assert!(!src.contains("duration_s"));
    assert!(
        src.contains("sim: (dt_s: 0.02"),
        "corridor.ron sets its step"
    );
    let src = src.replacen("sim: (dt_s: 0.02", "sim: (dt_s: 1e-9", 1);
    rejected(&src, "sim.dt_s");
}

#[test]
fn resources_that_would_overflow_a_group_sum_are_an_error() {
    rejected(
        &paper_with("rescuing_resources: 10,", "rescuing_resources: 4294967295,"),
        "kinds[1].rescuing_resources",
    );
    rejected(
        &paper_with("carrying_capacity: 6,", "carrying_capacity: 4294967295,"),
        "kinds[0].carrying_capacity",
    );
}

#[test]
fn a_huge_clearance_or_rescuee_grid_ratio_is_an_error_not_an_overflow() {
    rejected(
        &paper_with("clearance_m: 0.1", "clearance_m: 1e308"),
        "navigation.clearance_m",
    );
    rejected(
        &paper_with("spacing_m: 1.0", "spacing_m: 5e-324"),
        "tasks[0].rescuees.spacing_m",
    );
}

/// Byte ranges of the number literals of RON text `src`, outside comments and strings.
fn number_literals(src: &str) -> Vec<std::ops::Range<usize>> {
    let b = src.as_bytes();
    let (mut out, mut i) = (Vec::new(), 0);
    while i < b.len() {
        match b[i] {
            b'/' if b.get(i + 1) == Some(&b'/') => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
            }
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' {
                    i += 1 + usize::from(b[i] == b'\\');
                }
                i += 1;
            }
            c if c.is_ascii_alphabetic() || c == b'_' => {
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
            }
            c if c.is_ascii_digit()
                || (c == b'-' && b.get(i + 1).is_some_and(u8::is_ascii_digit)) =>
            {
                let start = i;
                i += 1;
                while i < b.len()
                    && (b[i].is_ascii_alphanumeric()
                        || b[i] == b'.'
                        || (b[i] == b'-' && matches!(b[i - 1], b'e' | b'E')))
                {
                    i += 1;
                }
                out.push(start..i);
            }
            _ => i += 1,
        }
    }
    out
}

/// The longest run of digits in `text`.
fn longest_digit_run(text: &str) -> usize {
    text.split(|c: char| !c.is_ascii_digit())
        .map(str::len)
        .max()
        .unwrap_or(0)
}

#[test]
fn huge_or_tiny_numbers_in_any_field_give_a_short_one_line_error() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../scenarios");
    let extremes = [
        "1e300",
        "-1e300",
        "1e-300",
        "123456789012345678901234567890.0",
    ];
    let (mut checked, mut faults) = (0, Vec::new());
    for name in ["paper.ron", "three-tasks.ron", "swarm-1000.ron"] {
        let src = std::fs::read_to_string(dir.join(name)).expect(name);
        let literals = number_literals(&src);
        assert!(
            literals.len() > 20,
            "{name}: only {} numbers",
            literals.len()
        );
        for range in literals {
            for x in extremes {
                let edited = format!("{}{x}{}", &src[..range.start], &src[range.end..]);
                let Err(e) = scenario::from_str(&edited, name) else {
                    continue;
                };
                let text = e.to_string();
                let fault = if e.line_col().is_none() {
                    "no position"
                } else if text.contains('\n') {
                    "not one line"
                } else if longest_digit_run(&text) > 24 || text.len() >= 400 {
                    "too long"
                } else {
                    ""
                };
                if !fault.is_empty() {
                    let literal = &src[range.clone()];
                    faults.push(format!("{name}: {literal} -> {x}: {fault}: {text}"));
                }
                checked += 1;
            }
        }
    }
    assert!(
        faults.is_empty(),
        "{} faults:\n{}",
        faults.len(),
        faults.join("\n")
    );
    assert!(checked > 100, "only {checked} edits were rejected");
}

#[test]
fn a_waypoint_tolerance_beyond_five_metres_is_an_error() {
    let e = rejected(
        &paper_with("waypoint_tolerance_m: 0.3", "waypoint_tolerance_m: 100.0"),
        "navigation.waypoint_tolerance_m",
    );
    assert!(e.to_string().contains("limit of 5 m"), "{e}");
    let s = scenario::from_str(
        &paper_with("waypoint_tolerance_m: 0.3", "waypoint_tolerance_m: 5.0"),
        "t.ron",
    )
    .expect("5 m is the limit, accepted");
    short_run(&s);
}

/// A tolerance below f32's reach was accepted and robots stalled short of their first
/// waypoint (1e-6 m: 4 rounds, then nothing; 1e-9 m: round 0 never completed).
#[test]
fn a_waypoint_tolerance_robots_cannot_meet_is_an_error() {
    for tiny in ["0.000001", "1e-9", "0.0009"] {
        let e = rejected(
            &paper_with(
                "waypoint_tolerance_m: 0.3",
                &format!("waypoint_tolerance_m: {tiny}"),
            ),
            "navigation.waypoint_tolerance_m",
        );
        assert!(
            e.to_string().contains("less than the least of 0.001 m"),
            "{e}"
        );
    }
    let s = scenario::from_str(
        &paper_with("waypoint_tolerance_m: 0.3", "waypoint_tolerance_m: 0.001"),
        "t.ron",
    )
    .expect("1 mm is the least in an 80 m arena");
    short_run(&s);
    // In a 10 km arena f32's spacing sets the bound.
    let least = scenario::limits::min_waypoint_tolerance_m(10_000.0);
    assert!((least - 0.019_073_486).abs() < 1e-6, "{least}");
}

/// A cell larger than the arena made a grid that saw no debris: robots drove into it and no
/// warning was given.
#[test]
fn a_navigation_cell_larger_than_the_arena_is_an_error() {
    let e = rejected(
        &paper_with("grid_cell_m: 0.25", "grid_cell_m: 200.0"),
        "navigation.grid_cell_m",
    );
    assert!(
        e.to_string()
            .contains("larger than the arena's shorter side (60 m)"),
        "{e}"
    );
    scenario::from_str(
        &paper_with("grid_cell_m: 0.25", "grid_cell_m: 60.0"),
        "t.ron",
    )
    .expect("a cell of the shorter side is accepted");
}

#[test]
fn a_wall_thicker_than_ten_kilometres_is_an_error_and_ten_run() {
    let e = rejected(
        &paper_with("wall_thickness_m: 1.0", "wall_thickness_m: 1e12"),
        "arena.wall_thickness_m",
    );
    assert!(
        e.to_string()
            .contains("1000000000000 m is longer than the limit of 10000 m"),
        "{e}"
    );
    let s = scenario::from_str(
        &paper_with("wall_thickness_m: 1.0", "wall_thickness_m: 10000.0"),
        "t.ron",
    )
    .expect("10 km is the limit, accepted");
    short_run(&s);
}

#[test]
fn a_scenario_file_past_the_size_limit_is_refused_not_read_whole() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("big.ron");
    // Sparse: no disk space is used, and the reader stops one byte past the limit.
    let file = std::fs::File::create(&path).expect("create");
    file.set_len(limits::MAX_SCENARIO_BYTES + 1)
        .expect("set_len");
    let e = scenario::load(&path).expect_err("too long");
    assert!(matches!(e, ScenarioError::Io { .. }), "{e}");
    assert_eq!(
        e.to_string(),
        format!(
            "{}: cannot read scenario file: longer than the limit of {} bytes",
            path.display(),
            limits::MAX_SCENARIO_BYTES
        )
    );
}

/// Regression (issue 70): a FIFO without a writer as the scenario waited for ever. It, and
/// `/dev/zero`, are refused as no regular file, in a thread so that a regression fails here.
#[cfg(unix)]
#[test]
fn a_fifo_or_a_device_as_the_scenario_is_refused_without_waiting() {
    let dir = tempfile::tempdir().expect("temp dir");
    let fifo = dir.path().join("fifo.ron");
    let made = std::process::Command::new("mkfifo").arg(&fifo).status();
    assert!(made.is_ok_and(|s| s.success()), "mkfifo");
    for path in [fifo, "/dev/zero".into()] {
        let (send, got) = std::sync::mpsc::channel();
        let p = path.clone();
        std::thread::spawn(move || send.send(scenario::load(&p).map(|_| ())));
        let e = got
            .recv_timeout(std::time::Duration::from_secs(10))
            .unwrap_or_else(|_| panic!("{}: still waiting after 10 s", path.display()))
            .expect_err("no regular file");
        assert!(matches!(e, ScenarioError::Io { .. }), "{e}");
        assert_eq!(
            e.to_string(),
            format!(
                "{}: cannot read scenario file: not a regular file (a folder, FIFO or device)",
                path.display()
            )
        );
    }
}

#[test]
fn read_source_skips_the_byte_order_mark_and_positions_a_bad_byte() {
    let dir = tempfile::tempdir().expect("temp dir");
    let path = dir.path().join("bom.ron");
    std::fs::write(
        &path,
        [b"\xEF\xBB\xBF".as_slice(), paper().as_bytes()].concat(),
    )
    .unwrap();
    assert_eq!(scenario::read_source(&path).expect("reads"), paper());
    std::fs::write(&path, b"(\n  name: \"a\xFFb\",\n)").unwrap();
    let e = scenario::read_source(&path).expect_err("not UTF-8");
    assert_eq!(e.line_col(), Some((2, 11)), "{e}");
}

#[test]
fn a_control_character_in_a_name_is_an_error_at_the_name() {
    for (from, to, field) in [
        ("name: \"paper\"", "name: \"pa\\nper\"", "name"),
        ("name: \"carrier\"", "name: \"car\\trier\"", "kinds[0].name"),
        ("name: \"hard\"", "name: \"ha\\u{7}rd\"", "tasks[0].name"),
    ] {
        let e = rejected(&paper_with(from, to), field);
        assert!(e.to_string().contains("holds the control character"), "{e}");
    }
    // A line separator is not a control character, but it breaks a line as one does.
    let e = rejected(
        &paper_with("name: \"easy\"", "name: \"ea\\u{2028}sy\""),
        "tasks[1].name",
    );
    assert!(
        e.to_string()
            .contains("holds the line-breaking character '\\u{2028}'"),
        "{e}"
    );
    // Other characters stay allowed.
    scenario::from_str(
        &paper_with("name: \"paper\"", "name: \"pa: per/é\""),
        "t.ron",
    )
    .expect("a name with punctuation and accents");
}

/// A task named `total` would give two `rescued_total` columns (the sum over the tasks and
/// the task's own): it is refused at its name.
#[test]
fn the_task_name_total_is_reserved() {
    let text = paper_with("name: \"hard\"", "name: \"total\"")
        .replace("\"hard\":", "\"total\":")
        .replace("hard:", "total:");
    let e = rejected(&text, "tasks[0].name");
    assert!(e.to_string().contains("\"total\" is reserved"), "{e}");
}

/// Regression: a task named `per_rescuee` made `energy_per_rescuee_pct` and
/// `hp_per_rescuee_pct` twice in trials.csv and summary.csv (the task's cost and the cost per
/// rescuee of all tasks), and `per_hard_rescuee` next to `hard` likewise, silently.
#[test]
fn task_names_that_would_repeat_a_per_rescuee_column_are_refused() {
    let renamed = |to: &str| {
        paper_with("name: \"easy\"", &format!("name: \"{to}\""))
            .replace("\"easy\":", &format!("\"{to}\":"))
            .replace("easy:", &format!("{to}:"))
    };
    for (name, whose) in [
        ("per_rescuee", "all tasks"),
        ("per_hard_rescuee", "task \"hard\""),
    ] {
        let e = rejected(&renamed(name), "tasks[1].name");
        let want = format!(
            "the task name \"{name}\" would give the column energy_{name}_pct, the energy per rescuee of {whose}"
        );
        assert!(e.to_string().contains(&want), "{e}");
    }
    // A name that only looks alike is a task like any other.
    for name in [
        "per_easy_rescuee",
        "per__rescuee",
        "per_rescuees",
        "rescuee",
    ] {
        scenario::from_str(&renamed(name), "t.ron").unwrap_or_else(|e| panic!("{name}: {e}"));
    }
}

#[test]
fn a_step_count_past_f64_is_said_in_words_not_inf() {
    let err = usar_sim::scenario::trial_steps(1e308, 0.02).unwrap_err();
    assert_eq!(
        err,
        "trial length 1e308 s is more than 1.8e308 steps of 0.02 s, more than the limit of \
         10000000 steps"
    );
    let err = usar_sim::scenario::trial_steps(1e300, 0.02).unwrap_err();
    assert!(err.contains("is 5e301 steps"), "{err}");
}

// `sim.control_period_s`: a whole number of steps, from one step to the whole trial.

#[test]
fn a_control_period_that_is_no_whole_number_of_steps_is_an_error() {
    for (bad, says) in [
        ("0.01", "shorter than one step"),
        ("1e-300", "shorter than one step"),
        ("0.05", "not a whole number of steps"),
        ("0.1000001", "not a whole number of steps"),
    ] {
        let src = paper_with(
            "sim: (dt_s: 0.02, seed: 2021,",
            &format!("sim: (dt_s: 0.02, seed: 2021, control_period_s: Some({bad}),"),
        );
        let e = rejected(&src, "sim.control_period_s");
        assert!(e.to_string().contains(says), "{bad}: {e}");
    }
}

#[test]
fn a_control_period_longer_than_the_trial_is_an_error() {
    let src = paper_with(
        "sim: (dt_s: 0.02, seed: 2021,",
        "sim: (dt_s: 0.02, seed: 2021, control_period_s: Some(600.02),",
    );
    let e = rejected(&src, "sim.control_period_s");
    assert!(e.to_string().contains("longer than the trial"), "{e}");
}

#[test]
fn control_periods_of_whole_steps_are_accepted_and_run() {
    for (period, steps) in [
        ("0.02", 1),
        ("0.1", 5),
        ("0.30000000000000004", 15),
        ("600", 30_000),
    ] {
        let src = paper_with(
            "sim: (dt_s: 0.02, seed: 2021,",
            &format!("sim: (dt_s: 0.02, seed: 2021, control_period_s: Some({period}),"),
        );
        let s = scenario::from_str(&src, "t.ron").unwrap_or_else(|e| panic!("{period}: {e}"));
        assert_eq!(ControlClock::of(s.sim()).period_steps(), steps, "{period}");
        short_run(&s);
    }
    let s = scenario::from_str(&paper(), "paper.ron").expect("paper.ron");
    assert_eq!(s.sim().control_period_s, None);
    assert_eq!(ControlClock::of(s.sim()).period_steps(), 1);
}

// A start touching debris is accepted as two touching starts are (`START_TOLERANCE`).

#[test]
fn a_start_touching_debris_is_accepted_and_one_overlapping_it_is_not() {
    let debris = "        Circle(center_m: (21.0, 24.0), radius_m: 1.5),\n";
    // Carrier 0 starts at (32.5, 3.0): a disc of 1.1 m at (31.0, 3.0) touches its 0.4 m body;
    // in floats its centre is 0.3999999999999999 m from the disc.
    let touching = paper_with(
        debris,
        &format!("{debris}        Circle(center_m: (31.0, 3.0), radius_m: 1.1),\n"),
    );
    let s = scenario::from_str(&touching, "t.ron").unwrap_or_else(|e| panic!("{e}"));
    short_run(&s);
    let overlapping = paper_with(
        debris,
        &format!("{debris}        Circle(center_m: (31.0, 3.0), radius_m: 1.1001),\n"),
    );
    let e = rejected(&overlapping, "kinds[0].starts");
    assert!(e.to_string().contains("overlaps debris"), "{e}");
}
