//! The emulator a multiverse's design is fitted to (`--design N`, [`super::design`]): for
//! every target, a ridge regression of its statistic on the universe's choices and the free
//! values, and where each universe's calibration starts ([`Emulator::start`]).
//!
//! **Model.** With `z` the free values in `[0, 1]^d` (log ranges on the log scale,
//! [`FreeField::to_unit`]) and `a` the indicators of the universe's alternatives (one per
//! alternative but each axis's first), the features are
//! `[1, a, z, z_i^2, z_i z_j (i < j), a_k z_i]`: a quadratic response surface in the free
//! values whose intercept and slopes shift with every alternative (no interaction between
//! axes). The coefficients minimise `sum (y - x b)^2 + lambda * |b without the intercept|^2`
//! (solved by Cholesky, nalgebra), `lambda` chosen from [`LAMBDAS`] by [`FOLDS`]-fold
//! cross-validation (the `k`-th point fitted in fold `p(k) mod 5`, `p` a fixed random
//! permutation, ChaCha8 seed 0, so that no fold lines up with a universe or an alternative;
//! the smallest held-out error, the smaller `lambda` on a tie). Design points whose
//! statistic is NaN are left out of that target's fit, and points where trials failed (a
//! calibration scores them +inf) out of every fit.
//!
//! **Fidelity.** Each fit reports its cross-validated root-mean-square error, which
//! `multiverse.md` sets against the target's band half-width: an emulator whose error is a
//! large part of the band can only start a calibration near its band, and the universe's own
//! evaluations (and the check on unseen trials) decide admissibility, never the emulator.
//! The model is the regression stage of history matching without its Gaussian-process
//! residual: interactions between axes and non-quadratic responses show up as error.
//!
//! Reference: I. Vernon, M. Goldstein and R. G. Bower (2010), "Galaxy formation: a Bayesian
//! uncertainty analysis", Bayesian Analysis 5(4):619-669 (emulators of regression form
//! fitted to a design, section 3); T. Hastie, R. Tibshirani and J. Friedman (2009), *The
//! Elements of Statistical Learning*, 2nd ed., sections 3.4.1 (ridge) and 7.10
//! (cross-validation).

use nalgebra::{DMatrix, DVector};
use serde::{Deserialize, Serialize};

use super::design::DesignPoint;
use super::universe::choices_at;
use crate::calibrate::{FreeField, Target, target_loss};

/// The ridge penalties tried, in order (`1e-6` to `10`).
pub const LAMBDAS: [f64; 7] = [1e-6, 1e-4, 1e-3, 1e-2, 1e-1, 1.0, 10.0];
/// Cross-validation folds (5).
pub const FOLDS: usize = 5;
/// Fewest design points with a statistic for its target to be emulated (two a fold:
/// [`super::setup::MIN_DESIGN`]).
pub const MIN_POINTS: usize = super::setup::MIN_DESIGN;

/// One target's fit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Fit {
    /// The coefficients, one per feature ([`features`]).
    pub coefficients: Vec<f64>,
    /// The ridge penalty chosen.
    pub lambda: f64,
    /// The cross-validated root-mean-square error, in the statistic's unit.
    pub cv_rmse: f64,
    /// The sample standard deviation of the statistic over the points fitted.
    pub sd: f64,
    /// Design points fitted (those with a statistic).
    pub points: usize,
}

/// The fitted emulator: a fit per target (`None` with fewer than [`MIN_POINTS`] points).
#[derive(Debug, Clone, PartialEq)]
pub struct Emulator {
    sizes: Vec<usize>,
    free: Vec<FreeField>,
    /// The fits, in target order.
    pub fits: Vec<Option<Fit>>,
}

/// Where a universe's calibration starts, and the loss the emulator predicts there.
#[derive(Debug, Clone, PartialEq)]
pub struct Start {
    /// The free values, rounded, in `--free` order.
    pub values: Vec<f64>,
    /// The loss of the predicted statistics over the targets the emulator fits
    /// ([`crate::calibrate::loss()`] without the others).
    pub predicted_loss: f64,
}

/// The features of a universe taking `choices` (axes of `sizes` alternatives) at `z`, as
/// the module documentation lists them.
pub fn features(sizes: &[usize], choices: &[usize], z: &[f64]) -> Vec<f64> {
    let onehot: Vec<f64> = sizes
        .iter()
        .zip(choices)
        .flat_map(|(&k, &c)| (1..k).map(move |a| f64::from(u8::from(a == c))))
        .collect();
    let d = z.len();
    let mut x = Vec::with_capacity(1 + onehot.len() * (1 + d) + 2 * d + d * d / 2);
    x.push(1.0);
    x.extend(&onehot);
    x.extend(z);
    x.extend(z.iter().map(|v| v * v));
    for i in 0..d {
        x.extend(z[i + 1..].iter().map(|v| z[i] * v));
    }
    for o in &onehot {
        x.extend(z.iter().map(|v| o * v));
    }
    x
}

