//! [`MultiverseError`]: why a multiverse ([`crate::multiverse::run_multiverse`],
//! [`crate::multiverse::merge_multiverse`]) did not start or finish.

use usar_report::claims::ClaimsError;
use usar_report::error::ReportError;
use usar_sweep::atomic::FileError;
use usar_sweep::data::hooks::Stopped;
use usar_sweep::data::owner::OwnerError;
use usar_sweep::data::setting_error::SettingError;
use usar_sweep::lock::LockError;
use usar_sweep::settings::Setting;
use usar_sweep::sweep::{ConfigError, SweepError};

use super::axes::AxesError;
use super::universe::UniverseError;
use crate::calibrate::{CalibrationError, SetupError};

/// Why a multiverse did not start (its setup refused: the first six variants) or finish: one
/// line (with its cause as the error's source, which an error chain such as `{:#}` of `anyhow`
/// appends). A universe whose scenario breaks a rule, whose calibration errs or whose trials
/// fail is not an error: its record says so and the others run.
#[derive(Debug, thiserror::Error)]
pub enum MultiverseError {
    /// The base scenario, the targets, the free fields or the methods (as a calibration
    /// checks them).
    #[error(transparent)]
    Calibration(#[from] SetupError),
    /// The axes file does not fit the scenario or the free fields.
    #[error(transparent)]
    Axes(#[from] AxesError),
    /// Too many universes, or a bad sample.
    #[error(transparent)]
    Universes(#[from] UniverseError),
    /// A claim names a task the base scenario lacks or a method neither built in nor run.
    #[error(transparent)]
    Claims(#[from] ClaimsError),
    /// An option out of range, named by its field.
    #[error(transparent)]
    Setting(#[from] SettingError),
    /// The sweep of one universe is above the limit of trials.
    #[error(transparent)]
    Sweep(#[from] ConfigError),
    /// `overwrite` with a shard: shards running at the same time would remove each other's
    /// work.
    #[error(
        "{} cannot be used with --shard: shards running at the same time would remove each \
         other's work; remove the output folder (or choose another {}), then run the shards",
        Setting::Overwrite,
        Setting::Out
    )]
    OverwriteShard,
    /// The output folder holds the plan of another multiverse.
    #[error(
        "{plan} holds another multiverse ({diff}): pass {} to start afresh (its universes \
         go), or choose another {}",
        Setting::Overwrite,
        Setting::Out
    )]
    OtherMultiverse {
        /// The plan's path, as shown.
        plan: String,
        /// What differs.
        diff: String,
    },
    /// A merge of a folder without a plan.
    #[error("{dir}: no multiverse plan (multiverse.json) here or in its shard folders")]
    NoPlan {
        /// The folder, as shown.
        dir: String,
    },
    /// A merge of plans of different multiverses.
    #[error(
        "the plans in {dir} are of different multiverses: {at} has {diff}; run that shard again \
         with the others' parameters, or move its folder away"
    )]
    MixedPlans {
        /// The folder, as shown.
        dir: String,
        /// Where the odd plan is (`the top`, `shard 1/4`).
        at: String,
        /// What differs.
        diff: String,
    },
    /// Universes (or design points) without a record that verifies: the message lists them
    /// with the commands that run them.
    #[error("{message}")]
    Missing {
        /// The whole message, on several lines.
        message: String,
    },
    /// A plan file that is not a multiverse plan (edited, or of another version).
    #[error(
        "{path}: not a multiverse plan (edited, or of another version of usar); pass {} to \
         start afresh, or choose another {}",
        Setting::Overwrite,
        Setting::Out
    )]
    NotAPlan {
        /// The plan's path, as shown.
        path: String,
        /// serde_json's error.
        #[source]
        source: serde_json::Error,
    },
    /// A plan or record that cannot be written as JSON (`what`: `the plan`, `a universe
    /// record`, `a design point`; not expected).
    #[error("serialising {what}")]
    Serialise {
        /// What was being written.
        what: &'static str,
        /// The serialiser's error.
        #[source]
        source: serde_json::Error,
    },
    /// The stop flag was set: finished universes keep their records.
    #[error(transparent)]
    Stopped(#[from] Stopped),
    /// A universe's calibration that could not go on (its folder, its lock; a calibration's
    /// own failures are in the universe's record).
    #[error(transparent)]
    CalibrationRun(#[from] CalibrationError),
    /// A universe's comparison sweep that could not go on (its folder, its journal).
    #[error(transparent)]
    SweepRun(#[from] SweepError),
    /// An output (a table, a figure, a file) could not be made or written.
    #[error(transparent)]
    Report(#[from] ReportError),
    /// A file or folder could not be written, listed or removed.
    #[error(transparent)]
    File(#[from] FileError),
    /// The output folder (or a shard's) is another run's, or not a folder.
    #[error(transparent)]
    Owner(#[from] OwnerError),
    /// The output folder is locked by another run.
    #[error(transparent)]
    Lock(#[from] LockError),
}

impl MultiverseError {
    /// Whether the multiverse stopped because its stop flag was set (directly, or inside a
    /// universe's calibration or comparison).
    pub fn is_stopped(&self) -> bool {
        matches!(
            self,
            Self::Stopped(_) | Self::CalibrationRun(CalibrationError::Stopped(_))
        )
    }
}
