//! `usar merge DIR`: the journals of a sweep's shards (`DIR/shards/<I>-of-<N>/`) combined into
//! one [`SweepOutcome`], from which `usar_report::output::write_outputs` writes the same CSV
//! files as the sweep run on one machine (the records are the same, and every output is
//! built from records sorted by cell, method order and trial).
//!
//! Before anything is combined, every shard of the split must be there, all journals must
//! have the same header (the sweep's, equal to the one the plan's configuration gives) and
//! every job must have a record: a shard with no journal, or with jobs it has not finished, is
//! named with the command that runs it again ([`MergeError::Incomplete`]). Failed trials do
//! not stop a merge (as they do not stop a sweep); [`Merged::failed_shards`] names the shards
//! to run again.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use usar_sim::scenario::{one_line_text, path_text};

use crate::atomic::remove_stale_temps;
pub use crate::data::merge_error::{MergeError, UnfinishedShard};
use crate::data::owner::{RunKind, check_owner, claim};
use crate::data::shard_folders::{SHARDS_DIR, shard_dir, shard_folders};
use crate::data::shard_split::{Shard, job_costs_ms, split, sweep_jobs};
use crate::data::sweep_plan::SweepPlan;
use crate::error::SweepError;
use crate::journal::JournalError;
use crate::journal::{
    Journal, Outcome, RejectedRecord, SweepHeader, TrialRecord, header_diff, holds_no_line,
    other_sweeps, read_journal, something_at,
};
use crate::journal_error::START_AFRESH;
use crate::lock::OutputLock;
use crate::sweep::{JournalUse, SweepConfig, SweepOutcome, cells_from_records, header_of};

/// What the functions of this module return.
type Result<T> = std::result::Result<T, SweepError>;

/// The merged sweep.
#[derive(Debug, Clone)]
pub struct Merged {
    /// The sweep's configuration, rebuilt from the plan, with the merge's output folder.
    pub config: SweepConfig,
    /// The plan (of the lowest shard whose journal has the sweep's header).
    pub plan: SweepPlan,
    /// The outcome: the sweep's header, every record of every shard; it holds the lock on
    /// the output folder. Every trial counts as reused ([`SweepOutcome::ran`] is 0).
    pub outcome: SweepOutcome,
    /// The shard count of the split.
    pub count: usize,
    /// Record lines that do not verify, with their journal (they were left out), but for
    /// those whose trial has a record that verifies in any shard's journal (the shard ran
    /// the trial again, or the line is a copy of another shard's trial): those change
    /// nothing.
    pub rejected: Vec<(PathBuf, RejectedRecord)>,
    /// Shards with failed trials, by index: their command ([`SweepPlan::shard_command`])
    /// retries them.
    pub failed_shards: Vec<Shard>,
}

/// The shards under `dir/shards/`, of one split (a misnamed folder there is refused,
/// [`shard_folders`]).
fn find_split(dir: &Path) -> Result<usize> {
    let counts: BTreeSet<usize> = shard_folders(dir)?.iter().map(|(s, _)| s.count).collect();
    match counts.len() {
        0 => Err(MergeError::NoShards {
            dir: dir.to_path_buf(),
        }
        .into()),
        1 => Ok(counts.into_iter().next().unwrap_or(1)),
        _ => Err(MergeError::MixedSplits {
            dir: dir.to_path_buf(),
            counts: counts.into_iter().collect(),
        }
        .into()),
    }
}

/// One shard's journal as found: `None` when the shard has none.
struct ShardJournal {
    shard: Shard,
    dir: PathBuf,
    contents: Option<crate::journal::JournalContents>,
}

fn read_shards(dir: &Path, count: usize) -> Result<Vec<ShardJournal>> {
    (0..count)
        .map(|i| {
            let shard = Shard::new(i, count)?;
            let sdir = shard_dir(dir, shard);
            let path = Journal::path_in(&sdir);
            // A journal killed before its header was whole holds no trial: as none.
            let contents = if something_at(&path) && !holds_no_line(&path) {
                Some(read_journal(&path).map_err(|e| damaged_shard(e, shard, &sdir, dir))?)
            } else {
                None
            };
            Ok(ShardJournal {
                shard,
                dir: sdir,
                contents,
            })
        })
        .collect()
}

