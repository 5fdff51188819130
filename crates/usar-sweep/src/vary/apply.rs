//! Applying overrides to a scenario spec through its JSON form, and the one-line error for a
//! spec with overrides that breaks a rule.

use serde_json::Value;
use usar_sim::scenario::{Scenario, ScenarioError, ScenarioSpec};

use crate::vary::field_override::Override;
use crate::vary::path::FieldPath;

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

/// Validates `spec`, the spec of the scenario source `text` (from `origin`) with `overrides`
/// applied, as a file. A rule about an overridden field is [`rule_error`]'s one line
/// (`FLAG FIELD=VALUE: field.path: message`); one the file itself breaks is the loader's
/// error unchanged (`origin:line:col: field.path: message`); any other names the overrides it
/// holds with (`... (with FLAG FIELD=VALUE ...)`). `flag` is how the overrides were given
/// (`--set` for `usar check`, `set` for the Python package).
///
/// # Errors
/// That one-line message.
pub fn validate_overridden(
    spec: &ScenarioSpec,
    text: &str,
    origin: &str,
    flag: &str,
    overrides: &[Override],
) -> Result<Scenario, String> {
    usar_sim::scenario::validate_in_source(spec, text, origin).map_err(|e| {
        let field = match &e {
            ScenarioError::Invalid { field, .. } => field.as_str(),
            _ => return e.to_string(),
        };
        if !touching(overrides, field).is_empty() {
            return rule_error(flag, overrides, &e);
        }
        let own = usar_sim::scenario::from_str(text, origin).err();
        if own.is_some_and(|own| own.to_string() == e.to_string()) {
            return e.to_string();
        }
        let with: Vec<String> = overrides
            .iter()
            .map(|o| format!("{flag} {}", o.brief()))
            .collect();
        format!("{e} (with {})", with.join(" "))
    })
}

#[cfg(test)]
mod tests {
    use usar_sim::scenario::{Role, StartsSpec, parse_spec};

    use super::*;
    use crate::vary::{QUOTED_ARG_CHARS, Vary, brief};

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
