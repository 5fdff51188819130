//! Needs distributions of a robot (Eq. 8) and of a group (Eqs. 11 and 16; Algorithm 4, NDC).

use nalgebra::DVector;
use serde::{Deserialize, Serialize};

use crate::error::{Result, RneError};
use crate::needs::{NeedsMatrix, NeedsVector, Weights};
use crate::vector_newtype::vector_newtype;

/// Default relative smoothing: `1e-9` of the total weighted needs is added to each category.
pub const DEFAULT_RELATIVE_EPSILON: f64 = 1e-9;

/// How zero categories are smoothed before normalising (not in the paper; see
/// `docs/trust-model.md`).
///
/// A category that is zero on one side only (an observer has `cap = res = 0`, a carrier does
/// not) makes `T(P||Q)` infinite. Smoothing adds `eps_abs` to every weighted need `n_k w_k`
/// before normalising:
///
/// * [`Smoothing::Relative`]`(e)`: `eps_abs = e * sum_k n_k w_k`. Scale invariant: multiplying
///   a needs vector by `c > 0` leaves its distribution unchanged. **Default**, with
///   `e = 1e-9` ([`DEFAULT_RELATIVE_EPSILON`]); then a zero category gets probability
///   `~1e-9` and a one-sided zero costs about `p_k * ln(p_k / 1e-9) <= ~20.7 p_k` nats. An
///   all-zero needs vector (a robot with nothing left: no HP, energy, resources or free
///   capacity) has no scale to take a share of; with `e > 0` it gets the uniform
///   distribution, as with `Absolute` (a convention: the paper leaves `0/0` open).
/// * [`Smoothing::Absolute`]`(e)`: `eps_abs = e` in weighted-need units. Not scale invariant,
///   but an all-zero needs vector gets the uniform distribution instead of an error.
/// * [`Smoothing::None`] (or either variant with `e = 0`): no smoothing; RNE may then be
///   `f64::INFINITY` (never NaN).
///
/// Valid range: `e` finite and `>= 0`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Smoothing {
    /// No smoothing.
    None,
    /// Add `e * total` to each weighted need (`e >= 0`).
    Relative(f64),
    /// Add `e` to each weighted need (`e >= 0`).
    Absolute(f64),
}

impl Default for Smoothing {
    fn default() -> Self {
        Self::Relative(DEFAULT_RELATIVE_EPSILON)
    }
}

impl Smoothing {
    /// Checks the epsilon.
    ///
    /// # Errors
    /// [`RneError::InvalidEpsilon`] if it is negative or not finite.
    pub fn validate(self) -> Result<()> {
        match self {
            Self::None => Ok(()),
            Self::Relative(e) | Self::Absolute(e) if e.is_finite() && e >= 0.0 => Ok(()),
            Self::Relative(e) | Self::Absolute(e) => Err(RneError::InvalidEpsilon(e)),
        }
    }
}

/// Which entries of two distributions are compared in `sum_k p_k log(p_k / q_k)`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub enum Alignment {
    /// Entry `k` is needs category `k` on both sides (Defs. 1-3, Eqs. 7, 12, 17). **Default.**
    #[default]
    Category,
    /// Each distribution is sorted ascending before comparing, as Algorithm 4 (NDC) returns
    /// `D.Sort()`: the `k`-th smallest share of one side is compared with the `k`-th smallest
    /// of the other, whatever the categories.
    Sorted,
}

/// Options for computing a needs distribution.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct DistributionOptions {
    /// Zero-category smoothing; default `Relative(1e-9)`.
    pub smoothing: Smoothing,
    /// Category-aligned (default) or sorted (Algorithm 4).
    pub alignment: Alignment,
}

/// How far from 1 the shares of a [`Distribution`] built by [`Distribution::new`] may sum
/// (absolute; the distributions this crate computes are within a few `f64::EPSILON`).
pub const DISTRIBUTION_SUM_TOLERANCE: f64 = 1e-9;

