//! Experiments on the USAR mission: parallel, resumable sweeps of grouping methods over trials
//! (and over grids of scenario values), their analysis and their outputs (tables, figures,
//! reports). The `usar` command line (`src/bin/usar/`: `cli.rs`, one file per subcommand in
//! `commands/`, and what they share in `shared/`) is a thin layer over this library.
//!
//! A sweep runs, analysis judges, outputs write: [`sweep::run_sweep`] runs the trials (of
//! every cell of a [`grid`] built from `--vary` overrides, [`vary`]) into the [`journal`] and
//! returns data ([`data`]); [`analysis::Analysis`] computes the statistics and [`claims`] once
//! per cell; [`output::write_outputs`] writes the CSV files ([`csv_tables`],
//! [`grid_outputs::grid_csv`]), figures ([`figures`], [`grid_outputs::grid_figures`]) and
//! reports ([`report`], [`grid_outputs::grid_md`]), and [`console`] the terminal summary, all
//! from that analysis. A sweep holds the [`lock`] on its output folder while it runs and
//! writes; every output file goes through [`atomic`]. A [`replay`] records one trial while it
//! runs and writes it as a page that plays it in a browser. [`calibrate`] fits free scenario
//! fields to target bands, and [`multiverse`] runs the calibrated comparison in every
//! combination of the paper's open choices.
//!
//! The modules stand in layers; a module imports only from its own layer or the layers below
//! it, never from one above (bottom first):
//!
//! 1. base: [`stats`], [`metrics`], [`table`], [`fingerprint`], [`atomic`], [`lock`],
//!    [`spec_ron`], [`stderr`], [`chart`], [`method_factory`], [`vary`], [`journal`],
//!    [`trial_json`];
//! 2. data: [`data`], the sweep's plan and outcome types, limits and output names;
//! 3. design: [`grid`], the cells of `--vary`;
//! 4. run: `executor`, [`stale_outputs`], [`sweep`], [`shard`], [`slurm`];
//! 5. fit: [`calibrate`], [`calibration`];
//! 6. analyse: [`claims`], [`analysis`];
//! 7. write: [`csv_tables`], [`figures`], [`report`], [`grid_outputs`], [`console`],
//!    [`output`], [`render`], [`replay`];
//! 8. study: [`multiverse`].

// 1. base
pub mod atomic;
pub mod chart;
pub mod fingerprint;
pub mod journal;
pub mod lock;
pub mod method_factory;
pub mod metrics;
pub mod spec_ron;
pub mod stats;
pub mod stderr;
pub mod table;
pub mod trial_json;
pub mod vary;
// 2. data
pub mod data;
// 3. design
pub mod grid;
// 4. run
mod executor;
pub mod shard;
pub mod slurm;
pub mod stale_outputs;
pub mod sweep;
// 5. fit
pub mod calibrate;
pub mod calibration;
// 6. analyse
pub mod analysis;
pub mod claims;
// 7. write
pub mod console;
pub mod csv_tables;
pub mod figures;
pub mod grid_outputs;
pub mod output;
pub mod render;
pub mod replay;
pub mod report;
// 8. study
pub mod multiverse;
