//! [`PathRecorder`]: the [`StepObserver`] that samples every robot's path during a trial, for
//! the picture `usar render --trace` draws.

use usar_sim::mission::{Simulation, StepObserver};

use super::robots::Trace;

/// Simulated time between two samples of a robot's path, seconds (0.5).
pub const TRACE_SAMPLE_S: f64 = 0.5;

/// Samples every robot's position at the start ([`StepObserver::on_start`]), every
/// [`TRACE_SAMPLE_S`] of simulated time (rounded to whole steps, at least one) and at the
/// trial's last step. It reads the simulation only: the trial's numbers do not change.
///
/// Memory: 16 bytes per robot and sample (a 600 s trial: 1,201 samples per robot).
#[derive(Debug, Default)]
pub struct PathRecorder {
    every_steps: u64,
    traces: Vec<Trace>,
}

impl PathRecorder {
    /// An empty recorder; it sizes itself at its first call.
    pub fn new() -> Self {
        Self::default()
    }

    /// Every robot's path so far, by robot id (empty before the first call).
    pub fn into_traces(self) -> Vec<Trace> {
        self.traces
    }

    fn sample(&mut self, sim: &Simulation) {
        if self.traces.is_empty() {
            let dt_s = sim.scenario().sim().dt_s.get();
            self.every_steps = ((TRACE_SAMPLE_S / dt_s).round() as u64).max(1);
            self.traces = vec![Vec::new(); sim.world().robots().len()];
        }
        for (id, t) in self.traces.iter_mut().enumerate() {
            t.push(sim.world().robot(id).position);
        }
    }
}

impl StepObserver for PathRecorder {
    fn on_start(&mut self, sim: &Simulation) {
        self.sample(sim);
    }

    fn on_step(&mut self, sim: &Simulation) {
        let (steps, _) = sim.progress();
        if self.traces.is_empty() || steps.is_multiple_of(self.every_steps) || sim.is_finished() {
            self.sample(sim);
        }
    }
}
