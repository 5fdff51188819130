//! Field paths into a scenario spec, as the loader's error messages write them
//! (`mission.duration_s`, `kinds[0].max_speed_m_per_s`, `tasks.hard.goal_m`), plus the
//! wildcard `[*]` for every element of a list, and setting the value(s) they name in the
//! spec's JSON form.
//!
//! The JSON form is what `serde_json::to_value` makes of a `ScenarioSpec`: structs are
//! objects, lists and tuples arrays, unit enum variants strings, other enum variants
//! single-key objects `{"Variant": content}` and `None` null. A path walks through a variant
//! object transparently (its key is not part of the path), so `kinds[0].starts.first_m`
//! names the `first_m` of a `Row(first_m: .., step_m: ..)` and `tasks.easy.rescuees[2]` the
//! third point of a `List([...])`, as in the loader's messages. A name step into a list picks
//! the element whose `name` field is that name, so `tasks.hard.goal_m` is the `goal_m` of the
//! task named `hard` wherever it stands in `tasks` (`tasks[1].goal_m` names it by position).

use std::fmt;

use serde_json::{Map, Value};
use usar_sim::scenario::did_you_mean;

/// One step of a [`FieldPath`].
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Step {
    /// A struct field, `.name` (or the first name of the path); applied to a list, the
    /// element whose `name` field is `name`.
    Field(String),
    /// A list element, `[i]` (0-based).
    Index(usize),
    /// Every element of a list, `[*]`.
    All,
}

/// A parsed field path: `name(.name | [i] | [*])*`, names being `[A-Za-z_][A-Za-z0-9_]*`.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct FieldPath {
    steps: Vec<Step>,
}

impl FieldPath {
    /// Parses `text`, e.g. `radiation_zones[*].dose_rate_factor`.
    ///
    /// # Errors
    /// An empty path, a name with characters outside `[A-Za-z0-9_]` or starting with a digit,
    /// a bracket that does not hold an index or `*`, or a misplaced `.`/`[`; the message says
    /// where.
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut steps = Vec::new();
        let mut rest = text;
        let mut expect_name = true;
        while !rest.is_empty() || expect_name {
            if expect_name {
                let end = rest.find(['.', '[']).unwrap_or(rest.len());
                let name = &rest[..end];
                check_name(name, text)?;
                steps.push(Step::Field(name.to_string()));
                rest = &rest[end..];
                expect_name = false;
            } else if let Some(after) = rest.strip_prefix('.') {
                rest = after;
                expect_name = true;
            } else if let Some(after) = rest.strip_prefix('[') {
                let close = after
                    .find(']')
                    .ok_or_else(|| format!("field path {text:?}: '[' is not closed"))?;
                let inner = after[..close].trim();
                steps.push(if inner == "*" {
                    Step::All
                } else {
                    Step::Index(inner.parse().map_err(|_| {
                        format!(
                            "field path {text:?}: expected an index or * in [], found {inner:?}"
                        )
                    })?)
                });
                rest = &after[close + 1..];
            } else {
                return Err(format!("field path {text:?}: unexpected {rest:?}"));
            }
        }
        Ok(Self { steps })
    }

    /// The steps, first to last.
    pub fn steps(&self) -> &[Step] {
        &self.steps
    }

    /// Whether two paths can name the same value: one is a prefix of the other, with `[*]`
    /// matching any index (`mission` and `mission.duration_s`; `zones[*].r` and `zones[2].r`)
    /// and a name matching any index (`tasks.hard` may be `tasks[0]`).
    pub fn overlaps(&self, other: &FieldPath) -> bool {
        self.steps
            .iter()
            .zip(&other.steps)
            .all(|(a, b)| match (a, b) {
                (Step::Field(x), Step::Field(y)) => x == y,
                (Step::Index(i), Step::Index(j)) => i == j,
                // `[*]`, or a name against an index: may be the same element.
                _ => true,
            })
    }

    /// Replaces the value(s) this path names inside `root` with `make(old value)`; `[*]`
    /// calls `make` once per element.
    ///
    /// # Errors
    /// A field the struct does not have (the message lists the fields it has), an index out
    /// of range or into something that is not a list, or `[*]` over an empty list, each
    /// message naming the path walked so far; or the error `make` returns, prefixed with the
    /// path of the value it was making (`zones[*].r: expected a number, found x`).
    pub fn set(
        &self,
        root: &mut Value,
        make: &mut dyn FnMut(&Value) -> Result<Value, String>,
    ) -> Result<(), String> {
        set_at(root, &self.steps, &mut String::new(), make)
    }
}

