//! Errors of scenario loading: reading, RON syntax/shape, and semantic validation.
//!
//! Every error names the file (its *origin*: the path given to [`crate::scenario::load`] or the
//! name given to [`crate::scenario::from_str`]); syntax and shape errors also carry the line and
//! column ron reports, and semantic errors carry the field path (e.g. `kinds[1].quota`) and,
//! when the field appears in the file, its line and column. Displayed as
//! `origin:line:col: field.path: message`, for example
//! `scenarios/bad.ron:12:5: kinds[0].quota: easy 3 + hard 2 = 5 but count is 6`.

use std::fmt;

use super::model::one_line_text;

/// Where in a scenario source an error is: the origin (file name) and, when known, a 1-based
/// line and column (columns count characters, as ron does). Displayed as `origin:line:col`,
/// the origin escaped by [`one_line_text`] (a line break in a file name is written `\n`).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SourceLocation {
    /// The file path or the name given to [`crate::scenario::from_str`].
    pub origin: String,
    /// 1-based line and column, if known.
    pub line_col: Option<(usize, usize)>,
}

impl fmt::Display for SourceLocation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line_col {
            Some((line, col)) => write!(f, "{}:{}:{}", one_line_text(&self.origin), line, col),
            None => f.write_str(&one_line_text(&self.origin)),
        }
    }
}

/// Why a scenario could not be loaded.
///
/// The `Display` form is one line: `origin[:line:col]: [field.path: ]message`.
#[derive(Debug, thiserror::Error)]
pub enum ScenarioError {
    /// The file could not be read. The I/O error is part of the one-line message (not also a
    /// `source()`, so a chain-printing caller does not repeat it).
    #[error("{}: cannot read scenario file: {error}", one_line_text(path))]
    Io {
        /// The path that was given.
        path: String,
        /// The underlying I/O error.
        error: std::io::Error,
    },
    /// The text is not valid RON or does not have the shape of a scenario spec (unknown or
    /// missing field, wrong type, unknown enum variant, ...). Reported by ron, with position.
    #[error("{location}: {}{message}", field_prefix(field))]
    Syntax {
        /// File and position ron reported.
        location: SourceLocation,
        /// Field path at that position (e.g. `kinds[0].speed` for an unknown field), when it
        /// could be worked out from the source text.
        field: Option<String>,
        /// ron's message (e.g. ``Unexpected field named `speed` in `KindSpec`, expected ...``).
        message: String,
    },
    /// The spec parsed but breaks a rule (counts, ranges, geometry, ...).
    #[error("{location}: {field}: {message}")]
    Invalid {
        /// File and, when the field (or its nearest enclosing field) appears in the source, its
        /// position.
        location: SourceLocation,
        /// Field path, e.g. `kinds[1].quota` or `tasks.hard.search_area`.
        field: String,
        /// What is wrong and what was expected.
        message: String,
    },
}

fn field_prefix(field: &Option<String>) -> String {
    match field {
        Some(f) => format!("{f}: "),
        None => String::new(),
    }
}

impl ScenarioError {
    /// The file path or origin name the error is about.
    pub fn origin(&self) -> &str {
        match self {
            ScenarioError::Io { path, .. } => path,
            ScenarioError::Syntax { location, .. } | ScenarioError::Invalid { location, .. } => {
                &location.origin
            }
        }
    }

    /// 1-based line and column, when known (never for [`ScenarioError::Io`]).
    pub fn line_col(&self) -> Option<(usize, usize)> {
        match self {
            ScenarioError::Io { .. } => None,
            ScenarioError::Syntax { location, .. } | ScenarioError::Invalid { location, .. } => {
                location.line_col
            }
        }
    }

    /// The field path the error is about, when known.
    pub fn field(&self) -> Option<&str> {
        match self {
            ScenarioError::Io { .. } => None,
            ScenarioError::Syntax { field, .. } => field.as_deref(),
            ScenarioError::Invalid { field, .. } => Some(field),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_matches_documented_form() {
        let e = ScenarioError::Invalid {
            location: SourceLocation {
                origin: "scenarios/bad.ron".into(),
                line_col: Some((12, 5)),
            },
            field: "kinds[0].quota".into(),
            message: "easy 3 + hard 2 = 5 but count is 6".into(),
        };
        assert_eq!(
            e.to_string(),
            "scenarios/bad.ron:12:5: kinds[0].quota: easy 3 + hard 2 = 5 but count is 6"
        );
        let e = ScenarioError::Syntax {
            location: SourceLocation {
                origin: "x.ron".into(),
                line_col: Some((1, 2)),
            },
            field: None,
            message: "Expected comma".into(),
        };
        assert_eq!(e.to_string(), "x.ron:1:2: Expected comma");
        assert_eq!(e.line_col(), Some((1, 2)));
        assert_eq!(e.field(), None);
    }

    #[test]
    fn a_path_with_line_breaks_is_shown_on_one_line() {
        let e = ScenarioError::Invalid {
            location: SourceLocation {
                origin: "a\nb\u{2028}c\td.ron".into(),
                line_col: Some((3, 20)),
            },
            field: "arena.width_m".into(),
            message: "expected a finite number > 0, found -1".into(),
        };
        assert_eq!(
            e.to_string(),
            "a\\nb\\u{2028}c\\td.ron:3:20: arena.width_m: expected a finite number > 0, found -1"
        );
        let e = ScenarioError::Io {
            path: "x\ny.ron".into(),
            error: std::io::Error::from(std::io::ErrorKind::NotFound),
        };
        assert!(e.to_string().starts_with("x\\ny.ron: cannot read"), "{e}");
        assert_eq!(one_line_text("plain/path.ron"), "plain/path.ron");
    }
}
