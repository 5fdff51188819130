//! `usar sweep --vary`: a grid writes every file (cell folders, grid.csv, grid.md, figures),
//! two fields give heat maps and more give tables only, each cell's scenario.ron round-trips
//! through `usar check`, and bad --vary inputs are one-line errors before anything runs.

use crate::common;

use std::path::Path;
use std::process::{Command, Output};

use usar_sim::scenario::parse_spec;

use common::{PAPER, ok, read_text, usar};

const HP: &str = "mission.hp_pct_per_step_in_radiation";

/// A short grid sweep of paper.ron into `out`: rne,dis x 2 trials x 5 s, then `extra`.
fn grid(out: &Path, extra: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_usar"))
        .args(["sweep", PAPER, "--methods", "rne,dis", "--trials", "2"])
        .args(["--duration", "5", "--threads", "1", "--quiet", "--out"])
        .arg(out)
        .args(extra)
        .output()
        .expect("run usar")
}

const CELL_FILES: [&str; 7] = [
    "trials.csv",
    "summary.csv",
    "report.md",
    "fig3a_rescuees.svg",
    "fig3b_energy_per_rescuee.svg",
    "fig3c_hp_per_rescuee.svg",
    "scenario.ron",
];

#[test]
fn a_two_value_grid_writes_every_file() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g");
    let vary = format!("{HP}=0.0003,0.003");
    let o = grid(&out, &["--vary", &vary]);
    ok(&o);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(stdout.contains("over a grid of 2 cells"), "{stdout}");

    let cells = [
        "c00_hp_pct_per_step_in_radiation=0.0003",
        "c01_hp_pct_per_step_in_radiation=0.003",
    ];
    for cell in cells {
        for f in CELL_FILES {
            let p = out.join(cell).join(f);
            assert!(
                p.metadata().is_ok_and(|m| m.len() > 0),
                "{} missing",
                p.display()
            );
        }
        let trials = read_text(&out.join(cell).join("trials.csv"));
        assert_eq!(trials.lines().count(), 1 + 4, "{trials}");
        let report = read_text(&out.join(cell).join("report.md"));
        assert!(
            report.contains("cell ") && report.contains("scenario.ron"),
            "{report}"
        );
    }
    for f in [
        "journal.jsonl",
        "grid.csv",
        "grid.md",
        "grid_rescued_total.svg",
        "grid_rescued_hard.svg",
        "grid_rescued_easy.svg",
    ] {
        assert!(out.join(f).exists(), "{f} missing");
    }
    // grid.csv: long form, one row per cell x method x metric (17 metrics).
    let csv = read_text(&out.join("grid.csv"));
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        format!("{HP},method,metric,n,mean,sd,ci95_low,ci95_high")
    );
    let rows: Vec<&str> = lines.collect();
    assert_eq!(rows.len(), 2 * 2 * 17);
    assert!(
        rows[0].starts_with("0.0003,RNE,rescued_total,2,"),
        "{}",
        rows[0]
    );
    assert!(
        rows[34].starts_with("0.003,RNE,rescued_total,2,"),
        "{}",
        rows[34]
    );
    // One line chart per chosen metric, linked from grid.md with both values in its tables.
    let md = read_text(&out.join("grid.md"));
    assert!(md.contains("![rescuees, total across the grid](grid_rescued_total.svg)"));
    assert!(md.contains("| 1 | `0.003` |"), "{md}");
    let svg = read_text(&out.join("grid_rescued_total.svg"));
    assert!(
        svg.contains("bands: 95 % confidence interval"),
        "not a line chart"
    );
    // The journal: one header with the grid, every record with its cell.
    let journal = read_text(&out.join("journal.jsonl"));
    let first = journal.lines().next().unwrap();
    assert!(first.contains(&format!("\"fields\":[\"{HP}\"]")), "{first}");
    let cells_seen: Vec<&str> = journal
        .lines()
        .skip(1)
        .map(|l| &l[..l.find(",\"method\"").unwrap()])
        .collect();
    assert_eq!(cells_seen.len(), 8);
    assert_eq!(
        cells_seen
            .iter()
            .filter(|c| c.ends_with("\"cell\":1"))
            .count(),
        4
    );
}