/// A needs distribution `D = (d_1, ..., d_j)`: `j >= 1` entries, each in `[0, 1]`, summing to 1
/// (up to rounding). Produced by [`needs_distribution`] or [`group_distribution`], or from
/// given shares by [`Distribution::new`].
///
/// Serialises as a plain list of numbers; deserialising validates (as [`Distribution::new`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "Vec<f64>", into = "Vec<f64>")]
pub struct Distribution(DVector<f64>);

impl Distribution {
    /// A distribution from given shares, e.g. one read back from a file.
    ///
    /// # Errors
    /// [`RneError::Empty`] if `shares` is empty; [`RneError::InvalidProbability`] naming the
    /// first share that is negative or not finite; [`RneError::NotNormalised`] if they do not
    /// sum to 1 within [`DISTRIBUTION_SUM_TOLERANCE`].
    pub fn new(shares: impl Into<Vec<f64>>) -> Result<Self> {
        let shares = shares.into();
        if shares.is_empty() {
            return Err(RneError::Empty {
                what: "distribution",
            });
        }
        if let Some(index) = shares.iter().position(|p| !p.is_finite() || *p < 0.0) {
            return Err(RneError::InvalidProbability {
                index,
                value: shares[index],
            });
        }
        let sum: f64 = shares.iter().sum();
        if (sum - 1.0).abs() > DISTRIBUTION_SUM_TOLERANCE {
            return Err(RneError::NotNormalised { sum });
        }
        Ok(Self(DVector::from_vec(shares)))
    }

    /// Normalises non-negative weighted needs `v_k` into `d_k = (v_k + eps) / sum_k (v_k + eps)`.
    fn from_weighted(
        mut v: DVector<f64>,
        opts: &DistributionOptions,
        what: &'static str,
    ) -> Result<Self> {
        opts.smoothing.validate()?;
        let total: f64 = v.sum();
        if total.is_infinite() {
            return Err(RneError::Overflow { what });
        }
        let eps = match opts.smoothing {
            Smoothing::None => 0.0,
            // All needs zero: no scale to take a share of; uniform, as `Absolute` gives.
            Smoothing::Relative(e) if total == 0.0 && e > 0.0 => 1.0,
            Smoothing::Relative(e) => e * total,
            Smoothing::Absolute(e) => e,
        };
        v.add_scalar_mut(eps);
        let total = v.sum();
        if total.is_infinite() {
            return Err(RneError::Overflow { what });
        }
        if total <= 0.0 || !total.is_finite() {
            return Err(RneError::ZeroTotal { what });
        }
        v /= total;
        if opts.alignment == Alignment::Sorted {
            v.as_mut_slice().sort_by(f64::total_cmp);
        }
        Ok(Self(v))
    }
}

vector_newtype!(Distribution, "shares", validated);

/// A robot's needs distribution, Eq. 8 (Def. 1) and Algorithm 4 (NDC):
///
/// `d_k = n_k w_k / sum_{k=1..j} n_k w_k`, then smoothed (see [`Smoothing`]) and, with
/// [`Alignment::Sorted`], sorted ascending.
///
/// # Errors
/// [`RneError::LengthMismatch`] if `needs.len() != weights.len()`; [`RneError::ZeroTotal`] if
/// all weighted needs are zero and there is no smoothing ([`Smoothing::None`] or `e = 0`);
/// [`RneError::Overflow`] if they and the smoothing add up past `f64::MAX` (with no or
/// relative smoothing, needs near `f64::MAX` are scaled first, so this takes a huge epsilon;
/// [`Smoothing::Absolute`] is not scale invariant, so its inputs are not scaled and products
/// near `f64::MAX` overflow); [`RneError::InvalidEpsilon`].
///
/// # Reference
/// `D_R = (N_R .* W) / <N_R, W>`; paper Def. 1, Eq. 8 and Algorithm 4 (NDC).
pub fn needs_distribution(
    needs: &NeedsVector,
    weights: &Weights,
    opts: &DistributionOptions,
) -> Result<Distribution> {
    if needs.len() != weights.len() {
        return Err(RneError::LengthMismatch {
            what: "needs vector",
            expected: weights.len(),
            actual: needs.len(),
        });
    }
    let v = weighted(needs.as_dvector(), weights.as_dvector(), opts.smoothing);
    Distribution::from_weighted(v, opts, "needs vector")
}

