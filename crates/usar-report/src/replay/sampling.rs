//! [`SampleClock`]: which steps of a trial a replay samples.

use super::error::ReplayError;

/// The default sampling rate of a replay, samples per simulated second (`--hz`).
pub const DEFAULT_HZ: f64 = 10.0;

/// Most robot-samples (robots times samples) a replay takes at its default rate: 6,100,000, so
/// a 1,000-robot, 600 s trial keeps [`DEFAULT_HZ`] (6,001,000) and larger ones get a lower
/// rate ([`default_hz`]). The page decodes about 60 bytes per robot-sample, so about 370 MB
/// in the browser, and the file takes about 1 to 2 bytes per robot-sample.
pub const DEFAULT_MAX_ROBOT_SAMPLES: f64 = 6_100_000.0;

/// The sampling rate of a replay without `--hz`, samples per simulated second, for a trial of
/// `total_steps` steps of `dt_s` seconds: [`DEFAULT_HZ`], lowered for a large team or a long
/// trial so that `robots` times the samples of its [`SampleClock`] stay within
/// [`DEFAULT_MAX_ROBOT_SAMPLES`] (frame decimation: a 10,000-robot, 600 s trial at the
/// paper's 0.02 s step is sampled every 50th step, 1 Hz). The rate returned is one the clock
/// uses exactly (a whole number of steps between samples). A team of no robots, a trial of
/// no steps or a bad step keeps [`DEFAULT_HZ`]; a team too large for even two samples (the
/// start and the end) gets the sparsest clock.
pub fn default_hz(robots: usize, total_steps: u64, dt_s: f64) -> f64 {
    if robots == 0 || total_steps == 0 || !(dt_s.is_finite() && dt_s > 0.0) {
        return DEFAULT_HZ;
    }
    // The clock has `1 + ceil(total_steps / every)` samples at most; it fits when
    // `every >= total_steps / (max_samples - 1)`.
    let max_samples = (DEFAULT_MAX_ROBOT_SAMPLES / robots as f64).floor();
    if max_samples < 2.0 {
        return DEFAULT_HZ.min(1.0 / (total_steps as f64 * dt_s));
    }
    let needed = (total_steps as f64 / (max_samples - 1.0)).ceil();
    let default_every = (1.0 / (DEFAULT_HZ * dt_s)).round().max(1.0);
    if needed <= default_every {
        DEFAULT_HZ
    } else {
        1.0 / (needed * dt_s)
    }
}

/// Which steps are sampled: the trial's start (step 0), every `every_steps`-th step, and the
/// last step. `every_steps = max(1, round(1 / (hz * dt_s)))`, so the rate actually used is
/// `1 / (every_steps * dt_s)` ([`SampleClock::actual_hz`]): 10 Hz at the paper's 0.02 s step
/// is every 5th step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct SampleClock {
    /// Steps between two samples, `>= 1`.
    pub every_steps: u64,
    /// Steps in the whole trial.
    pub total_steps: u64,
}

impl SampleClock {
    /// The clock of a trial of `total_steps` steps of `dt_s` seconds sampled at about `hz`
    /// samples per simulated second.
    ///
    /// # Errors
    /// [`ReplayError::Spec`] unless `hz` is finite and `> 0` and `dt_s > 0`.
    pub fn new(hz: f64, dt_s: f64, total_steps: u64) -> Result<Self, ReplayError> {
        if !(hz.is_finite() && hz > 0.0) {
            return Err(ReplayError::Spec(format!(
                "sampling rate {hz} Hz: it must be a positive number of samples per second"
            )));
        }
        if !(dt_s.is_finite() && dt_s > 0.0) {
            return Err(ReplayError::Spec(format!("step {dt_s} s is not positive")));
        }
        // A rate so low that `hz * dt_s` underflows gives an infinite spacing: the sparsest
        // clock (`as` saturates at u64::MAX), as any rate below one sample per trial.
        let every = (1.0 / (hz * dt_s)).round();
        let every_steps = if every >= 1.0 { every as u64 } else { 1 };
        Ok(Self {
            every_steps,
            total_steps,
        })
    }

    /// Whether the state after step `step` (1-based; 0 is the start) is sampled.
    pub fn is_sampled(&self, step: u64) -> bool {
        step.is_multiple_of(self.every_steps) || step == self.total_steps
    }

