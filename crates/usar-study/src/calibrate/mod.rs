//! `usar calibrate`: fit free scenario fields so that statistics of a sweep of the scenario
//! fall inside the bands of a targets file.
//!
//! A calibration ([`calibrate`], set up by [`CalibrationSetup`]) searches the free fields
//! ([`FreeField`], `--free FIELD=LO..HI[:log][,factor]`) with Nelder-Mead ([`optimizer`]) or
//! CMA-ES ([`cma_es`]) on normalised coordinates; each point is an [`evaluate`]d sweep (every method x trials from
//! one base seed, in parallel) whose [`Statistic`]s, pooled over methods, give the [`loss()`]
//! against the [`Targets`] (`TARGETS.ron`, [`usar_report::targets`]). Every evaluation is appended to
//! the checksummed [`trace`] as it ends, so a killed calibration continues where it stopped;
//! at the end the [`outputs`] are written atomically: `calibrated.ron`, `trace.csv`,
//! `calibration.md`, `convergence.svg`, `statistics.svg` and `tradeoff.svg`.
//!
//! Files depend one way (each imports only from those before it, and from the targets'
//! vocabulary below, [`usar_report::targets`]): loss, free, trial_plan, setup, trace_error,
//! error, evaluate, optimizer, cma_es, trace, outcome, figure, targets_figure, tradeoff_figure,
//! progress, markdown, outputs, searcher, run, summary.

pub mod cma_es;
pub mod error;
pub mod evaluate;
pub mod figure;
pub mod free;
pub mod loss;
pub mod markdown;
pub mod optimizer;
pub mod outcome;
pub mod outputs;
pub mod progress;
mod run;
mod searcher;
pub mod setup;
pub mod summary;
pub mod targets_figure;
pub mod trace;
pub mod trace_error;
pub mod tradeoff_figure;
pub mod trial_plan;

pub use error::CalibrationError;
pub use evaluate::{Evaluation, Evaluator, TrialSet};
pub use free::{FreeError, FreeField, parse_free, round_significant};
pub use loss::{loss, target_loss};
pub use optimizer::{Optimizer, StopReason};
pub use outcome::{CalibrationOutcome, CheckOutcome, TargetCheck};
pub use progress::{EvaluationHook, Progress};
pub use run::calibrate;
pub use setup::{CalibrationSetup, Checked, SetupError};
pub use summary::summary_text;
pub use trial_plan::TrialPlan;
// The targets it fits to (a vocabulary below the calibration, `usar_report::targets`).
pub use usar_report::targets::{Band, MetricRef, Statistic, Target, Targets, TargetsError};
