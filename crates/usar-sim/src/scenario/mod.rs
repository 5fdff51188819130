//! Scenarios: RON spec types, validation into [`Scenario`], and loading.

mod model;

pub use model::*;
