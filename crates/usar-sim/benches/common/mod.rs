//! What the benches share (a bench target is its own crate: each includes this module).

pub mod trial_steps;
