//! Experiments on the USAR mission: parallel, resumable sweeps of grouping methods over trials
//! (and over grids of scenario values), their analysis and their outputs (tables, figures,
//! reports). The `usar` command line (`src/bin/usar/`: `cli.rs` and one file per subcommand in
//! `commands/`) is a thin layer over this library.
//!
//! A sweep runs, analysis judges, outputs write: [`sweep::run_sweep`] runs the trials (of
//! every cell of a [`grid`] built from `--vary` overrides, [`vary`]) into the [`journal`] and
//! returns data; [`analysis::Analysis`] computes the statistics and [`claims`] once per cell;
//! [`output::write_outputs`] writes the CSV files ([`summary`], [`grid_outputs::csv`]),
//! figures ([`figures`], [`grid_outputs::figures`]) and reports ([`report`],
//! [`grid_outputs::report`]), and [`console`] the terminal summary, all from that analysis.
//! Module dependencies go one way: vary, grid -> sweep (with executor, journal) -> analysis
//! (with claims, metrics, stats) -> outputs. A sweep holds the [`lock`] on its output folder
//! while it runs and writes; every output file goes through [`atomic`]. A [`replay`] records
//! one trial while it runs and writes it as a page that plays it in a browser. [`calibrate`]
//! fits free scenario fields to target bands, and [`multiverse`] runs the calibrated
//! comparison in every combination of the paper's open choices.

pub mod analysis;
pub mod atomic;
pub mod calibrate;
pub mod calibration;
pub mod chart;
pub mod claims;
pub mod console;
pub mod data;
mod executor;
pub mod figures;
pub mod fingerprint;
pub mod grid;
pub mod grid_outputs;
pub mod journal;
pub mod lock;
pub mod method_factory;
pub mod metrics;
pub mod multiverse;
pub mod output;
pub mod render;
pub mod replay;
pub mod report;
pub mod shard;
pub mod slurm;
pub mod spec_ron;
pub mod stale_outputs;
pub mod stats;
pub mod stderr;
pub mod summary;
pub mod sweep;
pub mod table;
pub mod vary;