/// The weighted needs `a_k w_k` to normalise: the plain product when its sum is a normal
/// `f64` (every ordinary input, bit for bit), when all needs are zero, or with
/// [`Smoothing::Absolute`] (whose result depends on the scale); otherwise the product of
/// `a / max(a)` and `w / max(w)`. Without smoothing or with [`Smoothing::Relative`] the
/// distribution does not change with the scale of the needs or the weights, so scaling only
/// keeps inputs near `f64::MAX` (whose sum overflows) or among the subnormals (whose products
/// round to 0, or where `e * sum` does) computable.
fn weighted(a: &DVector<f64>, w: &DVector<f64>, smoothing: Smoothing) -> DVector<f64> {
    let v = a.component_mul(w);
    match needs_scale(v.sum(), a.amax(), w.amax(), smoothing) {
        None => v,
        Some((a_max, w_max)) => (a / a_max).component_mul(&(w / w_max)),
    }
}

/// The rule of `weighted`: `None` to multiply needs and weights as they are (their product's
/// sum `plain_sum` is a normal `f64`, the smoothing is [`Smoothing::Absolute`], or the largest
/// need `a_max` is 0 or infinite), else the divisors `(a_max, w_max)` to scale needs and
/// weights by first. Weights are finite and `> 0` (`Weights::new`); needs or column sums may
/// be 0 or infinite. Also used by the heuristic split's scorer, so both scale alike.
pub(crate) fn needs_scale(
    plain_sum: f64,
    a_max: f64,
    w_max: f64,
    smoothing: Smoothing,
) -> Option<(f64, f64)> {
    let as_they_are = plain_sum.is_normal()
        || matches!(smoothing, Smoothing::Absolute(_))
        || a_max == 0.0
        || !a_max.is_finite();
    (!as_they_are).then_some((a_max, w_max))
}

/// A group's needs distribution, Eqs. 11 and 16 (Defs. 2-3):
///
/// `D_G[k] = w_k sum_{r=1..i} N[r, k] / sum_{k'} w_k' sum_r N[r, k']` for the `i x j` needs
/// matrix `N` (weighted column sums, normalised), then smoothed and optionally sorted like
/// [`needs_distribution`]. A group of one robot has that robot's distribution.
///
/// # Errors
/// [`RneError::LengthMismatch`] if `group.categories() != weights.len()`, otherwise as
/// [`needs_distribution`].
///
/// # Reference
/// `D_G = (1_i^T N .* W^T) / (1_i^T N W)`; paper Defs. 2-3, Eqs. 11 and 16.
pub fn group_distribution(
    group: &NeedsMatrix,
    weights: &Weights,
    opts: &DistributionOptions,
) -> Result<Distribution> {
    if group.categories() != weights.len() {
        return Err(RneError::LengthMismatch {
            what: "group needs matrix",
            expected: weights.len(),
            actual: group.categories(),
        });
    }
    group_distribution_from_sums(group.as_dmatrix().row_sum().transpose(), weights, opts)
}

