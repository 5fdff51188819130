//! The error type of `rne-core`: every way its inputs can be invalid, as one-line messages.
//!
//! Numbers in the messages are written by [`number_text`] (`crate::message_text`).

use thiserror::Error;

use crate::message_text::number_text;

/// Everything that can go wrong in `rne-core`.
///
/// Every variant names the offending index or value so that a caller (for example the `usar`
/// command line) can turn it into a one-line message without more context.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RneError {
    /// Two vectors (or a vector and a matrix) that must have the same length do not.
    ///
    /// `what` names the mismatching input, `expected` is the reference length (usually the
    /// number of weights `j`) and `actual` the length found.
    #[error("{what} has {actual} values but {expected} were expected")]
    LengthMismatch {
        /// Which input mismatches (e.g. "needs vector", "group needs matrix").
        what: &'static str,
        /// The reference length.
        expected: usize,
        /// The length found.
        actual: usize,
    },
    /// A need is negative, NaN or infinite (needs must be finite and `>= 0`).
    #[error("needs[{index}] = {}; needs must be finite and >= 0", number_text(*.value))]
    InvalidNeed {
        /// 0-based index of the need in its vector.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A weight is zero, negative, NaN or infinite (weights must be finite and `> 0`).
    #[error("weights[{index}] = {}; weights must be finite and > 0", number_text(*.value))]
    InvalidWeight {
        /// 0-based index of the weight.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// A probability-like value (input of [`crate::relative_entropy`] or a share given to
    /// [`crate::Distribution::new`]) is negative or not finite.
    #[error(
        "probabilities[{index}] = {}; values must be finite and >= 0",
        number_text(*.value)
    )]
    InvalidProbability {
        /// 0-based index.
        index: usize,
        /// The offending value.
        value: f64,
    },
    /// An index given to [`crate::Bipartition::from_first`] is not in `0..n` or is repeated.
    #[error("split of 0..{n}: index {index} is {problem}")]
    InvalidSplitIndex {
        /// Size of the index set.
        n: usize,
        /// The offending index.
        index: usize,
        /// `"out of range"` or `"given twice"`.
        problem: &'static str,
    },
    /// The shares given to [`crate::Distribution::new`] do not sum to 1 (within
    /// [`crate::DISTRIBUTION_SUM_TOLERANCE`]).
    #[error("distribution shares sum to {}; they must sum to 1", number_text(*.sum))]
    NotNormalised {
        /// Their sum.
        sum: f64,
    },
    /// An input that must hold at least one element is empty (no needs, an empty group, an
    /// empty team or no task).
    #[error("{what} is empty")]
    Empty {
        /// Which input is empty.
        what: &'static str,
    },
    /// All weighted needs are zero and there is no smoothing ([`crate::Smoothing::None`], or
    /// an epsilon of 0), so the needs distribution (Eq. 8 / Eq. 11) is `0/0`. With smoothing
    /// (`e > 0`) an all-zero needs vector gets the uniform distribution.
    #[error(
        "{what} has all weighted needs equal to zero; its needs distribution is undefined without smoothing (enable smoothing or give it a non-zero need)"
    )]
    ZeroTotal {
        /// Which input (e.g. "needs vector", "group").
        what: &'static str,
    },
    /// The weighted needs plus the smoothing add up past `f64::MAX` even after scaling (a
    /// group's column sums past `f64::MAX`, or a huge smoothing epsilon), so the needs
    /// distribution cannot be computed.
    #[error("{what}: weighted needs plus smoothing too large to add up (the sum overflows f64)")]
    Overflow {
        /// Which input (e.g. "needs vector", "group").
        what: &'static str,
    },
    /// The smoothing epsilon is negative or not finite.
    #[error("smoothing epsilon is {}; it must be finite and >= 0", number_text(*.0))]
    InvalidEpsilon(f64),
    /// The logarithm base is not finite or not `> 1`.
    #[error("log base is {}; it must be finite and > 1", number_text(*.0))]
    InvalidLogBase(f64),
    /// A log base string could not be parsed.
    #[error("cannot parse log base {0:?}; use e, 2, 10 or a number > 1")]
    UnparsableLogBase(String),
    /// A subgroup size is larger than the set it is taken from (Algorithm 2, ASC).
    #[error("cannot take a subgroup of {size} from a set of {total}")]
    InvalidSubgroupSize {
        /// Requested subgroup size.
        size: usize,
        /// Size of the whole set.
        total: usize,
    },
    /// A robot's kind index is outside the quota list.
    #[error("robot id {id} has kind {kind} but only {kinds} kinds have quotas")]
    UnknownKind {
        /// Robot id.
        id: usize,
        /// Its kind index.
        kind: usize,
        /// Number of kinds (length of the quota list).
        kinds: usize,
    },
    /// The task quotas of a kind do not add up to the number of robots of that kind.
    #[error(
        "kind {kind} has {available} robots but its task quotas {quotas:?} sum to {}",
        quotas.iter().map(|&q| q as u128).sum::<u128>()
    )]
    QuotaMismatch {
        /// Kind index.
        kind: usize,
        /// Robots of that kind in the team.
        available: usize,
        /// The kind's quota per task.
        quotas: Vec<usize>,
    },
    /// A kind's quota list does not have one entry per task.
    #[error("kind {kind} has {actual} task quotas but there are {tasks} tasks")]
    QuotaTaskCount {
        /// Kind index.
        kind: usize,
        /// Number of tasks `K`.
        tasks: usize,
        /// Length of the kind's quota list.
        actual: usize,
    },
    /// A robot's distance list does not have one entry per task.
    #[error("robot id {id} has {actual} distances to task goals but there are {tasks} tasks")]
    DistanceCount {
        /// Robot id.
        id: usize,
        /// Number of tasks `K`.
        tasks: usize,
        /// Length of the robot's distance list.
        actual: usize,
    },
    /// A robot's distance to a task goal is not finite.
    #[error("robot id {id}: distance_to_goal_m[{task}] is {value}; it must be finite")]
    InvalidDistance {
        /// Robot id.
        id: usize,
        /// Task index.
        task: usize,
        /// The offending value.
        value: f64,
    },
    /// The tasks' difficulty order is not a permutation of the task indices `0..K`.
    #[error(
        "task difficulty order {order:?} is not a permutation of 0..{}",
        order.len()
    )]
    InvalidTaskOrder {
        /// The order given (hardest first).
        order: Vec<usize>,
    },
    /// Two robots share an id.
    #[error("robot id {0} appears more than once")]
    DuplicateRobot(usize),
    /// A robot's scalar state (energy or HP) is not finite.
    #[error("robot id {id}: {field} is {value}; it must be finite")]
    InvalidRobotState {
        /// Robot id.
        id: usize,
        /// Field name.
        field: &'static str,
        /// The offending value.
        value: f64,
    },
    /// An assignment is not a partition of the team that meets the quotas.
    #[error("invalid assignment: {0}")]
    InvalidAssignment(String),
    /// A grouping-method name is not known.
    #[error("unknown grouping method {name:?}; valid names: {valid}")]
    UnknownMethod {
        /// The name given.
        name: String,
        /// Comma-separated list of valid names.
        valid: String,
    },
}

/// Shorthand for `Result<T, RneError>`.
pub type Result<T> = std::result::Result<T, RneError>;
