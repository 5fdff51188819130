//! Trials per CPU-second (issue 54): the budget of every calibration and multiverse.
//!
//! For three scenarios it runs `usar sweep --threads 1` as a child process and divides the
//! trials it ran by the CPU seconds the child used (user + system, from the kernel's
//! accounting of waited-for children, `/proc/self/stat` fields `cutime` and `cstime`, so other
//! load on a shared machine does not count):
//!
//! | case | scenario | sweep |
//! |---|---|---|
//! | `paper` | `scenarios/paper.ron` | every method x 10 trials x 600 s (40 trials) |
//! | `three-tasks` | `scenarios/three-tasks.ron` | every method x 5 trials x 600 s (20 trials) |
//! | `swarm-1000` | `scenarios/swarm-1000.ron` | DIS x 1 trial x 300 s |
//!
//! **The ratio to today's figure.** With `USAR_REF_BIN=/path/to/usar` (a release build of the
//! commit to compare with; `docs/scaling.md`, "Physics only near contacts", says how to build
//! the one of issue 54) each case runs in pairs, the reference build then this one, and the
//! bench prints the median over the pairs of this build's trials per CPU-second divided by the
//! reference's, and whether the two wrote the same `trials.csv`. A reference that predates
//! `sim.physics` gets the scenario without its `physics:` field (its only behaviour is
//! `EveryStep`). Without `USAR_REF_BIN` the ratio is to [`RECORDED`], the reference's figures
//! measured on the project's 2-core VM on 2026-11-27: indicative only on another machine.
//!
//! Run in release: `cargo bench -p experiments --bench trials_per_cpu` (5 pairs per case; a
//! few minutes), `-- --pairs N`, `-- --quick` (one pair, paper 2 trials, three-tasks 1,
//! swarm-1000 60 s: a smoke test; without `USAR_REF_BIN` it prints no ratio), `-- --case paper` (repeatable).
//! Needs Linux (`/proc`); a failing child stops the bench with a one-line error, exit status 1,
//! a bad option exits with status 2.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};

/// Reference figures, trials per CPU-second of `usar` at commit 9461dcc (the build issue 54
/// compares with) on the project's shared 2-core VM, 2026-11-27, median of 5 runs, measured
/// with this bench and `USAR_REF_BIN`: (case, trials per CPU-second).
const RECORDED: [(&str, f64); 3] = [
    ("paper", 3.55),
    ("three-tasks", 3.72),
    ("swarm-1000", 0.173),
];

/// One case: a scenario and the sweep flags that size it.
struct Case {
    name: &'static str,
    scenario: &'static str,
    args: Vec<String>,
    trials: usize,
}

fn cases(quick: bool) -> Vec<Case> {
    let s = |v: &[&str]| v.iter().map(|x| (*x).to_owned()).collect::<Vec<_>>();
    let (paper, three, swarm_s) = if quick { (2, 1, "60") } else { (10, 5, "300") };
    vec![
        Case {
            name: "paper",
            scenario: "scenarios/paper.ron",
            args: s(&["--trials", &paper.to_string()]),
            trials: 4 * paper,
        },
        Case {
            name: "three-tasks",
            scenario: "scenarios/three-tasks.ron",
            args: s(&["--trials", &three.to_string()]),
            trials: 4 * three,
        },
        Case {
            name: "swarm-1000",
            scenario: "scenarios/swarm-1000.ron",
            args: s(&["--methods", "dis", "--trials", "1", "--duration", swarm_s]),
            trials: 1,
        },
    ]
}

/// The command line: `--pairs N`, `--quick`, `--case NAME` (repeatable).
struct Options {
    pairs: usize,
    quick: bool,
    only: Vec<String>,
}

