//! The studies of the USAR experiments and the `usar` command line, over the sweep library
//! ([`usar_sweep`]) and its outputs ([`usar_report`]): [`calibrate`] fits free scenario fields
//! to target bands, and [`multiverse`] runs the calibrated comparison in every combination of
//! the paper's open choices. The `usar` command line (`src/bin/usar/`: `cli.rs`, one file per
//! subcommand in `commands/`, and what they share in `shared/`) is a thin layer over these
//! libraries.
//!
//! # Entry points
//!
//! - [`calibrate::calibrate`] runs a calibration set up by a [`calibrate::CalibrationSetup`].
//! - [`multiverse::run_multiverse`] runs a multiverse set up by a [`multiverse::MultiverseSetup`].
//!
//! # Features
//!
//! - `cli` (default): the `usar` binary (clap) and the progress bars it draws (indicatif).
//!   Without it (`default-features = false`) the crate is the studies' library alone. A crate
//!   that only runs sweeps depends on `usar-sweep`, one that also writes their tables and
//!   figures on `usar-report`.
//!
//! The modules stand in layers; a module imports only from its own layer or the layers below
//! it (and from the sweep and report libraries), never from one above (bottom first):
//!
//! 1. fit: [`calibrate`];
//! 2. study: [`multiverse`].

// 1. fit
pub mod calibrate;
// 2. study
pub mod multiverse;

#[cfg(test)]
mod figure_props;
