//! What a sweep produced: per-cell results and failures, how the journal was come by, and
//! timings ([`SweepOutcome`]). Data only: the analysis (`usar_report::analysis`) judges it and
//! `usar_report::output` writes the files.

use std::sync::Arc;

use usar_sim::mission::TrialResult;

use crate::journal::SweepHeader;
use crate::lock::OutputLock;

/// A trial that failed.
#[derive(Debug, Clone, PartialEq)]
pub struct Failure {
    /// Grid cell index.
    pub cell: usize,
    /// Method (display name).
    pub method: String,
    /// Trial index.
    pub trial: u32,
    /// The trial's seed.
    pub seed: u64,
    /// The error or panic message.
    pub message: String,
}

/// What a sweep produced in one grid cell.
#[derive(Debug, Clone, Default)]
pub struct CellOutcome {
    /// Successful trials, sorted by method order then trial.
    pub results: Vec<TrialResult>,
    /// Failed trials, in the same order.
    pub failures: Vec<Failure>,
    /// Trials of this cell run by this invocation.
    pub ran: usize,
    /// Successful trials of this cell taken from the journal of an earlier run.
    pub reused: usize,
    /// Sum of the wall-clock times of this invocation's trials of this cell, seconds.
    pub trial_wall_sum_s: f64,
}

/// How the sweep came by its journal.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JournalUse {
    /// A new journal (none was there, or `--overwrite` removed it).
    Created,
    /// `--resume` continued the journal.
    Resumed,
    /// A journal with the same parameters was there and was continued as with `--resume`
    /// (running the same command twice).
    Reused,
    /// The records come from the journals of the sweep's shards (`usar merge`,
    /// [`crate::shard::merge_shards`]).
    Merged,
}

/// What a sweep produced: data only (see `usar_report::analysis` and `usar_report::output`).
#[derive(Debug, Clone)]
pub struct SweepOutcome {
    /// The journal header (the sweep's parameters and grid).
    pub header: SweepHeader,
    /// Per grid cell, in cell order.
    pub cells: Vec<CellOutcome>,
    /// How the journal was come by.
    pub journal: JournalUse,
    /// Trials run by this invocation.
    pub ran: usize,
    /// Successful trials taken from the journal of an earlier run.
    pub reused: usize,
    /// Wall-clock time of this invocation's trials, seconds.
    pub wall_s: f64,
    /// Sum of the wall-clock times of this invocation's trials, seconds (CPU-ish time).
    pub trial_wall_sum_s: f64,
    /// Threads used ([`sweep_threads`](crate::sweep::sweep_threads)).
    pub threads: usize,
    /// The lock on the output folder ([`crate::lock`]), held while this outcome (or a clone of
    /// it) lives, so that the files written from it are written under the same lock.
    pub lock: Arc<OutputLock>,
}

impl SweepOutcome {
    /// Simulated seconds run by this invocation.
    pub fn simulated_s(&self) -> f64 {
        self.cells
            .iter()
            .zip(&self.header.grid.cells)
            .map(|(c, h)| c.ran as f64 * h.duration_s)
            .sum()
    }

    /// Every failed trial, by cell, method order and trial.
    pub fn failures(&self) -> impl Iterator<Item = &Failure> {
        self.cells.iter().flat_map(|c| &c.failures)
    }

    /// Trials the sweep has in all: cells x methods x trials.
    pub fn expected_trials(&self) -> usize {
        self.header.grid.cells.len() * self.header.methods.len() * self.header.trials as usize
    }
}