/// A shard journal that cannot be used: the journal's message, with its advice to run the
/// sweep afresh (`--overwrite` in place of `--resume`, which `usar merge` does not have) made
/// the shard's own command, from the shard's plan where it has one.
fn damaged_shard(e: JournalError, shard: Shard, shard_dir: &Path, dir: &Path) -> SweepError {
    if !e.says_start_afresh() {
        return e.into();
    }
    let text = e.to_string();
    let here = std::env::current_dir().ok();
    let again = match SweepPlan::read(shard_dir) {
        Ok(plan) => format!(
            "run shard {shard} again from scratch: {} --overwrite",
            plan.shard_command(shard, dir, here.as_deref())
        ),
        Err(_) => format!(
            "run shard {shard} again from scratch with `usar sweep ... --shard {shard} --overwrite`"
        ),
    };
    // The command holds the scenario's and the folder's paths: one line whatever they hold.
    MergeError::DamagedShard {
        shard,
        message: text.replace(&START_AFRESH.to_string(), &one_line_text(&again)),
    }
    .into()
}

/// The header most shard journals have (ties: the one of the lowest shard); `None` when no
/// shard has a journal.
fn majority_header(shards: &[ShardJournal]) -> Option<&SweepHeader> {
    let mut seen: Vec<(&SweepHeader, usize)> = Vec::new();
    for c in shards.iter().filter_map(|s| s.contents.as_ref()) {
        match seen.iter_mut().find(|(h, _)| *h == &c.header) {
            Some((_, n)) => *n += 1,
            None => seen.push((&c.header, 1)),
        }
    }
    // max_by_key keeps the last of equal counts: reversed, the first seen wins a tie.
    seen.into_iter()
        .rev()
        .max_by_key(|&(_, n)| n)
        .map(|(h, _)| h)
}

/// The sweep's plan, its configuration and its header, which every shard's journal must
/// have. The plan is that of the lowest shard whose journal has the header most shards have
/// (the odd ones out are then named as such), or of the lowest shard with a plan. `here` is
/// the folder the commands of [`MergeError::OtherSweep`] are shown in.
fn plan_and_header(
    dir: &Path,
    shards: &[ShardJournal],
    here: Option<&Path>,
) -> Result<(SweepPlan, SweepConfig, SweepHeader)> {
    let majority = majority_header(shards);
    let with_plan = |s: &&ShardJournal| s.contents.is_some() && SweepPlan::path_in(&s.dir).exists();
    let Some(first) = shards
        .iter()
        .filter(with_plan)
        .find(|s| s.contents.as_ref().map(|c| &c.header) == majority)
        .or_else(|| shards.iter().find(with_plan))
    else {
        return Err(MergeError::NoPlan {
            shards_dir: dir.join(SHARDS_DIR),
        }
        .into());
    };
    let plan = SweepPlan::read(&first.dir)?;
    let config = super::plan_config::plan_config(&plan, dir).map_err(|e| SweepError::InPlan {
        path: path_text(&SweepPlan::path_in(&first.dir)),
        source: Box::new(e),
    })?;
    let mut header = header_of(&config)?;
    // The shards must share one build, not that of the binary that merges (which runs no
    // trial): the first shard's sets it.
    if let Some(c) = &first.contents {
        header.build.clone_from(&c.header.build);
    }
    // Each shard whose journal has another header, with the differences.
    let odd_of = |s: &ShardJournal| {
        let c = s.contents.as_ref().filter(|c| c.header != header)?;
        Some((s.shard, header_diff(&c.header, &header)))
    };
    if let Some((shard, diff)) = odd_of(first) {
        // The plan does not give its own shard's header: the plan was edited.
        return Err(MergeError::PlanMismatch {
            shard,
            shard_dir: first.dir.clone(),
            diff,
        }
        .into());
    }
    let odd: Vec<(Shard, String)> = shards
        .iter()
        .filter_map(|s| {
            odd_of(s).map(|(shard, diff)| (shard, format!("{}: {diff}", path_text(&s.dir))))
        })
        .collect();
    if odd.is_empty() {
        return Ok((plan, config, header));
    }
    Err(MergeError::OtherSweep {
        count: shards.len(),
        commands: odd
            .iter()
            .map(|(s, _)| format!("{} --overwrite", plan.shard_command(*s, dir, here)))
            .collect(),
        odd,
    }
    .into())
}

