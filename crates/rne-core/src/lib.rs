//! Relative Needs Entropy (RNE) trust model and RNE-based grouping.
//!
//! Pure math, no physics. Reference: Q. Yang and R. Parasuraman, "How Can Robots Trust Each
//! Other For Better Cooperation? A Relative Needs Entropy Based Robot-Robot Trust Assessment
//! Model", IEEE SMC 2021.
//!
//! * [`needs`]: needs vectors, weights, group needs matrices (Defs. 1-3).
//! * [`distribution`]: needs distributions (Eqs. 8, 11, 16; Algorithm 4), smoothing, alignment.
//! * [`rne`](mod@rne): RNE `T(P||Q)` (Eqs. 7, 12, 17; Algorithm 3) and [`TrustModel`].
//! * [`combinations`](mod@combinations): all subgroup combinations (Algorithm 2).
//! * [`grouping`]: hierarchical RNE grouping (Algorithm 1) and the DIS, ENG, HP_DIS baselines.
//!
//! ```
//! use rne_core::{NeedsVector, TrustModel, Weights};
//!
//! let model = TrustModel::with_weights(Weights::new(vec![6.0, 4.0, 2.0])?);
//! let r1 = NeedsVector::new(vec![86.0, 120.0, 30.0])?;
//! let r2 = NeedsVector::new(vec![20.0, 30.0, 10.0])?;
//! let t = model.agent_agent(&r1, &r2)?; // paper Example 1: 0.00373 nats
//! assert!((t - 0.003_725).abs() < 1e-6);
//! # Ok::<(), rne_core::RneError>(())
//! ```
//!
//! The formulas, the smoothing, the grouping's reading of Algorithm 1 and the paper's errata
//! are in `docs/trust-model.md`.

pub mod combinations;
pub mod distribution;
pub mod error;
pub mod grouping;
pub mod message_text;
pub mod needs;
pub mod rne;
mod vector_newtype;

pub use combinations::{
    Bipartition, Combinations, TwoWaySplits, binomial, combinations, split_count, two_way_splits,
};
pub use distribution::{
    Alignment, DEFAULT_RELATIVE_EPSILON, DISTRIBUTION_SUM_TOLERANCE, Distribution,
    DistributionOptions, Smoothing, group_distribution, needs_distribution,
};
pub use error::{Result, RneError};
pub use message_text::{error_line, number_text, one_line_text, path_text, short_numbers};
pub use needs::{NeedsMatrix, NeedsVector, Weights};
pub use rne::{LogBase, RneOptions, TrustModel, relative_entropy, rne};

#[cfg(test)]
mod paper_examples;
#[cfg(test)]
mod properties;
