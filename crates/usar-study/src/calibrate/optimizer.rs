//! The search: Nelder-Mead (argmin's [`NelderMead`]) on normalised coordinates `u` in
//! `[0, 1]^d`, derivative-free and deterministic (the same losses give the same sequence of
//! points).
//!
//! - **Start**: the initial simplex is the start point plus, along each axis in turn, a step
//!   of [`INITIAL_STEP`] of the range (inward when the step would leave the box). Its points
//!   are evaluated in that order before argmin starts, so that a budget spent during them
//!   stops the search cleanly.
//! - **Outside the box**: a point with a coordinate outside `[0, 1]` is evaluated at the
//!   nearest point of the box (clamped), and its cost is that loss plus
//!   [`OUTSIDE_PENALTY`] x its distance to the box, so the simplex is drawn back in; the
//!   objective only ever sees points of the box.
//! - **Stop**: when a loss is 0 (every band holds), when the objective refuses a point (its
//!   evaluation or time budget is spent), when the simplex is flat (argmin's
//!   standard-deviation test: every vertex has the same loss), or when [`STALL_LIMIT`]
//!   points in a row bring nothing new (all already evaluated).
//!
//! The same point is never handed to the objective twice (the search keeps every loss).

use std::cell::RefCell;
use std::collections::HashMap;
use std::fmt;

use argmin::core::{CostFunction, Executor, State, TerminationReason, TerminationStatus};
use argmin::solver::neldermead::NelderMead;
use argmin_math::{ArgminAdd, ArgminMul, ArgminSub};
use usar_sweep::settings::Setting;

/// The initial simplex's step along each axis, as a fraction of the range (0.15).
pub const INITIAL_STEP: f64 = 0.15;

/// Cost per unit of distance outside the box `[0, 1]^d`, added to the loss of the clamped
/// point (1.0).
pub const OUTSIDE_PENALTY: f64 = 1.0;

/// Points in a row that bring no new evaluation after which the search stops as stalled
/// (100): on a plateau the rounded values repeat and Nelder-Mead would shrink for ever.
pub const STALL_LIMIT: usize = 100;

/// Which search a calibration runs (`usar calibrate --optimizer`); part of its identity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Optimizer {
    /// Nelder-Mead from the start point ([`nelder_mead`]); the default, for one to three free
    /// values.
    #[default]
    NelderMead,
    /// CMA-ES seeded by the calibration's base seed ([`super::cma_es::cma_es`]); for wider free
    /// sets and noisy losses.
    CmaEs,
}

/// Why a search stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum StopReason {
    /// A loss of 0: every statistic lies in its band.
    TargetReached,
    /// The evaluation budget (`--max-evals`) is spent.
    MaxEvals,
    /// The wall-clock budget (`--max-time`) is spent.
    MaxTime,
    /// The simplex is flat: every vertex has the same loss.
    Converged,
    /// [`STALL_LIMIT`] points in a row brought nothing new.
    Stalled,
    /// The caller's stop flag was set ([`usar_sweep::data::hooks::CalibrationHooks::stop`]); a
    /// calibration so stopped writes no outputs.
    Interrupted,
    /// CMA-ES stopped by its own criteria (its step size or its recent losses too small to
    /// go on; `--optimizer cma-es`).
    Settled,
}

impl fmt::Display for StopReason {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            StopReason::TargetReached => "every statistic is in its band (loss 0)",
            StopReason::MaxEvals => {
                return write!(f, "the evaluation budget ({}) is spent", Setting::MaxEvals);
            }
            StopReason::MaxTime => {
                return write!(f, "the time budget ({}) is spent", Setting::MaxTimeS);
            }
            StopReason::Converged => "the simplex is flat (every vertex has the same loss)",
            StopReason::Stalled => "the search stalled (no new point in a long run)",
            StopReason::Interrupted => "stopped by the caller (its stop flag)",
            StopReason::Settled => {
                "CMA-ES settled (its step size or its recent losses too small to go on)"
            }
        })
    }
}

/// What the search minimises.
pub trait Objective {
    /// The loss at `u` (in `[0, 1]^d`; `>= 0`, +inf allowed, never NaN), and whether it is a
    /// point the search had not seen before (a new evaluation, or one recorded by an earlier
    /// run); or the reason to stop instead (a spent budget).
    ///
    /// # Errors
    /// The reason to stop; the search ends with it.
    fn loss(&mut self, u: &[f64]) -> Result<Scored, StopReason>;
}

/// The objective's answer for one point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Scored {
    /// The loss (`>= 0`, +inf allowed).
    pub loss: f64,
    /// Whether the point is new to the search (else its values were evaluated already).
    pub fresh: bool,
}