impl fmt::Display for FieldPath {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, step) in self.steps.iter().enumerate() {
            match step {
                Step::Field(name) if i == 0 => f.write_str(name)?,
                Step::Field(name) => write!(f, ".{name}")?,
                Step::Index(k) => write!(f, "[{k}]")?,
                Step::All => f.write_str("[*]")?,
            }
        }
        Ok(())
    }
}

fn check_name(name: &str, path: &str) -> Result<(), String> {
    let ok = name
        .chars()
        .next()
        .is_some_and(|c| c.is_ascii_alphabetic() || c == '_')
        && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
    if ok {
        Ok(())
    } else if name.is_empty() {
        Err(format!("field path {path:?}: expected a field name"))
    } else {
        Err(format!("field path {path:?}: {name:?} is not a field name"))
    }
}

/// The content of an enum variant object `{"Variant": content}` (one key, starting with an
/// upper-case letter; struct fields are snake_case).
fn variant_content(v: &mut Value) -> Option<(&str, &mut Value)> {
    match v {
        Value::Object(map) if map.len() == 1 => {
            let (k, content) = map.iter_mut().next()?;
            k.starts_with(|c: char| c.is_ascii_uppercase())
                .then_some((k.as_str(), content))
        }
        _ => None,
    }
}

/// What a JSON value is, in the words of a scenario file.
fn kind_of(v: &Value) -> String {
    match v {
        Value::Null => "None".into(),
        Value::Bool(_) => "a boolean".into(),
        Value::Number(_) => "a number".into(),
        Value::String(_) => "a string or unit variant".into(),
        Value::Array(_) => "a list or tuple".into(),
        Value::Object(_) => "a struct".into(),
    }
}

fn where_(here: &str) -> String {
    if here.is_empty() {
        "the scenario".into()
    } else {
        here.into()
    }
}

/// Walks `steps` from `node` and replaces the value(s) they name with `make(old value)`;
/// `here` is the path walked so far (restored on return), used in error messages.
fn set_at(
    node: &mut Value,
    steps: &[Step],
    here: &mut String,
    make: &mut dyn FnMut(&Value) -> Result<Value, String>,
) -> Result<(), String> {
    let Some(step) = steps.first() else {
        *node = make(node).map_err(|e| format!("{}: {e}", where_(here)))?;
        return Ok(());
    };
    // A variant object is walked through: its key is not part of the path.
    if let Some((_, content)) = variant_content(node) {
        return set_at(content, steps, here, make);
    }
    if matches!(step, Step::Index(_) | Step::All)
        && node.is_object()
        && ONE_OR_LIST_FIELDS.contains(&here.as_str())
    {
        return set_in_list_of_one(node, steps, here, make);
    }
    let shown = where_(here);
    let len = here.len();
    let rest = &steps[1..];
    let result = match (step, &mut *node) {
        (Step::Field(name), Value::Object(map)) => set_field(map, name, rest, here, make, &shown),
        (Step::Field(name), Value::Array(items)) => {
            set_named_element(items, name, rest, here, make, &shown)
        }
        (Step::Index(i), Value::Array(items)) => set_element(items, *i, rest, here, make, &shown),
        (Step::All, Value::Array(items)) => set_every_element(items, rest, here, make, &shown),
        (step, other) => Err(format!(
            "{shown} is {}, which has no {}",
            kind_of(other),
            describe(step)
        )),
    };
    here.truncate(len);
    result
}