fn options() -> Result<Options, String> {
    let mut o = Options {
        pairs: 5,
        quick: false,
        only: Vec::new(),
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--bench" => {}
            "--quick" => {
                o.quick = true;
                o.pairs = o.pairs.min(1);
            }
            "--pairs" => {
                let v = args.next().ok_or("--pairs: expected a number")?;
                o.pairs = v.parse().ok().filter(|n| *n >= 1).ok_or(format!(
                    "--pairs: expected a whole number >= 1, found `{v}`"
                ))?;
            }
            "--case" => {
                let v = args.next().ok_or("--case: expected a case name")?;
                if !["paper", "three-tasks", "swarm-1000"].contains(&v.as_str()) {
                    return Err(format!(
                        "--case: unknown case `{v}` (expected paper, three-tasks or swarm-1000)"
                    ));
                }
                o.only.push(v);
            }
            other => return Err(format!("unknown option `{other}`")),
        }
    }
    Ok(o)
}

/// CPU seconds (user + system) of this process's waited-for children so far.
fn children_cpu_s() -> Result<f64, String> {
    let stat = std::fs::read_to_string("/proc/self/stat")
        .map_err(|e| format!("/proc/self/stat: {e} (this bench needs Linux)"))?;
    // Fields after the command name, which is in parentheses and may hold spaces.
    let rest = stat
        .rsplit_once(')')
        .ok_or("/proc/self/stat: no `)` after the command name")?
        .1;
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // Field 16 is cutime and 17 cstime (1-based, man 5 proc); `rest` starts at field 3.
    let ticks = |i: usize| -> Result<f64, String> {
        fields
            .get(i - 3)
            .and_then(|f| f.parse::<f64>().ok())
            .ok_or(format!("/proc/self/stat: field {i} is not a number"))
    };
    let hz = 100.0; // USER_HZ on Linux
    Ok((ticks(16)? + ticks(17)?) / hz)
}

/// Runs one sweep of `case` with `bin` into `out`; returns the child's CPU seconds.
fn run(bin: &Path, scenario: &Path, case: &Case, out: &Path) -> Result<f64, String> {
    let before = children_cpu_s()?;
    let status = Command::new(bin)
        .arg("sweep")
        .arg(scenario)
        .args(&case.args)
        .args(["--threads", "1", "--quiet", "--overwrite", "--out"])
        .arg(out)
        .stdout(std::process::Stdio::null())
        .status()
        .map_err(|e| format!("{}: cannot start: {e}", bin.display()))?;
    if !status.success() {
        return Err(format!(
            "{} sweep {} failed ({status})",
            bin.display(),
            scenario.display()
        ));
    }
    Ok(children_cpu_s()? - before)
}

/// The scenario a reference build reads: `scenario` itself, or a copy without its
/// `physics:` field when the reference predates `sim.physics` (detected by `usar check`), in
/// `dir` beside copies of the other `.ron` files of its folder.
fn scenario_for(bin: &Path, scenario: &Path, dir: &Path) -> Result<PathBuf, String> {
    let ok = Command::new(bin)
        .arg("check")
        .arg(scenario)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .map_err(|e| format!("{}: cannot start: {e}", bin.display()))?
        .success();
    if ok {
        return Ok(scenario.to_path_buf());
    }
    let text =
        std::fs::read_to_string(scenario).map_err(|e| format!("{}: {e}", scenario.display()))?;
    let kept = without_physics(&text);
    // The files a scenario names (its targets, say) are relative to its folder: copied along.
    let folder = scenario.parent().unwrap_or(Path::new("."));
    let siblings = std::fs::read_dir(folder).map_err(|e| format!("{}: {e}", folder.display()))?;
    for entry in siblings.flatten() {
        let path = entry.path();
        if path.is_file() && path.extension().is_some_and(|x| x == "ron") {
            let to = dir.join(entry.file_name());
            std::fs::copy(&path, &to).map_err(|e| format!("{}: {e}", to.display()))?;
        }
    }
    let copy = dir.join(scenario.file_name().ok_or("scenario without a file name")?);
    std::fs::write(&copy, kept).map_err(|e| format!("{}: {e}", copy.display()))?;
    Ok(copy)
}

