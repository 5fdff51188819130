//! The scaling bench's command-line options (after `--`), each checked with a one-line error.

use crate::teams::{BASE, path};

/// Command-line options (after `--`).
pub struct Options {
    /// The scenario whose teams are scaled (`--base`), a path cargo reaches.
    pub base: String,
    /// Scenario files used as they are for the team of their robot count (`--scenario`).
    pub scenarios: Vec<String>,
    /// Grouping method (`--method`, default `dis`).
    pub method: String,
    /// Steps per measurement from the trial's first step (`--steps`).
    pub steps: u64,
    /// Wall-clock budget per measurement, seconds (`--budget-s`; none by default: every
    /// window is measured in full).
    pub budget_s: Option<f64>,
    /// Team sizes to measure, smallest first as given.
    pub teams: Vec<usize>,
    /// Where to draw the measured curve (SVG), if anywhere.
    pub svg: Option<String>,
    /// Whether the measurement with the software at every step is skipped (`--no-every-step`).
    pub no_every_step: bool,
    /// Threads of the one-against-several-threads measurement (`--threads`, default 2; 1
    /// skips it).
    pub threads: usize,
}

/// The default team sizes.
pub const TEAMS: [usize; 5] = [12, 100, 1000, 3000, 10_000];

/// Ends the bench with a one-line error about option `name` (exit status 2).
fn refuse(name: &str, why: &str) -> ! {
    eprintln!("error: scale bench: {name}: {why}");
    std::process::exit(2)
}

/// A positive number given for `name`, or `default` when the option is absent.
fn positive<T: std::str::FromStr + PartialOrd + Default>(
    name: &str,
    v: Option<String>,
    default: T,
) -> T {
    let Some(v) = v else { return default };
    match v.trim().parse::<T>() {
        Ok(x) if x > T::default() => x,
        _ => refuse(name, &format!("expected a number > 0, found {v:?}")),
    }
}

/// Reads the options from the process arguments; an unknown option or a bad value ends the
/// bench with a one-line error (exit 2). Cargo's own `--bench` argument is ignored.
pub fn options() -> Options {
    let args: Vec<String> = std::env::args().skip(1).collect();
    const VALUED: [&str; 8] = [
        "--base",
        "--scenario",
        "--method",
        "--steps",
        "--budget-s",
        "--teams",
        "--svg",
        "--threads",
    ];
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        if VALUED.contains(&a) {
            if i + 1 >= args.len() {
                refuse(a, "expected a value after it");
            }
            i += 1;
        } else if !["--quick", "--bench", "--no-every-step"].contains(&a) {
            refuse(a, "unknown option (see the bench's module docs)");
        }
        i += 1;
    }
    let values = |name: &str| -> Vec<String> {
        (0..args.len())
            .filter(|&i| args[i] == name)
            .filter_map(|i| args.get(i + 1).cloned())
            .collect()
    };
    let value = |name: &str| values(name).pop();
    let quick = args.iter().any(|a| a == "--quick");
    let teams = value("--teams").map(|v| {
        v.split(',')
            .map(|t| positive("--teams", Some(t.to_owned()), 0usize))
            .collect()
    });
    Options {
        base: path(&value("--base").unwrap_or_else(|| BASE.into())),
        scenarios: values("--scenario").iter().map(|f| path(f)).collect(),
        method: value("--method").unwrap_or_else(|| "dis".into()),
        steps: positive("--steps", value("--steps"), if quick { 20 } else { 1500 }),
        budget_s: value("--budget-s").map(|v| positive("--budget-s", Some(v), 0.0)),
        svg: value("--svg").map(|f| path(&f)),
        teams: teams.unwrap_or_else(|| if quick { vec![12, 100] } else { TEAMS.to_vec() }),
        no_every_step: args.iter().any(|a| a == "--no-every-step"),
        threads: positive("--threads", value("--threads"), 2usize),
    }
}
