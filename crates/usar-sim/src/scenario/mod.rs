//! Scenarios: RON spec types, validation into [`Scenario`], and loading.
//!
//! Entry points, each ending in one validation into the read-only [`Scenario`] the simulator
//! takes ("parse, don't validate"):
//! - [`load`] a file, or [`from_str`] a text: parse the raw [`ScenarioSpec`] (serde + ron,
//!   unknown fields rejected; the leaf parameter blocks of [`params`] check their numbers as
//!   they are read) and validate it, expanding start rows, rescuee grids and debris fields.
//!   Errors ([`ScenarioError`]) name the file, line, column and field path.
//! - [`ScenarioSpec::builder`]: a scenario in code, from plain numbers, with the file's
//!   defaults ([`KindDraft`], [`TaskDraft`]); a bad value is an error at `build()` naming its
//!   field.
//! - [`Scenario::edit`]: a changed copy of a validated scenario, validated again (or
//!   [`Scenario::to_spec`], change, [`ScenarioSpec::validate`]).
//!
//! ```
//! use usar_sim::scenario;
//!
//! let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
//! let paper = scenario::load(path)?;
//! assert_eq!((paper.robots().len(), paper.tasks().len()), (12, 2));
//! // Seven carriers need quotas adding up to seven: the edit is refused, with its field.
//! let err = paper.edit(|spec| spec.kinds[0].count = 7).unwrap_err();
//! assert_eq!(err.field(), Some("kinds[0].quota"));
//! # Ok::<(), scenario::ScenarioError>(())
//! ```
//!
//! The file format is documented in `docs/scenario-format.md`.

mod added_fields;
mod bounded_read;
mod builder;
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
mod draft;
mod edit;
mod error;
mod generate;
mod index;
pub mod lifecycle_choices;
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
mod validated;

pub use added_fields::ADDED_FIELDS;
pub use bounded_read::{BoundedReadError, read_bounded};
pub use builder::ScenarioBuilder;
pub use check_names::RESERVED_TASK_NAME;
pub use check_starts::START_TOLERANCE;
pub use choices::*;
pub use draft::{KindDraft, TaskDraft, Xy};
pub use edit::{EditOutcome, number_at};
pub use error::{ScenarioError, SourceLocation};
pub use lifecycle_choices::{CostClock, CostsCount, ResourceStock, RestTiming, RoundClock};
pub use load::{field_line_col, from_str, load, parse_spec, read_source, validate_in_source};
pub use locate::SourceMap;
pub use model::*;
pub use numbers::{Factor, Finite, Fraction, NonNegative, Percent, Positive, RangeError};
pub use params::*;
pub use search_pattern::{sweep_point_count, sweep_spacing_m};
pub use shape::DebrisShape;
pub(crate) use shape::Primitive as DebrisPrimitive;
pub use spec::*;
pub use suggest::{SUGGEST_SIMILARITY, did_you_mean, nearest_name};
pub use validated::Scenario;
