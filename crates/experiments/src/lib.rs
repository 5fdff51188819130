//! Experiments on the USAR mission over the sweep library ([`usar_sweep`]): the analysis of a
//! sweep's results, its outputs (tables, figures, reports, replay pages) and the studies built
//! on sweeps (calibration, multiverse). The `usar` command line (`src/bin/usar/`: `cli.rs`, one
//! file per subcommand in `commands/`, and what they share in `shared/`) is a thin layer over
//! this library and the sweep library.
//!
//! A sweep runs, analysis judges, outputs write: [`usar_sweep::sweep::run_sweep`] runs the
//! trials into the journal and returns data ([`usar_sweep::data`]); [`analysis::Analysis`]
//! computes the statistics and [`claims`] once per cell; [`output::write_outputs`] writes the
//! CSV files ([`csv_tables`], [`grid_outputs::grid_csv`]), figures ([`figures`],
//! [`grid_outputs::grid_figures`]) and reports ([`report`], [`grid_outputs::grid_md`]), and
//! [`console`] the terminal summary, all from that analysis. A [`replay`] records one trial
//! while it runs and writes it as a page that plays it in a browser. [`calibrate`] fits free
//! scenario fields to target bands, and [`multiverse`] runs the calibrated comparison in every
//! combination of the paper's open choices.
//!
//! # Entry points
//!
//! - [`analysis::Analysis::of`] judges a sweep's outcome and [`output::write_outputs`] writes
//!   its tables, figures and report.
//! - [`calibrate`] and [`multiverse`] run the studies built on sweeps.
//!
//! # Features
//!
//! - `cli` (default): the `usar` binary (clap) and the progress bars it draws (indicatif).
//!   Without it (`default-features = false`) the crate is the library alone. A crate that only
//!   runs sweeps depends on `usar-sweep` instead, without plotters, statrs or any of this
//!   crate's dependencies.
//!
//! The modules stand in layers; a module imports only from its own layer or the layers below
//! it (and from the sweep library), never from one above (bottom first):
//!
//! 1. base: [`stats`], [`table`], [`chart`], [`source_date`], [`rounds_table`], [`targets`]
//!    (the vocabulary of calibration targets);
//! 2. judge: [`claims`], [`calibration`] (what a report compares with);
//! 3. analyse: [`analysis`];
//! 4. write: [`csv_tables`], [`figures`], [`report`], [`grid_outputs`], [`console`],
//!    [`output`], [`render`], [`replay`];
//! 5. fit: [`calibrate`];
//! 6. study: [`multiverse`].

// 1. base
pub mod chart;
pub mod rounds_table;
pub mod source_date;
pub mod stats;
pub mod table;
pub mod targets;
// 2. judge
pub mod calibration;
pub mod claims;
// 3. analyse
pub mod analysis;
// 4. write
pub mod console;
pub mod csv_tables;
pub mod figures;
pub mod grid_outputs;
pub mod output;
pub mod render;
pub mod replay;
pub mod report;
// 5. fit
pub mod calibrate;
// 6. study
pub mod multiverse;

#[cfg(test)]
mod figure_props;
