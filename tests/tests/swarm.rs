//! `scenarios/swarm-1000.ron` end to end: 1,000 robots, four tasks, every method. A short run
//! per method (default test run), and the ignored 1,800 s bound tests (every round but the
//! last completes; run in release by `.ci/run` and `just swarm-bound`, `docs/scaling.md`,
//! "Jams"). Speed is the scaling bench's.

use integration_tests::{load, method, scenario_path};
use usar_sim::mission::Simulation;
use usar_sim::scenario::Locomotion;

/// Seconds simulated per method: long enough for grouping and for the start grid to clear
/// (robots in the back rows wait for those in front).
const SHORT_S: f64 = 10.0;

#[test]
fn swarm_1000_groups_the_whole_team_and_sets_off_with_every_method() {
    let s = load(&scenario_path("swarm-1000.ron"));
    assert_eq!(s.robots().len(), 1000);
    assert_eq!(s.tasks().len(), 4);
    for name in ["rne", "dis", "eng", "hp_dis"] {
        let mut sim = Simulation::builder(&s)
            .method(method(name, &s))
            .duration_s(SHORT_S)
            .build()
            .unwrap();
        let r = sim.run_to_end().unwrap();
        assert_eq!(r.rescued.len(), 4, "{name}");
        let first = &r.rounds[0];
        let mut seen = vec![false; s.robots().len()];
        for (t, group) in first.groups.iter().enumerate() {
            for (kind, spec) in s.kinds().iter().enumerate() {
                let n = group
                    .iter()
                    .filter(|&&id| s.robots()[id].kind == kind)
                    .count();
                assert_eq!(n, spec.quota[t], "{name}: task {t}, kind {kind}");
            }
            for &id in group {
                assert!(!seen[id], "{name}: robot {id} in two groups");
                seen[id] = true;
            }
        }
        assert!(seen.iter().all(|&s| s), "{name}: a robot without a group");
        // The team has set off: at most one ground robot in ten still waits in the start grid.
        let ground = s
            .robots()
            .iter()
            .filter(|r| s.kinds()[r.kind].locomotion == Locomotion::Ground)
            .count();
        let stuck: Vec<usize> = sim
            .world()
            .robots()
            .iter()
            .filter(|r| r.locomotion == Locomotion::Ground && r.distance_travelled_m < 0.5)
            .map(|r| r.id)
            .collect();
        assert!(
            stuck.len() * 10 <= ground,
            "{name}: {} ground robots moved less than 0.5 m in {SHORT_S} s: {:?}",
            stuck.len(),
            &stuck[..stuck.len().min(20)]
        );
    }
}

/// Length of the round-bound trials, seconds.
const BOUND_S: f64 = 1800.0;

/// The bound of `docs/scaling.md` ("Jams"): in an 1,800 s trial of swarm-1000 (trial 0) every
/// round but the last completes (every grouped robot back at its start), at least two rounds
/// start, and every task's group brings rescuees back. About 70 s per method in release.
fn rounds_complete_within_the_trial(name: &str) {
    let s = load(&scenario_path("swarm-1000.ron"));
    let r = Simulation::builder(&s)
        .method(method(name, &s))
        .duration_s(BOUND_S)
        .build()
        .unwrap()
        .run_to_end()
        .unwrap();
    let summary: Vec<(f64, f64, bool)> = r
        .rounds
        .iter()
        .map(|k| (k.start_s, k.end_s, k.completed))
        .collect();
    assert!(
        r.rounds.len() >= 2,
        "{name}: one round in {BOUND_S} s: {summary:?}"
    );
    let (_, done) = r.rounds.split_last().unwrap();
    assert!(
        done.iter().all(|k| k.completed),
        "{name}: a round before the last did not complete: {summary:?}"
    );
    for (t, &n) in r.rescued.iter().enumerate() {
        assert!(
            n > 0,
            "{name}: task {} rescued nothing: {:?}",
            r.tasks[t],
            r.rescued
        );
    }
}

#[test]
#[ignore = "1,800 s of 1,000 robots: run in release (.ci/run, just swarm-bound)"]
fn every_round_but_the_last_completes_with_rne() {
    rounds_complete_within_the_trial("rne");
}

#[test]
#[ignore = "1,800 s of 1,000 robots: run in release (.ci/run, just swarm-bound)"]
fn every_round_but_the_last_completes_with_dis() {
    rounds_complete_within_the_trial("dis");
}

#[test]
#[ignore = "1,800 s of 1,000 robots: run in release (.ci/run, just swarm-bound)"]
fn every_round_but_the_last_completes_with_eng() {
    rounds_complete_within_the_trial("eng");
}

#[test]
#[ignore = "1,800 s of 1,000 robots: run in release (.ci/run, just swarm-bound)"]
fn every_round_but_the_last_completes_with_hp_dis() {
    rounds_complete_within_the_trial("hp_dis");
}
