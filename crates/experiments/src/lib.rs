//! Library side of the `usar` command line: argument parsing ([`cli`]) and the commands
//! ([`commands`]). The binary `src/bin/usar.rs` only parses and dispatches.

pub mod atomic;
pub mod cli;
pub mod commands;
pub mod render;
pub mod table;