/// Refuses to merge into `dir` when its own journal (`dir/journal.jsonl`, of a sweep run
/// there without `--shard`) is another sweep's than the shards': the merge would write over
/// that sweep's files and mix the two.
fn refuse_other_sweeps_journal(dir: &Path, header: &SweepHeader) -> Result<()> {
    let path = Journal::path_in(dir);
    let Some(why) = other_sweeps(&path, header) else {
        return Ok(());
    };
    Err(MergeError::OtherSweepsJournal {
        journal: path,
        dir: dir.to_path_buf(),
        why,
    }
    .into())
}

/// What each shard lacks: no journal, or jobs with no record that verifies (a job whose only
/// record in the shard's journal does not verify names that record's line).
fn unfinished(
    header: &SweepHeader,
    shards: &[ShardJournal],
    records: &[TrialRecord],
) -> Vec<UnfinishedShard> {
    let count = shards.len();
    let jobs = sweep_jobs(header);
    let owners = split(&job_costs_ms(header, &jobs), count);
    let has = |cell: usize, method: &str, trial: u32| {
        records.iter().any(|r| r.key() == (cell, method, trial))
    };
    let mut out = Vec::new();
    for s in shards {
        if s.contents.is_none() {
            out.push(UnfinishedShard {
                shard: s.shard,
                why: match Journal::path_in(&s.dir) {
                    p if something_at(&p) => {
                        format!("its journal holds no trial ({})", path_text(&p))
                    }
                    p => format!("no journal ({})", path_text(&p)),
                },
            });
            continue;
        }
        let own: Vec<_> = jobs
            .iter()
            .zip(&owners)
            .filter(|&(_, &o)| o == s.shard.index)
            .map(|(j, _)| j)
            .collect();
        let rejected = s.contents.as_ref().map_or(&[][..], |c| &c.rejected[..]);
        let lacking: Vec<String> = own
            .iter()
            .filter(|j| !has(j.cell, &header.methods[j.method], j.trial))
            .map(|j| {
                let method = &header.methods[j.method];
                let edited = rejected
                    .iter()
                    .rfind(|r| r.key() == (j.cell, method.as_str(), j.trial))
                    .map_or(String::new(), |r| {
                        format!(": its record on line {} does not verify (edited?)", r.line)
                    });
                format!("{method} #{} of cell {}{edited}", j.trial, j.cell)
            })
            .collect();
        if !lacking.is_empty() {
            let shown: Vec<&str> = lacking.iter().take(5).map(String::as_str).collect();
            let more = if lacking.len() > 5 { ", ..." } else { "" };
            out.push(UnfinishedShard {
                shard: s.shard,
                why: format!(
                    "{} of its {} trials have no record that verifies ({}{more})",
                    lacking.len(),
                    own.len(),
                    shown.join(", ")
                ),
            });
        }
    }
    out
}

