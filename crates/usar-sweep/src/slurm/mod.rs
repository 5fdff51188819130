//! A sweep on a Slurm cluster (`usar slurm`): a job array whose task I runs shard I of the
//! sweep (`usar sweep ... --shard I/N`, [`crate::shard`]; or of a multiverse, `usar
//! multiverse ... --shard I/N`, `usar_study::multiverse`), and a merge job (`usar merge`)
//! chained to it with `--dependency=afterok`. [`script`] writes the files, [`mod@submit`] submits
//! them with `sbatch`.

pub mod error;
pub mod script;
pub mod submit;

pub use error::SlurmError;
pub use script::{
    SLURM_DIR, ShardedWork, SlurmFiles, SlurmJob, SlurmOptions, array_script, check_options,
    merge_script, submit_script, write_scripts,
};
pub use submit::{Submitted, parse_job_id, submit};
