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

/// Rewrites the jargon in `code`'s message in place: the found and expected parts of a
/// wrong-type error and the few bare "Expected ..." errors that name a RON kind of value
/// (`Expected unit`, `Expected option`, `Expected identifier`). Other errors are left as they
/// are (their words, `Expected comma`, `Expected closing `)``, are plain already).
pub(crate) fn plain_words(code: &mut RonError) {
    match code {
        RonError::InvalidValueForType { expected, found } => {
            *expected = plain(expected);
            *found = plain(found);
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
