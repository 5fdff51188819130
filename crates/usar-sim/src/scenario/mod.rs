//! Scenarios: RON spec types, validation into [`Scenario`], and loading.
//!
//! Load a file with [`load`] (or text with [`from_str`]); both parse the raw [`ScenarioSpec`]
//! (serde + ron, unknown fields rejected) and validate it once into the [`Scenario`] the
//! simulator takes. Errors ([`ScenarioError`]) name the file, line, column and field path. The
//! file format is documented in `docs/scenario-format.md`.

mod error;
mod load;
mod locate;
mod model;
mod shape;
mod spec;
mod validate;

pub use error::{ScenarioError, SourceLocation};
pub use load::{from_str, load, parse_spec};
pub use model::*;
pub use shape::DebrisShape;
pub(crate) use shape::Primitive as DebrisPrimitive;
pub use spec::*;
