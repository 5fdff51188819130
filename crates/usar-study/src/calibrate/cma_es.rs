//! The search of `--optimizer cma-es`: CMA-ES (fcmaes-core's active CMA-ES, ask and tell) on
//! normalised coordinates `u` in `[0, 1]^d`, seeded, so the same losses give the same
//! sequence of points (and a resumed calibration replays its trace).
//!
//! - **Start**: the start point is evaluated first (as Nelder-Mead's first vertex), then
//!   generations of [`population`]`(d)` points drawn around a mean that starts there, with a
//!   step size of [`INITIAL_SIGMA`] of each range.
//! - **Outside the box**: fcmaes-core clamps each drawn point to `[0, 1]^d`; the objective
//!   only ever sees points of the box. A loss of +inf is told as [`INFINITE_LOSS`].
//! - **Stop**: when a loss is 0, when the objective refuses a point (a spent budget), when
//!   [`super::optimizer::STALL_LIMIT`] points in a row bring nothing new, or when CMA-ES's own
//!   criteria fire ([`StopReason::Settled`]).
//!
//! CMA-ES adapts a full covariance of its search distribution to the loss's landscape, and
//! ranks points by their losses only, which suits a noisy objective with 6-8 free values better
//! than a simplex.
//!
//! # Reference
//! N. Hansen, "The CMA Evolution Strategy: A Tutorial", arXiv:1604.00772 (2016); G. A.
//! Jastrebski and D. V. Arnold, "Improving evolution strategies through active covariance
//! matrix adaptation", IEEE CEC 2006 (the active update).

use fcmaes_core::{Cmaes, CmaesParams, Fitness};

use super::optimizer::{Objective, Search, StopReason};

/// The initial step size, as a fraction of each free range (0.25).
pub const INITIAL_SIGMA: f64 = 0.25;

/// What a loss of +inf (a point whose trials failed or whose values break a rule) is told to
/// CMA-ES as (1e9): finite, so its ranking and its stop tests stay defined, and worse than any
/// loss a calibration gives.
pub const INFINITE_LOSS: f64 = 1e9;

/// Points per generation for `d` free values: CMA-ES's default `4 + floor(3 ln d)` (4 for
/// one value, 9 for six, 10 for eight).
pub fn population(d: usize) -> usize {
    4 + (3.0 * (d.max(1) as f64).ln()).floor() as usize
}

/// Minimises `objective` over `[0, 1]^d` from `start` (`d >= 1`) with CMA-ES seeded by `seed`,
/// and says why it stopped.
pub fn cma_es(start: &[f64], objective: &mut dyn Objective, seed: u64) -> StopReason {
    let d = start.len();
    let start: Vec<f64> = start.iter().map(|u| u.clamp(0.0, 1.0)).collect();
    let params = CmaesParams {
        popsize: population(d) as i32,
        max_evaluations: u64::MAX,
        seed,
        ..CmaesParams::default()
    };
    let fitness = Fitness::bounded(d, 1, &vec![0.0; d], &vec![1.0; d]);
    let mut cma = Cmaes::new(fitness, &start, &[INITIAL_SIGMA], &params);
    let mut search = Search::new(objective);
    if let Err(reason) = search.cost(&start) {
        return reason;
    }
    loop {
        let points = cma.ask();
        let mut losses = Vec::with_capacity(points.len());
        for p in &points {
            match search.cost(p) {
                Ok(c) => losses.push(c.min(INFINITE_LOSS)),
                Err(reason) => return reason,
            }
        }
        if cma.tell(&losses) != 0 {
            return StopReason::Settled;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calibrate::optimizer::Scored;

    /// Six "statistics" of six free values, each with a band that a narrow box of values
    /// meets, and the loss as a calibration computes it (distance outside the bands).
    struct Bands {
        points: Vec<Vec<f64>>,
        max_evals: usize,
    }

    impl Objective for Bands {
        fn loss(&mut self, u: &[f64]) -> Result<Scored, StopReason> {
            if self.points.len() >= self.max_evals {
                return Err(StopReason::MaxEvals);
            }
            assert!(u.iter().all(|x| (0.0..=1.0).contains(x)), "{u:?}");
            self.points.push(u.to_vec());
            // Coupled statistics: each mixes two values, as speeds and costs do.
            let stats = (0..u.len()).map(|i| u[i] + 0.5 * u[(i + 1) % u.len()]);
            // Met exactly at u = (0.7, 0.2, 0.55, 0.35, 0.8, 0.25).
            let centres = [0.8, 0.475, 0.725, 0.75, 0.925, 0.6];
            let loss = stats
                .zip(centres)
                .map(|(s, c)| ((s - c).abs() - 0.03).max(0.0) / 0.03)
                .sum::<f64>();
            Ok(Scored { loss, fresh: true })
        }
    }

    #[test]
    fn it_reaches_six_coupled_bands_and_repeats_itself_for_a_seed() {
        let run = |seed| {
            let mut b = Bands {
                points: vec![],
                max_evals: 3000,
            };
            let why = cma_es(&[0.5; 6], &mut b, seed);
            (why, b.points)
        };
        let (why, points) = run(7);
        assert_eq!(
            why,
            StopReason::TargetReached,
            "after {} points",
            points.len()
        );
        assert_eq!(points[0], vec![0.5; 6], "the start is evaluated first");
        let (again, repeated) = run(7);
        assert_eq!((why, &points), (again, &repeated));
        let (_, other) = run(8);
        assert_ne!(points[1], other[1], "another seed draws other points");
    }

    #[test]
    fn a_spent_budget_stops_it_with_that_reason() {
        let mut b = Bands {
            points: vec![],
            max_evals: 5,
        };
        assert_eq!(cma_es(&[0.1; 6], &mut b, 1), StopReason::MaxEvals);
        assert_eq!(b.points.len(), 5);
    }

    #[test]
    fn population_is_cma_es_default() {
        assert_eq!(
            [1, 2, 6, 8].map(population),
            [4, 6, 9, 10],
            "4 + floor(3 ln d)"
        );
    }
}
