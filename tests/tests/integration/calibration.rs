//! The calibrated paper mission against the eighteen targets of `scenarios/paper-targets.ron`
//! (docs/calibration.md), pooled over all methods: a whole paper sweep (4 methods x 10 trials
//! x 600 s, the sweep's default seeds) and 30 trials per method it was never fitted on (base
//! seed 7, as `usar calibrate --check-seed` defaults to).
//!
//! `paper.ron` runs on the authors' clock (docs/calibration.md, "The authors' clock") with one
//! team stock of rescuing resources per round ("A rule that couples the tasks"): the tests
//! assert exactly which bands it holds on each set of trials (all eighteen on both),
//! so a change that moves a statistic across its band's edge fails here by name. The recorded
//! regimes of issue 55 are checked the same way.

use integration_tests::{method, paper, scenario_path};
use rayon::prelude::*;
use usar_report::calibration::check;
use usar_sim::mission::{Simulation, TrialResult};
use usar_sim::scenario::Scenario;
use usar_study::calibrate::{FreeField, Targets};
use usar_study::multiverse::{Axes, MultiverseSetup};

/// The spread targets (pooled within-method SDs of the rescuees per trial).
const SPREAD: [&str; 3] = [
    "pooled SD of total rescuees",
    "pooled SD of hard-task rescuees",
    "pooled SD of easy-task rescuees",
];

/// The nine mean targets, in the order of `paper-targets.ron`.
const MEANS: [&str; 9] = [
    "rounds per trial",
    "easy / hard rescuees",
    "rescuees per trial",
    "easy rescuees per round",
    "hard rescuees per round",
    "hard HP / hard energy",
    "easy HP / easy energy",
    "hard / easy energy",
    "hard / easy HP",
];

/// Every built-in method x `trials` trials of `s` from base seed `base_seed`, in parallel.
fn sweep(s: &Scenario, trials: u32, base_seed: u64) -> Vec<TrialResult> {
    let jobs: Vec<(&str, u32)> = ["rne", "dis", "eng", "hp_dis"]
        .into_iter()
        .flat_map(|m| (0..trials).map(move |k| (m, k)))
        .collect();
    jobs.par_iter()
        .map(|&(name, k)| {
            Simulation::builder(s)
                .method(method(name, s))
                .trial(k)
                .base_seed(base_seed)
                .build()
                .and_then(|mut sim| sim.run_to_end())
                .expect("built-in methods do not fail")
        })
        .collect()
}

/// Asserts that `results` hold exactly the targets named in `held` (in the order of
/// `paper-targets.ron`) and every statistic is defined; the message lists those out of band.
fn assert_holds<S: AsRef<str>>(results: &[TrialResult], what: &str, held: &[S]) {
    let checked = check(results);
    assert_eq!(checked.len(), 18);
    let holds: Vec<&str> = checked
        .iter()
        .filter(|(t, x)| t.holds(*x))
        .map(|(t, _)| t.name.as_str())
        .collect();
    let out: Vec<String> = checked
        .iter()
        .filter(|(t, x)| !t.holds(*x))
        .map(|(t, x)| format!("{} {x:.3} ({})", t.name, t.describe()))
        .collect();
    assert!(
        checked.iter().all(|(_, x)| x.is_finite()),
        "{what}: {out:?}"
    );
    let held: Vec<&str> = held.iter().map(AsRef::as_ref).collect();
    assert_eq!(holds, held, "{what}: out of band: {}", out.join("; "));
}

/// The targets of `paper-targets.ron` but those named in `out`, in the file's order.
fn all_but(out: &[&str]) -> Vec<String> {
    let t = usar_report::calibration::paper_targets();
    t.targets()
        .iter()
        .map(|t| t.name.clone())
        .filter(|n| !out.contains(&n.as_str()))
        .collect()
}

#[test]
#[ignore = "long: the paper sweep, 40 trials of 600 s (about 11 s in debug); just test-all, CI in release"]
fn a_paper_sweep_holds_all_eighteen_bands() {
    let s = paper();
    assert_holds(
        &sweep(&s, 10, s.sim().seed),
        "the paper sweep",
        &all_but(&[]),
    );
}

#[test]
#[ignore = "long: 120 unseen trials of 600 s (about 35 s in debug); just test-all, CI in release"]
fn thirty_unseen_trials_hold_all_eighteen_bands() {
    // With one team stock of rescuing resources per round the hard and easy yields trade off
    // on unseen trials too (S5 -0.46; docs/calibration.md, "A rule that couples the tasks").
    let held = all_but(&[]);
    assert!(MEANS.iter().all(|m| held.iter().any(|h| h == m)));
    assert_holds(&sweep(&paper(), 30, 7), "30 trials from seed 7", &held);
}

#[test]
#[ignore = "long: 120 unseen trials of 600 s (about 35 s in debug); just test-all, CI in release"]
fn before_the_team_stock_thirty_unseen_trials_held_sixteen_bands() {
    // paper-v2.ron, the model before the team stock: out on the unseen trials the SD of total
    // rescuees (9.75 against at most 7) and the hard-easy correlation within a method (S5:
    // +0.17 against at most -0.10), which the fit's 10 trials per method met.
    let s = usar_sim::scenario::load(scenario_path("paper-v2.ron")).expect("paper-v2.ron loads");
    let held = all_but(&[SPREAD[0], "hard-easy correlation within a method"]);
    assert_holds(
        &sweep(&s, 30, 7),
        "paper-v2.ron, 30 trials from seed 7",
        &held,
    );
}

