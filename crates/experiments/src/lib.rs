//! Library side of the `usar` command line: argument parsing ([`cli`]) and the commands
//! ([`commands`]). The binary `src/bin/usar.rs` only parses and dispatches.

pub mod atomic;
pub mod cli;
pub mod commands;
pub mod figures;
pub mod journal;
pub mod render;
pub mod report;
pub mod spec_ron;
pub mod stats;
pub mod summary;
pub mod sweep;
pub mod table;
pub mod vary;
