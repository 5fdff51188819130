//! Lines on stderr, written without ever panicking: `usar`'s own warnings, and the libraries'
//! notices ([`usar_sweep::notice`]), which [`show_notices`] prints as they come.

use std::io::Write;

use tracing::Level;

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

/// Installs the process's notice subscriber: each library warning is printed as
/// `warning: MESSAGE`, each progress line as it is, both with [`warn`] and on the thread that
/// emitted it (a library that draws a bar emits inside the bar's `suspend`, so the line is
/// not drawn over). Once per process, at start.
pub fn show_notices() {
    let installed = usar_sweep::notice::install(|level, message| {
        if level <= Level::WARN {
            warn(format_args!("warning: {message}"));
        } else {
            warn(message);
        }
    });
    if installed.is_err() {
        unreachable!("the notice subscriber is installed once, at start");
    }
}