/// Sets the `rest` of the path in the struct field `name` of `map`; `shown` names the struct
/// in errors. A missing field is an error listing the fields there are.
fn set_field(
    map: &mut Map<String, Value>,
    name: &str,
    rest: &[Step],
    here: &mut String,
    make: &mut dyn FnMut(&Value) -> Result<Value, String>,
    shown: &str,
) -> Result<(), String> {
    match map.get_mut(name) {
        Some(child) => {
            push_field(here, name);
            set_at(child, rest, here, make)
        }
        None => {
            let fields: Vec<&str> = map.keys().map(String::as_str).collect();
            Err(format!(
                "no field {name:?} in {shown} (fields: {}){}",
                fields.join(", "),
                did_you_mean(name, fields.iter().copied())
            ))
        }
    }
}

/// Sets the `rest` of the path in the element of `items` whose `name` field is `name`;
/// `shown` names the list in errors. No such element is an error listing the names there are
/// (or saying the list has no names).
fn set_named_element(
    items: &mut [Value],
    name: &str,
    rest: &[Step],
    here: &mut String,
    make: &mut dyn FnMut(&Value) -> Result<Value, String>,
    shown: &str,
) -> Result<(), String> {
    let names: Vec<String> = items.iter().filter_map(element_name).collect();
    match items
        .iter_mut()
        .find(|item| element_name(item).as_deref() == Some(name))
    {
        Some(child) => {
            push_field(here, name);
            set_at(child, rest, here, make)
        }
        None if names.is_empty() => Err(format!(
            "{shown} is a list or tuple, which has no field {name:?}"
        )),
        None => Err(format!(
            "no element named {name:?} in {shown} (names: {})",
            names.join(", ")
        )),
    }
}

/// Sets the `rest` of the path in element `i` of `items`; `shown` names the list in errors.
/// An index out of range is an error giving the list's length.
fn set_element(
    items: &mut [Value],
    i: usize,
    rest: &[Step],
    here: &mut String,
    make: &mut dyn FnMut(&Value) -> Result<Value, String>,
    shown: &str,
) -> Result<(), String> {
    let n = items.len();
    match items.get_mut(i) {
        Some(child) => {
            here.push_str(&format!("[{i}]"));
            set_at(child, rest, here, make)
        }
        None if n == 0 => Err(format!("no element [{i}] in {shown}: it is empty")),
        None => Err(format!(
            "no element [{i}] in {shown}: it has {n} (indices 0 to {})",
            n - 1
        )),
    }
}

/// Sets the `rest` of the path in every element of `items` (`[*]`), first to last, stopping
/// at the first error; `shown` names the list in errors. An empty list is an error.
fn set_every_element(
    items: &mut [Value],
    rest: &[Step],
    here: &mut String,
    make: &mut dyn FnMut(&Value) -> Result<Value, String>,
    shown: &str,
) -> Result<(), String> {
    if items.is_empty() {
        Err(format!("{shown} is empty: [*] sets nothing"))
    } else {
        here.push_str("[*]");
        items
            .iter_mut()
            .try_for_each(|child| set_at(child, rest, here, make))
    }
}

/// The fields a scenario writes either as one struct or as a list of them, where a list of
/// one behaves as the struct ([`usar_sim::scenario::RestStationsSpec`]): an index or `[*]`
/// reaches the single struct as element 0 (`rest_station[0].radius_m`, `rest_station[*]`).
const ONE_OR_LIST_FIELDS: &[&str] = &["rest_station"];

/// Sets `steps` (starting with an index or `[*]`) in the single struct `node` taken as a list
/// of one, and keeps `node` a single struct, so the scenario keeps the form it was written in.
fn set_in_list_of_one(
    node: &mut Value,
    steps: &[Step],
    here: &mut String,
    make: &mut dyn FnMut(&Value) -> Result<Value, String>,
) -> Result<(), String> {
    let mut list = Value::Array(vec![node.take()]);
    let result = set_at(&mut list, steps, here, make);
    *node = match list {
        Value::Array(mut items) if items.len() == 1 => items.pop().unwrap_or_default(),
        other => other,
    };
    result
}

/// The `name` field of a list element that is a struct with one.
fn element_name(item: &Value) -> Option<String> {
    item.get("name")?.as_str().map(str::to_string)
}

fn push_field(here: &mut String, name: &str) {
    if !here.is_empty() {
        here.push('.');
    }
    here.push_str(name);
}

