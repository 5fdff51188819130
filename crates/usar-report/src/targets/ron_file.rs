//! Reading a small RON file of the studies (targets, axes, claims): bounded in size, UTF-8,
//! parsed with its source map, every error one line placed at its file, line, column and
//! field ([`Located`], which each file's own error type is made from). A checked list keeps
//! its [`Source`] to place the errors of its later checks.

use std::path::Path;
use std::sync::Arc;

use serde::de::DeserializeOwned;
use usar_sim::scenario::{
    BoundedReadError, SourceLocation, path_text, read_bounded, short_numbers,
};

use usar_sim::scenario::SourceMap;

/// A positioned error of a study file: one line, `origin[:line:col]: [field: ]message[;
/// scenario: SCENARIO]`, a number of more than 17 digits in the message written short
/// ([`short_numbers`]: `1e308`, not 309 digits; the scenario's path as it is). Each kind of
/// file wraps it in its own error type (`TargetsError`, `ClaimsError`, `AxesError`), so that a
/// caller can tell which file was refused.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "{location}: {}{}{}",
    field.as_ref().map(|f| format!("{f}: ")).unwrap_or_default(),
    short_numbers(message),
    scenario.as_ref().map(|s| format!("; scenario: {s}")).unwrap_or_default()
)]
pub struct Located {
    /// The file (as given) and, when known, the line and column.
    pub location: SourceLocation,
    /// The field the error is about, when known.
    pub field: Option<String>,
    /// What is wrong.
    pub message: String,
    /// The scenario (a path as given) the message is about, when it names one: a task the
    /// scenario lacks ([`Located::in_scenario`]); `None` otherwise.
    pub scenario: Option<String>,
}

impl Located {
    /// This error with `; scenario: SCENARIO` after its message: a file's metric about a task
    /// the scenario read from `scenario` (a path as given) lacks, as `usar sweep`, `usar
    /// calibrate` and `usar multiverse` all report it.
    pub fn in_scenario(mut self, scenario: &str) -> Self {
        self.scenario = Some(scenario.to_owned());
        self
    }
}

/// Longest name in a study file, characters: a target's name, an axis's or an
/// alternative's, a claim's sentence and the methods it names. Names are printed in tables,
/// headers and errors, padded to the longest (a name of 65,536 characters could not be
/// padded at all).
pub const MAX_NAME_CHARS: usize = 200;

/// Refuses a name that is empty (or blank), longer than [`MAX_NAME_CHARS`] characters, or
/// holds a control character (a line break would split a table row, a CSV row or an error
/// line); `what` names it in the message (`target`, `axis`, `alternative`).
///
/// # Errors
/// The message, without the field (the caller places it).
pub fn check_name(name: &str, what: &str) -> Result<(), String> {
    if name.trim().is_empty() {
        return Err(format!("empty {what} name: say what it is"));
    }
    let chars = name.chars().count();
    if chars > MAX_NAME_CHARS {
        return Err(format!(
            "{what} name of {chars} characters, longer than the limit of {MAX_NAME_CHARS}"
        ));
    }
    if name.chars().any(char::is_control) {
        return Err(format!(
            "{what} name {name:?} holds a control character (a line break, a tab)"
        ));
    }
    Ok(())
}

/// The text of the file at `path` (and its name as errors give it), at most `max_bytes`
/// long. `kind` names the file for messages with its article: `a targets file`.
///
/// # Errors
/// The file cannot be read, is not a regular file (a FIFO, device or folder: refused before it
/// is opened), is longer than `max_bytes` or is not UTF-8.
pub fn read_text(path: &Path, max_bytes: u64, kind: &str) -> Result<(String, String), Located> {
    let origin = path_text(path);
    let fail = |message: String| Located {
        location: SourceLocation {
            origin: origin.clone(),
            line_col: None,
        },
        field: None,
        message,
        scenario: None,
    };
    let bare = kind.split_once(' ').map_or(kind, |(_, k)| k);
    let bytes = read_bounded(path, max_bytes).map_err(|e| match e {
        BoundedReadError::Io(e) => fail(format!("cannot read {bare}: {e}")),
        not_a_file @ BoundedReadError::NotAFile => {
            fail(format!("cannot read {bare}: {not_a_file}"))
        }
        too_long @ BoundedReadError::TooLong { .. } => fail(format!("{too_long} for {kind}")),
    })?;
    let text = String::from_utf8(bytes)
        .map_err(|_| fail(format!("not UTF-8 text; {kind} is RON text")))?;
    Ok((text, origin))
}

