//! [`ControlClock`]: when the robots' software runs, in steps, computed once from the
//! scenario's `sim` section and passed to [`World::new`](super::World::new) and every
//! [`World::step`](super::World::step) by whoever drives the world (the mission's
//! `Simulation`, a test, a bench). The world itself counts steps and keeps no clock.

use super::path_following_params::PATH_CHECK_INTERVAL_STEPS;
use crate::scenario::SimParams;

/// The robots' control clock: how many fixed steps `sim.dt_s` make one control period, and
/// every how many control steps a ground robot checks its path.
///
/// Built by [`ControlClock::of`], the one place `sim.control_period_s` is turned into steps;
/// timing is kept in steps only (seconds are derived with the world's step,
/// [`ControlClock::period_s`]). Source: not in the paper (its Unity scripts ran at the
/// engine's rate, one control step per step, the default); see `docs/world-model.md`,
/// "Control period".
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ControlClock {
    /// Steps per control period, >= 1.
    period_steps: u64,
    /// A ground robot checks its path every this many control steps, >= 1:
    /// [`PATH_CHECK_INTERVAL_STEPS`] over `period_steps`, at least 1.
    path_check_every: u64,
}

impl ControlClock {
    /// The clock of a scenario's `sim` section: 1 step per control period without
    /// `control_period_s` (the default), else `control_period_s / dt_s` rounded to the nearest
    /// whole number, at least 1 (exact in a validated scenario, which holds a whole number of
    /// steps; a huge ratio, refused by validation, saturates instead of overflowing).
    pub fn of(sim: &SimParams) -> Self {
        let period_steps = sim.control_period_s.map_or(1, |p| {
            let steps = (p.get() / sim.dt_s.get()).round();
            // `as` saturates: a huge ratio (refused by validation) stays finite.
            (steps as u64).max(1)
        });
        Self {
            period_steps,
            path_check_every: (PATH_CHECK_INTERVAL_STEPS / period_steps).max(1),
        }
    }

    /// Steps per control period, >= 1 (1 without `sim.control_period_s`).
    pub fn period_steps(&self) -> u64 {
        self.period_steps
    }

    /// The control period, seconds: [`ControlClock::period_steps`] times the world's fixed
    /// step `dt_s` (seconds, > 0).
    pub fn period_s(&self, dt_s: f64) -> f64 {
        self.period_steps as f64 * dt_s
    }

    /// Whether step `step` (the number of steps taken before it) is a control step: a multiple
    /// of [`ControlClock::period_steps`], so every step without a control period. A control
    /// step updates every robot's intent and runs the resolver; the steps between hold each
    /// robot's commanded velocity. The mission runs its decisions before a control step and
    /// its reviews (detection, phases) after the step before one.
    pub fn is_control_step(&self, step: u64) -> bool {
        step.is_multiple_of(self.period_steps)
    }

    /// The control steps taken before step `step`: `step / period_steps`.
    pub fn tick(&self, step: u64) -> u64 {
        step / self.period_steps
    }

    /// Whether ground robot `id` checks its path on control step `tick` (the control steps
    /// taken before it, [`ControlClock::tick`]): when `tick + id` is a multiple of the check
    /// interval in control steps, so the checks of a team are spread over the control steps.
    pub fn path_check_due(&self, tick: u64, id: usize) -> bool {
        (tick + id as u64).is_multiple_of(self.path_check_every)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::Positive;

    fn sim(dt_s: f64, period_s: Option<f64>) -> SimParams {
        SimParams {
            dt_s: Positive::new(dt_s).expect("> 0"),
            control_period_s: period_s.map(|p| Positive::new(p).expect("> 0")),
            ..SimParams::default()
        }
    }

    #[test]
    fn without_a_period_every_step_is_a_control_step_and_checks_every_ten() {
        let c = ControlClock::of(&sim(0.02, None));
        assert_eq!(c.period_steps(), 1);
        assert!((0..5).all(|s| c.is_control_step(s)));
        assert_eq!(c.tick(7), 7);
        let due: Vec<u64> = (0..30).filter(|&t| c.path_check_due(t, 3)).collect();
        assert_eq!(due, [7, 17, 27]);
        approx::assert_relative_eq!(c.period_s(0.02), 0.02, max_relative = 1e-15);
    }

    #[test]
    fn a_period_rounds_to_whole_steps_and_spreads_the_checks_over_fewer_ticks() {
        let c = ControlClock::of(&sim(0.02, Some(0.1)));
        assert_eq!(c.period_steps(), 5);
        assert_eq!(
            (0..11)
                .filter(|&s| c.is_control_step(s))
                .collect::<Vec<_>>(),
            [0, 5, 10]
        );
        assert_eq!(c.tick(14), 2);
        assert!(c.path_check_due(1, 1) && !c.path_check_due(1, 0));
        approx::assert_relative_eq!(c.period_s(0.02), 0.1, max_relative = 1e-12);
        // A period longer than the check interval checks every control step.
        let slow = ControlClock::of(&sim(0.02, Some(1.0)));
        assert_eq!(slow.period_steps(), 50);
        assert!((0..4).all(|t| slow.path_check_due(t, 0)));
    }

    #[test]
    fn a_huge_ratio_saturates() {
        assert_eq!(
            ControlClock::of(&sim(1e-300, Some(1e300))).period_steps(),
            u64::MAX
        );
    }
}
