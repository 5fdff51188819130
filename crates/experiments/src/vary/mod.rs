//! Scenario field overrides: `usar sweep --vary FIELD=V1,V2,...` and
//! `usar check --set FIELD=VALUE`.
//!
//! A field path ([`FieldPath`]) is written as the loader's error messages write it
//! (`mission.hp_pct_per_step_in_radiation`, `kinds[0].max_speed_m_per_s`,
//! `tasks.hard.goal_m`), with `[*]` for every element of a list
//! (`radiation_zones[*].dose_rate_factor`). Values are RON ([`RonValue`]).
//!
//! An override is applied to a parsed [`ScenarioSpec`] through its JSON form: the spec is
//! serialised with `serde_json::to_value` (so fields the file omits are there with their
//! defaults and can be varied too), the path is walked and its value replaced (converted
//! guided by the JSON shape of the value it replaces), and the JSON is deserialised back into
//! a [`ScenarioSpec`], which checks the types. Nothing here knows the scenario's fields: a
//! field added to the spec can be varied without a change here. Rules (ranges, geometry) are
//! checked afterwards by [`ScenarioSpec::validate`], as for a file.

mod path;
mod split;
mod value;

use std::fmt;

use serde_json::Value;
use usar_sim::scenario::{ScenarioError, ScenarioSpec, one_line_text};

pub use path::{FieldPath, Step};
pub use split::split_top_level;
pub use value::{Args, RonValue};

/// One value given for a field: the text as written (trimmed) and its parse.
#[derive(Debug, Clone, PartialEq)]
pub struct FieldValue {
    /// The value as written, trimmed, e.g. `0.003` or `(1.0, 2.0)`.
    pub text: String,
    /// The parsed value.
    pub value: RonValue,
}

impl FieldValue {
    /// Parses one value.
    ///
    /// # Errors
    /// Empty text, or text that is not one RON value.
    pub fn parse(text: &str) -> Result<Self, String> {
        let text = text.trim();
        if text.is_empty() {
            return Err("empty value".into());
        }
        Ok(Self {
            text: text.to_string(),
            value: RonValue::parse(text)?,
        })
    }
}

/// `FIELD=VALUE`: sets one field, or every element a `[*]` names.
#[derive(Debug, Clone, PartialEq)]
pub struct Override {
    /// The field.
    pub path: FieldPath,
    /// Its new value.
    pub value: FieldValue,
}

impl Override {
    /// Parses `FIELD=VALUE`; everything after the first `=` is the value (commas included).
    ///
    /// # Errors
    /// No `=`, a malformed path or value.
    pub fn parse(arg: &str) -> Result<Self, String> {
        let (path, text) = split_arg(arg)?;
        Ok(Self {
            path,
            value: FieldValue::parse(text)?,
        })
    }

    /// Sets the value in `spec_json` (the JSON form of a spec, see [`spec_json`]).
    ///
    /// # Errors
    /// A path that names nothing in the spec, or a value that cannot have the shape of the
    /// value it replaces (message prefixed with the field path).
    pub fn apply(&self, spec_json: &mut Value) -> Result<(), String> {
        self.path
            .set(spec_json, &mut |old| self.value.value.to_json(Some(old)))
    }
}

/// Longest command-line argument an error message quotes in full, characters ([`brief`]).
pub const QUOTED_ARG_CHARS: usize = 80;

/// `arg` (a `--set` or `--vary` argument, or a value) as an error message quotes it, control
/// characters escaped ([`one_line_text`], as paths are): in full up to
/// [`QUOTED_ARG_CHARS`] characters, else its first 60 and the length (`rest_station=[(center_m:
/// ... (10412 characters)`), so that an error about a long value stays a short line.
pub fn brief(arg: &str) -> String {
    // A control character is written escaped (`\n`), so the message stays one line.
    let arg = one_line_text(arg).into_owned();
    let n = arg.chars().count();
    if n <= QUOTED_ARG_CHARS {
        arg
    } else {
        let head: String = arg.chars().take(60).collect();
        format!("{head}... ({n} characters)")
    }
}