/// A point of the search, in normalised coordinates (argmin's parameter type).
#[derive(Debug, Clone, PartialEq)]
struct Point(Vec<f64>);

impl ArgminAdd<Point, Point> for Point {
    fn add(&self, other: &Point) -> Point {
        Point(self.0.iter().zip(&other.0).map(|(a, b)| a + b).collect())
    }
}

impl ArgminSub<Point, Point> for Point {
    fn sub(&self, other: &Point) -> Point {
        Point(self.0.iter().zip(&other.0).map(|(a, b)| a - b).collect())
    }
}

impl ArgminMul<f64, Point> for Point {
    fn mul(&self, k: &f64) -> Point {
        Point(self.0.iter().map(|a| a * k).collect())
    }
}

/// The initial simplex around `start` (clamped to the box): `start`, then `start` moved by
/// [`INITIAL_STEP`] along each axis (backwards where forwards would leave the box).
pub fn initial_simplex(start: &[f64]) -> Vec<Vec<f64>> {
    let start: Vec<f64> = start.iter().map(|u| u.clamp(0.0, 1.0)).collect();
    let mut simplex = vec![start.clone()];
    for i in 0..start.len() {
        let mut v = start.clone();
        v[i] += if v[i] + INITIAL_STEP <= 1.0 {
            INITIAL_STEP
        } else {
            -INITIAL_STEP
        };
        simplex.push(v);
    }
    simplex
}

/// The cost function argmin sees: memoised losses, clamping and the outside penalty.
struct Cost<'a> {
    inner: RefCell<Search<'a>>,
}

pub(super) struct Search<'a> {
    objective: &'a mut dyn Objective,
    /// Loss per clamped point (by the bits of its coordinates).
    seen: HashMap<Vec<u64>, f64>,
    /// Points in a row that brought nothing new.
    idle: usize,
}

/// A stop raised inside argmin, carried out through its error.
#[derive(Debug)]
struct Halt(StopReason);

impl fmt::Display for Halt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "search stopped: {}", self.0)
    }
}

impl std::error::Error for Halt {}

impl<'a> Search<'a> {
    /// A search of `objective` that has seen no point yet.
    pub(super) fn new(objective: &'a mut dyn Objective) -> Self {
        Self {
            objective,
            seen: HashMap::new(),
            idle: 0,
        }
    }

    /// The cost at `u`: the loss at the clamped point plus the outside penalty; or why to
    /// stop (a loss of 0, a spent budget, [`STALL_LIMIT`] points in a row seen before).
    pub(super) fn cost(&mut self, u: &[f64]) -> Result<f64, StopReason> {
        let clamped: Vec<f64> = u.iter().map(|x| x.clamp(0.0, 1.0)).collect();
        let outside = u
            .iter()
            .zip(&clamped)
            .map(|(a, b)| (a - b).powi(2))
            .sum::<f64>()
            .sqrt();
        let key: Vec<u64> = clamped.iter().map(|x| x.to_bits()).collect();
        let loss = match self.seen.get(&key) {
            Some(&l) => {
                self.idle += 1;
                l
            }
            None => {
                let s = self.objective.loss(&clamped)?;
                let l = if s.loss.is_nan() {
                    f64::INFINITY
                } else {
                    s.loss
                };
                self.idle = if s.fresh { 0 } else { self.idle + 1 };
                self.seen.insert(key, l);
                if l <= 0.0 {
                    return Err(StopReason::TargetReached);
                }
                l
            }
        };
        if self.idle >= STALL_LIMIT {
            return Err(StopReason::Stalled);
        }
        Ok(loss + OUTSIDE_PENALTY * outside)
    }
}

impl CostFunction for Cost<'_> {
    type Param = Point;
    type Output = f64;

    fn cost(&self, p: &Point) -> Result<f64, argmin::core::Error> {
        self.inner
            .borrow_mut()
            .cost(&p.0)
            .map_err(|r| argmin::core::Error::new(Halt(r)))
    }
}

