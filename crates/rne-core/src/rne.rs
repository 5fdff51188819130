//! Relative Needs Entropy (Eqs. 1, 7, 12, 17; Algorithm 3, GRC) and the trust model.

use std::fmt;
use std::str::FromStr;

use serde::{Deserialize, Serialize};

use crate::distribution::{
    Alignment, Distribution, DistributionOptions, Smoothing, group_distribution, needs_distribution,
};
use crate::error::{Result, RneError};
use crate::needs::{NeedsMatrix, NeedsVector, Weights};

/// Base of the logarithm in RNE. Default `e` (RNE in nats); `2` gives bits, `10` gives
/// hartleys (the paper's Example 3 numbers are base 10).
///
/// Valid range: finite and `> 1` (a base below 1 would flip the sign and with it the
/// meaning "lower RNE = more trust").
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "f64", into = "f64")]
pub struct LogBase(f64);

impl LogBase {
    /// Natural logarithm (nats). The default.
    pub const E: Self = Self(std::f64::consts::E);
    /// Base 2 (bits).
    pub const TWO: Self = Self(2.0);
    /// Base 10 (hartleys).
    pub const TEN: Self = Self(10.0);

    /// A custom base.
    ///
    /// # Errors
    /// [`RneError::InvalidLogBase`] unless `base` is finite and `> 1`.
    pub fn new(base: f64) -> Result<Self> {
        if base.is_finite() && base > 1.0 {
            Ok(Self(base))
        } else {
            Err(RneError::InvalidLogBase(base))
        }
    }

    /// The base as a number.
    pub fn value(self) -> f64 {
        self.0
    }

    /// `ln(base)`, the divisor that converts nats into this base.
    fn ln(self) -> f64 {
        self.0.ln()
    }
}

impl Default for LogBase {
    fn default() -> Self {
        Self::E
    }
}

impl TryFrom<f64> for LogBase {
    type Error = RneError;
    fn try_from(base: f64) -> Result<Self> {
        Self::new(base)
    }
}

impl From<LogBase> for f64 {
    fn from(b: LogBase) -> Self {
        b.0
    }
}

impl FromStr for LogBase {
    type Err = RneError;
    /// Parses `e` (case-insensitive), `2`, `10` or any number `> 1`.
    fn from_str(s: &str) -> Result<Self> {
        let t = s.trim();
        if t.eq_ignore_ascii_case("e") {
            return Ok(Self::E);
        }
        let v: f64 = t
            .parse()
            .map_err(|_| RneError::UnparsableLogBase(s.to_string()))?;
        Self::new(v)
    }
}

impl fmt::Display for LogBase {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if *self == Self::E {
            write!(f, "e")
        } else {
            write!(f, "{}", crate::message_text::number_text(self.0))
        }
    }
}

/// Relative entropy (Kullback-Leibler divergence), paper Eq. 1, on raw non-negative vectors:
///
/// `D(p||q) = sum_k p_k log_b(p_k / q_k)`, with `0 log(0/q) = 0` for any `q` (including 0) and
/// `p log(p/0) = +inf` for `p > 0`.
///
/// Domain: `p` and `q` of equal length `j >= 1`, entries finite and `>= 0`. They need not sum
/// to 1 (the paper's worked examples use rounded shares), so the result may be negative for
/// such inputs. Each term is computed as `p_k (ln p_k - ln q_k)`, so the result is finite or
/// `+inf`, never NaN. Unit: nats for [`LogBase::E`].
///
/// # Errors
/// [`RneError::LengthMismatch`], [`RneError::Empty`], [`RneError::InvalidProbability`].
///
/// # Reference
/// `D(p||q) = E_p[log p(X)/q(X)]`, T. Cover and J. Thomas, *Elements of Information Theory*;
/// paper Eq. 1.
pub fn relative_entropy(p: &[f64], q: &[f64], base: LogBase) -> Result<f64> {
    if p.len() != q.len() {
        return Err(RneError::LengthMismatch {
            what: "second distribution",
            expected: p.len(),
            actual: q.len(),
        });
    }
    if p.is_empty() {
        return Err(RneError::Empty {
            what: "distribution",
        });
    }
    for v in [p, q] {
        if let Some(index) = v.iter().position(|x| !x.is_finite() || *x < 0.0) {
            return Err(RneError::InvalidProbability {
                index,
                value: v[index],
            });
        }
    }
    let nats: f64 = p
        .iter()
        .zip(q)
        .map(|(&pk, &qk)| match (pk, qk) {
            (0.0, _) => 0.0,
            (_, 0.0) => f64::INFINITY,
            _ => pk * (pk.ln() - qk.ln()),
        })
        .sum();
    Ok(nats / base.ln())
}

