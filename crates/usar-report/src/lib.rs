//! What a sweep of grouping methods over USAR trials becomes, over the sweep library
//! ([`usar_sweep`]): the statistics of its trials ([`analysis::Analysis`]), the paper's claims
//! ([`claims`]) and calibration targets ([`targets`], [`calibration`]) checked against them,
//! and the files written from that analysis: CSV tables ([`csv_tables`],
//! [`grid_outputs::grid_csv`]), figures ([`figures`], [`grid_outputs::grid_figures`]),
//! reports ([`report`], [`grid_outputs::grid_md`]), the terminal summary ([`console`]),
//! [`render`]ed pictures and [`replay`] pages that play one trial in a browser. No command line
//! and no study: `usar_study` (calibration, multiverse) and the `experiments` crate (the `usar`
//! binary) are built on this one.
//!
//! A sweep runs, analysis judges, outputs write: [`usar_sweep::sweep::run_sweep`] returns a
//! `SweepOutcome`; [`analysis::Analysis::of`] computes the statistics and checks the claims
//! once per cell; [`output::write_outputs`] writes every file, atomically, from that analysis.
//!
//! The modules stand in layers; a module imports only from its own layer or the layers below
//! it (and from the sweep library), never from one above (bottom first):
//!
//! 1. base: [`error`], [`stats`], [`paired`] (the paired tests), [`table`], [`chart`], [`source_date`], [`rounds_table`],
//!    [`scenario_summary`] (what `usar check` and `Scenario.check()` show), [`targets`] (the
//!    vocabulary of calibration targets);
//! 2. judge: [`claims`], [`calibration`] (what a report compares with);
//! 3. analyse: [`analysis`];
//! 4. write: [`csv_tables`], [`figures`], [`report`], [`grid_outputs`], [`console`],
//!    [`output`], [`render`], [`replay`].

// 1. base
pub mod chart;
pub mod error;
pub mod paired;
pub mod rounds_table;
pub mod scenario_summary;
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
// Test helpers, for this crate's tests and (feature `testing`) those of the crates above.
#[cfg(any(test, feature = "testing"))]
pub mod testing;

#[cfg(test)]
mod figure_props;
