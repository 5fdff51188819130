//! The `usar` command line. See `usar --help`.

use std::io::Write as _;
use std::process::ExitCode;

use clap::Parser;
use clap::error::ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand;
mod cli;
mod commands;
#[cfg(test)]
mod doc_commands;
mod shared;

use cli::{Cli, run};

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        // `--help`, `--version` and the help shown for a bare `usar` print as clap writes them.
        Err(e) if !e.use_stderr() || e.kind() == DisplayHelpOnMissingArgumentOrSubcommand => {
            e.exit()
        }
        Err(e) => {
            let text = one_line(&e.render().to_string());
            return match writeln!(std::io::stderr(), "{text}") {
                Ok(()) | Err(_) => ExitCode::from(2),
            };
        }
    };
    // The libraries report progress and notices; `usar` draws and prints them. Installed
    // once, before any run.
    shared::stderr_lines::show_notices();
    // The libraries' messages name a setting by its flag (`pass --overwrite`).
    if usar_sweep::settings::set_namer(|s| s.flag().to_string()).is_err() {
        unreachable!("the settings' namer is installed once, here");
    }
    if usar_sweep::progress::set_sink(Box::new(shared::progress::TerminalBars)).is_err() {
        unreachable!("the progress sink is installed once, here");
    }
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    match run(cli, &mut out) {
        Ok(()) => ExitCode::SUCCESS,
        // The reader of a pipe went away (`usar run ... | head`): nothing to say, and the exit
        // status a program killed by SIGPIPE gets from the shell.
        Err(e) if is_broken_pipe(&e) => ExitCode::from(BROKEN_PIPE_EXIT_CODE),
        Err(e) => {
            // Not `eprintln!`, which panics (exit 101) when stderr is a closed pipe: the exit
            // status reports the failure whether or not the message could be written.
            let line = shared::error_text::error_line(&e);
            match writeln!(std::io::stderr(), "error: {line}") {
                Ok(()) | Err(_) => ExitCode::FAILURE,
            }
        }
    }
}

/// Exit status when the reader of a pipe `usar` writes to has gone: 128 + SIGPIPE (13), as a
/// shell reports a program killed by that signal.
const BROKEN_PIPE_EXIT_CODE: u8 = 141;

/// Whether `e` comes from writing to a pipe whose reader has gone.
fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        // The terminal summary's write errors come wrapped (transparently) in a ReportError.
        let io = match c.downcast_ref::<usar_report::error::ReportError>() {
            Some(usar_report::error::ReportError::Io(io)) => Some(io),
            _ => c.downcast_ref::<std::io::Error>(),
        };
        io.is_some_and(|io| io.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

/// A usage error of clap on one line, as every other error of `usar`: its paragraphs (the
/// error, a tip, the usage, the pointer to `--help`) joined by `; `, the lines of each by a
/// space.
fn one_line(rendered: &str) -> String {
    rendered
        .split("\n\n")
        .map(|p| {
            let lines: Vec<&str> = p.lines().map(str::trim).filter(|l| !l.is_empty()).collect();
            lines.join(" ")
        })
        .filter(|p| !p.is_empty())
        .collect::<Vec<_>>()
        .join("; ")
}