/// Minimises `objective` over `[0, 1]^d` from `start` (`d >= 1` coordinates) and says why it
/// stopped. The objective keeps what it needs of the points (the search only returns why it
/// ended).
pub fn nelder_mead(start: &[f64], objective: &mut dyn Objective) -> StopReason {
    let simplex = initial_simplex(start);
    let cost = Cost {
        inner: RefCell::new(Search::new(objective)),
    };
    // The simplex first, in order: a budget spent here stops before argmin starts (its
    // `init` cannot stop), and argmin then finds every vertex known.
    for v in &simplex {
        if let Err(reason) = cost.inner.borrow_mut().cost(v) {
            return reason;
        }
    }
    let solver = NelderMead::new(simplex.into_iter().map(Point).collect());
    let run = Executor::new(cost, solver)
        .configure(|state| state.max_iters(u64::MAX).target_cost(0.0))
        .run();
    match run {
        Ok(result) => match result.state().get_termination_status() {
            TerminationStatus::Terminated(TerminationReason::TargetCostReached) => {
                StopReason::TargetReached
            }
            TerminationStatus::Terminated(TerminationReason::SolverConverged) => {
                StopReason::Converged
            }
            _ => StopReason::Stalled,
        },
        Err(e) => match e.downcast_ref::<Halt>() {
            Some(Halt(reason)) => *reason,
            // argmin's own errors ("reached unreachable point") are not expected.
            None => StopReason::Stalled,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A cheap analytic objective: two "statistics" of the point with bands, the loss as a
    /// calibration computes it, an evaluation budget, and every point asked for.
    struct Analytic {
        max_evals: usize,
        points: Vec<Vec<f64>>,
        losses: Vec<f64>,
    }

    impl Objective for Analytic {
        fn loss(&mut self, u: &[f64]) -> Result<Scored, StopReason> {
            if self.points.len() >= self.max_evals {
                return Err(StopReason::MaxEvals);
            }
            assert!(u.iter().all(|x| (0.0..=1.0).contains(x)), "{u:?}");
            // Statistics 10 x + y and x y / 0.2 with bands 6 ± 0.25 and 0.5 ± 0.05.
            let (x, y) = (u[0], u[1]);
            let outside = |s: f64, v: f64, w: f64| (((s - v).abs() - w).max(0.0) / w).powi(2);
            let loss = outside(10.0 * x + y, 6.0, 0.25) + outside(x * y / 0.2, 0.5, 0.05);
            self.points.push(u.to_vec());
            self.losses.push(loss);
            Ok(Scored { loss, fresh: true })
        }
    }

    #[test]
    fn reaches_the_bands_of_an_analytic_function() {
        let mut f = Analytic {
            max_evals: 200,
            points: vec![],
            losses: vec![],
        };
        let why = nelder_mead(&[0.1, 0.9], &mut f);
        assert_eq!(why, StopReason::TargetReached, "{:?}", f.losses);
        let last = f.points.last().unwrap();
        assert_eq!(*f.losses.last().unwrap(), 0.0);
        assert!(((10.0 * last[0] + last[1]) - 6.0).abs() <= 0.25, "{last:?}");
        assert!(f.points.len() < 200);
        // The same losses give the same points.
        let mut again = Analytic {
            max_evals: 200,
            points: vec![],
            losses: vec![],
        };
        nelder_mead(&[0.1, 0.9], &mut again);
        assert_eq!(again.points, f.points);
        // No point is asked for twice.
        for (i, p) in f.points.iter().enumerate() {
            assert!(!f.points[..i].contains(p), "point {i} repeated");
        }
    }

    #[test]
    fn a_budget_stops_the_search_even_inside_the_first_simplex() {
        for budget in [1, 2, 5] {
            let mut f = Analytic {
                max_evals: budget,
                points: vec![],
                losses: vec![],
            };
            assert_eq!(nelder_mead(&[0.1, 0.9], &mut f), StopReason::MaxEvals);
            assert_eq!(f.points.len(), budget);
        }
    }

    #[test]
    fn the_simplex_steps_inward_at_an_edge_and_a_flat_loss_converges() {
        assert_eq!(
            initial_simplex(&[0.9, 0.2]),
            vec![
                vec![0.9, 0.2],
                vec![0.75, 0.2],
                vec![0.9, 0.2 + INITIAL_STEP]
            ]
        );
        assert_eq!(initial_simplex(&[1.5])[0], vec![1.0]);
        struct Flat;
        impl Objective for Flat {
            fn loss(&mut self, _: &[f64]) -> Result<Scored, StopReason> {
                Ok(Scored {
                    loss: 3.0,
                    fresh: true,
                })
            }
        }
        assert_eq!(nelder_mead(&[0.5, 0.5], &mut Flat), StopReason::Converged);
    }

    #[test]
    fn infinite_losses_stall_without_a_crash() {
        /// Every point fails, and only the first few are new (values rounded coarsely).
        struct Broken(usize);
        impl Objective for Broken {
            fn loss(&mut self, _: &[f64]) -> Result<Scored, StopReason> {
                self.0 += 1;
                Ok(Scored {
                    loss: f64::INFINITY,
                    fresh: self.0 <= 5,
                })
            }
        }
        let mut b = Broken(0);
        assert_eq!(nelder_mead(&[0.5, 0.5], &mut b), StopReason::Stalled);
        assert!(b.0 >= STALL_LIMIT / 2, "{}", b.0);
    }
}