/// Merges the shards of the sweep whose output folder is `dir`: reads every shard's journal,
/// checks it, and returns the sweep's configuration and outcome for the analysis and the
/// output files. Every shard's folder and `dir` must belong to a sharded sweep (or to no run
/// yet: [`crate::data::owner`]). It claims and locks `dir` ([`OutputLock`], held by the outcome) and removes the
/// temporary files killed writers left there and in the cell folders.
///
/// # Errors
/// [`MergeError`] (no shards, shards of two splits, shards that ran another sweep than the
/// rest, unfinished shards: nothing is merged then), a plan that does not match its shard's
/// journal, a journal of another sweep at the top of `dir` (the differences are listed), a
/// damaged journal or plan, a folder of another kind of run, a locked `dir`, or an I/O error.
pub fn merge_shards(dir: &Path) -> Result<Merged> {
    check_owners(dir)?;
    let count = find_split(dir)?;
    let shards = read_shards(dir, count)?;
    // The folder the suggested commands are shown in (see `SweepPlan::shard_command`).
    let here = std::env::current_dir().ok();
    let (plan, config, header) = plan_and_header(dir, &shards, here.as_deref())?;
    refuse_other_sweeps_journal(dir, &header)?;
    let mut records = Vec::new();
    let mut rejected = Vec::new();
    for s in &shards {
        if let Some(c) = &s.contents {
            records.extend(c.records.iter().cloned());
            let path = Journal::path_in(&s.dir);
            rejected.extend(c.rejected.iter().map(|r| (path.clone(), r.clone())));
        }
    }
    // A line whose trial has a record that verifies (a later one of the same journal, after
    // the shard ran it again, or the owning shard's) changes nothing; only the others are
    // left out of the merge with a warning.
    rejected.retain(|(_, r)| !records.iter().any(|k| k.key() == r.key()));
    let unfinished = unfinished(&header, &shards, &records);
    if !unfinished.is_empty() {
        let commands = unfinished
            .iter()
            .map(|u| plan.shard_command(u.shard, dir, here.as_deref()))
            .collect();
        return Err(MergeError::Incomplete {
            count,
            unfinished,
            commands,
        }
        .into());
    }
    claim(dir, RunKind::ShardedSweep)?;
    let lock = OutputLock::acquire(dir)?;
    remove_stale_temps(dir)?;
    if let Some(g) = &config.grid {
        for cell in &g.cells {
            remove_stale_temps(&dir.join(&cell.dir))?;
        }
    }
    let failed_shards = failed_shards(&header, count, &records);
    let cells = cells_from_records(&header, records);
    let outcome = SweepOutcome {
        header,
        reused: cells.iter().map(|c| c.reused).sum(),
        cells,
        journal: JournalUse::Merged,
        ran: 0,
        wall_s: 0.0,
        trial_wall_sum_s: 0.0,
        threads: 1,
        lock: Arc::new(lock),
    };
    Ok(Merged {
        config,
        plan,
        outcome,
        count,
        rejected,
        failed_shards,
    })
}

/// Refuses to merge `dir` when it, or one of its shards' folders, belongs to another kind of
/// run than a sharded sweep ([`crate::data::owner`]): a multiverse's shards, say, are merged
/// as a multiverse's, never as a sweep's.
fn check_owners(dir: &Path) -> Result<()> {
    if dir.is_dir() {
        check_owner(dir, RunKind::ShardedSweep)?;
    }
    for (_, shard) in shard_folders(dir)? {
        check_owner(&shard, RunKind::ShardedSweep)?;
    }
    Ok(())
}

/// The shards (by index) whose jobs' last records include a failure.
fn failed_shards(header: &SweepHeader, count: usize, records: &[TrialRecord]) -> Vec<Shard> {
    let jobs = sweep_jobs(header);
    let owners = split(&job_costs_ms(header, &jobs), count);
    let mut failed = BTreeSet::new();
    for (j, owner) in jobs.iter().zip(owners) {
        let last = records
            .iter()
            .rev()
            .find(|r| r.key() == (j.cell, header.methods[j.method].as_str(), j.trial));
        if let Some(TrialRecord {
            outcome: Outcome::Failed(_),
            ..
        }) = last
        {
            failed.insert(owner);
        }
    }
    failed
        .into_iter()
        .filter_map(|i| Shard::new(i, count).ok())
        .collect()
}
