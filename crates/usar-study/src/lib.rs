//! The studies of the USAR experiments, over the sweep library ([`usar_sweep`]) and its outputs
//! ([`usar_report`]): [`calibrate`] fits free scenario fields to target bands, and
//! [`multiverse`] runs the calibrated comparison in every combination of the paper's open
//! choices. The crate has no command line: the `experiments` crate (the `usar` binary, its
//! flags, progress bars and exit codes) is a thin layer over it, and the Python package calls
//! it directly.
//!
//! # Entry points
//!
//! - [`calibrate::calibrate`] runs a calibration set up by a [`calibrate::CalibrationSetup`].
//! - [`multiverse::run_multiverse`] runs a multiverse set up by a [`multiverse::MultiverseSetup`].
//!
//! A refused option is a [`calibrate::SetupError::Setting`] or a
//! [`multiverse::MultiverseError::Setting`] naming the setup's field (`trials must be at least
//! 1`); [`refused_setting::RefusedSetting::of`] finds one (or a sweep plan's) among an error's
//! causes, and a front end names the field its own way (`usar` by its flag, Python by its
//! keyword argument).
//!
//! The modules stand in layers; a module imports only from its own layer or the layers below
//! it (and from the sweep and report libraries), never from one above (bottom first):
//!
//! 1. fit: [`calibrate`];
//! 2. study: [`multiverse`];
//! 3. for the front ends: [`refused_setting`].

// 1. fit
pub mod calibrate;
// 2. study
pub mod multiverse;
// 3. for the front ends
pub mod refused_setting;

#[cfg(test)]
mod figure_props;
