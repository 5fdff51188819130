//! Loading: read a RON file, deserialize the [`ScenarioSpec`], validate it into a [`Scenario`].

use std::borrow::Cow;
use std::path::Path;

use ron::error::{Error as RonError, SpannedError};

use super::bounded_read::{BoundedReadError, read_bounded};
use super::context::Ctx;
use super::error::{ScenarioError, SourceLocation};
use super::limits::MAX_SCENARIO_BYTES;
use super::locate::{SourceMap, join};
use super::model::{path_text, short_numbers};
use super::plain_words::{plain_words, shorten};
use super::spec::ScenarioSpec;
use super::suggest::did_you_mean;
use super::validate::validate;
use super::validated::Scenario;

/// Loads and validates the scenario file at `path` (RON, format in `docs/scenario-format.md`).
/// Errors name the path as given ([`path_text`]: on one line).
///
/// # Errors
/// [`ScenarioError::Io`] if the file cannot be read, [`ScenarioError::Syntax`] for RON syntax
/// or shape errors (unknown or missing fields, wrong types), [`ScenarioError::Invalid`] for a
/// broken rule (with field path and, where the field appears, line and column).
pub fn load(path: impl AsRef<Path>) -> Result<Scenario, ScenarioError> {
    let path = path.as_ref();
    from_str(&read_source(path)?, &path_text(path))
}

/// The text of the scenario file at `path`, as [`load`] reads it: at most
/// [`MAX_SCENARIO_BYTES`] bytes (a longer file is refused once it passes the limit, not read
/// into memory; a FIFO, device or folder is refused before it is opened), a leading UTF-8
/// byte-order mark skipped, and UTF-8 checked. Errors name the path as given.
///
/// # Errors
/// [`ScenarioError::Io`] if the file cannot be read, is not a regular file or is longer than
/// the limit,
/// [`ScenarioError::Syntax`] at the line and column of the first byte that is not UTF-8.
pub fn read_source(path: impl AsRef<Path>) -> Result<String, ScenarioError> {
    let path = path.as_ref();
    let origin = path_text(path);
    let io_error = |error| ScenarioError::Io {
        path: origin.clone(),
        error,
    };
    let bytes = read_bounded(path, MAX_SCENARIO_BYTES).map_err(|e| match e {
        BoundedReadError::Io(error) => io_error(error),
        too_long @ BoundedReadError::TooLong { .. } => io_error(std::io::Error::new(
            std::io::ErrorKind::FileTooLarge,
            too_long.to_string(),
        )),
        not_a_file @ BoundedReadError::NotAFile => io_error(std::io::Error::new(
            std::io::ErrorKind::InvalidInput,
            not_a_file.to_string(),
        )),
    })?;
    // The byte-order mark goes first, so a bad byte on line 1 gets its column without it.
    let text = bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(&bytes);
    Ok(utf8(text, &origin)?.to_owned())
}

/// The file's text, or a [`ScenarioError::Syntax`] at the first byte that is not UTF-8 (line
/// and column of that byte; columns count the characters before it, as ron does).
fn utf8<'a>(bytes: &'a [u8], origin: &str) -> Result<&'a str, ScenarioError> {
    std::str::from_utf8(bytes).map_err(|e| {
        let valid = &bytes[..e.valid_up_to()];
        // A line ends at `\n`, or at a `\r` not followed by `\n` (as in [`normalised_source`]).
        let ends_line =
            |i: usize| bytes[i] == b'\n' || (bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n'));
        let line_start = (0..valid.len())
            .rev()
            .find(|&i| ends_line(i))
            .map_or(0, |i| i + 1);
        let line = (0..valid.len()).filter(|&i| ends_line(i)).count() + 1;
        // The prefix is valid UTF-8 by construction.
        let col = std::str::from_utf8(&valid[line_start..]).map_or(1, |s| s.chars().count() + 1);
        ScenarioError::Syntax {
            location: SourceLocation {
                origin: origin.to_owned(),
                line_col: Some((line, col)),
            },
            field: Some(field_open_at_end(std::str::from_utf8(valid).unwrap_or(""))),
            message: format!(
                "byte 0x{:02x} is not UTF-8; scenario files are UTF-8 text",
                bytes[e.valid_up_to()]
            ),
        }
    })
}

/// The field whose value `prefix` (the valid text before a bad byte) leaves open: the
/// innermost bracket's field or element (`kinds[0]`), else `Scenario`.
fn field_open_at_end(prefix: &str) -> String {
    let prefix = normalised_source(prefix);
    let map = SourceMap::build(&prefix);
    match map.innermost_unclosed() {
        Some((path, _)) if !path.is_empty() => path.to_owned(),
        _ => "Scenario".to_owned(),
    }
}

