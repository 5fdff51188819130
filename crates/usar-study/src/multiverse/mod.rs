//! `usar multiverse`: the paper's method comparison in every *universe*, a combination of one
//! alternative per open choice of the paper (an axis of `AXES.ron`, [`Axes`]).
//!
//! In each universe ([`universe`]: the full factorial, or `--sample N` of it) the free
//! fields are first calibrated to the targets ([`crate::calibrate`]); the universe is
//! *admissible* when its calibration reaches every band (loss 0). Then every method runs its
//! trials on the calibrated scenario ([`usar_sweep::sweep::run_sweep`], common random numbers),
//! and each claim of its claims file gets its verdict and its effect ([`effect`]: the subject
//! minus its strongest rival, with a 95 % Welch interval). Each universe's result is kept as
//! a checksummed record ([`record`]) in its folder, and the top files (`multiverse.csv`,
//! `multiverse.md`, a specification curve per claim) are made from the records alone, so a
//! resumed, sharded ([`run_multiverse`] with `--shard I/N`) and merged
//! ([`merge_multiverse`]) multiverse writes the same bytes as one uninterrupted run.
//!
//! Files depend one way (each imports only from those before it): columns, axes, axis_targets,
//! validate, universe, effect, record, error, setup, plan, design, design_run, emulator,
//! universe_run, tally, conclusions, csv, spec_curve, markdown, emulator_md, outputs, progress,
//! outcome, summary, folder, run, merge.

pub mod axes;
mod axis_targets;
pub mod columns;
pub mod conclusions;
pub mod csv;
pub mod decompose;
pub mod design;
pub mod design_run;
pub mod effect;
pub mod emulator;
pub mod emulator_md;
pub mod error;
pub mod folder;
pub mod markdown;
mod merge;
pub mod outcome;
pub mod outputs;
pub mod plan;
pub mod progress;
pub mod record;
mod run;
pub mod sensitivity_figure;
pub mod sensitivity_md;
pub mod setup;
pub mod spec_curve;
pub mod summary;
pub mod tally;
pub mod universe;
pub mod universe_run;
pub mod validate;

pub use axes::{Alternative, Axes, AxesError, Axis};
pub use effect::{ClaimEffect, claim_effect};
pub use folder::is_multiverse_dir;
pub use merge::merge_multiverse;
pub use outcome::MultiverseOutcome;
pub use plan::{MultiverseIdentity, MultiversePlan};
pub use progress::MultiverseProgress;
pub use record::{Status, UniverseRecord};
pub use run::run_multiverse;
pub use setup::{MultiverseError, MultiverseHooks, MultiverseSetup};
pub use summary::summary_text;
pub use universe::{MAX_UNIVERSES, Sample, Universe, UniverseError};
