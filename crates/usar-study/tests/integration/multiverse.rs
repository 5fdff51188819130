//! `usar_study::multiverse::run_multiverse` as a library call: its stop flag (the Python
//! package's Ctrl-C) ends the run without a partial record or the top files, and a rerun
//! writes the files of an uninterrupted run.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

use usar_study::calibrate::{FreeField, Targets};
use usar_study::multiverse::{Axes, MultiverseProgress, MultiverseSetup, run_multiverse};

const CORRIDOR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/corridor.ron");
const DATA: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data");

/// The tiny multiverse of `multiverse_cli` (2 x 2 universes of corridor.ron, two methods, 2
/// trials of 60 s, calibrations of 1 trial and at most 3 evaluations), on 2 threads.
fn setup() -> MultiverseSetup {
    let text = std::fs::read_to_string(CORRIDOR).unwrap();
    let base = usar_sim::scenario::parse_spec(&text, "corridor.ron").unwrap();
    let axes = Axes::load(&Path::new(DATA).join("multiverse-axes.ron")).unwrap();
    let targets = Targets::load(&Path::new(DATA).join("multiverse-targets.ron")).unwrap();
    let free = vec![FreeField::parse("mission.pickup_s=0.5..2").unwrap()];
    let mut setup = MultiverseSetup {
        calibration_trials: 1,
        max_evals: 3,
        threads: 2,
        working_dir: None,
        date: Some("2000-01-01T00:00:00Z".into()),
        ..MultiverseSetup::new(base, "corridor.ron", axes, targets, free)
    };
    setup.comparison.methods = vec!["rne".into(), "dis".into()];
    setup.comparison.trials = 2;
    setup.comparison.duration_s = Some(60.0);
    setup
}

/// Stopped at the first comparison trial journaled, the run returns [`Stopped`], writes no
/// top file and no record for the universe it was in; the calibration trials were observed;
/// run again, it writes what an uninterrupted run writes.
#[test]
fn a_stopped_multiverse_keeps_no_partial_record_and_continues() {
    let (a, b) = (tempfile::tempdir().unwrap(), tempfile::tempdir().unwrap());
    let stop = Arc::new(AtomicBool::new(false));
    let observed = Arc::new(AtomicUsize::new(0));
    let mut s = setup();
    let (flag, count) = (stop.clone(), observed.clone());
    s.hooks.stop = Some(stop.clone());
    s.hooks.sweep.on_journaled = Some(Arc::new(move |_, _| flag.store(true, Ordering::SeqCst)));
    s.hooks.calibration_trials = Some(Arc::new(move |_| {
        count.fetch_add(1, Ordering::SeqCst);
        None
    }));
    let e = run_multiverse(&s, a.path(), MultiverseProgress::off()).unwrap_err();
    assert!(e.is_stopped(), "{e}");
    assert!(observed.load(Ordering::SeqCst) >= 2);
    assert!(!a.path().join("multiverse.csv").exists());
    let records = walk(a.path(), "universe.json");
    assert!(records.is_empty(), "{records:?}");
    // The comparison it stopped in wrote no tables of a partial set of trials.
    let tables = walk(a.path(), "trials.csv");
    assert!(tables.is_empty(), "{tables:?}");
    assert_eq!(walk(a.path(), "journal.jsonl").len(), 1);
    stop.store(false, Ordering::SeqCst);
    s.hooks = Default::default();
    run_multiverse(&s, a.path(), MultiverseProgress::off()).unwrap();
    run_multiverse(&setup(), b.path(), MultiverseProgress::off()).unwrap();
    for f in ["multiverse.csv", "multiverse.md"] {
        let read = |d: &Path| {
            let text = std::fs::read_to_string(d.join(f)).unwrap();
            text.replace(&d.display().to_string(), "OUT")
        };
        assert_eq!(read(a.path()), read(b.path()), "{f} differs");
    }
}

/// The paths of the files named `name` under `dir`.
fn walk(dir: &Path, name: &str) -> Vec<std::path::PathBuf> {
    let mut found = Vec::new();
    for e in std::fs::read_dir(dir).unwrap().flatten() {
        let p = e.path();
        if p.is_dir() {
            found.extend(walk(&p, name));
        } else if p.file_name().is_some_and(|n| n == name) {
            found.push(p);
        }
    }
    found
}
