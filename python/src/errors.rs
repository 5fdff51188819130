//! The exceptions of the native module and the conversion of library errors into Python
//! exceptions: a bad scenario or argument is a `ValueError` with the library's one-line
//! message, a failed trial a `TrialError`, a grouping method's bad answer a `GroupingError`.

use std::error::Error;

use pyo3::exceptions::{PyRuntimeError, PyUserWarning, PyValueError};
use pyo3::prelude::*;
use usar_study::refused_setting::RefusedSetting;
use usar_sweep::settings::Setting;

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
/// keyword argument that sets it; every other message names its settings through
/// [`keyword`], installed as the libraries' namer ([`usar_sweep::settings::set_namer`]).
pub fn sweep_value_error(e: &(dyn Error + 'static)) -> PyErr {
    let line = chain(e)
        .map(|cause| match RefusedSetting::of(cause) {
            Some(refused) => refused.line(str::to_owned),
            None => cause.to_string(),
        })
        .collect::<Vec<_>>()
        .join(": ");
    PyValueError::new_err(one_line(&line))
}

/// A setting as the package names it in messages: its keyword argument (`max_evals`,
/// `duration_s`, `out`), and `overwrite=True` or `resume=True` for a switch.
pub fn keyword(setting: Setting) -> String {
    if setting.is_switch() {
        format!("{}=True", setting.field())
    } else {
        setting.field().to_string()
    }
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
    use super::keyword;
    use usar_sweep::settings::Setting;

    #[test]
    fn settings_are_keyword_arguments() {
        assert_eq!(keyword(Setting::MaxEvals), "max_evals");
        assert_eq!(keyword(Setting::DurationS), "duration_s");
        assert_eq!(keyword(Setting::Overwrite), "overwrite=True");
        assert_eq!(keyword(Setting::Out), "out");
    }
}
