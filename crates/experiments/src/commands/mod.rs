//! The `usar` subcommands, one module each.

pub mod trust;