/// RNE `T(P||Q) = sum_k p_k log_b(p_k / q_k)` between two needs distributions (Eqs. 7, 12, 17;
/// Algorithm 3 loop body). `>= 0` by Gibbs' inequality; rounding noise below zero is clamped
/// to 0. Returns `f64::INFINITY` when `q_k = 0 < p_k` for some `k` (only possible without
/// smoothing). Lower = more trust.
///
/// # Errors
/// [`RneError::LengthMismatch`] if the lengths differ.
///
/// # Reference
/// `T(P||Q) = D_KL(P||Q)`; paper Eqs. 7, 12, 17 and Algorithm 3 (GRC).
pub fn rne(p: &Distribution, q: &Distribution, base: LogBase) -> Result<f64> {
    Ok(relative_entropy(p.as_slice(), q.as_slice(), base)?.max(0.0))
}

/// Options of the trust model: smoothing, alignment and logarithm base.
///
/// Defaults: `Smoothing::Relative(1e-9)`, `Alignment::Category`, `LogBase::E` (nats).
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct RneOptions {
    /// Zero-category smoothing (see [`Smoothing`]).
    pub smoothing: Smoothing,
    /// Category-aligned (Defs. 1-3) or sorted (Algorithm 4).
    pub alignment: Alignment,
    /// Logarithm base.
    pub log_base: LogBase,
}

impl RneOptions {
    /// The distribution part of the options.
    pub fn distribution(&self) -> DistributionOptions {
        DistributionOptions {
            smoothing: self.smoothing,
            alignment: self.alignment,
        }
    }
}

/// The RNE trust model: a weight vector (length `j`) plus [`RneOptions`]. Computes the three
/// trust relations of the paper; every value is `T(trustor || trustee) >= 0`, lower = more
/// trust, in nats unless another base is set.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrustModel {
    weights: Weights,
    options: RneOptions,
}

impl TrustModel {
    /// Builds a model.
    ///
    /// # Errors
    /// [`RneError::InvalidEpsilon`] if the smoothing epsilon is negative or not finite.
    pub fn new(weights: Weights, options: RneOptions) -> Result<Self> {
        options.smoothing.validate()?;
        Ok(Self { weights, options })
    }

    /// A model with default options (relative smoothing `1e-9`, category-aligned, nats).
    pub fn with_weights(weights: Weights) -> Self {
        Self {
            weights,
            options: RneOptions::default(),
        }
    }

    /// The weight vector.
    pub fn weights(&self) -> &Weights {
        &self.weights
    }

    /// The options.
    pub fn options(&self) -> &RneOptions {
        &self.options
    }

    /// A robot's needs distribution (Eq. 8, Algorithm 4). Errors as [`needs_distribution`].
    pub fn distribution(&self, needs: &NeedsVector) -> Result<Distribution> {
        needs_distribution(needs, &self.weights, &self.options.distribution())
    }

    /// A group's needs distribution (Eqs. 11, 16). Errors as [`group_distribution`].
    pub fn group_distribution(&self, group: &NeedsMatrix) -> Result<Distribution> {
        group_distribution(group, &self.weights, &self.options.distribution())
    }

    /// RNE between two distributions with this model's log base (see [`rne`]).
    ///
    /// # Errors
    /// [`RneError::LengthMismatch`].
    pub fn rne(&self, p: &Distribution, q: &Distribution) -> Result<f64> {
        rne(p, q, self.options.log_base)
    }

    /// Agent-agent trust `T(R1||R2)`, Def. 1, Eq. 7 (Example 1).
    ///
    /// # Errors
    /// As [`needs_distribution`] for either robot.
    pub fn agent_agent(&self, trustor: &NeedsVector, trustee: &NeedsVector) -> Result<f64> {
        self.rne(&self.distribution(trustor)?, &self.distribution(trustee)?)
    }

