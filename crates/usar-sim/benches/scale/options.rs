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
    /// `--steps` as given (`None`: absent); `--robot-step` sizes its windows when absent.
    pub steps_given: Option<u64>,
    /// Whether to measure the cost per robot-step instead (`--robot-step`, `robot_step.rs`).
    pub robot_step: bool,
    /// `--robot-step` configurations not measured (`--skip MODE@N`, repeatable): the physics
    /// mode's name (as in `sim.physics`) and the team.
    pub skip: Vec<(String, usize)>,
    /// Untimed steps before each `--robot-step` window (`--warmup-steps`, default
    /// [`WARMUP_STEPS`]).
    pub warmup_steps: u64,
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

/// The default team sizes of `--robot-step`: the shipped `scenarios/swarm-<n>.ron`.
pub const ROBOT_STEP_TEAMS: [usize; 3] = [1000, 10_000, 100_000];

/// The default warm-up of `--robot-step`, steps (5 simulated seconds at 0.02 s: the first
/// round's plans are made).
pub const WARMUP_STEPS: u64 = 250;

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

/// A `--skip` value `MODE@N` (e.g. `NearContacts@100000`) as the mode's name and the team.
fn skip(v: &str) -> (String, usize) {
    const MODES: [&str; 3] = ["EveryStep", "NearContacts", "NearBodies"];
    let bad = || {
        refuse(
            "--skip",
            &format!("expected MODE@ROBOTS with MODE one of {MODES:?}, found {v:?}"),
        )
    };
    let (mode, n) = v.split_once('@').unwrap_or_else(bad);
    if !MODES.contains(&mode) {
        bad();
    }
    (
        mode.to_owned(),
        positive("--skip", Some(n.to_owned()), 0usize),
    )
}

/// Reads the options from the process arguments; an unknown option or a bad value ends the
/// bench with a one-line error (exit 2). Cargo's own `--bench` argument is ignored.
pub fn options() -> Options {
    let args: Vec<String> = std::env::args().skip(1).collect();
    const VALUED: [&str; 10] = [
        "--base",
        "--scenario",
        "--method",
        "--steps",
        "--budget-s",
        "--teams",
        "--svg",
        "--threads",
        "--warmup-steps",
        "--skip",
    ];
    let mut i = 0;
    while i < args.len() {
        let a = args[i].as_str();
        if VALUED.contains(&a) {
            if i + 1 >= args.len() {
                refuse(a, "expected a value after it");
            }
            i += 1;
        } else if !["--quick", "--bench", "--no-every-step", "--robot-step"].contains(&a) {
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
    let robot_step = args.iter().any(|a| a == "--robot-step");
    let steps_given = value("--steps").map(|v| positive("--steps", Some(v), 0u64));
    let default_teams = if robot_step {
        ROBOT_STEP_TEAMS.to_vec()
    } else if quick {
        vec![12, 100]
    } else {
        TEAMS.to_vec()
    };
    let teams = value("--teams").map(|v| {
        v.split(',')
            .map(|t| positive("--teams", Some(t.to_owned()), 0usize))
            .collect()
    });
    Options {
        base: path(&value("--base").unwrap_or_else(|| BASE.into())),
        scenarios: values("--scenario").iter().map(|f| path(f)).collect(),
        method: value("--method").unwrap_or_else(|| "dis".into()),
        steps: steps_given.unwrap_or(if quick { 20 } else { 1500 }),
        steps_given,
        robot_step,
        skip: values("--skip").iter().map(|v| skip(v)).collect(),
        warmup_steps: match value("--warmup-steps") {
            None => WARMUP_STEPS,
            Some(v) => v.trim().parse().unwrap_or_else(|_| {
                refuse(
                    "--warmup-steps",
                    &format!("expected a number >= 0, found {v:?}"),
                )
            }),
        },
        budget_s: value("--budget-s").map(|v| positive("--budget-s", Some(v), 0.0)),
        svg: value("--svg").map(|f| path(&f)),
        teams: teams.unwrap_or(default_teams),
        no_every_step: args.iter().any(|a| a == "--no-every-step"),
        threads: positive("--threads", value("--threads"), 2usize),
    }
}
