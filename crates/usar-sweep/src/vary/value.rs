//! Values written in RON on the command line, turned into the JSON form of a scenario spec
//! guided by the value they replace.
//!
//! Accepted: numbers (`0.003`, `-5`, `1e-4`), `true`/`false`, strings quoted (`"a b"`, with
//! `\"` and `\\` escapes) or bare (`paper2`, `Aerial`: a unit enum variant is a string in
//! JSON), `Some(x)` and `None`, tuples and lists (`(1.0, 2.0)`, `[(1, 2), (3, 4)]`), structs
//! (`(mean_pct: 70.0, std_dev_pct: 5.0)`, the struct name optional) and enum variants with
//! data (newtype `Name(x)`, struct-like `Row(first_m: (30.0, 3.0), step_m: (3.0, 0.0))`) and
//! maps (`{"hard": 3, "easy": 3}`, keys quoted or bare).
//!
//! The JSON shape of the old value decides what a bare word becomes: `1` for a string field is
//! the string `"1"`, `true` for a boolean field a boolean; a number field takes only a finite
//! number. Whether the result has the right type is finally decided by deserialising the spec.

use super::brief;
use serde_json::{Map, Number, Value};

/// A parsed RON value.
#[derive(Debug, Clone, PartialEq)]
pub enum RonValue {
    /// A bare word: a number, `true`, `false`, `None`, a unit variant or a bare string.
    Bare(String),
    /// A double-quoted string, unescaped.
    Str(String),
    /// `Name(...)`: `Some(x)`, an enum variant or a named struct.
    Call(String, Args),
    /// `(...)`: a tuple or an unnamed struct.
    Tuple(Args),
    /// `[...]`: a list.
    List(Vec<RonValue>),
    /// `{key: value, ...}`: a map, keys quoted or bare (e.g. a kind's `quota`,
    /// `{"hard": 3, "easy": 3}`).
    Map(Vec<(String, RonValue)>),
}

/// The inside of `(...)`: positional items or `name: value` fields.
#[derive(Debug, Clone, PartialEq)]
pub enum Args {
    /// `(a, b, ...)`.
    Positional(Vec<RonValue>),
    /// `(x: a, y: b, ...)`.
    Named(Vec<(String, RonValue)>),
}

impl RonValue {
    /// Parses one value from `text` (surrounding white space allowed).
    ///
    /// # Errors
    /// Text that is not one value, with the 1-based character position of the problem;
    /// values nested more than 128 deep (`MAX_NESTING`).
    pub fn parse(text: &str) -> Result<Self, String> {
        let mut p = Parser {
            s: text,
            pos: 0,
            depth: 0,
        };
        let v = p.value()?;
        p.skip_ws();
        if p.pos < text.len() {
            return Err(p.error("expected the end of the value"));
        }
        Ok(v)
    }

    /// The JSON form of this value for a field whose current JSON value is `guide` (`None`
    /// when unknown, e.g. inside a new variant).
    ///
    /// # Errors
    /// A value that cannot be what the guide is: a non-number for a number, a non-boolean for
    /// a boolean, a non-finite number.
    pub fn to_json(&self, guide: Option<&Value>) -> Result<Value, String> {
        match self {
            RonValue::Bare(t) => bare_to_json(t, guide),
            RonValue::Str(s) => match guide {
                Some(Value::Number(_)) => Err(format!(
                    "expected a number, found {}",
                    brief(&format!("{s:?}"))
                )),
                Some(Value::Bool(_)) => Err(format!(
                    "expected true or false, found {}",
                    brief(&format!("{s:?}"))
                )),
                _ => Ok(Value::String(s.clone())),
            },
            RonValue::Call(name, args) if name == "Some" => match args {
                Args::Positional(items) if items.len() == 1 => items[0].to_json(guide),
                _ => Err("Some(...) takes one value".into()),
            },
            RonValue::Call(name, args) => {
                scalar_guide(guide, &format!("{name}(...)"))?;
                match guide {
                    Some(Value::Object(m)) if !is_variant(m) && is_struct_body(args) => {
                        args_to_json(args, guide, false)
                    }
                    _ => {
                        let inner = guide.and_then(|g| g.get(name));
                        let mut map = Map::new();
                        map.insert(name.clone(), args_to_json(args, inner, true)?);
                        Ok(Value::Object(map))
                    }
                }
            }
            RonValue::Tuple(args) => {
                scalar_guide(guide, "(...)")?;
                args_to_json(args, guide, false)
            }
            RonValue::List(items) => {
                scalar_guide(guide, "[...]")?;
                seq_to_json(items, guide)
            }
            RonValue::Map(entries) => {
                scalar_guide(guide, "{...}")?;
                fields_to_json(entries, guide)
            }
        }
    }
}