impl Override {
    /// The override as an error quotes it ([`brief`] of `FIELD=VALUE`).
    pub fn brief(&self) -> String {
        brief(&self.to_string())
    }
}

impl fmt::Display for Override {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}={}", self.path, self.value.text)
    }
}

/// A parsed `FIELD=V1,V2,...`: a field and the values it takes, in order.
#[derive(Debug, Clone, PartialEq)]
pub struct Vary {
    /// The field.
    pub path: FieldPath,
    /// Its values, at least one.
    pub values: Vec<FieldValue>,
}

impl Vary {
    /// Parses `FIELD=V1,V2,...`, splitting the values on top-level commas
    /// ([`split_top_level`]).
    ///
    /// # Errors
    /// No `=`, a malformed path, an empty or malformed value, unbalanced brackets.
    pub fn parse(arg: &str) -> Result<Self, String> {
        let (path, list) = split_arg(arg)?;
        let values = split_top_level(list)?
            .iter()
            .enumerate()
            .map(|(i, t)| FieldValue::parse(t).map_err(|e| format!("value {}: {e}", i + 1)))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self { path, values })
    }

    /// The override that sets value `i`.
    ///
    /// # Panics
    /// If `i >= self.values.len()`.
    pub fn at(&self, i: usize) -> Override {
        Override {
            path: self.path.clone(),
            value: self.values[i].clone(),
        }
    }
}

fn split_arg(arg: &str) -> Result<(FieldPath, &str), String> {
    let (field, value) = arg
        .split_once('=')
        .ok_or_else(|| "expected FIELD=VALUE".to_string())?;
    Ok((FieldPath::parse(field.trim())?, value))
}

/// The JSON form of `spec` that [`Override::apply`] edits: every field present, defaults
/// filled in.
///
/// # Errors
/// A spec serde_json cannot represent (not expected for a parsed spec).
pub fn spec_json(spec: &ScenarioSpec) -> Result<Value, String> {
    serde_json::to_value(spec).map_err(|e| format!("cannot represent the scenario: {e}"))
}

/// Reads a spec back from its JSON form.
///
/// # Errors
/// serde_json's message for a value of the wrong type, an unknown variant or field.
pub fn spec_from_json(json: Value) -> Result<ScenarioSpec, String> {
    serde_json::from_value(json).map_err(|e| e.to_string())
}

/// `spec` with `overrides` applied in order. Each override is type-checked on its own (the
/// spec is read back after it), so an error names the override that caused it.
///
/// # Errors
/// `(index of the override, message)`; the message starts with the field path when it is
/// about a value.
pub fn apply_overrides(
    spec: &ScenarioSpec,
    overrides: &[Override],
) -> Result<ScenarioSpec, (usize, String)> {
    let mut json = spec_json(spec).map_err(|e| (0, e))?;
    let mut out = spec.clone();
    for (i, o) in overrides.iter().enumerate() {
        o.apply(&mut json).map_err(|e| (i, e))?;
        out = spec_from_json(json.clone()).map_err(|e| (i, format!("{}: {e}", o.path)))?;
    }
    Ok(out)
}

/// The overrides whose field overlaps `field` (a path as errors write it: the same field, one
/// inside it, or one it lies in), in order.
pub fn touching<'a>(overrides: &'a [Override], field: &str) -> Vec<&'a Override> {
    let about = FieldPath::parse(field).ok();
    overrides
        .iter()
        .filter(|o| about.as_ref().is_some_and(|p| p.overlaps(&o.path)))
        .collect()
}

