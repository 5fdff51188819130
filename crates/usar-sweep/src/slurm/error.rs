//! Why Slurm scripts were not written ([`crate::slurm::write_scripts`]) or submitted
//! ([`crate::slurm::submit()`]): [`SlurmError`].

use crate::atomic::FileError;

/// Why Slurm scripts were not written or submitted: one line naming the option, path or
/// program it is about.
#[derive(Debug, thiserror::Error)]
pub enum SlurmError {
    /// A shard count of 0 or above the limit.
    #[error("--shards must be from 1 to {max}")]
    Shards {
        /// The most shards ([`MAX_SHARDS`](crate::shard::MAX_SHARDS)).
        max: usize,
    },
    /// No CPU per task.
    #[error("--cpus-per-task must be at least 1")]
    CpusPerTask,
    /// A value that is empty or holds a space or a line break (it would end the `#SBATCH`
    /// line).
    #[error("{option} {value:?}: expected one word (no spaces or line breaks)")]
    NotOneWord {
        /// The option (`--partition`, `--time`, `--mem`, `--account`).
        option: &'static str,
        /// The value, as given.
        value: String,
    },
    /// A time limit in none of Slurm's formats.
    #[error(
        "--time {value:?}: expected one of Slurm's time formats: MINUTES, MINUTES:SECONDS, \
         HOURS:MINUTES:SECONDS, DAYS-HOURS, DAYS-HOURS:MINUTES, DAYS-HOURS:MINUTES:SECONDS \
         or UNLIMITED (e.g. 90, 1:30:00, 2-12)"
    )]
    Time {
        /// The value, as given.
        value: String,
    },
    /// A memory size that is not one.
    #[error(
        "--mem {value:?}: expected a whole number with an optional unit K, M, G or T \
         (megabytes when none; e.g. 4G, 500M)"
    )]
    Memory {
        /// The value, as given.
        value: String,
    },
    /// A path holding a line break, which would end a script's line.
    #[error("{what} {path:?} holds a line break, which an sbatch script cannot hold")]
    LineBreak {
        /// Which path (`the scenario path`, `--out`, `the current folder`, `the usar
        /// executable's path`).
        what: &'static str,
        /// The path, as given.
        path: String,
    },
    /// An output folder holding a double quote, which would end the quoted `#SBATCH --output`
    /// value.
    #[error("--out {path:?} holds a double quote, which an #SBATCH line cannot hold")]
    OutQuote {
        /// The output folder, as given.
        path: String,
    },
    /// A script or the logs folder could not be written.
    #[error(transparent)]
    File(#[from] FileError),
    /// `sbatch` could not be run (not on the `PATH`).
    #[error("running {program}")]
    Run {
        /// The program, as given.
        program: String,
        /// The system's error.
        #[source]
        source: std::io::Error,
    },
    /// `sbatch` refused a script.
    #[error("sbatch {script} failed ({status}): {message}")]
    Refused {
        /// The script, as shown.
        script: String,
        /// How sbatch ended (`exit status: 1`).
        status: String,
        /// What it printed on stderr, on one line.
        message: String,
    },
    /// `sbatch --parsable` printed no job id.
    #[error("sbatch --parsable printed {stdout:?}, not a job id")]
    NoJobId {
        /// What it printed.
        stdout: String,
    },
    /// The array was submitted but its merge was not.
    #[error(
        "the array was submitted as job {array_job}, but not the merge; submit it by hand once \
         the array is done: sbatch {merge_script}"
    )]
    MergeNotSubmitted {
        /// The array's job id.
        array_job: String,
        /// The merge's script, as shown.
        merge_script: String,
        /// Why sbatch refused it.
        #[source]
        source: Box<SlurmError>,
    },
}