fn describe(step: &Step) -> String {
    match step {
        Step::Field(name) => format!("field {name:?}"),
        Step::Index(i) => format!("element [{i}]"),
        Step::All => "elements [*]".into(),
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    fn p(s: &str) -> FieldPath {
        FieldPath::parse(s).unwrap()
    }

    #[test]
    fn parses_and_displays_paths() {
        for s in [
            "mission.hp_pct_per_step_in_radiation",
            "kinds[0].max_speed_m_per_s",
            "radiation_zones[*].dose_rate_factor",
            "tasks.hard.goal_m",
            "tasks.easy.rescuees[2][1]",
            "name",
        ] {
            assert_eq!(p(s).to_string(), s);
        }
        assert_eq!(
            p("kinds[1].count").steps(),
            [
                Step::Field("kinds".into()),
                Step::Index(1),
                Step::Field("count".into())
            ]
        );
        assert_eq!(p("a[ * ]").steps()[1], Step::All);
    }

    #[test]
    fn rejects_malformed_paths() {
        for (s, needle) in [
            ("", "expected a field name"),
            ("mission.", "expected a field name"),
            ("a..b", "expected a field name"),
            (".a", "expected a field name"),
            ("kinds[x]", "expected an index or * in [], found \"x\""),
            ("kinds[-1]", "expected an index"),
            ("kinds[0", "'[' is not closed"),
            ("kinds[0]x", "unexpected \"x\""),
            ("max-speed", "\"max-speed\" is not a field name"),
            ("0abc", "is not a field name"),
        ] {
            let e = FieldPath::parse(s).unwrap_err();
            assert!(e.contains(needle), "{s:?}: {e}");
        }
    }

    #[test]
    fn overlap_treats_wildcards_and_prefixes() {
        assert!(p("mission").overlaps(&p("mission.duration_s")));
        assert!(p("zones[*].r").overlaps(&p("zones[2].r")));
        assert!(p("zones[2].r").overlaps(&p("zones[*]")));
        assert!(!p("zones[1].r").overlaps(&p("zones[2].r")));
        assert!(!p("zones[*].r").overlaps(&p("zones[*].c")));
        assert!(!p("mission.a").overlaps(&p("sim.a")));
    }

    fn set(v: &mut Value, path: &str, new: Value) -> Result<(), String> {
        p(path).set(v, &mut |_| Ok(new.clone()))
    }

    fn doc() -> Value {
        json!({
            "mission": {"duration_s": 600.0, "low_hp_pct": 30.0},
            "kinds": [
                {"count": 6, "starts": {"Row": {"first_m": [1.0, 2.0], "step_m": [3.0, 0.0]}}},
                {"count": 4, "starts": {"List": [[1.0, 1.0], [2.0, 2.0]]}}
            ],
            "zones": [{"r": 1.0}, {"r": 2.0}],
            "empty": [],
            "seed": null
        })
    }

    #[test]
    fn sets_fields_elements_and_wildcards() {
        let mut v = doc();
        set(&mut v, "mission.duration_s", json!(5.0)).unwrap();
        set(&mut v, "kinds[1].count", json!(2)).unwrap();
        set(&mut v, "zones[*].r", json!(9.0)).unwrap();
        set(&mut v, "seed", json!(42)).unwrap();
        assert_eq!(v["mission"]["duration_s"], json!(5.0));
        assert_eq!(v["kinds"][1]["count"], json!(2));
        assert_eq!(v["zones"], json!([{"r": 9.0}, {"r": 9.0}]));
        assert_eq!(v["seed"], json!(42));
        // The maker sees each old value.
        let mut seen = Vec::new();
        p("zones[*].r")
            .set(&mut doc(), &mut |old| {
                seen.push(old.clone());
                Ok(json!(0))
            })
            .unwrap();
        assert_eq!(seen, [json!(1.0), json!(2.0)]);
        let e = p("zones[*].r")
            .set(&mut doc(), &mut |_| Err("bad".into()))
            .unwrap_err();
        assert_eq!(e, "zones[*].r: bad");
    }

    #[test]
    fn a_name_picks_the_list_element_of_that_name() {
        let mut v = json!({"tasks": [{"name": "hard", "d": 1.0}, {"name": "easy", "d": 2.0}]});
        set(&mut v, "tasks.easy.d", json!(5.0)).unwrap();
        assert_eq!(v["tasks"][1]["d"], json!(5.0));
        assert_eq!(v["tasks"][0]["d"], json!(1.0));
        let e = set(&mut v, "tasks.medium.d", json!(0)).unwrap_err();
        assert_eq!(
            e,
            "no element named \"medium\" in tasks (names: hard, easy)"
        );
        let e = set(&mut doc(), "zones.x", json!(0)).unwrap_err();
        assert_eq!(e, "zones is a list or tuple, which has no field \"x\"");
        // A name may be any index: such axes overlap.
        assert!(p("tasks.easy.d").overlaps(&p("tasks[1]")));
        assert!(!p("tasks.easy.d").overlaps(&p("tasks.hard.d")));
    }

    #[test]
    fn walks_through_enum_variants() {
        let mut v = doc();
        set(&mut v, "kinds[0].starts.first_m", json!([5.0, 6.0])).unwrap();
        assert_eq!(v["kinds"][0]["starts"]["Row"]["first_m"], json!([5.0, 6.0]));
        set(&mut v, "kinds[1].starts[1]", json!([7.0, 7.0])).unwrap();
        assert_eq!(v["kinds"][1]["starts"]["List"][1], json!([7.0, 7.0]));
        // The variant itself can be replaced.
        set(&mut v, "kinds[1].starts", json!({"Row": {}})).unwrap();
        assert_eq!(v["kinds"][1]["starts"], json!({"Row": {}}));
    }

    #[test]
    fn a_single_rest_station_is_element_0_of_a_list_of_one() {
        let one = json!({"rest_station": {"center_m": [1.0, 2.0], "radius_m": 2.0}});
        let mut v = one.clone();
        set(&mut v, "rest_station[0].radius_m", json!(3.0)).unwrap();
        assert_eq!(
            v,
            json!({"rest_station": {"center_m": [1.0, 2.0], "radius_m": 3.0}}),
            "the station keeps its single form"
        );
        set(&mut v, "rest_station[*].radius_m", json!(4.0)).unwrap();
        assert_eq!(v["rest_station"]["radius_m"], json!(4.0));
        let mut v = one.clone();
        let e = set(&mut v, "rest_station[1].radius_m", json!(3.0)).unwrap_err();
        assert_eq!(
            e,
            "no element [1] in rest_station: it has 1 (indices 0 to 0)"
        );
        assert_eq!(v, one, "a failed set leaves the station as it was");
        // Only fields written as one or a list: any other struct has no element [0].
        let e = set(
            &mut json!({"drop_off": {"r": 1.0}}),
            "drop_off[0].r",
            json!(2),
        )
        .unwrap_err();
        assert_eq!(e, "drop_off is a struct, which has no element [0]");
    }

    #[test]
    fn explains_bad_paths() {
        let cases = [
            (
                "mission.hp_rate",
                "no field \"hp_rate\" in mission (fields: duration_s, low_hp_pct)",
            ),
            (
                "nope",
                "no field \"nope\" in the scenario (fields: mission, kinds, zones, empty, seed)",
            ),
            (
                "mission.duraton_s",
                "no field \"duraton_s\" in mission (fields: duration_s, low_hp_pct); did you \
                 mean `duration_s`?",
            ),
            (
                "zones[5].r",
                "no element [5] in zones: it has 2 (indices 0 to 1)",
            ),
            ("empty[0]", "no element [0] in empty: it is empty"),
            ("empty[*].r", "empty is empty: [*] sets nothing"),
            (
                "mission.duration_s.x",
                "mission.duration_s is a number, which has no field \"x\"",
            ),
            (
                "mission[0]",
                "mission is a struct, which has no element [0]",
            ),
            (
                "zones.r",
                "zones is a list or tuple, which has no field \"r\"",
            ),
            (
                "kinds[1].starts.first_m",
                "kinds[1].starts is a list or tuple, which has no field \"first_m\"",
            ),
            (
                "kinds[0].starts.nope",
                "no field \"nope\" in kinds[0].starts (fields: first_m, step_m)",
            ),
        ];
        for (path, want) in cases {
            let e = set(&mut doc(), path, json!(1)).unwrap_err();
            assert_eq!(e, want, "{path}");
        }
    }
}
