//! Plain words for ron's and serde's jargon in scenario errors: `()` instead of "a unit value",
//! "a list `[...]`" instead of "a sequence", and so on, so a message names what to write.

use ron::error::Error as RonError;

/// serde's names of what was found or expected (`serde::de::Unexpected` and the `expecting`
/// texts of derived types), and what a scenario author writes for each. Longest first where
/// one contains another.
const PLAIN: &[(&str, &str)] = &[
    ("a unit value", "`()` (an empty value)"),
    ("unit value", "`()` (an empty value)"),
    ("a unit variant", "a bare name"),
    ("a newtype variant", "a name with one value in brackets"),
    ("a tuple variant", "a name with values in brackets"),
    ("a struct variant", "a name with fields in brackets"),
    ("a newtype struct", "a value in brackets"),
    ("an Option value", "`Some(...)` or `None`"),
    ("option", "`Some(...)` or `None`"),
    ("a sequence", "a list `[...]`"),
    ("sequence", "list `[...]`"),
    ("a map", "a map `{...}`"),
];

/// The most characters of the file's text a message repeats (an unknown name, a wrong
/// value); a longer text is cut there, see [`shorten`].
pub(crate) const SHOWN_TEXT_MAX_CHARS: usize = 60;

/// Rewrites the jargon in `code`'s message in place: the found and expected parts of a
/// wrong-type error, the few bare "Expected ..." errors that name a RON kind of value
/// (`Expected unit`, `Expected option`, `Expected identifier`), ron's advice for its own
/// users (raw identifiers, its recursion limit), and any text of the file it repeats cut to
/// [`SHOWN_TEXT_MAX_CHARS`]. Other errors are left as they are (their words, `Expected
/// comma`, `Expected closing `)``, are plain already).
pub(crate) fn plain_words(code: &mut RonError) {
    match code {
        RonError::InvalidValueForType { expected, found } => {
            *expected = plain(expected);
            // A number is written short later (`short_numbers`); any other text is cut here.
            let number = NUMBER_FOUND.iter().any(|n| found.starts_with(n));
            *found = if number {
                plain(found)
            } else {
                shorten(&plain(found))
            };
        }
        RonError::NoSuchEnumVariant { found, .. } | RonError::NoSuchStructField { found, .. }
            if found.chars().nth(SHOWN_TEXT_MAX_CHARS).is_some() =>
        {
            // ron's wording, with the name cut (ron would quote a cut name as an invalid
            // identifier): said with a placeholder name, which is then replaced.
            let long = std::mem::replace(found, PLACEHOLDER.to_owned());
            let said = code.to_string();
            let quoted = format!("`{PLACEHOLDER}`");
            let said = if said.contains(&quoted) {
                said.replacen(&quoted, &quoted_short(&long), 1)
            } else {
                said.replace(PLACEHOLDER, &shorten(&long))
            };
            *code = RonError::Message(said);
        }
        RonError::InvalidIdentifier(text) | RonError::SuggestRawIdentifier(text) => {
            *code = RonError::Message(format!(
                "expected a name (letters, digits and `_`), found {}",
                quoted_short(text)
            ));
        }
        RonError::NoSuchExtension(name) => {
            *code = RonError::Message(format!("no RON extension named {}", quoted_short(name)));
        }
        RonError::ExpectedDifferentStructName { expected, found } => {
            *code = RonError::Message(format!(
                "Expected struct `{expected}` but found {}",
                quoted_short(found)
            ));
        }
        RonError::ExceededRecursionLimit => {
            *code = RonError::Message(format!("brackets nested more than {RECURSION_LIMIT} deep"));
        }
        RonError::ExpectedUnit => *code = RonError::Message("expected `()`".into()),
        RonError::ExpectedOption => {
            *code = RonError::Message("expected `Some(...)` or `None`".into());
        }
        RonError::ExpectedIdentifier => {
            *code = RonError::Message("expected a name (letters, digits and `_`)".into());
        }
        _ => {}
    }
}

/// ron's default recursion limit (`ron::Options::default()`, which scenarios are read with):
/// how deep brackets may nest.
const RECURSION_LIMIT: usize = 128;

/// `text` whole when at most [`SHOWN_TEXT_MAX_CHARS`] characters long, else its first
/// [`SHOWN_TEXT_MAX_CHARS`] characters, `…` and its length (`CCC… (1000000 characters)`).
pub(crate) fn shorten(text: &str) -> String {
    match text.char_indices().nth(SHOWN_TEXT_MAX_CHARS) {
        None => text.to_owned(),
        Some((cut, _)) => format!("{}… ({} characters)", &text[..cut], text.chars().count()),
    }
}

/// How ron and serde begin the "found" part of a wrong-type error about a number: such a
/// number is written short later (`short_numbers`), not cut here.
const NUMBER_FOUND: &[&str] = &[
    "the unsigned integer",
    "the signed integer",
    "the floating point number",
    "integer ",
    "floating point ",
];

/// A name no scenario field or variant has, standing for a cut one in ron's message.
const PLACEHOLDER: &str = "__name_cut_here__";