/// The bands one recorded calibration of docs/calibration.md, "The authors' regime", holds:
/// its `calibrated.ron` run again on the fit's trials (10 per method from the scenario's seed)
/// and on 30 unseen trials per method from seed 7 must hold exactly the targets named here,
/// in the order of `paper-targets.ron`, and no other (every trial is a function of its seed, so
/// these are the numbers the calibration's `calibration.md` reports).
fn assert_regime(run: &str, in_fit: &[&str], unseen: &[&str]) {
    let path = format!(
        "{}/../docs/calibration/{run}/calibrated.ron",
        env!("CARGO_MANIFEST_DIR")
    );
    let s = integration_tests::load(&path);
    for (what, trials, seed, expected) in [
        ("the fit's trials", 10, s.sim().seed, in_fit),
        ("30 unseen trials", 30, 7, unseen),
    ] {
        assert_holds(
            &sweep(&s, trials, seed),
            &format!("{run} on {what}"),
            expected,
        );
    }
}

#[test]
#[ignore = "long: 160 trials of 600 s (about 10 s in release); just test-all, CI in release"]
fn regime_a_holds_the_structure_but_not_the_means() {
    // Out on both: rounds, easy / hard, both per-round yields but none, the HP and energy
    // ratios but one, the three spreads, S1 and S2; on the unseen trials also S6.
    let fit = [
        "rescuees per trial",
        "easy HP / easy energy",
        "energy CV within a method, %",
        "pooled SD of rounds",
        "hard-easy correlation within a method",
        "cross-method correlation of trial totals",
    ];
    assert_regime("regime-a", &fit, &fit[..5]);
}

#[test]
#[ignore = "long: 160 trials of 600 s (about 10 s in release); just test-all, CI in release"]
fn regime_b_holds_most_means_but_not_the_structure() {
    // Out on both: rounds, easy / hard, hard rescuees per round, hard HP / hard energy, the
    // SD of total rescuees, S1, S2, the energy CV and S6; on the unseen trials also the
    // hard-easy correlation, while two spreads come into their bands.
    let means = [
        "rescuees per trial",
        "easy rescuees per round",
        "easy HP / easy energy",
        "hard / easy energy",
        "hard / easy HP",
    ];
    let fit = [
        &means[..],
        &[
            "pooled SD of easy-task rescuees",
            "pooled SD of rounds",
            "hard-easy correlation within a method",
        ],
    ]
    .concat();
    let unseen = [
        &means[..],
        &[
            "pooled SD of hard-task rescuees",
            "pooled SD of easy-task rescuees",
            "pooled SD of rounds",
        ],
    ]
    .concat();
    assert_regime("regime-b", &fit, &unseen);
}

#[test]
fn the_spread_targets_are_names_of_the_paper_targets() {
    let mut t = Targets::load(std::path::Path::new(&scenario_path("paper-targets.ron")))
        .expect("paper-targets.ron loads");
    let names: Vec<String> = SPREAD.iter().map(|n| n.to_string()).collect();
    t.set_report_only(&names)
        .expect("--report-only names of the recorded calibration");
    // The three, and S1 and S2, reported under today's reading of the sheet's cost unit.
    assert_eq!(t.targets().iter().filter(|t| t.report_only).count(), 5);
}

/// `scenarios/paper-axes.ron`, the multiverse's axes: at least ten axes of the paper's open
/// choices, each with at least two alternatives and the paper's words, checked against
/// paper.ron as `usar multiverse` checks them (every alternative applies and validates, no two
/// alternatives of an axis give the same scenario, no axis sets a free field).
#[test]
fn the_paper_axes_check_against_paper_ron() {
    let axes = Axes::load(std::path::Path::new(&scenario_path("paper-axes.ron")))
        .expect("paper-axes.ron parses");
    assert!(axes.axes.len() >= 10, "{} axes", axes.axes.len());
    for a in &axes.axes {
        assert!(a.alternatives.len() >= 2, "axis {}", a.name);
        assert!(
            !a.paper.trim().is_empty(),
            "axis {} quotes no paper",
            a.name
        );
    }
    let text = std::fs::read_to_string(scenario_path("paper.ron")).unwrap();
    let base = usar_sim::scenario::parse_spec(&text, "scenarios/paper.ron").unwrap();
    let targets = usar_report::calibration::paper_targets().clone();
    let free = vec![
        FreeField::parse("mission.hp_pct_per_step_in_radiation=0.002..0.02:log").unwrap(),
        FreeField::parse("mission.search_time_budget_s=6..30").unwrap(),
    ];
    let mut setup = MultiverseSetup::new(base, "scenarios/paper.ron", axes, targets, free);
    // More universes than one multiverse runs whole: the committed command draws a sample.
    let whole = setup.check().unwrap_err().to_string();
    assert!(whole.contains("draw some with --sample N"), "{whole}");
    setup.sample = Some(usar_study::multiverse::universe::Sample { n: 64, seed: 2021 });
    let checked = setup.check().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(checked.universes.len(), 64);
    let size = usar_study::multiverse::universe::factorial_size(&setup.axes.sizes()).unwrap();
    assert!(size >= 4096, "{size}");
}

/// Every claims file in `scenarios/` (`paper-claims.ron`) parses, and the paper's checks
/// against paper.ron's tasks and the built-in methods, as a sweep checks it.
#[test]
fn the_claims_files_parse_and_fit_paper_ron() {
    let claims =
        usar_report::claims::Claims::load(std::path::Path::new(&scenario_path("paper-claims.ron")))
            .expect("paper-claims.ron parses");
    assert_eq!(claims, *usar_report::claims::paper_claims());
    let paper = usar_sim::scenario::load(scenario_path("paper.ron")).unwrap();
    claims.check_tasks(&paper.task_names()).unwrap();
    claims.check_methods(&[]).unwrap();
    assert_eq!(
        paper.report().claims.as_deref(),
        Some("paper-claims.ron"),
        "paper.ron names its claims"
    );
}
