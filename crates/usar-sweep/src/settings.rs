//! [`Setting`]: a run's setting as the libraries' messages name it, in the words of the
//! front end that runs them: `usar` names a flag (`pass --overwrite to start afresh`), the
//! Python package a keyword argument (`pass overwrite=True to start afresh`).
//!
//! A message never spells a flag: it writes a [`Setting`] (`format!("pass {}",
//! Setting::Overwrite)`), whose `Display` asks the process's namer ([`set_namer`], installed
//! once by a front end; without one, the command line's flag, [`Setting::flag`]). Commands
//! written into files (a shard's command line, a Slurm script, a multiverse's plan) are
//! `usar` commands and spell their flags themselves.

use std::fmt;
use std::sync::OnceLock;

/// A setting that a message names.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Setting {
    /// The output folder.
    Out,
    /// Discard the output folder's earlier run and start afresh (a switch).
    Overwrite,
    /// Continue the journaled sweep (a switch).
    Resume,
    /// Trials per method.
    Trials,
    /// The trial length, seconds.
    DurationS,
    /// A calibration's budget of evaluations.
    MaxEvals,
    /// A calibration's budget of time, seconds.
    MaxTimeS,
    /// A calibration's free fields.
    Free,
    /// A grid's varied fields.
    Vary,
    /// A multiverse's sample of universes.
    Sample,
    /// The targets file.
    Targets,
    /// The claims file.
    Claims,
    /// Targets shown but not fitted.
    ReportOnly,
    /// Targets that must be met.
    Require,
    /// A check's trials after a calibration.
    CheckTrials,
    /// A multiverse's loss below which a universe counts as near.
    NearLoss,
}

impl Setting {
    /// The field's name in the libraries, which is also the Python package's keyword
    /// argument: snake case, `_s` for seconds (`max_evals`, `duration_s`, `out`).
    pub fn field(self) -> &'static str {
        match self {
            Self::Out => "out",
            Self::Overwrite => "overwrite",
            Self::Resume => "resume",
            Self::Trials => "trials",
            Self::DurationS => "duration_s",
            Self::MaxEvals => "max_evals",
            Self::MaxTimeS => "max_time_s",
            Self::Free => "free",
            Self::Vary => "vary",
            Self::Sample => "sample",
            Self::Targets => "targets",
            Self::Claims => "claims",
            Self::ReportOnly => "report_only",
            Self::Require => "require",
            Self::CheckTrials => "check_trials",
            Self::NearLoss => "near_loss",
        }
    }

    /// The `usar` flag that sets it: `--` and the field with `-` for `_`, but `--duration`
    /// and `--max-time` for the seconds.
    pub fn flag(self) -> &'static str {
        match self {
            Self::Out => "--out",
            Self::Overwrite => "--overwrite",
            Self::Resume => "--resume",
            Self::Trials => "--trials",
            Self::DurationS => "--duration",
            Self::MaxEvals => "--max-evals",
            Self::MaxTimeS => "--max-time",
            Self::Free => "--free",
            Self::Vary => "--vary",
            Self::Sample => "--sample",
            Self::Targets => "--targets",
            Self::Claims => "--claims",
            Self::ReportOnly => "--report-only",
            Self::Require => "--require",
            Self::CheckTrials => "--check-trials",
            Self::NearLoss => "--near-loss",
        }
    }

    /// Whether it is a switch, on or off (`overwrite`, `resume`), rather than a value.
    pub fn is_switch(self) -> bool {
        matches!(self, Self::Overwrite | Self::Resume)
    }
}

/// How a front end names a setting in messages.
pub type Namer = fn(Setting) -> String;

static NAMER: OnceLock<Namer> = OnceLock::new();

/// Installs the process's namer of settings. Once per process: a front end calls it at
/// start, before any message is made.
///
/// # Errors
/// A namer is installed already (the new one is handed back, unused).
pub fn set_namer(namer: Namer) -> Result<(), Namer> {
    NAMER.set(namer)
}

/// The setting as the installed namer words it, or its flag without one.
impl fmt::Display for Setting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match NAMER.get() {
            Some(name) => f.write_str(&name(*self)),
            None => f.write_str(self.flag()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn without_a_namer_a_setting_is_its_flag() {
        // No test of this crate installs a namer.
        assert_eq!(
            format!(
                "pass {}, or choose another {}",
                Setting::Overwrite,
                Setting::Out
            ),
            "pass --overwrite, or choose another --out"
        );
        assert_eq!(Setting::DurationS.to_string(), "--duration");
        assert_eq!(
            (Setting::MaxTimeS.field(), Setting::MaxTimeS.flag()),
            ("max_time_s", "--max-time")
        );
        assert!(Setting::Resume.is_switch() && !Setting::Out.is_switch());
    }
}
