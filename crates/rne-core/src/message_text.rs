//! How every crate's messages write numbers, text and paths: short, on one line, whatever an
//! input holds.
//!
//! [`number_text`] switches to scientific notation outside `[1e-6, 1e15)`; [`one_line_text`]
//! and [`path_text`] escape line breaks and control characters. The error types of every crate
//! of the workspace ([`crate::RneError`], the scenario's and the experiments' errors) and their
//! warnings write values with these.

use std::borrow::Cow;
use std::path::Path;

/// `v` as error and warning messages write a number: plainly (`0.5`, `600`) when its
/// magnitude is in `[1e-6, 1e15)` or it is zero, else in scientific notation (`1e300`, not 301
/// digits; `1e-320`, not 320; `-inf`, `NaN`), so a message stays one short line whatever number
/// an input holds. Used by every crate of the workspace (`usar_sim::scenario` re-exports it).
pub fn number_text(v: f64) -> String {
    if v != 0.0 && !(1e-6..1e15).contains(&v.abs()) {
        format!("{v:e}")
    } else {
        format!("{v}")
    }
}

/// `text` (a value or a path) as error and warning messages write it: a control character (a
/// line break, a tab, an escape) or a Unicode line or paragraph separator escaped as Rust
/// writes it (`\n`, `\t`, `\u{1b}`, `\u{2028}`), every other character as it is, so a message
/// stays one line whatever a file name or a value holds. Escaping twice changes nothing.
pub fn one_line_text(text: &str) -> Cow<'_, str> {
    let breaks = |c: char| c.is_control() || matches!(c, '\u{2028}' | '\u{2029}');
    if !text.chars().any(breaks) {
        return Cow::Borrowed(text);
    }
    let mut out = String::with_capacity(text.len() + 8);
    for c in text.chars() {
        if breaks(c) {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    Cow::Owned(out)
}

/// `path` as error and warning messages write it: as [`Path::display`] shows it, escaped by
/// [`one_line_text`] (a line break in a file name is written `\n`, so the message stays one
/// line).
pub fn path_text(path: &Path) -> String {
    one_line_text(&path.display().to_string()).into_owned()
}

/// `e` and each of its sources in turn, joined by `: ` (`the journal could not be written;
/// the sweep stopped: appending to out/journal.jsonl: No space left on device (os error
/// 28)`): what `{:#}` of an `anyhow::Error` prints, for a caller that keeps a typed error.
pub fn error_line(e: &(dyn std::error::Error + 'static)) -> String {
    let mut line = e.to_string();
    let mut cause = e.source();
    while let Some(c) = cause {
        line.push_str(": ");
        line.push_str(&c.to_string());
        cause = c.source();
    }
    line
}

/// Significant digits past which a number in a message is rewritten: more than an `f64`
/// holds (17), so such a run of digits says nothing a shorter form does not.
const MAX_MESSAGE_DIGITS: usize = 17;

/// `message` with every number of more than 17 digits (`MAX_MESSAGE_DIGITS`) written as
/// [`number_text`] writes it: ron writes a float it found in full (`-1e63` as 64 digits), and
/// so does `{}` of an `f64` (`1e308` as 309 digits). The one pass every file's error
/// messages go through (the scenario's ron errors, the targets', claims' and axes' errors).
pub fn short_numbers(message: &str) -> String {
    let b = message.as_bytes();
    let mut out = String::with_capacity(message.len());
    let (mut copied, mut i) = (0, 0);
    while i < b.len() {
        let end = number_end(b, i);
        if end == i {
            i += 1;
            continue;
        }
        let text = &message[i..end];
        let digits = text.bytes().filter(u8::is_ascii_digit).count();
        if digits > MAX_MESSAGE_DIGITS
            && let Ok(v) = text.parse::<f64>()
        {
            out.push_str(&message[copied..i]);
            out.push_str(&number_text(v));
            copied = end;
        }
        i = end;
    }
    out.push_str(&message[copied..]);
    out
}

/// The end of the number (`-?digits[.digits][e[+-]digits]`) starting at byte `i` of `b`, or
/// `i` when none starts there (nor inside a word: `x12` is a name).
fn number_end(b: &[u8], i: usize) -> usize {
    let starts_word = i > 0 && (b[i - 1].is_ascii_alphanumeric() || b[i - 1] == b'_');
    let digits_from = |j: usize| j + b[j..].iter().take_while(|c| c.is_ascii_digit()).count();
    let j = if b[i] == b'-' { i + 1 } else { i };
    if starts_word || j >= b.len() || !b[j].is_ascii_digit() {
        return i;
    }
    let mut end = digits_from(j);
    if end + 1 < b.len() && b[end] == b'.' && b[end + 1].is_ascii_digit() {
        end = digits_from(end + 1);
    }
    if end + 1 < b.len() && matches!(b[end], b'e' | b'E') {
        let k = if matches!(b[end + 1], b'+' | b'-') {
            end + 2
        } else {
            end + 1
        };
        if k < b.len() && b[k].is_ascii_digit() {
            end = digits_from(k);
        }
    }
    end
}

#[cfg(test)]
mod tests {
    use super::{error_line, number_text, one_line_text, path_text, short_numbers};

    /// An error with a source, as a library's typed error with its cause.
    #[derive(Debug)]
    struct Wrapped(std::fmt::Error);

    impl std::fmt::Display for Wrapped {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.write_str("writing out/a.csv")
        }
    }

    impl std::error::Error for Wrapped {
        fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
            Some(&self.0)
        }
    }

    #[test]
    fn an_error_line_gives_each_cause_after_the_error() {
        let e = Wrapped(std::fmt::Error);
        assert_eq!(
            error_line(&e),
            format!("writing out/a.csv: {}", std::fmt::Error)
        );
        assert_eq!(error_line(&std::fmt::Error), std::fmt::Error.to_string());
    }

    #[test]
    fn text_and_paths_are_written_on_one_line() {
        let cases = [
            ("scenarios/paper.ron", "scenarios/paper.ron"),
            ("a\nb.ron", "a\\nb.ron"),
            ("tab\there\r", "tab\\there\\r"),
            ("esc\u{1b}[1m", "esc\\u{1b}[1m"),
            ("line\u{2028}sep", "line\\u{2028}sep"),
            ("é \\ \"quoted\"", "é \\ \"quoted\""),
        ];
        for (text, shown) in cases {
            assert_eq!(one_line_text(text), shown, "{text:?}");
            assert_eq!(one_line_text(shown), shown, "escaping twice: {shown:?}");
            assert_eq!(path_text(std::path::Path::new(text)), shown);
        }
    }

    #[test]
    fn numbers_are_plain_in_range_and_scientific_outside() {
        let cases = [
            (0.5, "0.5"),
            (600.0, "600"),
            (0.0, "0"),
            (-0.0, "-0"),
            (1e-6, "0.000001"),
            (1e15, "1e15"),
            (1e300, "1e300"),
            (-1e-320, "-1e-320"),
            (f64::INFINITY, "inf"),
            (f64::NAN, "NaN"),
        ];
        for (v, text) in cases {
            assert_eq!(number_text(v), text, "{v}");
        }
    }

    #[test]
    fn numbers_longer_than_an_f64_holds_are_shortened() {
        let long = format!("-1{}", "0".repeat(63));
        let cases = [
            (
                format!("found the floating point number `{long}`"),
                "found the floating point number `-1e63`".to_string(),
            ),
            (format!("a {long}.5e+3 b"), "a -1e66 b".to_string()),
            // Short numbers, digits in names and other text stay as they are.
            (
                "x12345678901234567890 count 2.5 é 7".to_string(),
                "x12345678901234567890 count 2.5 é 7".to_string(),
            ),
            (
                "12345678901234567 of them".to_string(),
                "12345678901234567 of them".to_string(),
            ),
            (
                "123456789012345678 of them".to_string(),
                "1.2345678901234568e17 of them".to_string(),
            ),
        ];
        for (message, short) in cases {
            assert_eq!(short_numbers(&message), short);
        }
    }
}
