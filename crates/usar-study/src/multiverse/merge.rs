//! `usar merge DIR` for a multiverse ([`merge_multiverse`]): once every shard's universes
//! have their records, writes the top files exactly as a run without shards does.

use std::path::Path;
use std::time::Instant;

use super::error::MultiverseError;
use super::folder::plans_in;
use super::outcome::MultiverseOutcome;
use super::outputs::write_outputs;
use super::plan::{MultiversePlan, identity_diff};
use super::record::{RecordRead, UniverseRecord};
use super::universe::{Universe, shard_of};
use super::universe_run::universe_dir;
use usar_sweep::data::owner::{RunKind, check_owner, claim};
use usar_sweep::lock::OutputLock;
use usar_sweep::shard::{Shard, shard_folders};

/// Writes `multiverse.csv`, `multiverse.md` and the figures of the multiverse in `dir` from
/// its universes' records (the same bytes as the run without shards), locking `dir` while it
/// writes. `here` is the folder the suggested commands are run from (for absolute paths when
/// it is not the shards').
///
/// # Errors
/// No plan in `dir`; plans of different multiverses (each odd one named with what differs);
/// a folder, or a shard's folder, of another kind of run ([`usar_sweep::data::owner`]);
/// universes without a record that verifies (listed, with the command of each shard that
/// runs them, or the command without `--shard`, which runs only the missing ones); a folder
/// locked by a running shard; an I/O error. Failed universes are not an error here (the
/// caller reports them).
pub fn merge_multiverse(
    dir: &Path,
    here: Option<&Path>,
) -> Result<MultiverseOutcome, MultiverseError> {
    let t0 = Instant::now();
    if dir.is_dir() {
        check_owner(dir, RunKind::Multiverse)?;
    }
    for (_, shard) in shard_folders(dir)? {
        check_owner(&shard, RunKind::Multiverse)?;
    }
    claim(dir, RunKind::Multiverse)?;
    let _lock = OutputLock::acquire(dir)?;
    let plans = plans_in(dir)?;
    let Some((_, plan)) = plans.first().cloned() else {
        return Err(MultiverseError::NoPlan {
            dir: dir.display().to_string(),
        });
    };
    for (shard, other) in &plans[1..] {
        if other.identity != plan.identity {
            let at = shard.map_or("the top".to_string(), |s| format!("shard {s}"));
            return Err(MultiverseError::MixedPlans {
                dir: dir.display().to_string(),
                at,
                diff: identity_diff(&other.identity, &plan.identity),
            });
        }
    }
    let sum = plan.identity_sum();
    let universes = plan.universes();
    let mut records = Vec::with_capacity(universes.len());
    let mut missing: Vec<(usize, String)> = Vec::new();
    for (j, u) in universes.iter().enumerate() {
        let id = u.id(plan.factorial());
        match UniverseRecord::read(&universe_dir(dir, &id), &sum) {
            RecordRead::Done(r) => records.push(*r),
            RecordRead::Missing => missing.push((j, format!("{id}: not run yet"))),
            RecordRead::Unusable(why) => missing.push((j, why)),
        }
    }
    if !missing.is_empty() {
        let splits: Vec<usize> = plans
            .iter()
            .filter_map(|(s, _)| s.map(|s| s.count))
            .collect();
        return Err(MultiverseError::Missing {
            message: missing_message(&plan, &universes, &missing, &splits, dir, here),
        });
    }
    let files = write_outputs(&plan, &records, dir)?;
    Ok(MultiverseOutcome {
        reused: records.len(),
        plan,
        records,
        shard: None,
        ran: 0,
        files,
        wall_s: t0.elapsed().as_secs_f64(),
    })
}

/// The refusal for `missing` universes (position, why): each named, then the commands of
/// the shards of the one split in `splits` that own them, or else the command without
/// `--shard`.
fn missing_message(
    plan: &MultiversePlan,
    universes: &[Universe],
    missing: &[(usize, String)],
    splits: &[usize],
    dir: &Path,
    here: Option<&Path>,
) -> String {
    let mut counts = splits.to_vec();
    counts.sort_unstable();
    counts.dedup();
    let owner = |j: usize| -> Option<Shard> {
        let &[n] = counts.as_slice() else { return None };
        (0..n)
            .filter_map(|i| Shard::new(i, n).ok())
            .find(|s| shard_of(universes.len(), *s).contains(&j))
    };
    let lines: Vec<String> = missing
        .iter()
        .map(|(j, why)| match owner(*j) {
            Some(s) => format!("  {why} (shard {s})"),
            None => format!("  {why}"),
        })
        .collect();
    let mut shards: Vec<Shard> = missing.iter().filter_map(|(j, _)| owner(*j)).collect();
    shards.sort_by_key(|s| s.index);
    shards.dedup();
    let commands: Vec<String> = if shards.is_empty() {
        vec![format!("  {}", plan.command_at(None, dir, here))]
    } else {
        shards
            .iter()
            .map(|s| format!("  {}", plan.shard_command(*s, dir, here)))
            .collect()
    };
    format!(
        "{} of {} universes are not done, so nothing was merged:\n{}\nrun them (a command \
         continues where it stopped), then merge again:\n{}",
        missing.len(),
        universes.len(),
        lines.join("\n"),
        commands.join("\n")
    )
}
