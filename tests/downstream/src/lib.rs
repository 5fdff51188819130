//! A downstream crate's own grouping method, written against the public API only: `random`
//! deals each kind's robots to the tasks at random, meeting the quotas, drawing from the
//! trial's seeded stream (`TrialContext::rng`), so a parallel sweep of it is reproducible.
//!
//! The method is `crates/usar-sweep/examples/random_method.rs`, included as it is (the
//! example says to copy it into your own crate; including it keeps one copy in this
//! repository). It compiles here against the sweep library, `usar-sweep`.

#[allow(dead_code)] // the example's `main`; this crate uses its method and factory
#[path = "../../../crates/usar-sweep/examples/random_method.rs"]
mod random_method;

pub use random_method::{RandomQuotas, factory};
