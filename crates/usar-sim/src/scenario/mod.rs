//! Scenarios: RON spec types, validation into [`Scenario`], and loading.
//!
//! Load a file with [`load`] (or text with [`from_str`]); both parse the raw [`ScenarioSpec`]
//! (serde + ron, unknown fields rejected; the leaf parameter blocks of [`params`] check their
//! numbers as they are read) and validate it once into the [`Scenario`] the simulator takes,
//! expanding start rows, rescuee grids and debris fields. Errors ([`ScenarioError`]) name the
//! file, line, column and field path. The file format is documented in
//! `docs/scenario-format.md`.

mod check_clear_places;
mod check_debris;
mod check_kinds;
mod check_names;
mod check_params;
mod check_radiation;
mod check_rest_stations;
mod check_starts;
mod check_tasks;
pub mod choices;
mod context;
mod error;
mod generate;
mod index;
pub mod limits;
mod load;
mod locate;
mod model;
pub mod numbers;
pub mod params;
mod plain_words;
mod search_pattern;
mod shape;
mod spec;
mod suggest;
mod validate;

pub use check_names::RESERVED_TASK_NAME;
pub use check_starts::START_TOLERANCE;
pub use choices::*;
pub use error::{ScenarioError, SourceLocation};
pub use load::{from_str, load, parse_spec, read_source, validate_in_source};
pub use model::*;
pub use numbers::{Factor, Finite, Fraction, NonNegative, Percent, Positive, RangeError};
pub use params::*;
pub use search_pattern::{sweep_point_count, sweep_spacing_m};
pub use shape::DebrisShape;
pub(crate) use shape::Primitive as DebrisPrimitive;
pub use spec::*;
pub use suggest::{SUGGEST_SIMILARITY, did_you_mean, nearest_name};