/// `text` in backticks when at most [`SHOWN_TEXT_MAX_CHARS`] characters long, else its first
/// [`SHOWN_TEXT_MAX_CHARS`] characters with `…` in backticks and its length after them
/// (`` `CCC…` (1000000 characters) ``).
fn quoted_short(text: &str) -> String {
    match text.char_indices().nth(SHOWN_TEXT_MAX_CHARS) {
        None => format!("`{text}`"),
        Some((cut, _)) => format!("`{}…` ({} characters)", &text[..cut], text.chars().count()),
    }
}

/// `text` with its serde jargon replaced: a whole match of one of [`PLAIN`]'s names (the
/// whole text, or the text's start followed by a space), else `text` unchanged.
fn plain(text: &str) -> String {
    for (jargon, words) in PLAIN {
        if text == *jargon {
            return (*words).to_owned();
        }
        if let Some(rest) = text.strip_prefix(jargon)
            && rest.starts_with(' ')
        {
            return format!("{words}{rest}");
        }
    }
    text.to_owned()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn said(mut code: RonError) -> String {
        plain_words(&mut code);
        code.to_string()
    }

    #[test]
    fn an_empty_value_is_called_brackets_not_a_unit() {
        let m = said(RonError::InvalidValueForType {
            expected: "robots per task by task name".into(),
            found: "a unit value".into(),
        });
        assert_eq!(
            m,
            "Expected robots per task by task name but found `()` (an empty value) instead"
        );
        assert!(!m.contains("unit"), "{m}");
    }

    #[test]
    fn sequences_maps_and_options_are_named_by_their_brackets() {
        let m = said(RonError::InvalidValueForType {
            expected: "a sequence".into(),
            found: "a map".into(),
        });
        assert_eq!(m, "Expected a list `[...]` but found a map `{...}` instead");
        assert_eq!(
            said(RonError::ExpectedOption),
            "expected `Some(...)` or `None`"
        );
        assert_eq!(said(RonError::ExpectedUnit), "expected `()`");
    }

    #[test]
    fn ron_advice_for_programmers_becomes_what_to_write() {
        let m = said(RonError::SuggestRawIdentifier("5".into()));
        assert_eq!(m, "expected a name (letters, digits and `_`), found `5`");
        let m = said(RonError::ExceededRecursionLimit);
        assert_eq!(m, "brackets nested more than 128 deep");
        assert!(!m.contains("serde_stacker"), "{m}");
    }

    #[test]
    fn long_texts_of_the_file_are_cut_in_messages() {
        let long = "C".repeat(1_000_000);
        let m = said(RonError::NoSuchEnumVariant {
            expected: &["Carrier", "Supplier"],
            found: long.clone(),
            outer: Some("Role".into()),
        });
        assert!(m.len() < 200, "{} bytes", m.len());
        assert_eq!(
            m,
            format!(
                "Unexpected variant named `{}…` (1000000 characters) in enum `Role`, \
                 expected either `Carrier` or `Supplier` instead",
                &long[..60]
            )
        );
        let m = said(RonError::InvalidValueForType {
            expected: "a finite number".into(),
            found: format!("the string \"{long}\""),
        });
        assert!(m.len() < 200, "{} bytes", m.len());
        // A string that says "number" is still cut; a number is not (short_numbers writes it).
        let m = said(RonError::InvalidValueForType {
            expected: "a finite number".into(),
            found: format!("the string \"a number {long}\""),
        });
        assert!(m.len() < 200, "{} bytes", m.len());
        let m = said(RonError::InvalidValueForType {
            expected: "a list".into(),
            found: format!("the floating point number `1{}`", "0".repeat(80)),
        });
        assert!(m.contains(&"0".repeat(80)), "{m}");
        for code in [
            RonError::NoSuchExtension(long.clone()),
            RonError::ExpectedDifferentStructName {
                expected: "Arena",
                found: long.clone(),
            },
        ] {
            let m = said(code);
            assert!(m.len() < 200, "{} bytes: {m:.200}", m.len());
            assert!(m.contains("(1000000 characters)"), "{m:.200}");
        }
        let m = said(RonError::InvalidIdentifier(long.clone()));
        assert!(m.len() < 200, "{} bytes", m.len());
        assert_eq!(shorten("carrier"), "carrier");
        assert_eq!(
            shorten(&"é".repeat(60)),
            "é".repeat(60),
            "60 characters, not bytes"
        );
        assert_eq!(
            shorten(&"é".repeat(61)),
            format!("{}… (61 characters)", "é".repeat(60))
        );
    }

    #[test]
    fn plain_texts_and_other_errors_are_left_alone() {
        let m = said(RonError::InvalidValueForType {
            expected: "a finite number".into(),
            found: "the string \"x\"".into(),
        });
        assert_eq!(
            m,
            "Expected a finite number but found the string \"x\" instead"
        );
        assert_eq!(said(RonError::ExpectedComma), "Expected comma");
        // A name that only starts like a jargon word is not rewritten.
        assert_eq!(plain("optional speed"), "optional speed");
    }
}
