//! The `usar` subcommands, one module each.

pub mod render;
pub mod trust;