#[test]
fn a_cell_scenario_ron_round_trips_through_check() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g");
    let vary = "kinds[0].starts.first_m=(32.5, 3.0),(31.5, 2.5)";
    ok(&grid(&out, &["--vary", vary]));
    let cell = out.join("c01_first_m=31.5_2.5");
    let ron = cell.join("scenario.ron");
    let o = usar(["check", ron.to_str().unwrap(), "--hash"]);
    ok(&o);
    let hash = String::from_utf8(o.stdout).unwrap().trim().to_string();
    // The same hash as the journal records for the cell, and as the report shows.
    let header = read_text(&out.join("journal.jsonl"));
    let header = header.lines().next().unwrap();
    let cell1 = &header[header.find("{\"values\":[\"(31.5, 2.5)\"]").unwrap()..];
    assert!(
        cell1.contains(&format!("\"scenario_hash\":\"{hash}\"")),
        "{hash} not in {header}"
    );
    assert!(read_text(&cell.join("report.md")).contains(&hash));
    // The spec equals the one `check --set --print` gives for the same override.
    let o = usar([
        "check",
        PAPER,
        "--set",
        "kinds[0].starts.first_m=(31.5, 2.5)",
        "--print",
    ]);
    ok(&o);
    let printed = parse_spec(&String::from_utf8(o.stdout).unwrap(), "printed").unwrap();
    let written = parse_spec(&read_text(&ron), "written").unwrap();
    assert_eq!(printed, written);
    let base = parse_spec(&read_text(Path::new(PAPER)), "paper").unwrap();
    assert_ne!(written, base);
}

#[test]
fn two_fields_give_heat_maps_and_more_give_tables_only() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("g");
    let o = grid(
        &out,
        &[
            "--vary",
            &format!("{HP}=0.0003,0.003"),
            "--vary",
            "kinds[0].max_speed_m_per_s=1.0,2.0",
            "--grid-metrics",
            "rescued_total,rounds",
        ],
    );
    ok(&o);
    let dirs: Vec<String> = std::fs::read_dir(&out)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with('c'))
        .collect();
    assert_eq!(dirs.len(), 4, "{dirs:?}");
    assert!(
        out.join("c03_hp_pct_per_step_in_radiation=0.003_max_speed_m_per_s=2.0")
            .is_dir()
    );
    for metric in ["rescued_total", "rounds"] {
        let svg = read_text(&out.join(format!("grid_{metric}.svg")));
        assert!(
            svg.contains("cells: mean over trials"),
            "{metric}: not a heat map"
        );
        for needle in ["RNE", "DIS", HP, "kinds[0].max_speed_m_per_s"] {
            assert!(svg.contains(needle), "{metric}: {needle} missing");
        }
    }
    assert!(!out.join("grid_rescued_hard.svg").exists());
    let md = read_text(&out.join("grid.md"));
    assert!(md.contains("## rounds (`rounds`)"), "{md}");

    // Three fields (one value each: a single cell): tables, no figure, and grid.md says so.
    let out3 = tmp.path().join("g3");
    ok(&grid(
        &out3,
        &[
            "--vary",
            &format!("{HP}=0.003"),
            "--vary",
            "sim.dt_s=0.025",
            "--vary",
            "collision.enabled=false",
        ],
    ));
    assert!(!out3.join("grid_rescued_total.svg").exists());
    let md = read_text(&out3.join("grid.md"));
    assert!(md.contains("No figure: 3 fields are varied"), "{md}");
    assert!(
        out3.join("c00_hp_pct_per_step_in_radiation=0.003_dt_s=0.025_enabled=false/trials.csv")
            .exists()
    );
}