/// [`group_distribution`] from the group's column sums `sum_r N[r, k]` (length `j`, equal to
/// `weights.len()`; the caller checks). Bit-identical to [`group_distribution`] when the sums
/// are accumulated member by member from `0.0` in the matrix's row order, which is how
/// `nalgebra` sums a column.
pub(crate) fn group_distribution_from_sums(
    column_sums: DVector<f64>,
    weights: &Weights,
    opts: &DistributionOptions,
) -> Result<Distribution> {
    let v = weighted(&column_sums, weights.as_dvector(), opts.smoothing);
    Distribution::from_weighted(v, opts, "group")
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    fn w() -> Weights {
        Weights::new(vec![6.0, 4.0, 2.0]).unwrap()
    }

    #[test]
    fn a_distribution_reads_back_what_it_writes_and_nothing_invalid() {
        let d = needs_distribution(
            &NeedsVector::new(vec![1.0, 3.0, 0.0]).unwrap(),
            &w(),
            &DistributionOptions::default(),
        )
        .unwrap();
        let json = serde_json::to_string(&d).unwrap();
        assert!(json.starts_with('[') && !json.starts_with("[["), "{json}");
        assert_eq!(serde_json::from_str::<Distribution>(&json).unwrap(), d);
        assert_eq!(Distribution::new(d.as_slice().to_vec()).unwrap(), d);
        for (bad, why) in [
            ("[]", "distribution is empty"),
            (
                "[-1.0, 2.0]",
                "probabilities[0] = -1; values must be finite and >= 0",
            ),
            (
                "[0.7, 0.7]",
                "distribution shares sum to 1.4; they must sum to 1",
            ),
            ("[[0.5, 0.5], 2, null]", "invalid type"),
        ] {
            let e = serde_json::from_str::<Distribution>(bad).unwrap_err();
            assert!(e.to_string().contains(why), "{bad}: {e}");
        }
        assert!(Distribution::new(vec![0.5, 0.5 + 1e-12]).is_ok());
    }

    #[test]
    fn example1_distributions() {
        let opts = DistributionOptions {
            smoothing: Smoothing::None,
            ..Default::default()
        };
        let d = needs_distribution(
            &NeedsVector::new(vec![86.0, 120.0, 30.0]).unwrap(),
            &w(),
            &opts,
        )
        .unwrap();
        // The paper prints 0.4884 for d_11 in the text and 0.4886 in Eq. 9; 0.4886 is right.
        for (got, want) in d.as_slice().iter().zip([0.488_636, 0.454_545, 0.056_818]) {
            assert_relative_eq!(*got, want, epsilon = 1e-6);
        }
    }

    #[test]
    fn example2_group_distributions() {
        let opts = DistributionOptions {
            smoothing: Smoothing::None,
            ..Default::default()
        };
        let g1 =
            NeedsMatrix::from_rows(&[vec![82.0, 114.0, 24.0], vec![79.0, 117.0, 23.0]]).unwrap();
        let d = group_distribution(&g1, &w(), &opts).unwrap();
        for (got, want) in d.as_slice().iter().zip([0.4869, 0.4657, 0.0474]) {
            assert_relative_eq!(*got, want, epsilon = 5e-5);
        }
    }

    #[test]
    fn smoothing_and_sorting() {
        let n = NeedsVector::new(vec![0.0, 3.0, 1.0]).unwrap();
        let ones = Weights::uniform(3).unwrap();
        let none = DistributionOptions {
            smoothing: Smoothing::None,
            ..Default::default()
        };
        assert_eq!(
            needs_distribution(&n, &ones, &none).unwrap().as_slice(),
            &[0.0, 0.75, 0.25]
        );
        let d = needs_distribution(&n, &ones, &DistributionOptions::default()).unwrap();
        assert!(d.as_slice()[0] > 0.0 && d.as_slice()[0] < 1e-8);
        assert_relative_eq!(d.as_slice().iter().sum::<f64>(), 1.0, epsilon = 1e-12);
        let sorted = DistributionOptions {
            smoothing: Smoothing::None,
            alignment: Alignment::Sorted,
        };
        assert_eq!(
            needs_distribution(&n, &ones, &sorted).unwrap().as_slice(),
            &[0.0, 0.25, 0.75]
        );
    }

    #[test]
    fn a_zero_vector_is_uniform_with_smoothing_and_an_error_without() {
        let z = NeedsVector::new(vec![0.0, 0.0]).unwrap();
        let ones = Weights::uniform(2).unwrap();
        // Relative smoothing (the default) has no scale to take a share of: uniform.
        assert_eq!(
            needs_distribution(&z, &ones, &DistributionOptions::default())
                .unwrap()
                .as_slice(),
            &[0.5, 0.5]
        );
        let none = DistributionOptions {
            smoothing: Smoothing::None,
            ..Default::default()
        };
        let e = needs_distribution(&z, &ones, &none).unwrap_err();
        assert!(matches!(e, RneError::ZeroTotal { .. }));
        assert!(
            e.to_string()
                .ends_with("(enable smoothing or give it a non-zero need)")
        );
        let abs = DistributionOptions {
            smoothing: Smoothing::Absolute(1e-9),
            ..Default::default()
        };
        assert_eq!(
            needs_distribution(&z, &ones, &abs).unwrap().as_slice(),
            &[0.5, 0.5]
        );
        let bad = DistributionOptions {
            smoothing: Smoothing::Relative(-1.0),
            ..Default::default()
        };
        assert_eq!(
            needs_distribution(&z, &ones, &bad),
            Err(RneError::InvalidEpsilon(-1.0))
        );
    }

    #[test]
    fn needs_near_the_ends_of_f64_keep_their_distribution() {
        let opts = DistributionOptions::default();
        let d = |needs: &[f64], weights: &[f64]| {
            let n = NeedsVector::new(needs.to_vec()).unwrap();
            let w = Weights::new(weights.to_vec()).unwrap();
            needs_distribution(&n, &w, &opts)
        };
        // The sum overflows: scaled, the needs keep their shares.
        let big = d(&[9e307, 9e307], &[1.0, 1.0]).unwrap();
        assert_relative_eq!(big.as_slice(), &[0.5, 0.5][..], epsilon = 1e-12);
        let heavy = d(&[1e300, 1.0], &[1e10, 1.0]).unwrap();
        assert_relative_eq!(heavy.as_slice(), &[1.0, 0.0][..], epsilon = 1e-8);
        // Subnormal needs: the same distribution as any other scale, smoothing included.
        let tiny = d(&[5e-324, 0.0, 0.0], &[1.0, 1.0, 1.0]).unwrap();
        let unit = d(&[1.0, 0.0, 0.0], &[1.0, 1.0, 1.0]).unwrap();
        assert_eq!(tiny, unit);
        // Needs whose products all round to 0: scaled, the same distribution too.
        let vanishing = d(&[1e-200, 0.0], &[1e-200, 1.0]).unwrap();
        let one = d(&[1.0, 0.0], &[1.0, 1.0]).unwrap();
        assert_relative_eq!(vanishing.as_slice(), one.as_slice(), epsilon = 1e-12);
        // Absolute smoothing depends on the scale: those needs are not rescaled.
        let abs = DistributionOptions {
            smoothing: Smoothing::Absolute(1e-9),
            ..DistributionOptions::default()
        };
        let n = NeedsVector::new(vec![1e-310, 0.0]).unwrap();
        let w = Weights::new(vec![1.0, 1.0]).unwrap();
        let a = needs_distribution(&n, &w, &abs).unwrap();
        assert_relative_eq!(a.as_slice(), &[0.5, 0.5][..], epsilon = 1e-12);
        // Ordinary inputs are the plain product, bit for bit.
        let plain = d(&[86.0, 120.0, 30.0], &[6.0, 4.0, 2.0]).unwrap();
        let total = 86.0 * 6.0 + 120.0 * 4.0 + 30.0 * 2.0;
        let eps = 1e-9 * total;
        let t = (86.0 * 6.0 + eps) + (120.0 * 4.0 + eps) + (30.0 * 2.0 + eps);
        assert_eq!(plain.as_slice()[0], (86.0 * 6.0 + eps) / t);
    }

    #[test]
    fn a_group_sum_past_f64_max_is_an_overflow_error() {
        let sums = DVector::from_vec(vec![f64::INFINITY, 1.0]);
        let w = Weights::new(vec![1.0, 1.0]).unwrap();
        for smoothing in [
            Smoothing::Relative(1e-9),
            Smoothing::Relative(0.0),
            Smoothing::None,
        ] {
            let opts = DistributionOptions {
                smoothing,
                ..DistributionOptions::default()
            };
            let e = group_distribution_from_sums(sums.clone(), &w, &opts);
            assert_eq!(
                e.unwrap_err(),
                RneError::Overflow { what: "group" },
                "{smoothing:?}"
            );
        }
    }

    #[test]
    fn length_mismatch_is_reported() {
        let n = NeedsVector::new(vec![1.0, 2.0]).unwrap();
        assert_eq!(
            needs_distribution(&n, &w(), &DistributionOptions::default()),
            Err(RneError::LengthMismatch {
                what: "needs vector",
                expected: 3,
                actual: 2
            })
        );
    }
}
