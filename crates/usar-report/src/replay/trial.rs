//! [`record_trial`]: run one trial and record it for its replay.

use usar_sim::mission::{Simulation, StepObserver, TrialResult};

use super::error::ReplayError;
use super::recorder::ReplayRecorder;
use super::recording::Recording;

/// A recorded trial: the recording and the trial's own result (the same numbers as without
/// the recorder).
#[derive(Debug, Clone)]
pub struct ReplayTrial {
    /// What the page plays.
    pub recording: Recording,
    /// The trial's metrics.
    pub result: TrialResult,
}

/// Runs `sim` (a fresh trial, e.g. from `Simulation::builder`) to its end while a
/// [`ReplayRecorder`] sampling at about `hz` samples per simulated second records it, and,
/// when given, `also` watches every step too (e.g. a progress bar).
///
/// # Errors
/// [`ReplayError::Spec`] for a bad `hz`; [`ReplayError::Trial`] if the trial fails.
pub fn record_trial(
    mut sim: Simulation,
    hz: f64,
    also: Option<&mut dyn StepObserver>,
) -> Result<ReplayTrial, ReplayError> {
    let mut recorder = ReplayRecorder::new(hz)?;
    let mut also = also;
    // Both see the start here; the closure below forwards every step.
    recorder.on_start(&sim);
    if let Some(o) = also.as_mut() {
        o.on_start(&sim);
    }
    let mut observe = |sim: &Simulation| {
        recorder.on_step(sim);
        if let Some(o) = also.as_mut() {
            o.on_step(sim);
        }
    };
    let result = sim.run_observed(&mut observe)?;
    let recording = recorder
        .take()
        .ok_or_else(|| ReplayError::Spec("the trial recorded nothing".into()))?;
    Ok(ReplayTrial { recording, result })
}

#[cfg(test)]
mod tests {
    use usar_sim::mission::MissionEventKind;
    use usar_sim::scenario;

    use super::*;
    use crate::replay::{Channel, MarkKind, SampleClock};

    fn paper() -> usar_sim::scenario::Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
        scenario::load(path).expect("paper.ron loads")
    }

    fn sim(s: &usar_sim::scenario::Scenario, duration_s: f64) -> Simulation {
        Simulation::builder(s)
            .method_named("rne")
            .duration_s(duration_s)
            .build()
            .expect("trial builds")
    }

    /// The recording samples the trial at 10 Hz: its positions at each sample are the
    /// trial's own positions at that step (to the centimetre), its result is the trial's
    /// result without a recorder, and its marks are the trial's rounds and deliveries.
    #[test]
    fn the_recording_is_the_trial_sampled() {
        let s = paper();
        let mut expected: Vec<(u64, Vec<(f64, f64)>)> = Vec::new();
        let mut events = Vec::new();
        let mut watch = |sim: &Simulation| {
            let (done, _) = sim.progress();
            if done % 5 == 0 {
                let p = sim
                    .world()
                    .robots()
                    .iter()
                    .map(|w| (w.position.x, w.position.y));
                expected.push((done, p.collect()));
            }
            events.extend_from_slice(sim.events());
        };
        let t = record_trial(sim(&s, 120.0), 10.0, Some(&mut watch)).expect("records");
        let rec = &t.recording;
        assert_eq!(
            rec.clock,
            SampleClock {
                every_steps: 5,
                total_steps: 6_000
            }
        );
        assert_eq!(rec.samples, 1_201);
        assert_eq!(rec.channels[0].len(), 1_201 * 12);
        for (step, positions) in &expected {
            let i = (*step / 5) as usize;
            assert!((rec.time_of(i) - *step as f64 * 0.02).abs() < 1e-9);
            for (r, (x, y)) in positions.iter().enumerate() {
                let (rx, ry) = rec.position_m(i, r);
                assert!((rx - x).abs() <= 0.005 + 1e-9 && (ry - y).abs() <= 0.005 + 1e-9);
            }
        }
        let plain = sim(&s, 120.0).run_to_end().expect("runs");
        assert_eq!(format!("{:?}", plain), format!("{:?}", t.result));
        let rounds = rec
            .marks
            .iter()
            .filter(|m| m.kind == MarkKind::RoundStart)
            .count();
        assert_eq!(rounds, t.result.rounds.len());
        assert_eq!(rec.rounds, t.result.rounds);
        let delivered: u32 = rec
            .marks
            .iter()
            .filter(|m| m.kind == MarkKind::Delivery)
            .map(|m| m.value)
            .sum();
        assert_eq!(delivered, t.result.rescued.iter().sum::<u32>());
        assert!(delivered > 0);
        let left = events
            .iter()
            .filter(|e| matches!(e.kind, MissionEventKind::LeftForRest { .. }))
            .count();
        let left_marks = rec
            .marks
            .iter()
            .filter(|m| m.kind == MarkKind::LeftToRecharge)
            .count();
        assert_eq!(left, left_marks);
        // Every robot starts at its start, at the start of a round, in a group after it.
        assert_eq!(rec.value(Channel::Group, 0, 0), 0);
        assert!((0..12).any(|r| rec.value(Channel::Group, 10, r) > 0));
        // Rescuees picked up show as changes to carried.
        let picked: u32 = t.result.robots.iter().map(|r| r.picked_up).sum();
        let carried = rec
            .rescuee_changes
            .iter()
            .filter(|c| c.code == crate::replay::RescueeCode::Carried)
            .count();
        assert!(carried as u32 <= picked && carried > 0);
    }

    /// A robot's deadlock counters grow by at most one per step, so the marks list every
    /// increment: their robots add up to the counters at the end of the trial.
    #[test]
    fn deadlock_marks_follow_the_resolver_counters() {
        let s = paper();
        let mut totals = (0u64, 0u64);
        let mut watch = |sim: &Simulation| {
            if sim.is_finished() {
                totals = sim.world().robots().iter().fold((0, 0), |(d, r), w| {
                    (
                        d + w.counters.deadlocks_detected,
                        r + w.counters.deadlocks_resolved,
                    )
                });
            }
        };
        let t = record_trial(sim(&s, 300.0), 10.0, Some(&mut watch)).expect("records");
        let listed = |kind: MarkKind| -> u64 {
            let marks = t.recording.marks.iter().filter(|m| m.kind == kind);
            marks.map(|m| m.robots.len() as u64).sum()
        };
        assert!(totals.0 > 0, "300 s of the paper's mission see a deadlock");
        assert_eq!(listed(MarkKind::DeadlockDetected), totals.0);
        assert_eq!(listed(MarkKind::DeadlockResolved), totals.1);
        assert!(
            t.recording
                .marks
                .windows(2)
                .all(|w| w[0].time_s <= w[1].time_s)
        );
    }
}
