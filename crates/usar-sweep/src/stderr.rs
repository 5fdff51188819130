//! Warnings on stderr: one line each, written without ever panicking.
//!
//! Every module that warns while it works (the sweep's executor, calibration, the multiverse,
//! the `usar` commands) prints through [`warn`], so a stderr that cannot be written never
//! changes a command's outcome.

use std::io::Write;

/// Prints one line on stderr: a warning, or a failed trial's message while a sweep goes on.
///
/// Unlike `eprintln!`, it does not panic (exit status 101) when stderr cannot be written, for
/// example when it is `/dev/full` or a pipe whose reader has gone: a warning that cannot be
/// shown has nowhere else to go, and the command's own outcome and exit status stay what they
/// would have been. Errors that end a command are printed by `main`, which exits 1 either way.
pub fn warn(line: impl std::fmt::Display) {
    match writeln!(std::io::stderr(), "{line}") {
        Ok(()) | Err(_) => {}
    }
}
