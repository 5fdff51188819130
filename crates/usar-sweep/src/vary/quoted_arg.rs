//! How an error message quotes a `--set` or `--vary` argument: one line, and short.

use usar_sim::scenario::one_line_text;

/// Longest command-line argument an error message quotes in full, characters ([`brief`]).
pub const QUOTED_ARG_CHARS: usize = 80;

/// `arg` (a `--set` or `--vary` argument, or a value) as an error message quotes it, control
/// characters escaped ([`one_line_text`], as paths are): in full up to
/// [`QUOTED_ARG_CHARS`] characters, else its first 60 and the length (`rest_station=[(center_m:
/// ... (10412 characters)`), so that an error about a long value stays a short line.
pub fn brief(arg: &str) -> String {
    // A control character is written escaped (`\n`), so the message stays one line.
    let arg = one_line_text(arg).into_owned();
    let n = arg.chars().count();
    if n <= QUOTED_ARG_CHARS {
        arg
    } else {
        let head: String = arg.chars().take(60).collect();
        format!("{head}... ({n} characters)")
    }
}
