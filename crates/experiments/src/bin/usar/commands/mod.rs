//! The `usar` subcommands, one module each.

pub mod calibrate;
pub mod check;
pub mod merge;
pub mod multiverse;
pub mod render;
pub mod replay;
pub mod run;
pub mod slurm;
pub mod sweep;
pub mod trust;
