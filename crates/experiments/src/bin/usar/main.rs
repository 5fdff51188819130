//! The `usar` command line. See `usar --help`.

use std::io::Write as _;
use std::process::ExitCode;

use clap::Parser;
mod cli;
mod commands;

use cli::{Cli, run};

fn main() -> ExitCode {
    let cli = Cli::parse();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    match run(cli, &mut out) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // Not `eprintln!`, which panics (exit 101) when stderr is a closed pipe: the exit
            // status reports the failure whether or not the message could be written.
            match writeln!(std::io::stderr(), "error: {e:#}") {
                Ok(()) | Err(_) => ExitCode::FAILURE,
            }
        }
    }
}