/// The one-line message for a spec with `overrides` that breaks a rule:
/// `FLAG FIELD=VALUE: field.path: message`, naming the override whose field the rule is
/// about, or every override when the rule is about none (or several) of their fields. `flag`
/// is how the overrides were given (`--vary`, `--set`).
pub fn rule_error(flag: &str, overrides: &[Override], e: &ScenarioError) -> String {
    let (field, message) = match e {
        ScenarioError::Invalid { field, message, .. } => (field.as_str(), message.as_str()),
        other => return format!("{other}"),
    };
    let culprits = touching(overrides, field);
    let named: Vec<&Override> = if culprits.len() == 1 {
        culprits
    } else {
        overrides.iter().collect()
    };
    let names: Vec<String> = named
        .iter()
        .map(|o| format!("{flag} {}", o.brief()))
        .collect();
    format!("{}: {field}: {message}", names.join(" "))
}

#[cfg(test)]
mod tests {
    use usar_sim::scenario::{Role, StartsSpec, parse_spec};

    use super::*;

    const PAPER: &str = include_str!("../../../../scenarios/paper.ron");

    fn paper() -> ScenarioSpec {
        parse_spec(PAPER, "paper.ron").unwrap()
    }

    #[test]
    fn brief_quotes_short_arguments_whole_and_long_ones_by_their_start() {
        let short = "kinds[0].count=7";
        assert_eq!(brief(short), short);
        let exactly = "x".repeat(QUOTED_ARG_CHARS);
        assert_eq!(brief(&exactly), exactly);
        let long = format!("rest_station=[{}]", "é".repeat(200));
        let head: String = long.chars().take(60).collect();
        assert_eq!(brief(&long), format!("{head}... (215 characters)"));
        assert_eq!(brief("name=\"a\nb\""), "name=\"a\\nb\"");
    }

    fn set(args: &[&str]) -> Result<ScenarioSpec, (usize, String)> {
        let o: Vec<Override> = args.iter().map(|a| Override::parse(a).unwrap()).collect();
        apply_overrides(&paper(), &o)
    }

    #[test]
    fn parses_vary_arguments() {
        let v = Vary::parse("kinds[0].starts.first_m=(1.0, 2.0), (3, 4)").unwrap();
        assert_eq!(v.path.to_string(), "kinds[0].starts.first_m");
        let texts: Vec<&str> = v.values.iter().map(|x| x.text.as_str()).collect();
        assert_eq!(texts, ["(1.0, 2.0)", "(3, 4)"]);
        assert_eq!(v.at(1).to_string(), "kinds[0].starts.first_m=(3, 4)");
        assert_eq!(Vary::parse("a.b=1,,2").unwrap_err(), "value 2: empty value");
        assert_eq!(Vary::parse("a.b").unwrap_err(), "expected FIELD=VALUE");
        assert!(Vary::parse("a.b=(1,2").unwrap_err().contains("not closed"));
        // --set keeps commas.
        let o = Override::parse("tasks.hard.goal_m=(10.0, 50.0)").unwrap();
        assert_eq!(o.value.text, "(10.0, 50.0)");
    }

    #[test]
    fn overrides_reach_fields_elements_variants_and_defaults() {
        let s = set(&[
            "mission.hp_pct_per_step_in_radiation=0.003",
            "kinds[0].max_speed_m_per_s=2",
            "radiation_zones[*].dose_rate_factor=2.5",
            "tasks.hard.goal_m=(10.0, 50.0)",
            "kinds[0].starts.first_m=(30.0, 3.0)",
            "kinds[2].locomotion=Ground",
            "debris_fields[0].seed=None",
            "collision.enabled=false",
            "description=\"a, b\"",
        ])
        .unwrap();
        assert_eq!(s.mission.hp_pct_per_step_in_radiation, 0.003);
        assert_eq!(s.kinds[0].max_speed_m_per_s, 2.0);
        assert!(s.radiation_zones.iter().all(|z| z.dose_rate_factor == 2.5));
        assert_eq!(s.tasks[0].goal_m, [10.0, 50.0]);
        assert!(matches!(
            s.kinds[0].starts,
            StartsSpec::Row {
                first_m: [30.0, 3.0],
                ..
            }
        ));
        assert_eq!(s.kinds[2].role, Role::Observer);
        assert_eq!(s.debris_fields[0].seed, None);
        assert!(!s.collision.enabled);
        assert_eq!(s.description, "a, b");
        // A variant can be swapped for another.
        let s = set(&["kinds[1].starts=Row(first_m: (34.0, 6.5), step_m: (3.0, 0.0))"]).unwrap();
        assert!(matches!(s.kinds[1].starts, StartsSpec::Row { .. }));
    }

