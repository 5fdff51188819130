//! Running a sweep: every job without a successful record in the journal, through one
//! thread pool, into per-cell outcomes.

use std::collections::HashSet;
use std::sync::Arc;
use std::time::Instant;

use crate::atomic::remove_stale_temps;
use crate::data::config::SweepConfig;
use crate::data::jobs::{JobId, job_list};
use crate::data::outcome::SweepOutcome;
use crate::data::owner::{claim, record_kind};
use crate::error::SweepError;
use crate::executor::{Job, Runner, execute, threads_for};
use crate::journal::TrialRecord;
use crate::lock::OutputLock;
use crate::sweep::checks::check_config;
use crate::sweep::header::header_of;
use crate::sweep::open_journal::open_journal;
use crate::sweep::plans::{cell_plans, job_of};
use crate::sweep::records::{Slots, collect, is_ok, warn_rejected};

/// Runs the sweep (every job without a successful record in the journal) and returns its
/// data. Failed trials do not stop it: they are journaled and listed in
/// [`CellOutcome::failures`](crate::sweep::CellOutcome::failures) (the caller decides the exit status). No file but the journal
/// (and the lock file) is written.
///
/// Once the parameters are checked, it claims the output folder (and a shard's folder) for
/// its kind of run ([`crate::data::owner::claim`]: a folder of another kind is refused, with
/// or without `overwrite`), locks it ([`OutputLock`]; the lock stays in
/// [`SweepOutcome::lock`]) and removes the temporary files killed runs left there and
/// in the cell folders ([`remove_stale_temps`]) before it opens the journal.
///
/// With [`SweepConfig::shard`] it runs only the shard's jobs, and the folder it locks, cleans
/// and journals into is the shard's ([`SweepConfig::journal_dir`]), where it also writes the
/// plan ([`crate::shard::SweepPlan`]) once the journal is open; the outcome holds the shard's
/// records only.
///
/// # Errors
/// Bad parameters, an output folder that is not a folder or belongs to another kind of run
/// ([`crate::data::owner::OwnerError`]), one locked by another sweep, a journal that cannot be started
/// or resumed, or an I/O error writing the journal.
pub fn run_sweep(cfg: &SweepConfig) -> Result<SweepOutcome, SweepError> {
    let header = header_of(cfg)?;
    check_config(cfg, &header)?;
    let plans = cell_plans(cfg, &header)?;
    let dir = cfg.journal_dir();
    let kind = cfg.run_kind();
    claim(&cfg.out_dir, kind)?;
    if dir != cfg.out_dir {
        claim(&dir, kind)?;
    }
    let lock = OutputLock::acquire(&dir)?;
    remove_stale_temps(&dir)?;
    if let (Some(g), None) = (&cfg.grid, &cfg.shard) {
        for cell in &g.cells {
            remove_stale_temps(&cfg.out_dir.join(&cell.dir))?;
        }
    }
    let opened = open_journal(cfg, &dir, &header)?;
    record_kind(&dir, kind)?;
    if let Some(s) = &cfg.shard {
        s.plan.write(&dir)?;
    }
    let in_shard: Option<HashSet<JobId>> = cfg
        .shard
        .as_ref()
        .map(|s| s.shard.jobs(&header).into_iter().collect());

    let slots = Slots {
        methods: header.methods.clone(),
        cells: plans.len(),
        trials: cfg.trials,
    };
    // Last record per (cell, method, trial) wins.
    let mut records: Vec<Option<TrialRecord>> = vec![None; slots.len()];
    for r in opened.records {
        if let Some(i) = slots.of_record(&r) {
            records[i] = Some(r);
        }
    }
    warn_rejected(&dir, &opened.rejected, &slots, &records, in_shard.as_ref());
    let jobs: Vec<Job> = job_list(plans.len(), header.methods.len(), cfg.trials)
        .into_iter()
        .filter(|id| in_shard.as_ref().is_none_or(|own| own.contains(id)))
        .filter(|id| {
            let i = slots.of(id.cell, &header.methods[id.method], id.trial);
            !is_ok(i.and_then(|i| records[i].as_ref()))
        })
        .map(|id| job_of(cfg, &header, id))
        .collect();

    let (threads, inside_trials) = threads_for(cfg.threads, &plans, jobs.len());
    let start = Instant::now();
    let runner = Runner {
        factory: &cfg.method_factory,
        hooks: &cfg.hooks,
        progress: cfg.progress,
        threads,
        inside_trials,
    };
    let new_records = execute(&runner, &plans, &jobs, Some(opened.journal))?;
    let wall_s = start.elapsed().as_secs_f64();
    let ran = new_records.len();
    let trial_wall_sum_s = new_records.iter().map(|r| r.wall_s).sum();
    let cells = collect(&slots, records, new_records);
    Ok(SweepOutcome {
        header,
        reused: cells.iter().map(|c| c.reused).sum(),
        cells,
        journal: opened.how,
        ran,
        wall_s,
        trial_wall_sum_s,
        threads,
        lock: Arc::new(lock),
    })
}
