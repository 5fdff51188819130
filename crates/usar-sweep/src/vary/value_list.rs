//! A field and the values it takes, `FIELD=V1,V2,...` ([`Vary`]): one `--vary` of a grid.

use crate::vary::field_override::{FieldValue, Override, split_arg};
use crate::vary::path::FieldPath;
use crate::vary::split::split_top_level;

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
