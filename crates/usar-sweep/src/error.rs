//! [`SweepError`]: why a sweep, a merge of shards or the building of a sweep's header and
//! plans failed, one variant per kind of failure, each the error of the module that found it.

use crate::atomic::FileError;
use crate::data::config_error::ConfigError;
use crate::data::merge_error::MergeError;
use crate::data::owner::OwnerError;
use crate::data::shard_split::ShardError;
use crate::data::sweep_plan::PlanError;
use crate::grid::GridError;
use crate::journal::JournalError;
use crate::lock::LockError;
use crate::method_factory::MethodError;
use crate::settings::Setting;

/// Why a sweep ([`crate::sweep::run_sweep`], [`crate::sweep::run_in_memory`]), a merge
/// ([`crate::shard::merge_shards`]) or the preparation of either failed: one line (with its
/// causes as the error's sources, which an error chain such as `{:#}` of `anyhow` appends).
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    /// A plan refused before any trial runs (no trials, no threads, a method twice, ...).
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// A method that cannot be built, or the scenario's trust model.
    #[error(transparent)]
    Method(#[from] MethodError),
    /// A grid that cannot be built from its `--vary` arguments.
    #[error(transparent)]
    Grid(#[from] GridError),
    /// A journal that cannot be read, continued or written.
    #[error(transparent)]
    Journal(#[from] JournalError),
    /// A shard's plan that cannot be written or read.
    #[error(transparent)]
    Plan(#[from] PlanError),
    /// Shards that cannot be merged.
    #[error(transparent)]
    Merge(#[from] MergeError),
    /// A shard that does not exist (`index >= count`).
    #[error(transparent)]
    Shard(#[from] ShardError),
    /// An output folder of another kind of run, or not a folder.
    #[error(transparent)]
    Owner(#[from] OwnerError),
    /// An output folder locked by another run.
    #[error(transparent)]
    Lock(#[from] LockError),
    /// A file that could not be written or removed, or a folder listed.
    #[error(transparent)]
    File(#[from] FileError),
    /// A scenario (a shard's plan's) that does not load.
    #[error(transparent)]
    Scenario(#[from] usar_sim::scenario::ScenarioError),
    /// A scenario that cannot be written as JSON to hash it (not expected).
    #[error("serialising the scenario")]
    Serialise(#[source] serde_json::Error),
    /// The worker threads could not be started.
    #[error("starting the thread pool")]
    ThreadPool(#[source] rayon::ThreadPoolBuildError),
    /// A record could not be appended to the journal: the sweep stopped (the trials recorded
    /// so far are kept, and a resume runs the rest).
    #[error("the journal could not be written; the sweep stopped")]
    JournalStopped(#[source] JournalError),
    /// A shard run in memory: a shard is a part of a sweep on disk.
    #[error(
        "--shard {index}/{count}: a sweep in memory runs whole; shards are run on disk \
         (run_sweep)"
    )]
    ShardInMemory {
        /// The shard's index.
        index: usize,
        /// Shards in the split.
        count: usize,
    },
    /// A journal in the output folder that this sweep cannot continue or reuse: `why` says
    /// whose it is, `advice` what to do.
    #[error("{path} already exists ({why}): {advice}")]
    JournalExists {
        /// The journal's path, as shown.
        path: String,
        /// Why it cannot be continued (another build, other parameters).
        why: String,
        /// What works instead.
        advice: String,
    },
    /// A shard's journal under the output folder written by another sweep, whose merge would
    /// write into the same folder.
    #[error(
        "{path} is a shard's journal of another sweep ({why}), whose merge writes its files \
         into {dir}: pass {} to start afresh there (the merged files go, the shards stay), \
         or choose another {}",
        Setting::Overwrite,
        Setting::Out
    )]
    OtherSweepsShard {
        /// The shard's journal, as shown.
        path: String,
        /// The differences, or that its header cannot be read.
        why: String,
        /// The output folder, as shown.
        dir: String,
    },
    /// A shard's plan whose sweep cannot be rebuilt: the plan's path, and why as the source.
    #[error("{path}")]
    InPlan {
        /// The plan's path, as shown.
        path: String,
        /// Why its sweep cannot be rebuilt.
        #[source]
        source: Box<SweepError>,
    },
}
