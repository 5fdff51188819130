//! Throughput of `usar multiverse` (a `harness = false` bench that prints its figures): the
//! full factorial of four binary axes of `scenarios/paper.ron` (16 universes), each
//! calibrated as the committed multiverse is (docs/multiverse.md: two free fields, the
//! paper's targets with the three spread targets report-only, 4 trials per method and
//! evaluation, at most 20 evaluations) and then compared (4 methods x 10 trials), every trial
//! 600 s, on all cores. Prints the wall time, the trials run and the simulated seconds per wall-clock
//! second.
//!
//! Run in release: `cargo bench -p experiments --bench multiverse` (minutes). A small version
//! for CI and a quick look (2 universes drawn from the 16, 2 methods x 2 trials of 60 s, 1
//! calibration trial per method, at most 2 evaluations): `cargo bench -p experiments --bench
//! multiverse -- --quick` (or `MULTIVERSE_BENCH_QUICK=1`).

use std::path::{Path, PathBuf};
use std::time::Instant;

use usar_study::calibrate::{FreeField, Targets, TrialPlan};
use usar_study::multiverse::{
    Axes, MultiverseOutcome, MultiverseProgress, MultiverseSetup, Sample, run_multiverse,
};

/// Four of the paper's open choices, two alternatives each (`usar_sim::scenario::choices`).
const AXES: &str = r#"Axes(axes: [
    (name: "hp effect", paper: "\"the lower its HP, the smaller its velocity, sensing, and observing range\" (VI.B)",
     alternatives: [(name: "linear", set: ["mission.hp_effect=Linear"]),
                    (name: "none", set: ["mission.hp_effect=NoEffect"])]),
    (name: "round start", paper: "\"when all agents are back to the initial position, the whole group members will regroup\" (VI.B)",
     alternatives: [(name: "available", set: ["mission.round_start=Available"]),
                    (name: "all back", set: ["mission.round_start=AllBack"])]),
    (name: "load on leave", alternatives: [(name: "abandon", set: ["mission.load_on_leave=Abandon"]),
                                            (name: "deliver first", set: ["mission.load_on_leave=DeliverFirst"])]),
    (name: "refresh", paper: "\"recharging its energy (or for refreshing its health HP)\"",
     alternatives: [(name: "both", set: ["mission.refresh=Both"]),
                    (name: "low only", set: ["mission.refresh=LowOnly"])]),
])"#;

/// The two free fields, as the committed multiverse's.
const FREE: [&str; 2] = [
    "mission.hp_pct_per_step_in_radiation=0.002..0.02:log",
    "mission.search_time_budget_s=6..30",
];

/// The targets reported but not required, as the committed multiverse's.
const REPORT_ONLY: [&str; 3] = [
    "pooled SD of total rescuees",
    "pooled SD of hard-task rescuees",
    "pooled SD of easy-task rescuees",
];

fn root() -> PathBuf {
    PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
}

/// The bench's setup: the full one, or the quick one.
fn setup(quick: bool) -> MultiverseSetup {
    let path = root().join("scenarios/paper.ron");
    let text = std::fs::read_to_string(&path).expect("paper.ron");
    let base = usar_sim::scenario::parse_spec(&text, "scenarios/paper.ron").expect("parses");
    let axes = Axes::parse(AXES, "bench axes").expect("axes");
    let mut targets =
        Targets::load(&root().join("scenarios/paper-targets.ron")).expect("paper targets");
    let report_only: Vec<String> = REPORT_ONLY.iter().map(|n| n.to_string()).collect();
    targets
        .set_report_only(&report_only)
        .expect("names of the paper's targets");
    let free = FREE
        .iter()
        .map(|f| FreeField::parse(f).expect("free field"))
        .collect();
    let mut full = MultiverseSetup {
        calibration_trials: 4,
        max_evals: 20,
        ..MultiverseSetup::new(base, "scenarios/paper.ron", axes, targets, free)
    };
    full.comparison.trials = 10;
    if !quick {
        return full;
    }
    MultiverseSetup {
        comparison: TrialPlan {
            methods: vec!["rne".into(), "dis".into()],
            trials: 2,
            duration_s: Some(60.0),
            ..full.comparison.clone()
        },
        calibration_trials: 1,
        max_evals: 2,
        sample: Some(Sample { n: 2, seed: 1 }),
        ..full
    }
}

/// Trials the outcome's universes ran: every calibration evaluation's and the comparison's.
fn trials_run(setup: &MultiverseSetup, o: &MultiverseOutcome) -> usize {
    let per_evaluation = setup.comparison.methods.len() * setup.calibration_trials as usize;
    o.records
        .iter()
        .map(|r| {
            let calibration = r.calibration.as_ref().map_or(0, |c| c.evaluations);
            let comparison = r
                .comparison
                .as_ref()
                .map_or(0, |c| c.trials_ok + c.trials_failed);
            calibration * per_evaluation + comparison
        })
        .sum()
}

fn main() {
    let quick = std::env::args().any(|a| a == "--quick")
        || std::env::var_os("MULTIVERSE_BENCH_QUICK").is_some_and(|v| v != "0");
    let setup = setup(quick);
    let tmp = tempfile::tempdir().expect("temp dir");
    let length = setup
        .comparison
        .duration_s
        .unwrap_or(setup.base.mission.duration_s.get());
    println!(
        "multiverse bench{}: {} of 16 universes x {} methods x {} trials of {length} s; \
         calibration of 2 free fields: {} trial(s) per method and evaluation, at most {} \
         evaluations; {} thread(s)",
        if quick { " (quick)" } else { "" },
        setup.sample.map_or(16, |s| s.n),
        setup.comparison.methods.len(),
        setup.comparison.trials,
        setup.calibration_trials,
        setup.max_evals,
        setup.threads
    );
    let t0 = Instant::now();
    let o = run_multiverse(&setup, Path::new(tmp.path()), MultiverseProgress::off())
        .expect("the multiverse runs");
    let wall = t0.elapsed().as_secs_f64();
    let trials = trials_run(&setup, &o);
    let sim = trials as f64 * length;
    println!(
        "{} universes ({} admissible) in {wall:.2} s wall: {trials} trials, {:.0} sim-s per \
         wall-s ({:.0} per thread)",
        o.records.len(),
        o.admissible(),
        sim / wall,
        sim / wall / setup.threads as f64
    );
}
