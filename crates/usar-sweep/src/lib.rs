//! The sweep library of the USAR experiments: parallel, resumable sweeps of grouping methods
//! over trials of a scenario (and over grids of scenario values), with nothing of a command
//! line, an analysis or a figure in it. `usar_report` (tables, figures, reports), `usar_study`
//! (calibration, multiverse) and the `usar` binary are built on it; a researcher's own crate
//! can depend on this one alone (docs/library.md, "Depending on the library only").
//!
//! [`sweep::run_sweep`] runs the trials (of every cell of a [`grid`] built from `--vary`
//! overrides, [`vary`]) into the [`journal`] and returns data ([`data`]). A sweep holds the
//! [`lock`] on its output folder while it runs; every file it writes goes through [`atomic`].
//! [`shard`] splits a sweep over machines and merges their journals; [`slurm`] writes the
//! batch scripts that run the shards on a cluster.
//!
//! # Entry points
//!
//! - [`sweep::SweepConfig`] plans a sweep (`SweepConfig::new` gives the defaults of
//!   `usar sweep`); [`sweep::run_in_memory`] runs it and returns the results, with nothing on
//!   disk; [`sweep::run_sweep`] runs it into a journal in its output folder (resumable, locked).
//! - [`sweep::MethodFactory`] adds grouping methods of your own to a sweep.
//! - [`executor`] runs any set of trials in parallel (a sweep's, a calibration's), lending the
//!   threads a sweep's tail leaves idle to its last trials ([`idle_threads`]).
//!
//! Long runs report their progress to a sink the program installs ([`progress`]); the library
//! draws nothing. A plan refused before it runs is a [`sweep::ConfigError`] naming the field
//! of the plan (`trials must be at least 1`), and a study's refused option a
//! [`sweep::SettingError`]; a front end names the field its own way (`usar` by its flag).
//! Every fallible function returns a typed error (`thiserror`): a sweep or a merge an
//! [`error::SweepError`], whose variants are the errors of the modules that found the problem
//! ([`journal::JournalError`], [`grid::GridError`], [`shard::MergeError`],
//! [`atomic::FileError`], ...); [`rne_core::error_line`] prints one with its causes on one
//! line.
//!
//! A sweep of paper.ron in memory:
//!
//! ```
//! use usar_sweep::sweep::{SweepConfig, run_in_memory};
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
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The modules stand in layers; a module imports only from its own layer or the layers below
//! it, never from one above (bottom first):
//!
//! 1. base: [`metrics`], [`fingerprint`], [`atomic`], [`bounded_file`], [`lock`], [`spec_ron`], [`notice`],
//!    [`progress`], [`settings`], [`method_factory`], [`vary`], [`checked_log`], [`journal`],
//!    [`journal_error`], [`trial_json`], [`idle_threads`];
//! 2. data: [`data`], the sweep's plan and outcome types, limits and output names;
//! 3. design: [`grid`], the cells of `--vary`;
//! 4. run: [`error`], [`executor`], [`stale_outputs`], [`sweep`], [`shard`], [`slurm`].

// 1. base
pub mod atomic;
pub mod bounded_file;
pub mod checked_log;
pub mod fingerprint;
pub mod idle_threads;
pub mod journal;
pub mod journal_error;
pub mod lock;
pub mod method_factory;
pub mod metrics;
pub mod notice;
pub mod progress;
pub mod settings;
pub mod spec_ron;
pub mod trial_json;
pub mod vary;
// 2. data
pub mod data;
// 3. design
pub mod grid;
// 4. run
pub mod error;
pub mod executor;
pub mod shard;
pub mod slurm;
pub mod stale_outputs;
pub mod sweep;
