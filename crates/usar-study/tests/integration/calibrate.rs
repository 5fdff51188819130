//! `usar_study::calibrate::calibrate` as a library call (the multiverse command runs one per
//! universe): progress off, any folder; failing trials and broken rules are evaluations with
//! an infinite loss, not errors; loss 0 stops the search; a larger budget continues it.

use std::path::Path;
use std::sync::{Arc, Mutex};

use rne_core::grouping::{Assignment, GroupingMethod, GroupingRequest};
use usar_study::calibrate::{
    CalibrationSetup, Checked, Evaluator, FreeField, Progress, StopReason, Targets, calibrate,
};
use usar_sweep::sweep::MethodFactory;

const PAPER: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper-v1.ron");

/// Targets every short paper run meets (bands wide open) but for `rescued` rescuees per
/// trial, within 1.
fn targets(rescued: Option<f64>) -> Targets {
    let mut text = String::from(
        "Targets(targets: [(name: \"rounds\", statistic: Mean(\"rounds\"), value: 1.0, band: \
         Between(0.0, 100.0))",
    );
    if let Some(r) = rescued {
        text.push_str(&format!(
            ", (name: \"rescuees\", statistic: Mean(\"rescued_total\"), value: {r:?}, band: \
             PlusMinus(1.0))"
        ));
    }
    text.push_str("])");
    Targets::parse(&text, "test targets").unwrap()
}

/// A short calibration of `free` in paper-v1.ron (the model before the authors' clock, pinned): RNE, 1 trial of 60 s per evaluation (the first
/// deliveries come after about 40 s), no check.
fn setup(free: &[&str], targets: Targets, max_evals: usize) -> CalibrationSetup {
    let text = std::fs::read_to_string(PAPER).unwrap();
    let base = usar_sim::scenario::parse_spec(&text, "paper.ron").unwrap();
    let free = free.iter().map(|f| FreeField::parse(f).unwrap()).collect();
    let mut setup = CalibrationSetup {
        max_evals,
        check_trials: 0,
        threads: 2,
        date: Some("2000-01-01T00:00:00Z".into()),
        ..CalibrationSetup::new(base, "paper.ron", targets, free)
    };
    setup.trial_plan.methods = vec!["rne".into()];
    setup.trial_plan.trials = 1;
    setup.trial_plan.duration_s = Some(60.0);
    setup
}

/// A grouping method that panics when asked to group.
struct Boom;

impl GroupingMethod for Boom {
    fn name(&self) -> &str {
        "boom"
    }

    fn assign(&self, _: &GroupingRequest) -> rne_core::Result<Assignment> {
        panic!("boom on purpose")
    }
}

#[test]
fn loss_zero_stops_at_once_and_writes_every_file() {
    let dir = tempfile::tempdir().unwrap();
    let s = setup(&["mission.pickup_s=0.5..2"], targets(None), 10);
    let o = calibrate(&s, dir.path(), Progress::off()).unwrap();
    assert_eq!(o.stop, StopReason::TargetReached);
    assert_eq!((o.evaluations.len(), o.ran, o.reused), (1, 1, 0));
    assert!(o.admissible && o.loss == 0.0);
    // The start is the scenario's own value.
    assert_eq!(o.best_values(), [1.2]);
    assert_eq!(o.best_spec.mission.pickup_s.get(), 1.2);
    assert!(o.check.is_none());
    let names: Vec<String> = o
        .files
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect();
    assert_eq!(
        names,
        [
            "trace.jsonl",
            "calibrated.ron",
            "trace.csv",
            "calibration.md",
            "convergence.svg",
            "statistics.svg"
        ]
    );
    assert!(
        o.files
            .iter()
            .all(|p| p.starts_with(dir.path()) && p.is_file())
    );
}