/// `src` (a leading byte-order mark skipped) parsed as a `T`, with its source map; a RON
/// error is placed at ron's line and column and at the field found there, except a missing
/// field, which is placed at the start of the entry that lacks it (`claims[0]: missing field
/// `id``; ron reports it at the entry's closing bracket, which would name its last field).
///
/// # Errors
/// RON syntax or shape (an unknown field or variant, a missing field).
pub fn parse<T: DeserializeOwned>(src: &str, origin: &str) -> Result<(T, Arc<SourceMap>), Located> {
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    let map = Arc::new(SourceMap::build(src));
    let value = ron::Options::default().from_str(src).map_err(|e| {
        let offset = map.offset_of(e.span.start.line, e.span.start.col);
        let at = |line_col, field: Option<&str>, message| Located {
            location: SourceLocation {
                origin: origin.to_owned(),
                line_col: Some(line_col),
            },
            field: field.filter(|f| !f.is_empty()).map(str::to_owned),
            message,
            scenario: None,
        };
        match &e.code {
            ron::Error::MissingStructField { field, .. } => {
                let entry = map.path_within(offset).unwrap_or("");
                let line_col = map.line_col_of(entry).unwrap_or((1, 1));
                at(line_col, Some(entry), format!("missing field `{field}`"))
            }
            code => at(
                (e.span.start.line, e.span.start.col),
                map.path_at(offset),
                code.to_string(),
            ),
        }
    })?;
    Ok((value, map))
}

/// Where a checked list of a study (targets, claims) came from: the origin its errors name
/// (a path as given, or a name given in code) and, for a file, its source map, which places a
/// field at its line and column.
#[derive(Debug, Clone, Default)]
pub struct Source {
    origin: String,
    map: Option<Arc<SourceMap>>,
}

impl Source {
    /// Items given in code, named `origin` in errors (no line numbers).
    pub fn given(origin: &str) -> Self {
        Self {
            origin: origin.to_owned(),
            map: None,
        }
    }

    /// The origin errors name.
    pub fn origin(&self) -> &str {
        &self.origin
    }

    /// An error about `field` (a path such as `targets[2].band`), placed where the field is
    /// in the file when known.
    pub fn error(&self, field: &str, message: String) -> Located {
        Located {
            location: SourceLocation {
                origin: self.origin.clone(),
                line_col: self.map.as_ref().and_then(|m| m.line_col_of(field)),
            },
            field: Some(field.to_owned()),
            message,
            scenario: None,
        }
    }

    /// An error about the whole list (no field, no line).
    pub fn whole_error(&self, message: String) -> Located {
        Located {
            location: SourceLocation {
                origin: self.origin.clone(),
                line_col: None,
            },
            field: None,
            message,
            scenario: None,
        }
    }
}

/// `src` parsed as [`parse`] does, with its [`Source`] named `origin`.
///
/// # Errors
/// As [`parse`].
pub fn parse_with_source<T: DeserializeOwned>(
    src: &str,
    origin: &str,
) -> Result<(T, Source), Located> {
    let (value, map) = parse(src, origin)?;
    let source = Source {
        origin: origin.to_owned(),
        map: Some(map),
    };
    Ok((value, source))
}

/// A study's file kind read through this module (targets, claims, axes): how its top level
/// becomes the checked value, and the checks after parsing. Its `parse` and `load` are
/// [`StudyFile::parse_checked`] and [`StudyFile::load_checked`].
pub trait StudyFile: Sized {
    /// The file's top level as RON writes it (`Targets(targets: [...])`).
    type File: DeserializeOwned;
    /// The kind's own error, made from a [`Located`].
    type Error: From<Located>;
    /// Longest file read, bytes.
    const MAX_BYTES: u64;
    /// The kind with its article, for messages (`a targets file`).
    const KIND: &'static str;

    /// The value of a parsed `file` from `source`, before its checks.
    fn from_file(file: Self::File, source: Source) -> Self;

    /// The checks after parsing, each error placed through the value's [`Source`].
    ///
    /// # Errors
    /// The first check that fails.
    fn check_file(&self) -> Result<(), Self::Error>;

    /// Parses and checks the RON text `src` of a file named `origin` in errors (a leading
    /// byte-order mark is skipped).
    ///
    /// # Errors
    /// RON syntax or shape, at ron's line and column; else the first failed check.
    fn parse_checked(src: &str, origin: &str) -> Result<Self, Self::Error> {
        let (file, source) = parse_with_source(src, origin)?;
        let value = Self::from_file(file, source);
        value.check_file()?;
        Ok(value)
    }

    /// Reads (at most [`StudyFile::MAX_BYTES`]), parses and checks the file at `path`, named
    /// in errors as given.
    ///
    /// # Errors
    /// The file cannot be read, is too long or is not UTF-8; else as
    /// [`StudyFile::parse_checked`].
    fn load_checked(path: &Path) -> Result<Self, Self::Error> {
        let (text, origin) = read_text(path, Self::MAX_BYTES, Self::KIND)?;
        Self::parse_checked(&text, &origin)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scenario_follows_the_message_as_given_and_only_the_message_is_written_short() {
        let (long_number, long_path) = ("1".repeat(30), format!("runs/{}/s.ron", "9".repeat(20)));
        let e = Source::given("t.ron").error("targets[0].task", format!("{long_number} m"));
        let plain = e.to_string();
        assert!(plain.starts_with("t.ron: targets[0].task: "), "{plain}");
        assert!(!plain.contains(&long_number), "{plain}");
        let text = e.in_scenario(&long_path).to_string();
        assert_eq!(text, format!("{plain}; scenario: {long_path}"));
    }
}
