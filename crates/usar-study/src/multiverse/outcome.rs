//! What a multiverse run (or merge) produced ([`MultiverseOutcome`]): data only; the
//! terminal summary ([`super::summary`]) is rendered from it.

use std::path::PathBuf;

use super::plan::MultiversePlan;
use super::record::{Status, UniverseRecord};
use usar_sweep::shard::Shard;

/// What a multiverse run produced.
#[derive(Debug, Clone)]
pub struct MultiverseOutcome {
    /// The multiverse's plan.
    pub plan: MultiversePlan,
    /// The record of every universe of this run (a shard's universes, or all of them), in
    /// universe order.
    pub records: Vec<UniverseRecord>,
    /// The shard this run was (`None`: every universe, and the top files are written).
    pub shard: Option<Shard>,
    /// Universes run (or continued) by this invocation.
    pub ran: usize,
    /// Universes whose record an earlier run had written.
    pub reused: usize,
    /// The files written at the top of the output folder (none for a shard).
    pub files: Vec<PathBuf>,
    /// Wall-clock time of this invocation, seconds.
    pub wall_s: f64,
}

impl MultiverseOutcome {
    /// The universes that failed (calibration error or failed trials): a rerun retries them.
    pub fn failed(&self) -> impl Iterator<Item = &UniverseRecord> {
        self.records.iter().filter(|r| r.status == Status::Failed)
    }

    /// How many of the records are admissible.
    pub fn admissible(&self) -> usize {
        self.records.iter().filter(|r| r.admissible()).count()
    }
}