#[test]
fn start_mid_starts_at_the_middle_of_the_range_and_is_another_calibration() {
    let dir = tempfile::tempdir().unwrap();
    let s = CalibrationSetup {
        start_mid: true,
        ..setup(&["mission.pickup_s=0.5..2"], targets(None), 10)
    };
    let o = calibrate(&s, dir.path(), Progress::off()).unwrap();
    assert_eq!(o.best_values(), [1.25]);
    assert!(
        o.header.search.ends_with("start: the ranges' middles"),
        "{}",
        o.header.search
    );
    // The same folder refuses the calibration that starts from the scenario's values.
    let e = calibrate(
        &setup(&["mission.pickup_s=0.5..2"], targets(None), 10),
        dir.path(),
        Progress::off(),
    )
    .unwrap_err();
    assert!(
        format!("{e:#}").contains("holds another calibration"),
        "{e:#}"
    );
}

#[test]
fn a_given_start_is_the_first_point_checked_against_the_ranges_and_another_calibration() {
    let dir = tempfile::tempdir().unwrap();
    let s = CalibrationSetup {
        start: Some(vec![1.75]),
        ..setup(&["mission.pickup_s=0.5..2"], targets(None), 10)
    };
    let o = calibrate(&s, dir.path(), Progress::off()).unwrap();
    assert_eq!(o.evaluations[0].values, [1.75]);
    assert_eq!(
        o.best_values(),
        [1.75],
        "loss 0 at the start stops the search"
    );
    assert!(
        o.header.search.ends_with("start: 1.75"),
        "{}",
        o.header.search
    );
    let other = CalibrationSetup {
        start: Some(vec![1.5]),
        ..setup(&["mission.pickup_s=0.5..2"], targets(None), 10)
    };
    let e = calibrate(&other, dir.path(), Progress::off()).unwrap_err();
    assert!(
        format!("{e:#}").contains("holds another calibration"),
        "{e:#}"
    );
    for (start, mid, message) in [
        (
            vec![2.5],
            false,
            "the start point's 2.5 for mission.pickup_s lies outside its range",
        ),
        (
            vec![1.0, 1.0],
            false,
            "the start point has 2 values for 1 free fields",
        ),
        (
            vec![1.0],
            true,
            "start_mid and a given start point exclude each other",
        ),
    ] {
        let bad = CalibrationSetup {
            start: Some(start),
            start_mid: mid,
            ..setup(&["mission.pickup_s=0.5..2"], targets(None), 10)
        };
        let e = bad.check().unwrap_err().to_string();
        assert!(e.contains(message), "{e}");
    }
}

#[test]
fn a_panicking_trial_is_an_infinite_loss_with_its_message() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = setup(&["mission.pickup_s=0.5..2"], targets(None), 2);
    s.trial_plan.methods = vec!["rne".into(), "boom".into()];
    s.trial_plan.method_factory = MethodFactory::new(|name, model, ctx| match name {
        "boom" => Ok(Box::new(Boom) as Box<dyn GroupingMethod>),
        other => MethodFactory::builtin().build(other, model, ctx),
    });
    let seen = Arc::new(Mutex::new(Vec::new()));
    let hook_seen = Arc::clone(&seen);
    let progress = Progress {
        on_evaluated: Some(Arc::new(move |e, n| {
            hook_seen.lock().unwrap().push((e.index, n));
        })),
        ..Progress::off()
    };
    let o = calibrate(&s, dir.path(), progress).unwrap();
    assert_eq!(o.evaluations.len(), 2);
    for e in &o.evaluations {
        assert_eq!(e.loss, f64::INFINITY);
        assert_eq!(e.trials_ok, 1, "RNE's trial ran");
        let m = e.message.as_deref().unwrap();
        assert!(
            m.starts_with("1 of 2 trials failed: boom trial 0 (seed ")
                && m.contains("panicked: boom on purpose"),
            "{m}"
        );
        // The statistics of the trials that ran are kept.
        assert_eq!(e.statistics.len(), 1);
        assert!(e.statistics[0].is_finite());
    }
    assert!(!o.admissible);
    assert_eq!(*seen.lock().unwrap(), [(0, 1), (1, 2)]);
    let csv = std::fs::read_to_string(dir.path().join("trace.csv")).unwrap();
    assert!(
        csv.contains(",inf,1 of 2 trials failed: boom trial 0"),
        "{csv}"
    );
}

