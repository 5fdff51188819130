//! One field override, `FIELD=VALUE` ([`Override`]): its parse, how it sets its value in a
//! spec's JSON form, and how error messages quote it ([`brief`](crate::vary::brief)).

use std::fmt;

use serde_json::Value;

use crate::vary::path::FieldPath;
use crate::vary::quoted_arg::brief;
use crate::vary::value::RonValue;

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

    /// Sets the value in `spec_json` (the JSON form of a spec, see [`spec_json`](crate::vary::spec_json)).
    ///
    /// # Errors
    /// A path that names nothing in the spec, or a value that cannot have the shape of the
    /// value it replaces (message prefixed with the field path).
    pub fn apply(&self, spec_json: &mut Value) -> Result<(), String> {
        self.path
            .set(spec_json, &mut |old| self.value.value.to_json(Some(old)))
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

/// Splits `FIELD=VALUE` at the first `=` into the parsed field path and the value text.
pub(crate) fn split_arg(arg: &str) -> Result<(FieldPath, &str), String> {
    let (field, value) = arg
        .split_once('=')
        .ok_or_else(|| "expected FIELD=VALUE".to_string())?;
    Ok((FieldPath::parse(field.trim())?, value))
}