/// Whether `(...)` after a struct's name is its body: named fields, or none (`Name()`).
fn is_struct_body(args: &Args) -> bool {
    match args {
        Args::Named(_) => true,
        Args::Positional(items) => items.is_empty(),
    }
}

/// A struct object is not a variant object `{"Variant": ..}`.
fn is_variant(m: &Map<String, Value>) -> bool {
    m.len() == 1
        && m.keys()
            .all(|k| k.starts_with(|c: char| c.is_ascii_uppercase()))
}

/// Refuses a composite value where a number or boolean is expected.
fn scalar_guide(guide: Option<&Value>, found: &str) -> Result<(), String> {
    match guide {
        Some(Value::Number(_)) => Err(format!("expected a number, found {}", brief(found))),
        Some(Value::Bool(_)) => Err(format!("expected true or false, found {}", brief(found))),
        _ => Ok(()),
    }
}

fn bare_to_json(t: &str, guide: Option<&Value>) -> Result<Value, String> {
    if t == "None" {
        return Ok(Value::Null);
    }
    match guide {
        Some(Value::String(_)) => Ok(Value::String(t.to_string())),
        Some(Value::Bool(_)) => match t {
            "true" => Ok(Value::Bool(true)),
            "false" => Ok(Value::Bool(false)),
            _ => Err(format!("expected true or false, found {}", brief(t))),
        },
        Some(Value::Number(n)) if n.is_u64() => whole_number(t),
        Some(Value::Number(_)) => number(t),
        _ => match t {
            "true" => Ok(Value::Bool(true)),
            "false" => Ok(Value::Bool(false)),
            _ if t.parse::<f64>().is_ok() => number(t),
            _ => Ok(Value::String(t.to_string())),
        },
    }
}

/// A JSON unsigned integer from RON number text, for a field that holds one (a seed, a
/// count): `0` to `u64::MAX`, else an error saying what it found (`18446744073709551616`,
/// `-1`, `1.5` and `1e3` are not read as a float the field then refuses with serde's words).
/// A narrower field (a `u32`) refuses a larger whole number itself, with serde's words.
fn whole_number(t: &str) -> Result<Value, String> {
    if let Ok(u) = t.parse::<u64>() {
        return Ok(Value::from(u));
    }
    let Ok(x) = t.parse::<f64>() else {
        return Err(format!("expected a number, found {}", brief(t)));
    };
    Err(if t.bytes().all(|b| b.is_ascii_digit()) {
        // Digits only, yet not a u64: past the widest field's range. The field may be
        // narrower (a u32 count), so no bound is named.
        format!(
            "expected a whole number, found {}, too large for this field",
            brief(t)
        )
    } else if x >= 0.0 && x.fract() == 0.0 {
        // `1e3`, `5.0`, `-0`: whole, but a scenario file takes such a field in digits only.
        format!(
            "expected a whole number in digits only (no point, sign or exponent), found {}",
            brief(t)
        )
    } else {
        format!("expected a whole number (0 or more), found {}", brief(t))
    })
}

/// A JSON number from RON number text: an integer if it is one, else a finite float.
fn number(t: &str) -> Result<Value, String> {
    if let Ok(u) = t.parse::<u64>() {
        return Ok(Value::from(u));
    }
    if let Ok(i) = t.parse::<i64>() {
        return Ok(Value::from(i));
    }
    match t.parse::<f64>() {
        Ok(f) => Number::from_f64(f)
            .map(Value::Number)
            .ok_or_else(|| format!("expected a finite number, found {}", brief(t))),
        Err(_) => Err(format!("expected a number, found {}", brief(t))),
    }
}

/// The JSON of `(...)`: an array of positional items, an object of named ones. One
/// positional item is the item itself in a newtype variant `Name(x)`, and in `(x)` unless a
/// list or tuple is expected. An empty `()` for a struct is a struct with no field given (an
/// empty object: the spec's defaults, or an error naming the first missing field).
fn args_to_json(args: &Args, guide: Option<&Value>, newtype: bool) -> Result<Value, String> {
    match args {
        Args::Positional(items)
            if items.is_empty() && matches!(guide, Some(Value::Object(m)) if !is_variant(m)) =>
        {
            Ok(Value::Object(Map::new()))
        }
        Args::Positional(items)
            if items.len() == 1 && (newtype || !matches!(guide, Some(Value::Array(_)))) =>
        {
            items[0].to_json(guide)
        }
        Args::Positional(items) => seq_to_json(items, guide),
        Args::Named(fields) => fields_to_json(fields, guide),
    }
}