/// `src` without a leading UTF-8 byte-order mark (U+FEFF, which some editors write): ron
/// would reject it, and an editor does not show it, so columns count from after it. A bare
/// `\r` (old Mac line endings) becomes `\n`: ron ends a line, and a `//` comment, only at
/// `\n`, so such a file would fail in its first comment, at line 1. Byte offsets do not
/// change, and `\r\n` is left as it is.
fn normalised_source(src: &str) -> Cow<'_, str> {
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    let bytes = src.as_bytes();
    let bare_cr = |i: usize| bytes[i] == b'\r' && bytes.get(i + 1) != Some(&b'\n');
    if !(0..bytes.len()).any(bare_cr) {
        return Cow::Borrowed(src);
    }
    let lf: Vec<u8> = (0..bytes.len())
        .map(|i| if bare_cr(i) { b'\n' } else { bytes[i] })
        .collect();
    // One ASCII byte replaced by another: still UTF-8.
    Cow::Owned(String::from_utf8(lf).unwrap_or_else(|_| src.to_owned()))
}

/// Line and column (1-based) where the scenario text `src` writes the field `path` (such as
/// `report.claims`), or its nearest ancestor that it writes ([`SourceMap::line_col_of`]),
/// counted as [`from_str`] counts them in its errors (a byte-order mark skipped, bare `\r`
/// line endings read as `\n`); `None` only for a text without a value.
pub fn field_line_col(src: &str, path: &str) -> Option<(usize, usize)> {
    SourceMap::build(&normalised_source(src)).line_col_of(path)
}

/// Parses and validates a scenario from RON text (a leading byte-order mark is skipped).
/// `origin` names the source in errors (a file path, or e.g. `"<inline>"`).
///
/// # Errors
/// As [`load`], without [`ScenarioError::Io`].
pub fn from_str(src: &str, origin: &str) -> Result<Scenario, ScenarioError> {
    let src = normalised_source(src);
    let map = SourceMap::build(&src);
    let spec = parse_with(&src, origin, &map)?;
    validate(
        &spec,
        &Ctx {
            origin,
            map: Some(&map),
        },
    )
}

/// Validates `spec`, parsed from RON text `src` and perhaps changed since (say by
/// command-line overrides), placing a broken rule at the line and column where its field
/// appears in `src` (or its nearest ancestor that does), as [`from_str`] does.
///
/// # Errors
/// [`ScenarioError::Invalid`] for the first broken rule.
pub fn validate_in_source(
    spec: &ScenarioSpec,
    src: &str,
    origin: &str,
) -> Result<Scenario, ScenarioError> {
    let src = normalised_source(src);
    let map = SourceMap::build(&src);
    validate(
        spec,
        &Ctx {
            origin,
            map: Some(&map),
        },
    )
}

/// Parses RON text into the raw, unvalidated [`ScenarioSpec`] (e.g. to change a value, such as
/// a kind's `count`, before [`ScenarioSpec::validate`]).
///
/// # Errors
/// [`ScenarioError::Syntax`] with ron's position and, where it can be worked out, the field
/// path.
pub fn parse_spec(src: &str, origin: &str) -> Result<ScenarioSpec, ScenarioError> {
    let src = normalised_source(src);
    parse_with(&src, origin, &SourceMap::build(&src))
}

fn parse_with(src: &str, origin: &str, map: &SourceMap) -> Result<ScenarioSpec, ScenarioError> {
    ron::Options::default()
        .from_str::<ScenarioSpec>(src)
        .map_err(|e| syntax_error(e, src, origin, map))
}

