//! [`Recording`]: one trial as the replay page plays it.

use usar_sim::mission::RoundRecord;

use super::channels::{Channel, RescueeCode};
use super::marks::Mark;
use super::sampling::SampleClock;

/// A rescuee's code changed at a sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RescueeChange {
    /// The sample at which the new code was first seen (0-based).
    pub sample: u32,
    /// The rescuee's index over all tasks: the rescuees of task 0 first, then task 1's, ...
    pub rescuee: u32,
    /// Its new code.
    pub code: RescueeCode,
}

/// One trial, sampled ([`SampleClock`]): every robot's [`Channel`]s at every sample, every
/// change of a rescuee's [`RescueeCode`], the timeline's [`Mark`]s and the rounds. Filled by a
/// [`super::ReplayRecorder`] while the trial runs.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    /// The grouping method's display name (`RNE`).
    pub method: String,
    /// The trial's index.
    pub trial: u32,
    /// The seed of its starting team.
    pub seed: u64,
    /// Step length, seconds.
    pub dt_s: f64,
    /// Which steps are sampled.
    pub clock: SampleClock,
    /// Robots in the team.
    pub robots: usize,
    /// Samples recorded so far (`clock.samples()` once the trial has ended).
    pub samples: usize,
    /// Per channel (in [`Channel::ALL`] order), the quantised values sample-major: the value
    /// of robot `r` at sample `i` is at `i * robots + r`.
    pub channels: Vec<Vec<i32>>,
    /// Rescuee code changes, in sample order (every rescuee starts [`RescueeCode::Waiting`]).
    pub rescuee_changes: Vec<RescueeChange>,
    /// The timeline's marks, in time order.
    pub marks: Vec<Mark>,
    /// The trial's rounds (the last one may be cut by the time limit).
    pub rounds: Vec<RoundRecord>,
}

impl Recording {
    /// The quantised value of channel `c` for robot `robot` at sample `sample`.
    ///
    /// # Panics
    /// If `sample >= self.samples` or `robot >= self.robots`.
    pub fn value(&self, c: Channel, sample: usize, robot: usize) -> i32 {
        assert!(sample < self.samples && robot < self.robots);
        self.channels[c.index()][sample * self.robots + robot]
    }

    /// Robot `robot`'s position at sample `sample`, world frame, metres (to the centimetre).
    ///
    /// # Panics
    /// As [`Recording::value`].
    pub fn position_m(&self, sample: usize, robot: usize) -> (f64, f64) {
        let q = Channel::XCm.quantum();
        (
            f64::from(self.value(Channel::XCm, sample, robot)) * q,
            f64::from(self.value(Channel::YCm, sample, robot)) * q,
        )
    }

    /// The simulated time of sample `i`, seconds.
    pub fn time_of(&self, i: usize) -> f64 {
        self.clock.step_of(i) as f64 * self.dt_s
    }

    /// The trial's recorded length, seconds.
    pub fn duration_s(&self) -> f64 {
        self.clock.total_steps as f64 * self.dt_s
    }
}