/// The JSON object of `name: value` fields or map entries, each value guided by the guide's
/// entry of its name.
fn fields_to_json(fields: &[(String, RonValue)], guide: Option<&Value>) -> Result<Value, String> {
    let mut map = Map::new();
    for (name, v) in fields {
        let g = guide.and_then(|g| g.get(name));
        map.insert(name.clone(), v.to_json(g)?);
    }
    Ok(Value::Object(map))
}

fn seq_to_json(items: &[RonValue], guide: Option<&Value>) -> Result<Value, String> {
    let guides = guide.and_then(Value::as_array);
    items
        .iter()
        .enumerate()
        .map(|(i, v)| {
            let g = guides.and_then(|gs| gs.get(i).or_else(|| gs.first()));
            v.to_json(g)
        })
        .collect::<Result<Vec<_>, _>>()
        .map(Value::Array)
}

/// Characters that end a bare word.
const DELIMITERS: &[char] = &['(', ')', '[', ']', '{', '}', ',', ':', '"'];

/// Deepest nesting of values [`RonValue::parse`] reads (128, ron's own recursion limit for
/// scenario files); deeper text is an error, not a stack overflow.
pub const MAX_NESTING: usize = 128;

struct Parser<'a> {
    s: &'a str,
    pos: usize,
    /// Values being read around the current position.
    depth: usize,
}

impl Parser<'_> {
    fn peek(&self) -> Option<char> {
        self.s[self.pos..].chars().next()
    }

    fn skip_ws(&mut self) {
        while let Some(c) = self.peek().filter(|c| c.is_whitespace()) {
            self.pos += c.len_utf8();
        }
    }

    fn error(&self, what: &str) -> String {
        let at = self.s[..self.pos].chars().count() + 1;
        match self.peek() {
            Some(c) => format!("{what} at character {at}, found '{c}'"),
            None => format!("{what} at character {at}, found the end"),
        }
    }

    fn value(&mut self) -> Result<RonValue, String> {
        if self.depth >= MAX_NESTING {
            return Err(self.error(&format!("values nested more than {MAX_NESTING} deep")));
        }
        self.depth += 1;
        let v = self.one_value();
        self.depth -= 1;
        v
    }

    fn one_value(&mut self) -> Result<RonValue, String> {
        self.skip_ws();
        match self.peek() {
            Some('"') => self.string().map(RonValue::Str),
            Some('(') => self.args().map(RonValue::Tuple),
            Some('[') => self.list().map(RonValue::List),
            Some('{') => self.map().map(RonValue::Map),
            _ => {
                let word = self.bare();
                if word.is_empty() {
                    return Err(self.error("expected a value"));
                }
                self.skip_ws();
                if self.peek() == Some('(') {
                    Ok(RonValue::Call(word, self.args()?))
                } else {
                    Ok(RonValue::Bare(word))
                }
            }
        }
    }

    fn bare(&mut self) -> String {
        let rest = &self.s[self.pos..];
        let end = rest
            .find(|c: char| c.is_whitespace() || DELIMITERS.contains(&c))
            .unwrap_or(rest.len());
        self.pos += end;
        rest[..end].to_string()
    }

    fn string(&mut self) -> Result<String, String> {
        let start = self.pos;
        self.pos += 1;
        let mut out = String::new();
        let mut chars = self.s[self.pos..].chars();
        while let Some(c) = chars.next() {
            self.pos += c.len_utf8();
            match c {
                '"' => return Ok(out),
                '\\' => match chars.next() {
                    Some(e @ ('"' | '\\')) => {
                        self.pos += 1;
                        out.push(e);
                    }
                    Some('n') => {
                        self.pos += 1;
                        out.push('\n');
                    }
                    _ => return Err(self.error("unknown escape in a string")),
                },
                c => out.push(c),
            }
        }
        self.pos = start;
        Err(self.error("string not closed"))
    }

    /// `( item, ... )` where every item is `value` or every item is `name: value`.
    fn args(&mut self) -> Result<Args, String> {
        self.pos += 1;
        let mut positional = Vec::new();
        let mut named = Vec::new();
        loop {
            self.skip_ws();
            if self.peek() == Some(')') {
                self.pos += 1;
                break;
            }
            let start = self.pos;
            let word = self.bare();
            self.skip_ws();
            if !word.is_empty() && self.peek() == Some(':') {
                self.pos += 1;
                named.push((word, self.value()?));
            } else {
                self.pos = start;
                positional.push(self.value()?);
            }
            if !named.is_empty() && !positional.is_empty() {
                return Err(self.error("mixed named and unnamed items"));
            }
            if !self.separator(')')? {
                break;
            }
        }
        Ok(if named.is_empty() {
            Args::Positional(positional)
        } else {
            Args::Named(named)
        })
    }

    fn list(&mut self) -> Result<Vec<RonValue>, String> {
        self.pos += 1;
        let mut items = Vec::new();
        loop {
            self.skip_ws();
            if self.peek() == Some(']') {
                self.pos += 1;
                break;
            }
            items.push(self.value()?);
            if !self.separator(']')? {
                break;
            }
        }
        Ok(items)
    }

    /// `{ key: value, ... }` with keys quoted or bare.
    fn map(&mut self) -> Result<Vec<(String, RonValue)>, String> {
        self.pos += 1;
        let mut entries = Vec::new();
        loop {
            self.skip_ws();
            let key = match self.peek() {
                Some('}') => {
                    self.pos += 1;
                    break;
                }
                Some('"') => self.string()?,
                _ => self.bare(),
            };
            if key.is_empty() {
                return Err(self.error("expected a map key"));
            }
            self.skip_ws();
            if self.peek() != Some(':') {
                return Err(self.error("expected ':' after a map key"));
            }
            self.pos += 1;
            entries.push((key, self.value()?));
            if !self.separator('}')? {
                break;
            }
        }
        Ok(entries)
    }

    /// After an item: `,` (true: more may follow) or the closing bracket (false, consumed).
    fn separator(&mut self, close: char) -> Result<bool, String> {
        self.skip_ws();
        match self.peek() {
            Some(',') => {
                self.pos += 1;
                Ok(true)
            }
            Some(c) if c == close => {
                self.pos += 1;
                Ok(false)
            }
            _ => Err(self.error(&format!("expected ',' or '{close}'"))),
        }
    }
}