    /// How many samples the whole trial has: the start, every `every_steps`-th step and the
    /// last step.
    pub fn samples(&self) -> usize {
        let regular = self.total_steps / self.every_steps;
        let tail = u64::from(!self.total_steps.is_multiple_of(self.every_steps));
        (1 + regular + tail) as usize
    }

    /// The step of sample `i`: `min(i * every_steps, total_steps)`.
    pub fn step_of(&self, i: usize) -> u64 {
        (i as u64)
            .saturating_mul(self.every_steps)
            .min(self.total_steps)
    }

    /// The rate used, samples per simulated second, for steps of `dt_s` seconds.
    pub fn actual_hz(&self, dt_s: f64) -> f64 {
        1.0 / (self.every_steps as f64 * dt_s)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_default_rate_is_ten_hz_up_to_a_thousand_robots_for_600_s_and_decimated_beyond() {
        assert_eq!(default_hz(1_000, 30_000, 0.02), DEFAULT_HZ);
        assert_eq!(default_hz(12, 90_000, 0.02), DEFAULT_HZ);
        assert_eq!(default_hz(0, 30_000, 0.02), DEFAULT_HZ);
        let hz = default_hz(10_000, 30_000, 0.02);
        assert!((hz - 1.0).abs() < 1e-12, "{hz}");
        // Every team size and length keeps within the limit with the clock it gets.
        for robots in [
            1, 12, 1_000, 1_017, 3_000, 10_000, 100_000, 3_050_000, 7_000_000,
        ] {
            for total in [1, 7, 1_500, 30_000, 90_000] {
                let hz = default_hz(robots, total, 0.02);
                let c = SampleClock::new(hz, 0.02, total).unwrap();
                let fits = robots as f64 * c.samples() as f64 <= DEFAULT_MAX_ROBOT_SAMPLES;
                assert!(
                    fits || c.samples() == 2,
                    "{robots} robots, {total} steps: {hz} Hz"
                );
                assert!(hz <= DEFAULT_HZ, "{robots} robots, {total} steps: {hz} Hz");
            }
        }
    }

    #[test]
    fn ten_hz_at_the_papers_step_is_every_fifth_step() {
        let c = SampleClock::new(10.0, 0.02, 30_000).unwrap();
        assert_eq!(c.every_steps, 5);
        assert_eq!(c.samples(), 6_001);
        assert!((c.actual_hz(0.02) - 10.0).abs() < 1e-9);
        assert!(c.is_sampled(5) && !c.is_sampled(6) && c.is_sampled(30_000));
        assert_eq!(c.step_of(6_000), 30_000);
    }

    #[test]
    fn a_trial_that_is_not_a_whole_number_of_samples_ends_with_its_last_step() {
        let c = SampleClock::new(10.0, 0.02, 12).unwrap();
        assert_eq!(c.samples(), 4, "steps 0, 5, 10, 12");
        assert_eq!(
            (0..c.samples()).map(|i| c.step_of(i)).collect::<Vec<_>>(),
            [0, 5, 10, 12]
        );
        assert!(c.is_sampled(12) && !c.is_sampled(11));
    }

    #[test]
    fn rates_above_the_step_rate_sample_every_step_and_bad_rates_are_refused() {
        let c = SampleClock::new(1_000.0, 0.02, 10).unwrap();
        assert_eq!(c.every_steps, 1);
        assert_eq!(c.samples(), 11);
        for hz in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(SampleClock::new(hz, 0.02, 10).is_err(), "{hz}");
        }
    }

    #[test]
    fn the_lowest_rates_give_the_sparsest_clock_not_the_densest() {
        for hz in [1e-6, 1e-306, 1e-307, 1e-320, 5e-324] {
            let c = SampleClock::new(hz, 0.02, 250).unwrap();
            assert_eq!(c.samples(), 2, "{hz}: the start and the last step");
        }
    }

    #[test]
    fn sampled_steps_counted_while_running_match_the_count() {
        for (hz, total) in [(10.0, 30_000), (3.0, 1_001), (0.5, 7), (50.0, 99)] {
            let c = SampleClock::new(hz, 0.02, total).unwrap();
            let counted = 1 + (1..=total).filter(|&s| c.is_sampled(s)).count();
            assert_eq!(counted, c.samples(), "{hz} Hz, {total} steps");
        }
    }
}