/// `text` without its `physics: <Name>` field (and the comma that separated it).
fn without_physics(text: &str) -> String {
    let mut out = text.to_owned();
    while let Some(at) = out.find("physics:") {
        let after = &out[at + "physics:".len()..];
        let name_len = after.trim_start().len();
        let skipped = after.len() - name_len;
        let value = after
            .trim_start()
            .find(|c: char| !c.is_alphanumeric() && c != '_')
            .unwrap_or(name_len);
        let mut end = at + "physics:".len() + skipped + value;
        let mut start = at;
        if out[end..].trim_start().starts_with(',') {
            end += out[end..].find(',').unwrap_or(0) + 1;
        } else if let Some(comma) = out[..at].trim_end().strip_suffix(',') {
            start = comma.len();
        }
        out.replace_range(start..end, "");
    }
    out
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

fn bench(o: &Options) -> Result<(), String> {
    let root = PathBuf::from(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let this = PathBuf::from(env!("CARGO_BIN_EXE_usar"));
    let reference = std::env::var_os("USAR_REF_BIN").map(PathBuf::from);
    let tmp = tempfile::tempdir().map_err(|e| format!("a temporary folder: {e}"))?;
    match &reference {
        Some(r) => println!(
            "trials per CPU-second, this build against USAR_REF_BIN={} ({} pairs, median)",
            r.display(),
            o.pairs
        ),
        None => println!(
            "trials per CPU-second ({} runs, median); ratio to the figures recorded on 2026-11-27 \
             (set USAR_REF_BIN for a side-by-side ratio)",
            o.pairs
        ),
    }
    println!(
        "{:<12} {:>6} {:>14} {:>14} {:>7}  same trials.csv",
        "case", "trials", "this", "reference", "ratio"
    );
    for case in cases(o.quick) {
        if !o.only.is_empty() && !o.only.iter().any(|c| c == case.name) {
            continue;
        }
        let scenario = root.join(case.scenario);
        let (mut this_rates, mut ref_rates, mut ratios) = (Vec::new(), Vec::new(), Vec::new());
        let mut same = None;
        let ref_scenario = match &reference {
            Some(r) => Some(scenario_for(r, &scenario, tmp.path())?),
            None => None,
        };
        for _ in 0..o.pairs {
            let out_this = tmp.path().join(format!("{}-this", case.name));
            let this_rate = case.trials as f64 / run(&this, &scenario, &case, &out_this)?;
            this_rates.push(this_rate);
            if let (Some(r), Some(s)) = (&reference, &ref_scenario) {
                let out_ref = tmp.path().join(format!("{}-ref", case.name));
                let ref_rate = case.trials as f64 / run(r, s, &case, &out_ref)?;
                ref_rates.push(ref_rate);
                ratios.push(this_rate / ref_rate);
                let read = |d: &Path| std::fs::read(d.join("trials.csv")).ok();
                same = Some(read(&out_this) == read(&out_ref) && read(&out_this).is_some());
            }
        }
        let this_rate = median(this_rates);
        let (ref_rate, ratio) = if reference.is_some() {
            (median(ref_rates), median(ratios))
        } else {
            // The recorded figures are of the full cases, not of --quick's shorter ones.
            let recorded = RECORDED
                .iter()
                .find(|(n, _)| *n == case.name && !o.quick)
                .map_or(f64::NAN, |(_, r)| *r);
            (recorded, this_rate / recorded)
        };
        let or_dash = |v: f64, text: String| if v.is_nan() { "-".to_owned() } else { text };
        println!(
            "{:<12} {:>6} {:>14.4} {:>14} {:>7}  {}",
            case.name,
            case.trials,
            this_rate,
            or_dash(ref_rate, format!("{ref_rate:.4}")),
            or_dash(ratio, format!("{ratio:.2}x")),
            match same {
                Some(true) => "yes",
                Some(false) => "no",
                None => "-",
            }
        );
    }
    Ok(())
}

fn main() -> ExitCode {
    let o = match options() {
        Ok(o) => o,
        Err(e) => {
            eprintln!("trials_per_cpu: {e}");
            return ExitCode::from(2);
        }
    };
    match bench(&o) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("trials_per_cpu: {e}");
            ExitCode::FAILURE
        }
    }
}