/// Turns ron's error into a [`ScenarioError::Syntax`], adding the field path found at the
/// error's position (`src` is the text `map` was built from). A number with a fraction where
/// ron read an integer ([`integer_with_fraction`]) is reported at the number's start.
fn syntax_error(mut e: SpannedError, src: &str, origin: &str, map: &SourceMap) -> ScenarioError {
    let pos = e.span.start;
    let offset = map.offset_of(pos.line, pos.col);
    if let Some((field, message)) = cut_short(src, offset, map) {
        return ScenarioError::Syntax {
            location: SourceLocation {
                origin: origin.to_owned(),
                line_col: Some(map.line_col(map.text_end())),
            },
            field: Some(field.unwrap_or_else(|| "Scenario".into())),
            message,
        };
    }
    let here = map.path_at(offset);
    let field = match &e.code {
        RonError::NoSuchStructField { found, .. } => Some(cut_last(child_path(here, found), found)),
        RonError::DuplicateStructField { field, .. } => Some(child_path(here, field)),
        RonError::MissingStructField { field, .. } => {
            Some(join(map.path_within(offset).unwrap_or(""), field))
        }
        _ => here.map(str::to_owned),
    };
    name_single_rest_station(&mut e.code, field.as_deref());
    plain_words(&mut e.code);
    let (line_col, message) = match integer_with_fraction(&e.code, src, offset) {
        Some((start, number)) => (
            map.line_col(start),
            format!("expected an integer, found `{}`", shorten(number)),
        ),
        None if let Some((start, number)) = radix_number(&e.code, src, offset) => (
            map.line_col(start),
            format!(
                "expected a decimal number, found `{}` (hexadecimal, octal and binary \
                 numbers are read for integer fields only)",
                shorten(number)
            ),
        ),
        None => (
            (pos.line, pos.col),
            short_numbers(&e.code.to_string()) + &suggestion(&e.code),
        ),
    };
    ScenarioError::Syntax {
        location: SourceLocation {
            origin: origin.to_owned(),
            line_col: Some(line_col),
        },
        // An error outside every field (a file cut short, a missing `Scenario(`) is about the
        // scenario as a whole.
        field: Some(
            field
                .filter(|f| !f.is_empty())
                .unwrap_or_else(|| "Scenario".into()),
        ),
        message,
    }
}

/// The field and message for a file cut short: the text ends with brackets left open, and
/// ron's error (at byte `offset` of `src`) is one the cut caused, which it says as "Unexpected
/// end of RON" or as what it expected next (`Expected comma`) at the last character. The
/// error is the cut's when closing the open brackets at the end moves ron's error further on
/// (or away). The field is the innermost one still open at the error (none for the top-level
/// value), the message says which bracket is left open; the caller reports it where the text
/// ends. `None` for any other error, reported as ron gives it.
fn cut_short(src: &str, offset: usize, map: &SourceMap) -> Option<(Option<String>, String)> {
    let (path, open) = map.innermost_unclosed()?;
    let mut completed = src.to_owned();
    completed.extend(map.unclosed_closers());
    if let Err(e) = ron::Options::default().from_str::<ScenarioSpec>(&completed) {
        let moved = SourceMap::build(&completed).offset_of(e.span.start.line, e.span.start.col);
        if moved <= offset {
            return None;
        }
    }
    // The field open at the error, when it lies inside the open bracket's (`arena: ` cut
    // before its value is inside the scenario's `(`).
    let field = match map.path_within(offset) {
        Some(p) if p.len() > path.len() && p.starts_with(path) => p,
        _ => path,
    };
    let (line, col) = map.line_col(open);
    let bracket = src[open..].chars().next().unwrap_or('(');
    // The scenario's own bracket: named by the field `Scenario` (the caller's) when no field is
    // open, else in words.
    let whose = match (path.is_empty(), field.is_empty()) {
        (true, true) => "its ",
        (true, false) => "the scenario's ",
        _ => "",
    };
    Some((
        (!field.is_empty()).then(|| field.to_owned()),
        format!("the file ends before {whose}`{bracket}` at {line}:{col} is closed"),
    ))
}

/// "did you mean ...?" for an unknown field or variant whose name is near a valid one.
fn suggestion(code: &RonError) -> String {
    match code {
        RonError::NoSuchStructField {
            expected, found, ..
        }
        | RonError::NoSuchEnumVariant {
            expected, found, ..
        } => did_you_mean(found, expected.iter().copied()),
        _ => String::new(),
    }
}

/// A single-circle `rest_station` is read through a visitor (one circle or a list), so ron
/// names the struct around it, `Scenario`, in a message about one of its fields; the list
/// form's messages name `CircleSpec`, and so does this one's once fixed here. `field` is the
/// field path of the error (`rest_station.colour`).
fn name_single_rest_station(code: &mut RonError, field: Option<&str>) {
    let in_station = field
        .and_then(|f| f.strip_prefix("rest_station."))
        .is_some_and(|name| !name.contains(['.', '[']));
    if !in_station {
        return;
    }
    if let RonError::NoSuchStructField { outer, .. }
    | RonError::MissingStructField { outer, .. }
    | RonError::DuplicateStructField { outer, .. } = code
        && outer.as_deref() == Some("Scenario")
    {
        *outer = Some("CircleSpec".into());
    }
}