#[test]
fn values_that_break_a_rule_are_failed_evaluations_not_an_abort() {
    let s = setup(&["arena.width_m=10..20"], targets(None), 3);
    let checked: Checked = s.check().unwrap();
    let evaluator = Evaluator::new(&s, &checked).unwrap();
    let e = evaluator.evaluate(&[12.0]);
    assert_eq!(e.loss, f64::INFINITY);
    assert_eq!(e.trials_ok, 0);
    assert!(e.statistics[0].is_nan());
    let m = e.message.unwrap();
    assert!(m.starts_with("--free arena.width_m=12: "), "{m}");
    // Every point breaks it: the search runs its budget, then says no point is valid.
    let dir = tempfile::tempdir().unwrap();
    let err = calibrate(&s, dir.path(), Progress::off()).unwrap_err();
    let msg = format!("{err:#}");
    assert!(
        msg.starts_with(
            "no evaluated point gives a valid scenario; the best one: --free arena.width_m="
        ),
        "{msg}"
    );
    let trace = std::fs::read_to_string(dir.path().join("trace.jsonl")).unwrap();
    assert_eq!(trace.lines().count(), 1 + 3);
}

#[test]
fn a_larger_budget_continues_the_same_search() {
    let free = [
        "mission.pickup_s=0.5..2",
        "mission.search_time_budget_s=8..30",
    ];
    // 300 rescuees are out of reach in 60 s: the search runs its whole budget.
    let short = setup(&free, targets(Some(300.0)), 3);
    let long = setup(&free, targets(Some(300.0)), 5);
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let first = calibrate(&short, a.path(), Progress::off()).unwrap();
    assert_eq!((first.stop, first.ran), (StopReason::MaxEvals, 3));
    let more = calibrate(&long, a.path(), Progress::off()).unwrap();
    let fresh = calibrate(&long, b.path(), Progress::off()).unwrap();
    assert_eq!((more.ran, more.reused), (2, 3));
    assert_eq!(fresh.ran, 5);
    let rows = |o: &usar_study::calibrate::CalibrationOutcome| -> Vec<(Vec<f64>, String)> {
        o.evaluations
            .iter()
            .map(|e| (e.values.clone(), format!("{:?}", e.statistics)))
            .collect()
    };
    assert_eq!(rows(&more), rows(&fresh));
    assert_eq!(rows(&first)[..], rows(&fresh)[..3]);
    let csv = |d: &Path| std::fs::read(d.join("trace.csv")).unwrap();
    assert!(csv(a.path()) == csv(b.path()));
}

/// The stop flag ends a calibration after the evaluation running: no outputs, the trace keeps
/// what ran, and running it again gives the files of an uninterrupted run. The trial observer
/// sees every trial of every evaluation.
#[test]
fn a_stopped_calibration_writes_nothing_and_continues() {
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    let free = [
        "mission.pickup_s=0.5..2",
        "mission.search_time_budget_s=8..30",
    ];
    let stop = Arc::new(AtomicBool::new(false));
    let observed = Arc::new(AtomicUsize::new(0));
    let (flag, count) = (stop.clone(), observed.clone());
    let mut s = setup(&free, targets(Some(300.0)), 4);
    s.hooks.stop = Some(stop.clone());
    s.hooks.trial_observer = Some(Arc::new(move |_| {
        count.fetch_add(1, Ordering::SeqCst);
        None
    }));
    let progress = Progress {
        on_evaluated: Some(Arc::new(move |_, n| {
            if n == 2 {
                flag.store(true, Ordering::SeqCst);
            }
        })),
        ..Progress::off()
    };
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let e = calibrate(&s, a.path(), progress).unwrap_err();
    assert!(
        matches!(e, usar_study::calibrate::CalibrationError::Stopped(_)),
        "{e}"
    );
    assert_eq!(observed.load(Ordering::SeqCst), 2);
    let trace = std::fs::read_to_string(a.path().join("trace.jsonl")).unwrap();
    assert_eq!(trace.lines().count(), 1 + 2);
    assert!(!a.path().join("calibrated.ron").exists());
    stop.store(false, Ordering::SeqCst);
    let resumed = calibrate(&s, a.path(), Progress::off()).unwrap();
    assert_eq!((resumed.ran, resumed.reused), (2, 2));
    let fresh = calibrate(
        &setup(&free, targets(Some(300.0)), 4),
        b.path(),
        Progress::off(),
    )
    .unwrap();
    for f in ["trace.csv", "calibrated.ron"] {
        let read = |d: &Path| std::fs::read(d.join(f)).unwrap();
        assert!(read(a.path()) == read(b.path()), "{f} differs");
    }
    assert_eq!(fresh.ran, 4);
}

