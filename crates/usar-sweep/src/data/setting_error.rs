//! [`SettingError`]: a setting of a run (a sweep's, a calibration's, a multiverse's) refused
//! before the run starts, named by the field that holds it, so that each front end can name
//! that field in its own words.

/// A setting refused before a run starts: the field that holds it, by its name in the
/// library (snake case, `_s` for seconds: `max_evals`, `duration_s`), and what is wrong.
///
/// Its `Display` is one line, the field's name then the problem: `max_evals must be at least
/// 1`. The field's name is also the Python package's keyword argument, so the package shows
/// the line as it is; `usar` writes the flag that sets the field instead of its name
/// (`--max-evals must be at least 1`).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{field}{problem}")]
pub struct SettingError {
    field: &'static str,
    problem: String,
}

impl SettingError {
    /// The refusal of `field` for `problem`, the rest of the line after the field's name: it
    /// starts with a space or a colon (`" must be at least 1"`, `": expected FIELD=LO..HI"`).
    pub fn new(field: &'static str, problem: impl Into<String>) -> Self {
        Self {
            field,
            problem: problem.into(),
        }
    }

    /// The field's name (`max_evals`).
    pub fn field(&self) -> &'static str {
        self.field
    }

    /// What is wrong: the rest of the line after the field's name.
    pub fn problem(&self) -> &str {
        &self.problem
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_is_the_field_then_the_problem() {
        let e = SettingError::new("max_evals", " must be at least 1");
        assert_eq!(e.to_string(), "max_evals must be at least 1");
        assert_eq!(
            (e.field(), e.problem()),
            ("max_evals", " must be at least 1")
        );
    }
}
