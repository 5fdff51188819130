//! Why the shards of a sweep cannot be merged (`crate::shard::merge_shards`): [`MergeError`].

use std::fmt::Write as _;
use std::path::PathBuf;

use usar_sim::scenario::path_text;

use crate::data::shard_folders::SHARDS_DIR;
use crate::data::shard_split::Shard;
use crate::data::sweep_plan::PLAN_FILE;

/// A shard that is not done.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct UnfinishedShard {
    /// The shard.
    pub shard: Shard,
    /// What is missing, e.g. `no journal (DIR/shards/1-of-4/journal.jsonl)` or `2 of its 3
    /// trials have no record that verifies (RNE #1 of cell 0, DIS #0 of cell 0: its record on
    /// line 2 does not verify (edited?))`.
    pub why: String,
}

/// Why shards cannot be merged.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum MergeError {
    /// No folder `shards/<I>-of-<N>` under the output folder.
    #[error(
        "{}: no shards to merge (no folder {SHARDS_DIR}/<I>-of-<N>); run the shards first with \
         `usar sweep SCENARIO ... --shard I/N --out {}`",
        path_text(dir),
        path_text(dir)
    )]
    NoShards {
        /// The output folder.
        dir: PathBuf,
    },
    /// Shard folders of different splits (`0-of-4` next to `0-of-8`).
    #[error(
        "{}: shards of different splits ({}); a merge takes the shards of one split: move the \
         other folders away",
        path_text(dir),
        counts.iter().map(|n| format!("N = {n}")).collect::<Vec<_>>().join(", ")
    )]
    MixedSplits {
        /// The output folder.
        dir: PathBuf,
        /// The shard counts found, ascending.
        counts: Vec<usize>,
    },
    /// Shards whose journals are of another sweep than most shards' (another seed, trial
    /// count, scenario, ...): the rest of the split cannot be merged with them.
    #[error("{}", other_sweep_message(.count, .odd, .commands))]
    OtherSweep {
        /// The shard count of the split.
        count: usize,
        /// The odd shards, by index, each with its journal's differences from the sweep
        /// (`DIR/shards/0-of-3: journal has trials 8 vs 7`).
        odd: Vec<(Shard, String)>,
        /// The command that runs each of them afresh as a shard of the sweep, in the same
        /// order.
        commands: Vec<String>,
    },
    /// Shards with no journal or with jobs that have no record that verifies.
    #[error("{}", incomplete_message(.count, .unfinished, .commands))]
    Incomplete {
        /// The shard count of the split.
        count: usize,
        /// The shards that are not done, by index.
        unfinished: Vec<UnfinishedShard>,
        /// The command that runs each of them (again), in the same order.
        commands: Vec<String>,
    },
    /// No shard has both a journal and a plan.
    #[error(
        "{}: no shard has both a journal and a {PLAN_FILE} (run the shards with `usar sweep \
         ... --shard I/N`)",
        path_text(shards_dir)
    )]
    NoPlan {
        /// The folder of the shards (`DIR/shards`).
        shards_dir: PathBuf,
    },
    /// A shard's plan that does not give its own journal's header: the folder was edited or
    /// mixes two sweeps.
    #[error(
        "shard {shard} ({}): {}: the plan does not match the shard's journal ({diff}); the \
         folder was edited or mixes two sweeps",
        path_text(shard_dir),
        path_text(&shard_dir.join(PLAN_FILE))
    )]
    PlanMismatch {
        /// The shard.
        shard: Shard,
        /// Its folder.
        shard_dir: PathBuf,
        /// The differences between the journal's header and the plan's.
        diff: String,
    },
    /// The output folder's own journal (of a sweep run there without `--shard`) is another
    /// sweep's than the shards': merging would mix the two.
    #[error(
        "{} is the journal of another sweep than the shards' ({why}), whose files are in {}: \
         merging would mix the two; move that journal and its files away, or run the shards \
         with another --out",
        path_text(journal),
        path_text(dir)
    )]
    OtherSweepsJournal {
        /// The journal.
        journal: PathBuf,
        /// The output folder.
        dir: PathBuf,
        /// The differences, or that its header cannot be read.
        why: String,
    },
    /// A shard's journal that cannot be used: the journal's message, its advice to start
    /// afresh made the shard's own command.
    #[error("{message}")]
    DamagedShard {
        /// The shard.
        shard: Shard,
        /// The whole line.
        message: String,
    },
}

fn incomplete_message(
    count: &usize,
    unfinished: &[UnfinishedShard],
    commands: &[String],
) -> String {
    let mut m = format!(
        "{} of {count} shards are not done, so nothing was merged:",
        unfinished.len()
    );
    for u in unfinished {
        let _ = write!(m, "\n  shard {}: {}", u.shard, u.why);
    }
    m.push_str("\nrun them (a shard's command continues its journal), then merge again:");
    for c in commands {
        let _ = write!(m, "\n  {c}");
    }
    m
}

fn other_sweep_message(count: &usize, odd: &[(Shard, String)], commands: &[String]) -> String {
    let mut m = format!(
        "{} of {count} shards ran another sweep than the rest, so nothing was merged:",
        odd.len()
    );
    for (shard, why) in odd {
        let _ = write!(m, "\n  shard {shard} ({why})");
    }
    m.push_str("\nrun them afresh as shards of the sweep, then merge again:");
    for c in commands {
        let _ = write!(m, "\n  {c}");
    }
    m
}