/// Regression (issue 70): `max_time: Duration::MAX` (what `max_time_s=1e300` and `--max-time
/// 18446744073709551615s` become) panicked adding it to the start's `Instant`; an end that
/// cannot be represented is no limit.
#[test]
fn a_budget_past_what_an_instant_holds_is_no_limit() {
    let dir = tempfile::tempdir().unwrap();
    let mut s = setup(&["mission.pickup_s=0.5..2"], targets(Some(300.0)), 1);
    s.max_time = Some(std::time::Duration::MAX);
    let o = calibrate(&s, dir.path(), Progress::off()).unwrap();
    assert_eq!((o.evaluations.len(), o.stop), (1, StopReason::MaxEvals));
}

/// Regression (issue 70): one trial per method gave a spread of NaN, a loss of inf and no
/// message. Such a calibration is refused before it runs, naming `trials` and the target.
#[test]
fn one_trial_is_refused_for_a_spread_and_an_undefined_statistic_says_why() {
    let spread = Targets::parse(
        "Targets(targets: [(name: \"sd\", statistic: PooledSd(\"rescued_total\"), value: 3.0, \
         band: PlusMinus(1.0), report_only: true), (name: \"rounds\", statistic: \
         Mean(\"rounds\"), value: 1.0, band: Between(0.0, 100.0))])",
        "t",
    )
    .unwrap();
    let mut s = setup(&["mission.pickup_s=0.5..2"], spread, 1);
    let dir = tempfile::tempdir().unwrap();
    let e = calibrate(&s, dir.path(), Progress::off()).unwrap_err();
    let refused = usar_study::refused_setting::RefusedSetting::of(&e).expect("a setting");
    assert_eq!(refused.field, Some("trials"));
    assert_eq!(
        refused.problem,
        " must be at least 2: target \"sd\" (PooledSd(rescued_total)): it needs at least 2 \
         trials per method defining rescued_total"
    );
    assert!(!dir.path().join("trace.jsonl").exists());
    // With 2 trials it runs; a cost per rescuee in 1 s (no rescuee) is undefined, and the
    // evaluation says why instead of an empty message.
    s.trial_plan.trials = 2;
    s.trial_plan.duration_s = Some(1.0);
    s.targets = Targets::parse(
        "Targets(targets: [(name: \"cost\", statistic: Mean(\"energy_per_rescuee_pct\"), \
         value: 1.0, band: PlusMinus(0.5))])",
        "t",
    )
    .unwrap();
    let checked = s.check().unwrap();
    let e = Evaluator::new(&s, &checked).unwrap().evaluate(&[1.2]);
    assert_eq!(e.trials_ok, 2);
    assert_eq!(e.loss, f64::INFINITY);
    assert_eq!(
        e.message.as_deref(),
        Some(
            "target \"cost\": Mean(energy_per_rescuee_pct) is NaN: it needs a trial defining \
             energy_per_rescuee_pct"
        )
    );
}

/// Regression (issue 70): a tiny band made the loss of a point whose trials all ran +inf, as
/// if it had failed. It is finite (saturated), with no message.
#[test]
fn a_tiny_band_gives_a_finite_loss() {
    let tiny = Targets::parse(
        "Targets(targets: [(name: \"rounds\", statistic: Mean(\"rounds\"), value: 100.0, \
         band: PlusMinus(5e-324))])",
        "t",
    )
    .unwrap();
    let s = setup(&["mission.pickup_s=0.5..2"], tiny, 1);
    let checked = s.check().unwrap();
    let e = Evaluator::new(&s, &checked).unwrap().evaluate(&[1.2]);
    assert!(e.statistics[0].is_finite(), "{:?}", e.statistics);
    assert_eq!((e.loss, e.message), (f64::MAX, None));
}
