//! [`ReplayRecorder`]: the [`StepObserver`] that records a trial for its replay.

use usar_sim::mission::{Simulation, StepObserver};

use super::channels::{Channel, RescueeCode, StateFlags, phase_code, quantise};
use super::error::ReplayError;
use super::marks::{Mark, MarkKind};
use super::recording::{Recording, RescueeChange};
use super::sampling::SampleClock;

/// Records a trial while it runs: the state at the start ([`StepObserver::on_start`]) and at
/// every sampled step ([`SampleClock`]), every rescuee whose code changed since the last
/// sample, the marks of the mission's events of every step and the steps in which a robot's
/// deadlock counters grew. It reads the simulation only; the trial's numbers do not change.
///
/// Memory: `15 x 4` bytes per robot and sample (a 600 s paper trial at 10 Hz: 4.3 MB).
/// Without `on_start` (a caller stepping by hand) the first sample is the state after the
/// first observed step.
#[derive(Debug)]
pub struct ReplayRecorder {
    hz: f64,
    rec: Option<Recording>,
    /// Deadlocks detected and resolved per robot at the last step.
    counters: Vec<(u64, u64)>,
    /// Each rescuee's code at the last sample, all tasks in order.
    codes: Vec<RescueeCode>,
    /// Reused buffers of robots whose counters grew this step.
    detected: Vec<usize>,
    resolved: Vec<usize>,
}

impl ReplayRecorder {
    /// A recorder sampling at about `hz` samples per simulated second ([`SampleClock`]).
    ///
    /// # Errors
    /// [`ReplayError::Spec`] unless `hz` is finite and `> 0`.
    pub fn new(hz: f64) -> Result<Self, ReplayError> {
        SampleClock::new(hz, 1.0, 0)?;
        Ok(Self {
            hz,
            rec: None,
            counters: Vec::new(),
            codes: Vec::new(),
            detected: Vec::new(),
            resolved: Vec::new(),
        })
    }

    /// The recording so far (`None` before the first observed call).
    pub fn recording(&self) -> Option<&Recording> {
        self.rec.as_ref()
    }

    /// Takes the recording out (`None` before the first observed call); the recorder starts
    /// afresh on its next call.
    pub fn take(&mut self) -> Option<Recording> {
        self.rec.take()
    }

    fn start(&mut self, sim: &Simulation) {
        let s = sim.scenario();
        let dt_s = s.sim().dt_s.get();
        let (done, total) = sim.progress();
        let clock = SampleClock::new(self.hz, dt_s, total).unwrap_or(SampleClock {
            every_steps: 1,
            total_steps: total,
        });
        let robots = s.robots().len();
        let expected = clock.samples().saturating_sub(clock_index(&clock, done));
        let info = sim.result();
        self.rec = Some(Recording {
            method: info.method,
            trial: info.trial,
            seed: info.seed,
            dt_s,
            clock,
            robots,
            samples: 0,
            channels: Channel::ALL
                .iter()
                .map(|_| Vec::with_capacity(expected.saturating_mul(robots)))
                .collect(),
            rescuee_changes: Vec::new(),
            marks: Vec::new(),
            rounds: Vec::new(),
        });
        self.counters = sim
            .world()
            .robots()
            .iter()
            .map(|w| (w.counters.deadlocks_detected, w.counters.deadlocks_resolved))
            .collect();
        self.codes = (0..s.tasks().len())
            .flat_map(|t| {
                let f = sim.rescuees(t);
                (0..f.len()).map(move |i| RescueeCode::of(f.status(i)))
            })
            .collect();
        self.sample(sim);
    }

    /// Appends the state now as the next sample.
    fn sample(&mut self, sim: &Simulation) {
        let Some(rec) = self.rec.as_mut() else {
            return;
        };
        let sample = rec.samples as u32;
        for (id, (m, w)) in sim.robots().iter().zip(sim.world().robots()).enumerate() {
            let needs = sim.needs(id);
            let mut push = |c: Channel, v: i32| rec.channels[c.index()].push(v);
            push(Channel::XCm, quantise(w.position.x, Channel::XCm.quantum()));
            push(Channel::YCm, quantise(w.position.y, Channel::YCm.quantum()));
            push(Channel::EnergyCentiPct, quantise(m.energy_pct, 0.01));
            push(Channel::HpCentiPct, quantise(m.hp_pct, 0.01));
            push(Channel::Phase, phase_code(m.phase));
            push(Channel::Group, m.task.map_or(0, |t| t as i32 + 1));
            push(Channel::Load, m.load.len() as i32);
            push(Channel::Flags, StateFlags::of(m, w));
            for (i, v) in needs.as_slice().iter().enumerate().take(7) {
                push(Channel::Needs(i), quantise(*v, Channel::Needs(i).quantum()));
            }
        }
        let mut g = 0usize;
        for t in 0..sim.scenario().tasks().len() {
            let f = sim.rescuees(t);
            for i in 0..f.len() {
                let code = RescueeCode::of(f.status(i));
                if let Some(old) = self.codes.get_mut(g)
                    && *old != code
                {
                    *old = code;
                    rec.rescuee_changes.push(RescueeChange {
                        sample,
                        rescuee: g as u32,
                        code,
                    });
                }
                g += 1;
            }
        }
        rec.samples += 1;
    }

    /// Marks of this step: the mission's events, and one mark each for the robots whose
    /// deadlock counters grew.
    fn mark_step(&mut self, sim: &Simulation) {
        let Some(rec) = self.rec.as_mut() else {
            return;
        };
        rec.marks
            .extend(sim.events().iter().filter_map(Mark::of_event));
        self.detected.clear();
        self.resolved.clear();
        for (id, w) in sim.world().robots().iter().enumerate() {
            let now = (w.counters.deadlocks_detected, w.counters.deadlocks_resolved);
            let Some(before) = self.counters.get_mut(id) else {
                continue;
            };
            if now.0 > before.0 {
                self.detected.push(id);
            }
            if now.1 > before.1 {
                self.resolved.push(id);
            }
            *before = now;
        }
        for (kind, robots) in [
            (MarkKind::DeadlockDetected, &self.detected),
            (MarkKind::DeadlockResolved, &self.resolved),
        ] {
            if !robots.is_empty() {
                rec.marks.push(Mark {
                    time_s: sim.time_s(),
                    kind,
                    robots: robots.clone(),
                    task: None,
                    value: robots.len() as u32,
                });
            }
        }
    }
}

/// The index of the first sample at or after step `step`.
fn clock_index(clock: &SampleClock, step: u64) -> usize {
    step.div_ceil(clock.every_steps) as usize
}

impl StepObserver for ReplayRecorder {
    fn on_start(&mut self, sim: &Simulation) {
        self.start(sim);
    }

    fn on_step(&mut self, sim: &Simulation) {
        if self.rec.is_none() {
            self.start(sim);
            return;
        }
        self.mark_step(sim);
        let (done, _) = sim.progress();
        if self.rec.as_ref().is_some_and(|r| r.clock.is_sampled(done)) {
            self.sample(sim);
        }
        if sim.is_finished()
            && let Some(rec) = self.rec.as_mut()
        {
            rec.rounds = sim.rounds().to_vec();
        }
    }
}