/// Where ron read an integer and stopped at a decimal point, the number's byte offset in
/// `src` and its text: `count: 6.0` gives "Expected comma" at the `.`, `seed: Some(2021.0)`
/// "Expected closing `)`". `None` for any other error, or when the `.` at `offset` does not
/// follow an integer's digits (digits after a letter or a `.` belong to a name or a float).
fn integer_with_fraction<'a>(
    code: &RonError,
    src: &'a str,
    offset: usize,
) -> Option<(usize, &'a str)> {
    let bytes = src.as_bytes();
    if !stopped_early(code) || bytes.get(offset) != Some(&b'.') {
        return None;
    }
    let digit_like = |b: &u8| b.is_ascii_digit() || *b == b'_';
    let start = offset
        - bytes[..offset]
            .iter()
            .rev()
            .take_while(|b| digit_like(b))
            .count();
    let before = start.checked_sub(1).map(|i| bytes[i]);
    if start == offset || before.is_some_and(|b| b.is_ascii_alphanumeric() || b == b'.') {
        return None;
    }
    let tail = bytes[offset..]
        .iter()
        .take_while(|b| digit_like(b) || matches!(b, b'.' | b'e' | b'E' | b'+' | b'-'))
        .count();
    src.get(start..offset + tail).map(|number| (start, number))
}

/// Where a number field's value is written with a radix prefix (`0x1E`, `-0o17`, `0b101`),
/// which ron reads for integers only: in a float field it reads the `0` and stops at the
/// prefix's letter, so either the field's range check refuses the `0` at the number ("found
/// 0", a [`RangeError`](super::numbers::RangeError)) or ron expects a comma at the letter.
/// The number's byte offset in `src` and its text; `None` for any other error.
fn radix_number<'a>(code: &RonError, src: &'a str, offset: usize) -> Option<(usize, &'a str)> {
    let bytes = src.as_bytes();
    let prefixed = |i: usize| {
        bytes.get(i) == Some(&b'0')
            && matches!(
                bytes.get(i + 1),
                Some(b'x' | b'X' | b'o' | b'O' | b'b' | b'B')
            )
    };
    let signed = |i: usize| matches!(bytes.get(i), Some(b'+' | b'-'));
    // A field's range check ("expected a finite number > 0, found 0"), not another message
    // of the same form ("expected a name ..., found `0x1`" for an enum's value).
    let range_error = matches!(code, RonError::Message(m)
        if m.split_once(", found ").is_some_and(|(want, _)| want.starts_with("expected ") && want.contains("number")));
    let zero = if range_error && prefixed(offset) {
        offset
    } else if range_error && signed(offset) && prefixed(offset + 1) {
        offset + 1
    } else if stopped_early(code) && offset > 0 && prefixed(offset - 1) {
        offset - 1
    } else {
        return None;
    };
    let start = if zero > 0 && signed(zero - 1) {
        zero - 1
    } else {
        zero
    };
    let before = start.checked_sub(1).map(|i| bytes[i]);
    if before.is_some_and(|b| b.is_ascii_alphanumeric() || b == b'_' || b == b'.') {
        return None;
    }
    let len = 2 + bytes[zero + 2..]
        .iter()
        .take_while(|b| b.is_ascii_alphanumeric() || matches!(b, b'_' | b'.'))
        .count();
    src.get(start..zero + len).map(|number| (start, number))
}

/// Whether ron stopped reading a value early and asked for what follows one (a comma, a
/// closing bracket): the error a number's unread rest gives.
fn stopped_early(code: &RonError) -> bool {
    matches!(
        code,
        RonError::ExpectedComma
            | RonError::ExpectedOptionEnd
            | RonError::ExpectedStructLikeEnd
            | RonError::ExpectedArrayEnd
            | RonError::ExpectedMapEnd
    )
}

/// `path`, which ends with the field name `name`, with that name cut as messages cut it
/// ([`shorten`]): an unknown field of a million characters is not repeated whole.
fn cut_last(path: String, name: &str) -> String {
    match path.strip_suffix(name) {
        Some(parent) if shorten(name) != name => format!("{parent}{}", shorten(name)),
        _ => path,
    }
}

/// The path of field `name` given the innermost path at the error: the path itself if it
/// already ends with the field, otherwise the field inside it.
fn child_path(here: Option<&str>, name: &str) -> String {
    match here {
        Some(p) if p == name || p.ends_with(&format!(".{name}")) => p.to_owned(),
        Some(p) => join(p, name),
        None => name.to_owned(),
    }
}
