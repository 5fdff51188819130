//! The sweep's records sorted into per-cell outcomes: one slot per (cell, method, trial), the
//! last record of a slot winning.

use std::collections::HashSet;
use std::path::Path;
use usar_sim::scenario::path_text;

use crate::data::jobs::JobId;
use crate::data::outcome::{CellOutcome, Failure};
use crate::journal::{Journal, Outcome, RejectedRecord, SweepHeader, TrialRecord};

/// Where the record of each job goes: one slot per (cell, method, trial).
pub(crate) struct Slots {
    /// The sweep's methods, canonical names in order.
    pub(crate) methods: Vec<String>,
    /// Grid cells.
    pub(crate) cells: usize,
    /// Trials per method and cell.
    pub(crate) trials: u32,
}

impl Slots {
    pub(crate) fn len(&self) -> usize {
        self.cells * self.methods.len() * self.trials as usize
    }

    pub(crate) fn of(&self, cell: usize, method: &str, trial: u32) -> Option<usize> {
        let m = self.methods.iter().position(|x| x == method)?;
        (cell < self.cells && trial < self.trials)
            .then(|| (cell * self.methods.len() + m) * self.trials as usize + trial as usize)
    }

    pub(crate) fn of_record(&self, r: &TrialRecord) -> Option<usize> {
        self.of(r.cell, &r.method, r.trial)
    }
}

/// Warns about each journal line of `dir` that does not verify, with what becomes of its
/// trial: it runs again, it is another shard's (`in_shard` holds this shard's jobs), or it is
/// no trial of this sweep. A line that a later record of its trial (one that verifies)
/// supersedes changes nothing and is not reported.
pub(crate) fn warn_rejected(
    dir: &Path,
    rejected: &[RejectedRecord],
    slots: &Slots,
    records: &[Option<TrialRecord>],
    in_shard: Option<&HashSet<JobId>>,
) {
    for r in rejected {
        let method = slots.methods.iter().position(|m| *m == r.method);
        let owned_elsewhere = |method| {
            let id = JobId {
                cell: r.cell,
                method,
                trial: r.trial,
            };
            in_shard.is_some_and(|own| !own.contains(&id))
        };
        let fate = match (slots.of(r.cell, &r.method, r.trial), method) {
            (Some(i), _) if is_ok(records[i].as_ref()) => continue,
            (Some(_), Some(m)) if owned_elsewhere(m) => {
                "is another shard's (the shard that owns it runs it)"
            }
            (Some(_), _) => "will run again",
            (None, _) => "is not used (no such trial in this sweep)",
        };
        tracing::warn!(
            "{}:{}: record does not verify (edited?); trial {} #{} of cell {} {fate}",
            path_text(&Journal::path_in(dir)),
            r.line,
            r.method,
            r.trial,
            r.cell,
        );
    }
}

pub(crate) fn is_ok(r: Option<&TrialRecord>) -> bool {
    matches!(
        r,
        Some(TrialRecord {
            outcome: Outcome::Ok(_),
            ..
        })
    )
}

/// The per-cell outcomes of the sweep with `header` from journal `records` (in journal
/// order: the last record per `(cell, method, trial)` wins; records of no job of the sweep are
/// left out). Every successful record counts as reused ([`CellOutcome::reused`]).
pub(crate) fn cells_from_records(
    header: &SweepHeader,
    records: Vec<TrialRecord>,
) -> Vec<CellOutcome> {
    let slots = Slots {
        methods: header.methods.clone(),
        cells: header.grid.cells.len(),
        trials: header.trials,
    };
    let mut by_slot: Vec<Option<TrialRecord>> = vec![None; slots.len()];
    for r in records {
        if let Some(i) = slots.of_record(&r) {
            by_slot[i] = Some(r);
        }
    }
    collect(&slots, by_slot, Vec::new())
}

/// Sorts the journal's and this run's records into per-cell outcomes.
pub(crate) fn collect(
    slots: &Slots,
    mut records: Vec<Option<TrialRecord>>,
    new_records: Vec<TrialRecord>,
) -> Vec<CellOutcome> {
    let mut cells = vec![CellOutcome::default(); slots.cells];
    for r in &records {
        if let Some(r) = r.as_ref().filter(|r| is_ok(Some(r))) {
            cells[r.cell].reused += 1;
        }
    }
    for r in new_records {
        let cell = &mut cells[r.cell];
        cell.ran += 1;
        cell.trial_wall_sum_s += r.wall_s;
        if let Some(i) = slots.of_record(&r) {
            records[i] = Some(r);
        }
    }
    for r in records.into_iter().flatten() {
        let cell = &mut cells[r.cell];
        match r.outcome {
            Outcome::Ok(res) => cell.results.push(*res),
            Outcome::Failed(message) => cell.failures.push(Failure {
                cell: r.cell,
                method: r.method,
                trial: r.trial,
                seed: r.seed,
                message,
            }),
        }
    }
    cells
}
