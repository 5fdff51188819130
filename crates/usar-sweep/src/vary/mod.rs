//! Scenario field overrides: `usar sweep --vary FIELD=V1,V2,...` and
//! `usar check --set FIELD=VALUE`.
//!
//! A field path ([`FieldPath`]) is written as the loader's error messages write it
//! (`mission.hp_pct_per_step_in_radiation`, `kinds[0].max_speed_m_per_s`,
//! `tasks.hard.goal_m`), with `[*]` for every element of a list
//! (`radiation_zones[*].dose_rate_factor`). Values are RON ([`RonValue`]).
//!
//! An override is applied to a parsed [`ScenarioSpec`](usar_sim::scenario::ScenarioSpec) through its JSON form: the spec is
//! serialised with `serde_json::to_value` (so fields the file omits are there with their
//! defaults and can be varied too), the path is walked and its value replaced (converted
//! guided by the JSON shape of the value it replaces), and the JSON is deserialised back into
//! a [`ScenarioSpec`](usar_sim::scenario::ScenarioSpec), which checks the types. Nothing here knows the scenario's fields: a
//! field added to the spec can be varied without a change here. Rules (ranges, geometry) are
//! checked afterwards by [`ScenarioSpec::validate`](usar_sim::scenario::ScenarioSpec::validate), as for a file.

mod apply;
mod field_override;
mod path;
mod quoted_arg;
mod split;
mod value;
mod value_list;

pub use apply::{
    apply_overrides, rule_error, spec_from_json, spec_json, touching, validate_overridden,
};
pub use field_override::{FieldValue, Override};
pub use path::{FieldPath, Step};
pub use quoted_arg::{QUOTED_ARG_CHARS, brief};
pub use split::split_top_level;
pub use value::{Args, RonValue};
pub use value_list::Vary;