    #[test]
    fn type_errors_name_the_override_and_field() {
        let (i, e) = set(&["mission.duration_s=5", "kinds[0].count=2.5"]).unwrap_err();
        assert_eq!(i, 1);
        assert_eq!(
            e,
            "kinds[0].count: expected a whole number (0 or more), found 2.5"
        );
        // Past u64 (serde_json would read it as a float) and below zero.
        let (_, e) = set(&["sim.seed=18446744073709551616"]).unwrap_err();
        assert_eq!(
            e,
            "sim.seed: expected a whole number, found 18446744073709551616, too large for this \
             field"
        );
        // A u32 field names no u64 bound, past u64 or past u32.
        let (_, e) = set(&["kinds[0].carrying_capacity=99999999999999999999"]).unwrap_err();
        assert_eq!(
            e,
            "kinds[0].carrying_capacity: expected a whole number, found 99999999999999999999, \
             too large for this field"
        );
        for whole in ["1e3", "5.0", "-0"] {
            let (_, e) = set(&[&format!("kinds[0].carrying_capacity={whole}")]).unwrap_err();
            assert_eq!(
                e,
                format!(
                    "kinds[0].carrying_capacity: expected a whole number in digits only (no \
                     point, sign or exponent), found {whole}"
                )
            );
        }
        let (_, e) = set(&["kinds[0].carrying_capacity=4294967296"]).unwrap_err();
        assert!(
            e.starts_with("kinds[0].carrying_capacity: ") && e.contains("u32"),
            "{e}"
        );
        let (_, e) = set(&["kinds[0].carrying_capacity=-1"]).unwrap_err();
        assert_eq!(
            e,
            "kinds[0].carrying_capacity: expected a whole number (0 or more), found -1"
        );
        assert_eq!(
            set(&["sim.seed=18446744073709551615"]).unwrap().sim.seed,
            u64::MAX
        );
        let (_, e) = set(&["kinds[0].locomotion=Flying"]).unwrap_err();
        assert!(
            e.starts_with("kinds[0].locomotion: unknown variant `Flying`"),
            "{e}"
        );
        let (_, e) = set(&["mission.duration_s=abc"]).unwrap_err();
        assert_eq!(e, "mission.duration_s: expected a number, found abc");
        let (_, e) = set(&["mission.hp_rate=1"]).unwrap_err();
        assert!(
            e.starts_with("no field \"hp_rate\" in mission (fields: duration_s, "),
            "{e}"
        );
    }

    /// `()` for a struct is a struct with no field given: the first required field is named
    /// (serde said "invalid length 0, expected struct TaskSpec with 6 elements"), and a struct
    /// whose fields all have defaults takes them.
    #[test]
    fn an_empty_struct_names_its_first_missing_field() {
        let (_, e) = set(&["tasks[0]=()"]).unwrap_err();
        assert_eq!(e, "tasks[0]: missing field `name`");
        let (_, e) = set(&["tasks[0]=TaskSpec()"]).unwrap_err();
        assert_eq!(e, "tasks[0]: missing field `name`");
        let s = set(&["collision=()"]).unwrap();
        assert_eq!(s.collision, usar_sim::scenario::CollisionParams::default());
    }
}