#[test]
fn bad_vary_inputs_are_one_line_errors_and_run_nothing() {
    let tmp = tempfile::tempdir().unwrap();
    let out = tmp.path().join("bad");
    let cases: [(&[&str], &str); 8] = [
        (
            &["--vary", "mission.duration_s=60,-5"],
            "error: --vary mission.duration_s=-5: mission.duration_s: expected a finite number \
             > 0, found -5",
        ),
        (
            &["--vary", "mission.hp_rate=1"],
            "error: --vary mission.hp_rate=1: no field \"hp_rate\" in mission (fields: \
             duration_s, energy_pct_per_moving_step, energy_pct_per_m, \
             hp_pct_per_step_in_radiation,",
        ),
        (
            &["--vary", "radiation_zones[7].radius_m=1,2"],
            "error: --vary radiation_zones[7].radius_m=1,2: no element [7] in radiation_zones: \
             it has 7 (indices 0 to 6)",
        ),
        (
            &["--vary", "kinds[0].count=6,many"],
            "error: --vary kinds[0].count=many: kinds[0].count: expected a number, found many",
        ),
        (
            &["--vary", "kinds[0].count=2.5"],
            "error: --vary kinds[0].count=2.5: kinds[0].count: expected a whole number (0 or \
             more), found 2.5",
        ),
        (
            &["--vary", "sim.dt_s=0.01", "--vary", "sim.dt_s=0.02"],
            "error: --vary sim.dt_s is given twice: vary each field once",
        ),
        (
            &["--vary", "radiation_zones[*].radius_m=2,100"],
            "error: --vary radiation_zones[*].radius_m=100: radiation_zones[0]:",
        ),
        (
            &[
                "--vary",
                "sim.dt_s=0.01",
                "--grid-metrics",
                "rescued,rounds",
            ],
            "error: --grid-metrics: unknown metric \"rescued\" (metrics: rescued_total, \
             rescued_hard, rescued_easy,",
        ),
    ];
    for (args, want) in cases {
        let o = grid(&out, args);
        assert!(!o.status.success(), "{args:?}");
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(err.starts_with(want), "{args:?}:\n{err}");
        assert_eq!(err.lines().count(), 1, "{args:?}: {err}");
        assert!(!out.exists(), "{args:?} created {}", out.display());
    }
    // --grid-metrics needs --vary.
    let o = grid(&out, &["--grid-metrics", "rounds"]);
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("--vary"));
    assert!(!out.exists());
}

#[test]
fn each_cell_runs_its_own_duration_unless_duration_is_given() {
    let tmp = tempfile::tempdir().unwrap();
    // The simulated length of each journaled trial, by cell.
    let run = |out: &Path, extra: &[&str]| -> Vec<(u64, f64)> {
        let o = Command::new(env!("CARGO_BIN_EXE_usar"))
            .args([
                "sweep",
                PAPER,
                "--methods",
                "rne",
                "--trials",
                "1",
                "--quiet",
            ])
            .args(["--vary", "mission.duration_s=3,6", "--out"])
            .arg(out)
            .args(extra)
            .output()
            .expect("run usar");
        ok(&o);
        let mut d: Vec<(u64, f64)> = read_text(&out.join("journal.jsonl"))
            .lines()
            .skip(1)
            .map(|l| {
                let v: serde_json::Value = serde_json::from_str(l).unwrap();
                let t = &v["trial"];
                let cell = t["cell"].as_u64().unwrap();
                (cell, t["outcome"]["ok"]["duration_s"].as_f64().unwrap())
            })
            .collect();
        d.sort_by_key(|x| x.0);
        d
    };
    assert_eq!(run(&tmp.path().join("own"), &[]), [(0, 3.0), (1, 6.0)]);
    let md = read_text(&tmp.path().join("own/grid.md"));
    assert!(md.contains("of each cell's `mission.duration_s`"), "{md}");
    assert_eq!(
        run(&tmp.path().join("fixed"), &["--duration", "2"]),
        [(0, 2.0), (1, 2.0)]
    );
}
