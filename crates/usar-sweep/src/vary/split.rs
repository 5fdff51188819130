//! Splitting a `--vary` value list on its top-level commas.

/// Splits `text` on the commas that are not inside `()`, `[]`, `{}` or a double-quoted string
/// (where `\"` does not end the string), trimming each part.
///
/// `0.1,(1.0, 2.0),"a,b"` gives `["0.1", "(1.0, 2.0)", "\"a,b\""]`. An empty text gives one
/// empty part; empty parts are kept (the caller reports them).
///
/// # Errors
/// Unbalanced brackets (a closing bracket without its opening one, or one left open) or an
/// unterminated string, with the offending character's 1-based position.
pub fn split_top_level(text: &str) -> Result<Vec<String>, String> {
    let mut parts = Vec::new();
    let mut open: Vec<(char, usize)> = Vec::new();
    let mut in_string: Option<usize> = None;
    let mut escaped = false;
    let mut start = 0;
    for (pos, (i, c)) in text.char_indices().enumerate() {
        if in_string.is_some() {
            match (escaped, c) {
                (true, _) => escaped = false,
                (false, '\\') => escaped = true,
                (false, '"') => in_string = None,
                _ => {}
            }
            continue;
        }
        match c {
            '"' => in_string = Some(pos + 1),
            '(' | '[' | '{' => open.push((c, pos + 1)),
            ')' | ']' | '}' => {
                let want = match c {
                    ')' => '(',
                    ']' => '[',
                    _ => '{',
                };
                match open.pop() {
                    Some((o, _)) if o == want => {}
                    _ => return Err(format!("unmatched '{c}' at character {}", pos + 1)),
                }
            }
            ',' if open.is_empty() => {
                parts.push(text[start..i].trim().to_string());
                start = i + 1;
            }
            _ => {}
        }
    }
    if let Some(at) = in_string {
        return Err(format!("string opened at character {at} is not closed"));
    }
    if let Some((c, at)) = open.pop() {
        return Err(format!("'{c}' at character {at} is not closed"));
    }
    parts.push(text[start..].trim().to_string());
    Ok(parts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn splits_only_top_level_commas() {
        assert_eq!(
            split_top_level("0.1, (1.0, 2.0) ,\"a,b\",[1,2],Some((3, 4))").unwrap(),
            ["0.1", "(1.0, 2.0)", "\"a,b\"", "[1,2]", "Some((3, 4))"]
        );
        assert_eq!(
            split_top_level(r#"{"hard": 2, "easy": 4},{hard: 3, easy: 3}"#).unwrap(),
            [r#"{"hard": 2, "easy": 4}"#, "{hard: 3, easy: 3}"]
        );
        assert!(split_top_level("{a: (1}").is_err());
        assert_eq!(split_top_level("5").unwrap(), ["5"]);
        assert_eq!(split_top_level("").unwrap(), [""]);
        assert_eq!(split_top_level("1,,2").unwrap(), ["1", "", "2"]);
        assert_eq!(
            split_top_level(r#""say \"hi, there\"",x"#).unwrap(),
            [r#""say \"hi, there\"""#, "x"]
        );
    }

    #[test]
    fn reports_unbalanced_text() {
        assert_eq!(
            split_top_level("(1, 2").unwrap_err(),
            "'(' at character 1 is not closed"
        );
        assert_eq!(
            split_top_level("1)").unwrap_err(),
            "unmatched ')' at character 2"
        );
        assert_eq!(
            split_top_level("(1]").unwrap_err(),
            "unmatched ']' at character 3"
        );
        assert_eq!(
            split_top_level("\"ab, c").unwrap_err(),
            "string opened at character 1 is not closed"
        );
    }
}