    /// Agent-group trust `T(D_R||D_RG)`, Def. 2, Eq. 12 (Example 2).
    ///
    /// # Errors
    /// As [`needs_distribution`] and [`group_distribution`].
    pub fn agent_group(&self, trustor: &NeedsVector, trustee: &NeedsMatrix) -> Result<f64> {
        self.rne(
            &self.distribution(trustor)?,
            &self.group_distribution(trustee)?,
        )
    }

    /// Group-group trust `T(D_N1||D_N2)`, Def. 3, Eq. 17, Algorithm 3 (GRC) (Example 3).
    ///
    /// # Errors
    /// As [`group_distribution`] for either group.
    pub fn group_group(&self, trustor: &NeedsMatrix, trustee: &NeedsMatrix) -> Result<f64> {
        self.rne(
            &self.group_distribution(trustor)?,
            &self.group_distribution(trustee)?,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use approx::assert_relative_eq;

    #[test]
    fn log_base_parsing() {
        assert_eq!("e".parse::<LogBase>().unwrap(), LogBase::E);
        assert_eq!("E".parse::<LogBase>().unwrap(), LogBase::E);
        assert_eq!("10".parse::<LogBase>().unwrap(), LogBase::TEN);
        assert_eq!("1".parse::<LogBase>(), Err(RneError::InvalidLogBase(1.0)));
        assert!(matches!(
            "ten".parse::<LogBase>(),
            Err(RneError::UnparsableLogBase(_))
        ));
    }

    #[test]
    fn zero_handling_never_nan() {
        let b = LogBase::E;
        assert_eq!(relative_entropy(&[0.0, 1.0], &[0.0, 1.0], b).unwrap(), 0.0);
        assert_eq!(
            relative_entropy(&[0.5, 0.5], &[0.0, 1.0], b).unwrap(),
            f64::INFINITY
        );
        assert_relative_eq!(
            relative_entropy(&[0.0, 1.0], &[0.5, 0.5], b).unwrap(),
            2f64.ln(),
            epsilon = 1e-15
        );
        // Tiny q must not make the terms overflow into inf - inf = NaN.
        let v = relative_entropy(&[1e-300, 1.0], &[1.0, 1e-300], b).unwrap();
        assert!(v.is_finite() && v > 0.0);
    }

    #[test]
    fn base_conversion() {
        let p = [0.2, 0.8];
        let q = [0.5, 0.5];
        let nats = relative_entropy(&p, &q, LogBase::E).unwrap();
        assert_relative_eq!(
            relative_entropy(&p, &q, LogBase::TWO).unwrap(),
            nats / 2f64.ln(),
            epsilon = 1e-15
        );
        assert_relative_eq!(
            relative_entropy(&p, &q, LogBase::TEN).unwrap(),
            nats / 10f64.ln(),
            epsilon = 1e-15
        );
    }

    #[test]
    fn smoothing_zero_gives_infinity_not_nan() {
        let w = Weights::uniform(3).unwrap();
        let opts = RneOptions {
            smoothing: Smoothing::None,
            ..Default::default()
        };
        let m = TrustModel::new(w, opts).unwrap();
        let carrier = NeedsVector::new(vec![1.0, 2.0, 3.0]).unwrap();
        let observer = NeedsVector::new(vec![1.0, 2.0, 0.0]).unwrap();
        assert_eq!(m.agent_agent(&carrier, &observer).unwrap(), f64::INFINITY);
        let back = m.agent_agent(&observer, &carrier).unwrap();
        assert!(back.is_finite() && back > 0.0);
        let smoothed = TrustModel::with_weights(Weights::uniform(3).unwrap());
        let v = smoothed.agent_agent(&carrier, &observer).unwrap();
        assert!(v.is_finite() && v > 5.0, "{v}");
    }

    #[test]
    fn rejects_bad_epsilon() {
        let opts = RneOptions {
            smoothing: Smoothing::Absolute(f64::NAN),
            ..Default::default()
        };
        assert!(matches!(
            TrustModel::new(Weights::uniform(1).unwrap(), opts),
            Err(RneError::InvalidEpsilon(_))
        ));
    }
}
