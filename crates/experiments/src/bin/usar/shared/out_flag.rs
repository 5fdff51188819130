//! The setting an error about a run's output folder is blamed on: `--out`, or the default
//! folder the command picked when `--out` was not given (a folder owned by another run or by
//! the user, or locked by another run).

/// `--out` when the folder was given (`given`), else `the default output folder (--out DIR
/// sets another)`: the context of an owner or lock error of `usar sweep`, `usar calibrate`
/// and `usar multiverse`, and of `usar slurm`'s check of the folder its shards will claim.
pub fn out_setting(given: bool) -> &'static str {
    if given {
        "--out"
    } else {
        "the default output folder (--out DIR sets another)"
    }
}