#[cfg(test)]
mod tests {
    use serde_json::json;

    use super::*;

    fn conv(text: &str, guide: Value) -> Result<Value, String> {
        RonValue::parse(text)?.to_json(Some(&guide))
    }

    #[test]
    fn nesting_is_limited_not_a_stack_overflow() {
        let nested = |n: usize| format!("{}1{}", "[".repeat(n), "]".repeat(n));
        // 128 values in all: 127 lists around a number.
        assert!(RonValue::parse(&nested(MAX_NESTING - 1)).is_ok());
        for n in [MAX_NESTING, 100_000] {
            let e = RonValue::parse(&nested(n)).unwrap_err();
            assert!(e.contains("nested more than 128 deep"), "{e}");
        }
        let e = RonValue::parse(&"(".repeat(100_000)).unwrap_err();
        assert!(e.contains("nested more than 128 deep"), "{e}");
    }

    #[test]
    fn maps_with_quoted_or_bare_keys() {
        let guide = json!({"hard": 3, "easy": 3});
        assert_eq!(
            conv(r#"{"hard": 2, easy: 4}"#, guide.clone()).unwrap(),
            json!({"hard": 2, "easy": 4})
        );
        assert_eq!(conv("{}", guide.clone()).unwrap(), json!({}));
        assert_eq!(
            conv("{hard: x}", guide.clone()).unwrap_err(),
            "expected a number, found x"
        );
        assert!(
            RonValue::parse("{hard 2}")
                .unwrap_err()
                .contains("expected ':'")
        );
        assert!(
            RonValue::parse("{: 2}")
                .unwrap_err()
                .contains("expected a map key")
        );
        assert!(
            RonValue::parse("{a: 1")
                .unwrap_err()
                .contains("expected ',' or '}'")
        );
        let deep = format!("{}1{}", "{a: ".repeat(200), "}".repeat(200));
        assert!(
            RonValue::parse(&deep)
                .unwrap_err()
                .contains("nested more than 128")
        );
    }

    #[test]
    fn numbers_follow_the_guide() {
        assert_eq!(conv("0.003", json!(0.0003)).unwrap(), json!(0.003));
        assert_eq!(conv("-5", json!(600.0)).unwrap(), json!(-5));
        assert_eq!(conv("1e-4", json!(1.0)).unwrap(), json!(0.0001));
        assert_eq!(conv("7", json!(6)).unwrap(), json!(7));
        assert_eq!(
            conv("abc", json!(1.0)).unwrap_err(),
            "expected a number, found abc"
        );
        assert_eq!(
            conv("inf", json!(1.0)).unwrap_err(),
            "expected a finite number, found inf"
        );
        assert_eq!(
            conv("\"3\"", json!(1.0)).unwrap_err(),
            "expected a number, found \"3\""
        );
        assert_eq!(
            conv("(1, 2)", json!(1.0)).unwrap_err(),
            "expected a number, found (...)"
        );
    }

    #[test]
    fn booleans_strings_and_unit_variants() {
        assert_eq!(conv("false", json!(true)).unwrap(), json!(false));
        assert_eq!(
            conv("yes", json!(true)).unwrap_err(),
            "expected true or false, found yes"
        );
        assert_eq!(conv("Aerial", json!("Ground")).unwrap(), json!("Aerial"));
        assert_eq!(conv("\"a, b\"", json!("x")).unwrap(), json!("a, b"));
        assert_eq!(conv("42", json!("x")).unwrap(), json!("42"));
        assert_eq!(conv("true", json!("x")).unwrap(), json!("true"));
        assert_eq!(
            conv(r#""say \"hi\"""#, json!("x")).unwrap(),
            json!("say \"hi\"")
        );
    }

    #[test]
    fn options_tuples_lists_structs() {
        assert_eq!(conv("Some(42)", Value::Null).unwrap(), json!(42));
        assert_eq!(conv("None", json!(42)).unwrap(), Value::Null);
        assert_eq!(conv("42", Value::Null).unwrap(), json!(42));
        assert_eq!(
            conv("(1.0, 2.5)", json!([0.0, 0.0])).unwrap(),
            json!([1.0, 2.5])
        );
        assert_eq!(
            conv("[(1, 2), (3, 4)]", json!([[0.0, 0.0]])).unwrap(),
            json!([[1, 2], [3, 4]])
        );
        assert_eq!(conv("[]", json!([[0.0, 0.0]])).unwrap(), json!([]));
        assert_eq!(
            conv(
                "(mean_pct: 70.0, std_dev_pct: 5)",
                json!({"mean_pct": 1.0, "std_dev_pct": 1.0})
            )
            .unwrap(),
            json!({"mean_pct": 70.0, "std_dev_pct": 5})
        );
        // A named struct keeps its fields; the name is dropped.
        assert_eq!(
            conv(
                "Circle(radius_m: 2)",
                json!({"center_m": [0, 0], "radius_m": 1.0})
            )
            .unwrap(),
            json!({"radius_m": 2})
        );
    }

    #[test]
    fn enum_variants() {
        assert_eq!(
            conv("PerMetre(0.15)", json!("Linear")).unwrap(),
            json!({"PerMetre": 0.15})
        );
        assert_eq!(
            conv(
                "Row(first_m: (30, 3), step_m: (3.0, 0.0))",
                json!({"List": [[1.0, 1.0]]})
            )
            .unwrap(),
            json!({"Row": {"first_m": [30, 3], "step_m": [3.0, 0.0]}})
        );
        assert_eq!(
            conv("List([(1, 1)])", json!({"List": [[0.0, 0.0]]})).unwrap(),
            json!({"List": [[1, 1]]})
        );
        assert_eq!(
            conv(
                "Grid(spacing_m: 2)",
                json!({"Grid": {"spacing_m": 1.0, "margin_m": 0.5}})
            )
            .unwrap(),
            json!({"Grid": {"spacing_m": 2}})
        );
    }

    #[test]
    fn parse_errors_say_where() {
        for (text, want) in [
            ("", "expected a value at character 1, found the end"),
            ("(1, 2", "expected ',' or ')' at character 6, found the end"),
            (
                "1 2",
                "expected the end of the value at character 3, found '2'",
            ),
            (
                "(a: 1, 2)",
                "mixed named and unnamed items at character 9, found ')'",
            ),
            ("\"abc", "string not closed at character 1, found '\"'"),
            ("[1,,]", "expected a value at character 4, found ','"),
        ] {
            assert_eq!(RonValue::parse(text).unwrap_err(), want, "{text:?}");
        }
    }
}
