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
//! # Entry points
//!
//! - [`sweep::SweepConfig`] plans a sweep (`SweepConfig::new` gives the defaults of
//!   `usar sweep`); [`sweep::run_in_memory`] runs it and returns the results, with nothing on
//!   disk; [`sweep::run_sweep`] runs it into a journal in its output folder (resumable, locked).
//! - [`sweep::MethodFactory`] adds grouping methods of your own to a sweep.
//! - With feature `outputs`: `analysis::Analysis::of` judges a sweep's outcome and
//!   `output::write_outputs` writes its tables, figures and report; `calibrate` and
//!   `multiverse` run the studies built on sweeps.
//!
//! # Features
//!
//! - `cli` (default): the `usar` binary (clap) and the progress bars it draws (indicatif);
//!   implies `outputs`.
//! - `outputs`: the analysis, the written outputs (CSV, figures, reports, replay pages), the
//!   calibration and the multiverse (statrs, csv, plotters, flate2, base64, argmin,
//!   humantime, rand). The modules that need them are left out without it.
//!
//! Long runs report their progress to a sink the program installs ([`progress`]); the library
//! draws nothing.
//!
//! With `default-features = false` the crate is the sweep library alone (config, parallel
//! trials, journal, grids, shards, results and the metric columns), none of those
//! dependencies. A sweep of paper.ron in memory, on either:
//!
//! ```
//! use experiments::sweep::{SweepConfig, run_in_memory};
//!
//! # let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
//! let scenario = usar_sim::scenario::load(path)?; // path: "scenarios/paper.ron"
//! let cfg = SweepConfig {
//!     methods: vec!["rne".into(), "dis".into()],
//!     trials: 2,
//!     duration_s: Some(10.0),
//!     threads: 2,
//!     progress: false,
//!     ..SweepConfig::new(scenario, path)
//! };
//! let results = run_in_memory(&cfg)?;
//! assert_eq!(results.failures().count(), 0);
//! // Sorted as trials.csv: method order, then trial; the same seeds for every method.
//! let trials: Vec<(&str, u32)> = results.results().map(|r| (r.method.as_str(), r.trial)).collect();
//! assert_eq!(trials, [("RNE", 0), ("RNE", 1), ("DIS", 0), ("DIS", 1)]);
//! # Ok::<(), anyhow::Error>(())
//! ```
//!
//! The modules stand in layers; a module imports only from its own layer or the layers below
//! it, never from one above (bottom first):
//!
//! 1. base: [`stats`], [`metrics`], [`table`], [`fingerprint`], [`atomic`], [`lock`],
//!    [`spec_ron`], [`stderr`], [`progress`], [`chart`], [`method_factory`], [`vary`],
//!    [`checked_log`], [`journal`], [`trial_json`];
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
#[cfg(feature = "outputs")]
pub mod chart;
pub mod checked_log;
pub mod fingerprint;
pub mod journal;
pub mod lock;
pub mod method_factory;
pub mod metrics;
pub mod progress;
pub mod spec_ron;
#[cfg(feature = "outputs")]
pub mod stats;
pub mod stderr;
#[cfg(feature = "outputs")]
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
#[cfg(feature = "outputs")]
pub mod calibrate;
#[cfg(feature = "outputs")]
pub mod calibration;
// 6. analyse
#[cfg(feature = "outputs")]
pub mod analysis;
#[cfg(feature = "outputs")]
pub mod claims;
// 7. write
#[cfg(feature = "outputs")]
pub mod console;
#[cfg(feature = "outputs")]
pub mod csv_tables;
#[cfg(feature = "outputs")]
pub mod figures;
#[cfg(feature = "outputs")]
pub mod grid_outputs;
#[cfg(feature = "outputs")]
pub mod output;
#[cfg(feature = "outputs")]
pub mod render;
#[cfg(feature = "outputs")]
pub mod replay;
#[cfg(feature = "outputs")]
pub mod report;
#[cfg(feature = "outputs")]
pub mod rounds_table;
// 8. study
#[cfg(feature = "outputs")]
pub mod multiverse;

#[cfg(all(test, feature = "outputs"))]
mod figure_props;