impl Emulator {
    /// Fits every target's statistic to the design `points` of a multiverse whose axes have
    /// `sizes` alternatives and whose free fields are `free` (`targets` statistics per point).
    pub fn fit(
        points: &[DesignPoint],
        sizes: &[usize],
        free: &[FreeField],
        targets: usize,
    ) -> Self {
        let points: Vec<&DesignPoint> = points.iter().filter(|p| p.message.is_none()).collect();
        let rows: Vec<Vec<f64>> = points
            .iter()
            .map(|p| {
                let z: Vec<f64> = free
                    .iter()
                    .zip(&p.values)
                    .map(|(f, &v)| f.to_unit(v))
                    .collect();
                features(sizes, &choices_at(sizes, p.universe), &z)
            })
            .collect();
        let fits = (0..targets)
            .map(|t| {
                let (x, y): (Vec<&Vec<f64>>, Vec<f64>) = rows
                    .iter()
                    .zip(&points)
                    .filter_map(|(r, p)| {
                        p.statistics
                            .get(t)
                            .filter(|v| v.is_finite())
                            .map(|v| (r, *v))
                    })
                    .unzip();
                fit_one(&x, &y)
            })
            .collect();
        Self {
            sizes: sizes.to_vec(),
            free: free.to_vec(),
            fits,
        }
    }

    /// The predicted statistics (in target order; NaN for a target without a fit) of a
    /// universe taking `choices` at the free values `values`.
    pub fn predict(&self, choices: &[usize], values: &[f64]) -> Vec<f64> {
        let z: Vec<f64> = self
            .free
            .iter()
            .zip(values)
            .map(|(f, &v)| f.to_unit(v))
            .collect();
        self.predict_unit(choices, &z)
    }

    fn predict_unit(&self, choices: &[usize], z: &[f64]) -> Vec<f64> {
        let x = features(&self.sizes, choices, z);
        self.fits
            .iter()
            .map(|f| f.as_ref().map_or(f64::NAN, |f| dot(&f.coefficients, &x)))
            .collect()
    }

    /// Where the calibration of a universe taking `choices`, held to `targets` (its flags),
    /// starts: the free values of least predicted loss over the targets with a fit (ties:
    /// nearest the targets' values, in half-widths), rounded to `digits`. Searched on a fixed
    /// set of 2,048 points of `[0, 1]^d` (ChaCha8, seed 0), then by a compass search from the
    /// best of them (steps from 1/16 down to 1/1024 of each range). Deterministic. `None`
    /// when no target the loss counts has a fit: the search then starts at the scenario's
    /// values, as without a design.
    pub fn start(&self, choices: &[usize], targets: &[Target], digits: u32) -> Option<Start> {
        let fitted: Vec<bool> = self.fits.iter().map(Option::is_some).collect();
        if !targets
            .iter()
            .zip(&fitted)
            .any(|(t, &f)| f && !t.report_only)
        {
            return None;
        }
        use rand::{RngExt, SeedableRng};
        let d = self.free.len();
        let score = |z: &[f64]| objective(targets, &fitted, &self.predict_unit(choices, z));
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(0);
        let mut best: Vec<f64> = vec![0.5; d];
        let mut best_score = score(&best);
        for _ in 0..2048 {
            let z: Vec<f64> = (0..d).map(|_| rng.random::<f64>()).collect();
            let s = score(&z);
            if better(s, best_score) {
                (best, best_score) = (z, s);
            }
        }
        let mut step = 1.0 / 16.0;
        while step >= 1.0 / 1024.0 {
            let mut moved = false;
            for i in 0..d {
                for sign in [1.0, -1.0] {
                    let mut z = best.clone();
                    z[i] = (z[i] + sign * step).clamp(0.0, 1.0);
                    let s = score(&z);
                    if better(s, best_score) {
                        (best, best_score, moved) = (z, s, true);
                    }
                }
            }
            if !moved {
                step /= 2.0;
            }
        }
        let values: Vec<f64> = self
            .free
            .iter()
            .zip(&best)
            .map(|(f, &u)| f.from_unit(u, digits))
            .collect();
        let predicted = self.predict(choices, &values);
        Some(Start {
            predicted_loss: objective(targets, &fitted, &predicted).0,
            values,
        })
    }
}

