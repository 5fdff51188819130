//! The simulated length of a trial: the whole steps that run for a requested duration.

use usar_sim::scenario::trial_steps;

/// The simulated length of a trial asked to last `duration_s` at step `dt_s`, seconds: its
/// whole steps (`usar_sim::scenario::trial_steps`) times `dt_s`, or `duration_s` itself when
/// that is a whole number of steps (within 1e-9 relative: `600` stays `600`, not
/// `600.0000000000001`) or a length the sweep refuses anyway. `--duration 0.01` at the default
/// 0.02 s step runs 0.02 s. The product is rounded to 12 significant digits, so that it prints
/// as the steps' length (`0.7`, not `0.7000000000000001`, for 35 steps of 0.02 s).
pub fn simulated_length_s(duration_s: f64, dt_s: f64) -> f64 {
    match trial_steps(duration_s, dt_s) {
        Ok(steps) => {
            let ran_s = steps as f64 * dt_s;
            if (ran_s - duration_s).abs() <= 1e-9 * duration_s.abs().max(1.0) {
                duration_s
            } else {
                format!("{ran_s:.11e}").parse().unwrap_or(ran_s)
            }
        }
        Err(_) => duration_s,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn simulated_length_is_the_whole_steps_that_run() {
        assert_eq!(simulated_length_s(600.0, 0.02), 600.0);
        assert_eq!(simulated_length_s(30.0, 0.02), 30.0);
        assert_eq!(simulated_length_s(0.01, 0.02), 0.02);
        assert!((simulated_length_s(0.03, 0.02) - 0.04).abs() < 1e-12);
        assert!((simulated_length_s(12.345, 0.02) - 12.36).abs() < 1e-12);
        // Printed as the steps' length, without float noise: 35 x 0.02 s.
        assert_eq!(simulated_length_s(0.69, 0.02).to_string(), "0.7");
        // A length the sweep refuses is shown as asked (the sweep fails on it).
        assert_eq!(simulated_length_s(-1.0, 0.02), -1.0);
    }
}
