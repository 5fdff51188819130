//! [`RefusedSetting`]: the one place that finds, among an error's causes, a setting that a
//! sweep, a calibration or a multiverse refused before it ran, so that each front end (the
//! `usar` command line, the Python package) names the setting's field in its own words from
//! the same list of typed errors.

use std::error::Error;

use usar_sweep::sweep::{ConfigError, SettingError, SweepError};

use crate::calibrate::{CalibrationError, SetupError};
use crate::multiverse::MultiverseError;

/// A setting refused before a run started, as one cause of an error: the field that holds it
/// and what is wrong.
///
/// Found in a sweep plan's [`ConfigError`] (alone or as [`SweepError::Config`]), a study's
/// [`SettingError`], a calibration's [`SetupError::Setting`] (alone or as
/// [`CalibrationError::Setup`]), and a multiverse's [`MultiverseError::Setting`],
/// [`MultiverseError::Sweep`], [`MultiverseError::Calibration`],
/// [`MultiverseError::CalibrationRun`] or [`MultiverseError::SweepRun`] holding one of these.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RefusedSetting {
    /// The field's name in the library (snake case, `_s` for seconds: `max_evals`,
    /// `duration_s`); `None` when the refusal is about several fields at once (too many
    /// trials in all), whose `problem` is then the whole line.
    pub field: Option<&'static str>,
    /// What is wrong: the rest of the line after the field's name, starting with a space or a
    /// colon (`" must be at least 1"`).
    pub problem: String,
}

impl RefusedSetting {
    /// The refused setting that `cause` is, if it is one of the typed errors above (not
    /// looking into its own causes: walk the chain to find one anywhere).
    pub fn of(cause: &(dyn Error + 'static)) -> Option<Self> {
        if let Some(e) = cause.downcast_ref::<ConfigError>() {
            return Some(Self::config(e));
        }
        if let Some(e) = cause.downcast_ref::<SweepError>() {
            return Self::sweep(e);
        }
        if let Some(e) = cause.downcast_ref::<SettingError>() {
            return Some(Self::setting(e));
        }
        if let Some(e) = cause.downcast_ref::<SetupError>() {
            return Self::setup(e);
        }
        if let Some(e) = cause.downcast_ref::<CalibrationError>() {
            return Self::calibration(e);
        }
        match cause.downcast_ref::<MultiverseError>()? {
            MultiverseError::Setting(s) => Some(Self::setting(s)),
            MultiverseError::Sweep(e) => Some(Self::config(e)),
            MultiverseError::Calibration(e) => Self::setup(e),
            MultiverseError::CalibrationRun(e) => Self::calibration(e),
            MultiverseError::SweepRun(e) => Self::sweep(e),
            _ => None,
        }
    }

    /// The line, with the field named by `name` (the identity gives the library's own line,
    /// `max_evals must be at least 1`; `usar` passes the flag of a field).
    pub fn line(&self, name: impl Fn(&str) -> String) -> String {
        format!("{}{}", self.field.map_or(String::new(), name), self.problem)
    }

    fn config(e: &ConfigError) -> Self {
        Self {
            field: e.field().map(|f| f.name()),
            problem: e.problem(),
        }
    }

    fn setting(e: &SettingError) -> Self {
        Self {
            field: Some(e.field()),
            problem: e.problem().to_owned(),
        }
    }

    fn sweep(e: &SweepError) -> Option<Self> {
        match e {
            SweepError::Config(c) => Some(Self::config(c)),
            _ => None,
        }
    }

    fn calibration(e: &CalibrationError) -> Option<Self> {
        match e {
            CalibrationError::Setup(s) => Self::setup(s),
            _ => None,
        }
    }

    fn setup(e: &SetupError) -> Option<Self> {
        match e {
            SetupError::Setting(s) => Some(Self::setting(s)),
            _ => None,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(e: &(dyn Error + 'static)) -> Option<String> {
        RefusedSetting::of(e).map(|r| r.line(|f| format!("<{f}>")))
    }

    #[test]
    fn each_typed_refusal_is_found_and_its_line_is_its_display() {
        let setting = SettingError::new("max_evals", " must be at least 1");
        let config = ConfigError::NoTrials;
        let causes: Vec<(Box<dyn Error>, &str)> = vec![
            (Box::new(config.clone()), "<trials> must be at least 1"),
            (
                Box::new(SweepError::Config(config.clone())),
                "<trials> must be at least 1",
            ),
            (Box::new(setting.clone()), "<max_evals> must be at least 1"),
            (
                Box::new(SetupError::from(setting.clone())),
                "<max_evals> must be at least 1",
            ),
            (
                Box::new(MultiverseError::Setting(setting.clone())),
                "<max_evals> must be at least 1",
            ),
            (
                Box::new(MultiverseError::Sweep(config)),
                "<trials> must be at least 1",
            ),
            (
                Box::new(MultiverseError::Calibration(SetupError::from(
                    setting.clone(),
                ))),
                "<max_evals> must be at least 1",
            ),
            (
                Box::new(CalibrationError::Setup(SetupError::from(setting.clone()))),
                "<max_evals> must be at least 1",
            ),
            (
                Box::new(MultiverseError::CalibrationRun(CalibrationError::Setup(
                    SetupError::from(setting),
                ))),
                "<max_evals> must be at least 1",
            ),
            (
                Box::new(MultiverseError::SweepRun(SweepError::Config(
                    ConfigError::NoTrials,
                ))),
                "<trials> must be at least 1",
            ),
        ];
        for (cause, want) in &causes {
            assert_eq!(line(cause.as_ref()).as_deref(), Some(*want), "{cause:?}");
            let own = RefusedSetting::of(cause.as_ref())
                .unwrap()
                .line(str::to_owned);
            assert_eq!(own, cause.to_string(), "{cause:?}");
        }
    }

    #[test]
    fn a_refusal_of_no_single_field_is_its_whole_problem_and_others_are_not_found() {
        let many = ConfigError::TooManyTrials {
            cells: 2,
            methods: 4,
            trials: 10,
            total: 80,
            limit: 10,
        };
        let found = RefusedSetting::of(&many).unwrap();
        assert_eq!(found.field, None);
        assert_eq!(found.line(|f| format!("<{f}>")), many.to_string());
        let other = SetupError::Invalid("no free field".into());
        assert_eq!(RefusedSetting::of(&other), None);
        assert_eq!(RefusedSetting::of(&std::fmt::Error), None);
    }
}