/// The search's score of predicted statistics: (loss, squared distance from the targets'
/// values in half-widths over the required targets), both over the `fitted` targets only.
fn objective(targets: &[Target], fitted: &[bool], predicted: &[f64]) -> (f64, f64) {
    let known = || {
        targets
            .iter()
            .zip(predicted)
            .zip(fitted)
            .filter(|(_, f)| **f)
            .map(|(tx, _)| tx)
    };
    let loss: f64 = known().map(|(t, &x)| target_loss(t, x)).sum();
    let centre: f64 = known()
        .filter(|(t, _)| !t.report_only)
        .map(|(t, &x)| {
            let w = t.band.half_width(t.value);
            if w.is_finite() && w > 0.0 {
                ((x - t.value) / w).powi(2)
            } else {
                0.0
            }
        })
        .sum();
    (
        loss,
        if centre.is_nan() {
            f64::INFINITY
        } else {
            centre
        },
    )
}

/// Whether score `a` is strictly better than `b` (loss first, then the distance).
fn better(a: (f64, f64), b: (f64, f64)) -> bool {
    a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)).is_lt()
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// The ridge fit of `y` on the rows `x`, `lambda` by cross-validation; `None` with fewer
/// than [`MIN_POINTS`] rows.
fn fit_one(x: &[&Vec<f64>], y: &[f64]) -> Option<Fit> {
    let n = y.len();
    if n < MIN_POINTS {
        return None;
    }
    let p = x[0].len();
    let folds = folds(n);
    let mut grams = vec![(DMatrix::<f64>::zeros(p, p), DVector::<f64>::zeros(p)); FOLDS];
    for (j, (row, &yj)) in x.iter().zip(y).enumerate() {
        let r = DVector::from_column_slice(row);
        let (g, b) = &mut grams[folds[j]];
        g.ger(1.0, &r, &r, 1.0);
        b.axpy(yj, &r, 1.0);
    }
    let (total_g, total_b) = grams.iter().fold(
        (DMatrix::<f64>::zeros(p, p), DVector::<f64>::zeros(p)),
        |(g, b), (gf, bf)| (g + gf, b + bf),
    );
    let mut best: Option<(f64, f64)> = None;
    for &lambda in &LAMBDAS {
        let mut sse = 0.0;
        for (f, (gf, bf)) in grams.iter().enumerate() {
            let Some(beta) = solve(&(&total_g - gf), &(&total_b - bf), lambda) else {
                sse = f64::INFINITY;
                break;
            };
            sse += x
                .iter()
                .zip(y)
                .enumerate()
                .filter(|(j, _)| folds[*j] == f)
                .map(|(_, (row, &yj))| (yj - dot(beta.as_slice(), row)).powi(2))
                .sum::<f64>();
        }
        if best.is_none_or(|(s, _)| sse < s) {
            best = Some((sse, lambda));
        }
    }
    let (sse, lambda) = best?;
    let beta = solve(&total_g, &total_b, lambda)?;
    let mean = y.iter().sum::<f64>() / n as f64;
    let sd = (y.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
    Some(Fit {
        coefficients: beta.as_slice().to_vec(),
        lambda,
        cv_rmse: (sse / n as f64).sqrt(),
        sd,
        points: n,
    })
}

/// The fold of each of `n` points fitted: `p(k) mod FOLDS`, `p` a permutation of `0..n`
/// shuffled by ChaCha8 seeded with 0 (balanced folds that line up with nothing in the
/// design's order).
fn folds(n: usize) -> Vec<usize> {
    use rand::SeedableRng;
    use rand::seq::SliceRandom;
    let mut p: Vec<usize> = (0..n).collect();
    p.shuffle(&mut rand_chacha::ChaCha8Rng::seed_from_u64(0));
    p.into_iter().map(|k| k % FOLDS).collect()
}

/// `(G + lambda * diag(0, 1, ..., 1)) b = r`, by Cholesky; `None` when not positive
/// definite (too few points for the features at that penalty).
fn solve(g: &DMatrix<f64>, r: &DVector<f64>, lambda: f64) -> Option<DVector<f64>> {
    let mut a = g.clone();
    for i in 1..a.nrows() {
        a[(i, i)] += lambda;
    }
    a.cholesky().map(|c| c.solve(r))
}

#[cfg(test)]
mod tests {
    use super::*;
    use usar_report::targets::Targets;

    fn free() -> Vec<FreeField> {
        vec![
            FreeField::parse("mission.pickup_s=0..1").unwrap(),
            FreeField::parse("mission.search_time_budget_s=0..1").unwrap(),
        ]
    }

    /// Points of a known response: `y = 3 + 2 a + z0 - 4 (z1 - 0.5)^2` on an axis of two
    /// alternatives.
    fn points(n: usize) -> Vec<DesignPoint> {
        let plan = super::super::design::design_plan(n, 2, &free(), 17, 3);
        plan.into_iter()
            .enumerate()
            .map(|(j, (u, v))| DesignPoint {
                index: j,
                universe: u as u64,
                statistics: vec![
                    3.0 + 2.0 * u as f64 + v[0] - 4.0 * (v[1] - 0.5).powi(2),
                    f64::NAN,
                ],
                values: v,
                message: None,
            })
            .collect()
    }

    #[test]
    fn features_are_the_documented_terms() {
        let x = features(&[3, 2], &[2, 0], &[0.5, 0.25]);
        // 1; a = [0, 1 | 0]; z; z^2; z0 z1; a x z
        let want = [
            1.0, 0.0, 1.0, 0.0, 0.5, 0.25, 0.25, 0.0625, 0.125, 0.0, 0.0, 0.5, 0.25, 0.0, 0.0,
        ];
        assert_eq!(x, want);
    }

    #[test]
    fn a_quadratic_response_is_recovered_and_a_statistic_never_seen_is_not_fitted() {
        let e = Emulator::fit(&points(60), &[2], &free(), 2);
        let fit = e.fits[0].as_ref().unwrap();
        assert!(fit.cv_rmse < 1e-3, "exact model: {}", fit.cv_rmse);
        assert_eq!(fit.points, 60);
        assert!(e.fits[1].is_none());
        let y = e.predict(&[1], &[0.2, 0.9])[0];
        approx::assert_abs_diff_eq!(y, 3.0 + 2.0 + 0.2 - 4.0 * 0.16, epsilon = 1e-3);
        assert!(e.predict(&[1], &[0.2, 0.9])[1].is_nan());
    }

    #[test]
    fn the_start_is_where_the_predicted_statistic_is_in_band_and_nearest_its_value() {
        let e = Emulator::fit(&points(60), &[2], &free(), 1);
        let targets = Targets::parse(
            r#"Targets(targets: [(name: "a", statistic: Mean("rounds"), value: 5.5, band: PlusMinus(0.1))])"#,
            "t.ron",
        )
        .unwrap();
        // Universe 1: 5 + z0 - 4 (z1 - 0.5)^2 = 5.5 at z1 = 0.5, z0 = 0.5 (among others).
        let s = e.start(&[1], targets.targets(), 6).unwrap();
        assert_eq!(s.predicted_loss, 0.0);
        let y = 5.0 + s.values[0] - 4.0 * (s.values[1] - 0.5).powi(2);
        approx::assert_abs_diff_eq!(y, 5.5, epsilon = 0.01);
        assert_eq!(
            Some(s),
            e.start(&[1], targets.targets(), 6),
            "deterministic"
        );
        // Universe 0 reaches at most 4: the start is at z0 = 1, z1 = 0.5, loss > 0.
        let s0 = e.start(&[0], targets.targets(), 6).unwrap();
        assert!(s0.predicted_loss > 0.0);
        approx::assert_abs_diff_eq!(s0.values[0], 1.0, epsilon = 1e-3);
    }

    #[test]
    fn targets_without_a_fit_are_left_out_of_the_start_and_none_fitted_gives_no_start() {
        let e = Emulator::fit(&points(60), &[2], &free(), 2);
        let two = Targets::parse(
            r#"Targets(targets: [(name: "a", statistic: Mean("rounds"), value: 5.5, band: PlusMinus(0.1)), (name: "b", statistic: Mean("rescued_total"), value: 1.0, band: PlusMinus(0.1))])"#,
            "t.ron",
        )
        .unwrap();
        // Target "b" never has a statistic: the start is where "a" is in band.
        let s = e.start(&[1], two.targets(), 6).unwrap();
        assert_eq!(s.predicted_loss, 0.0);
        // Only "b" fitted... none: no start (the scenario's own values are used).
        let mut only_b = two.clone();
        only_b.set_report_only(&["a".to_string()]).unwrap();
        assert_eq!(e.start(&[1], only_b.targets(), 6), None);
    }

    #[test]
    fn folds_are_balanced_and_points_with_failed_trials_are_not_fitted() {
        let f = folds(20);
        for k in 0..FOLDS {
            assert_eq!(f.iter().filter(|&&x| x == k).count(), 4);
        }
        assert_ne!(f, (0..20).map(|j| j % FOLDS).collect::<Vec<_>>());
        let mut pts = points(60);
        for p in pts.iter_mut().take(5) {
            p.message = Some("1 of 2 trials failed".into());
            p.statistics[0] = 1e6;
        }
        let e = Emulator::fit(&pts, &[2], &free(), 1);
        assert_eq!(e.fits[0].as_ref().unwrap().points, 55);
        assert!(e.fits[0].as_ref().unwrap().cv_rmse < 1e-3);
    }
}
