//! Claims (hypotheses) as data: a claims file (`CLAIMS.ron`, such as
//! `scenarios/paper-claims.ron`) states what a sweep should show, each claim one method's mean
//! of one metric against its rivals; a sweep's reports, a merge and a multiverse check every
//! claim of the file they are given ([`check_claim`]) and nothing else.
//!
//! - [`claim`]: one claim ([`Claim`]): its subject, rivals, metric, direction, test, level
//!   and correction.
//! - [`mod@file`]: a checked list of claims read from a file ([`Claims`], [`ClaimsError`]).
//! - [`check`]: a claim checked against a sweep's results ([`ClaimCheck`], [`Verdict`]).

pub mod check;
pub mod claim;
pub mod file;

pub use check::{
    ClaimCheck, Comparison, Observation, Verdict, check_claim, check_claim_on, holm_adjusted,
    observations,
};
pub use claim::{Claim, Correction, DEFAULT_ALPHA, Direction, Rivals, Test, method_key};
pub use file::{Claims, ClaimsError, MAX_CLAIMS_BYTES, PAPER_CLAIMS_RON, paper_claims};
