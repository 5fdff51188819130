//! The exceptions of the native module and the conversion of library errors into Python
//! exceptions: a bad scenario or argument is a `ValueError` with the library's one-line
//! message, a failed trial a `TrialError`, a grouping method's bad answer a `GroupingError`.

use std::error::Error;

use pyo3::exceptions::{PyRuntimeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use usar_study::refused_setting::RefusedSetting;

pyo3::create_exception!(
    _usar,
    GroupingError,
    PyValueError,
    "A grouping method's answer broke a rule: not one group per task, a robot in no group or \
     in two, an unknown id, or a kind's quota not met. The message names the rule."
);

pyo3::create_exception!(
    _usar,
    TrialError,
    PyRuntimeError,
    "A trial failed while it ran (a grouping method that raised or failed). In a sweep the \
     other trials still ran; the message lists the failed ones."
);

pyo3::create_exception!(
    _usar,
    UsarWarning,
    PyUserWarning,
    "A notice of the libraries: a file the scenario names that is missing (a copy of paper.ron \
     outside the repository: its report leaves out the targets or claims), a figure that \
     could not be drawn, a journal record or calibration trace line that does not verify and \
     runs again. The lines `usar` prints as `warning: ...`, given when the call returns to \
     Python."
);

pyo3::create_exception!(
    _usar,
    ScenarioWarning,
    UsarWarning,
    "A valid scenario whose trials will yield less than it suggests: a task no group can \
     rescue from, or a goal some robots cannot reach from their starts. The lines `usar check` \
     prints as warnings, given when a Scenario is loaded, made from text or edited."
);

/// A `ValueError` with `e`'s message on one line.
pub fn value_error(e: impl std::fmt::Display) -> PyErr {
    PyValueError::new_err(one_line(&e.to_string()))
}

/// A `ValueError` from a library error, its whole chain (the error, then each of its sources)
/// on one line, joined by `: `.
pub fn chain_value_error(e: &(dyn Error + 'static)) -> PyErr {
    PyValueError::new_err(one_line(&rne_core::error_line(e)))
}

/// `e`, then each of its sources in turn.
fn chain<'a>(e: &'a (dyn Error + 'static)) -> impl Iterator<Item = &'a (dyn Error + 'static)> {
    std::iter::successors(Some(e), |&e| e.source())
}

/// A `ValueError` from a library error of a sweep or a study, its whole chain on one line and
/// in the package's words: a refused setting ([`RefusedSetting`]) names its field, which is the
/// keyword argument that sets it, in its own `Display`; every other cause goes through
/// [`python_words`].
pub fn sweep_value_error(e: &(dyn Error + 'static)) -> PyErr {
    let line = chain(e)
        .map(|cause| match RefusedSetting::of(cause) {
            Some(refused) => refused.line(str::to_owned),
            None => python_words(&cause.to_string()),
        })
        .collect::<Vec<_>>()
        .join(": ");
    PyValueError::new_err(one_line(&line))
}

/// `message` (a library error worded for the command line) in the Python package's words:
/// each flag becomes its keyword argument (`--max-evals` `max_evals`, `--duration`
/// `duration_s`, `--max-time` `max_time_s`), and the switches `--overwrite` and `--resume`
/// become `overwrite=True` and `resume=True`.
pub fn python_words(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(at) = rest.find("--") {
        out.push_str(&rest[..at]);
        let after = &rest[at + 2..];
        // A flag starts a word (`runs/my--out` is a path) and a lowercase letter follows.
        let starts_word = !out
            .chars()
            .last()
            .is_some_and(|c| c.is_alphanumeric() || "-_/.".contains(c));
        let len = after
            .find(|c: char| !(c.is_ascii_lowercase() || c == '-'))
            .unwrap_or(after.len());
        let flag = after[..len].trim_end_matches('-');
        if !starts_word || !flag.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push_str("--");
            rest = after;
            continue;
        }
        out.push_str(&match flag {
            "overwrite" | "resume" => format!("{flag}=True"),
            "duration" | "max-time" => format!("{}_s", flag.replace('-', "_")),
            _ => flag.replace('-', "_"),
        });
        rest = &after[flag.len()..];
    }
    out.push_str(rest);
    out
}

/// `text` on one line: line breaks become spaces.
pub fn one_line(text: &str) -> String {
    text.split(['\n', '\r'])
        .map(str::trim_end)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}

#[cfg(test)]
mod tests {
    use super::python_words;

    #[test]
    fn flags_become_keyword_arguments() {
        assert_eq!(
            python_words("--max-evals must be at least 1; pass --overwrite, or --out"),
            "max_evals must be at least 1; pass overwrite=True, or out"
        );
        assert_eq!(python_words("--duration: 0 -- x"), "duration_s: 0 -- x");
        assert_eq!(
            python_words("--max-time --resume"),
            "max_time_s resume=True"
        );
    }
}
