//! `report.md`: one cell's parameters, results table, round lengths, failed trials and
//! timings, rendered from the cell's [`CellAnalysis`]; when asked ([`ReportOptions`]), its
//! statistics pooled over methods against a targets file and the claims of a claims file
//! checked one by one with significance tests.

use std::fmt::Write as _;
use std::path::Path;

use usar_sim::mission::trial_seed;
use usar_sim::scenario::Scenario;

use crate::analysis::CellAnalysis;
use crate::calibration::ReportOptions;
use crate::table::{mean_sd, num};
use usar_sweep::data::figure_list::FIGURES;
use usar_sweep::data::grid_cells::GridCell;
use usar_sweep::data::outcome::SweepOutcome;
pub use usar_sweep::data::software::{software_build, software_version};

mod claims_md;
use usar_sweep::data::trial_length::simulated_length_s;

/// What [`report_md`] needs.
#[derive(Debug)]
pub struct ReportInput<'a> {
    /// The cell's scenario.
    pub scenario: &'a Scenario,
    /// Where the (base) scenario was loaded from.
    pub scenario_path: &'a Path,
    /// The sweep.
    pub outcome: &'a SweepOutcome,
    /// Index of the cell reported on.
    pub cell: usize,
    /// The cell's analysis.
    pub analysis: &'a CellAnalysis,
    /// The grid cell, for a sweep with `--vary`.
    pub grid_cell: Option<&'a GridCell>,
    /// Which sections beyond the results to show (the sweep's [`crate::analysis::Analysis`]
    /// has them).
    pub options: &'a ReportOptions,
}

/// The text of `report.md`: set-up, results and round lengths; the "Pooled statistics"
/// section only with targets and the claims section only with `claims`
/// ([`ReportOptions`]; a line says how to ask for what is left out); then figures, failed
/// trials and timings.
pub fn report_md(input: &ReportInput<'_>) -> String {
    let mut r = String::new();
    let _ = writeln!(r, "# Sweep report: {}\n", input.outcome.header.scenario);
    setup(&mut r, input);
    results(&mut r, input.analysis);
    round_lengths(&mut r, input.analysis);
    if let Some(targets) = &input.options.targets {
        pooled(&mut r, input.analysis, targets.origin());
    }
    if let Some(c) = &input.options.claims {
        claims_md::claims(&mut r, input.analysis, c);
    }
    if let Some(line) = input.options.how_to_ask() {
        let _ = writeln!(r, "{line}\n");
    }
    let _ = writeln!(r, "## Figures\n");
    for f in &FIGURES {
        let _ = writeln!(r, "![{}]({})\n", f.title, f.file);
    }
    failures(&mut r, input);
    timings(&mut r, input);
    r
}

fn setup(r: &mut String, input: &ReportInput<'_>) {
    let o = input.outcome;
    let h = &o.header;
    let cell = &h.grid.cells[input.cell];
    let s = input.scenario;
    let _ = writeln!(r, "## Set-up\n");
    match input.grid_cell {
        None => {
            let _ = writeln!(
                r,
                "- Scenario: `{}` from `{}` (scenario hash `{}`): {}",
                h.scenario,
                input.scenario_path.display(),
                cell.scenario_hash,
                s.description()
            );
        }
        Some(g) => {
            let values: Vec<String> = g.overrides.iter().map(|o| format!("`{o}`")).collect();
            let _ = writeln!(
                r,
                "- Scenario: `{}` from `{}` with {} (cell {} of {} of the grid in `../grid.md`; \
                 this cell's scenario is `scenario.ron`, scenario hash `{}`): {}",
                h.scenario,
                input.scenario_path.display(),
                values.join(", "),
                input.cell,
                h.grid.cells.len(),
                cell.scenario_hash,
                s.description()
            );
        }
    }
    let _ = writeln!(
        r,
        "- Team: {} robots ({}); step {} s.",
        s.robots().len(),
        s.kinds()
            .iter()
            .map(|k| format!("{} {}", k.count, k.name))
            .collect::<Vec<_>>()
            .join(", "),
        s.sim().dt_s
    );
    let _ = writeln!(r, "- Methods: {}.", h.methods.join(", "));
    let _ = writeln!(
        r,
        "- Trials: {} per method, {} s of simulated time each.",
        h.trials,
        simulated_length_s(cell.duration_s, s.sim().dt_s.get())
    );
    let _ = writeln!(
        r,
        "- Seeds: base seed {}; trial k starts from the team drawn with seed \
         `trial_seed({}, k)`, the same for every method (common random numbers): {}.",
        h.base_seed,
        h.base_seed,
        (0..h.trials)
            .map(|k| format!("{k}: {}", trial_seed(h.base_seed, k)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let _ = writeln!(r, "- Software: {}.", software_version());
    let c = &o.cells[input.cell];
    let _ = writeln!(
        r,
        "- Trials finished: {} of {}{}.\n",
        c.results.len(),
        h.methods.len() * h.trials as usize,
        if c.failures.is_empty() {
            String::new()
        } else {
            format!(", {} failed (see below)", c.failures.len())
        }
    );
}

fn results(r: &mut String, a: &CellAnalysis) {
    let _ = writeln!(r, "## Results\n");
    let _ = writeln!(
        r,
        "Mean ± standard deviation over trials, then the 95 % confidence interval of the mean \
         (Student's t, its lower end clipped at 0: every metric is a count, a cost or a time). \
         Costs are in percent points summed over the robots of a task's group; \
         per-rescuee costs average over the trials that rescued at least one (n shown when \
         fewer than all). The same numbers are in `summary.csv`, every trial in `trials.csv`.\n"
    );
    let _ = write!(r, "| metric |");
    for m in &a.methods {
        let _ = write!(r, " {} |", m.method);
    }
    let _ = write!(r, "\n|---|");
    for _ in &a.methods {
        let _ = write!(r, "---|");
    }
    r.push('\n');
    for (i, metric) in a.metrics.iter().enumerate() {
        let _ = write!(r, "| {} |", metric.label(&a.tasks));
        for m in &a.methods {
            let sm = m.metrics[i];
            let mut cell = mean_sd(&sm);
            if sm.ci95.is_finite() {
                let _ = write!(cell, " [{}, {}]", num(sm.ci_low()), num(sm.ci_high()));
            }
            if sm.n != m.trials {
                let _ = write!(cell, " (n = {})", sm.n);
            }
            let _ = write!(r, " {cell} |");
        }
        r.push('\n');
    }
    r.push('\n');
}

/// Appends the "Pooled statistics" subsection: the targets read from `origin` next to this
/// sweep's statistics pooled over all trials of all methods ([`CellAnalysis::pooled`]). A value outside its band
/// is marked **out**; a value that is n/a (no trials, a task the scenario lacks, a zero
/// denominator) is not.
fn pooled(r: &mut String, a: &CellAnalysis, origin: &str) {
    let _ = writeln!(
        r,
        "### Pooled statistics\n\nOver all trials of all methods (means, ratios of means and \
         pooled within-method standard deviations), against the targets of `{origin}` (see \
         `docs/calibration.md`). A value outside the band is marked **out**.\n\n\
         | statistic | this sweep | target | band |\n|---|---|---|---|"
    );
    for (k, (t, x)) in a.pooled.iter().enumerate() {
        let mark = if !x.is_finite() || t.holds(*x) {
            ""
        } else {
            " **out**"
        };
        let left_out = match a.pooled_left_out.get(k) {
            Some(&n) if n > 0 => format!(" ({n} of {} trials left out: undefined there)", a.trials),
            _ => String::new(),
        };
        let _ = writeln!(
            r,
            "| {} | {}{mark}{left_out} | {} | {} |",
            t.name,
            num(*x),
            t.value,
            t.band
        );
    }
    r.push('\n');
}

/// The "Round lengths" subsection: completed rounds per method and over all methods, with
/// their median, 95th percentile and longest length, seconds, and the mean number of rounds
/// started per trial. A stalled round (robots unable to get back) shows up here long before
/// it moves a mean.
fn round_lengths(r: &mut String, a: &CellAnalysis) {
    let _ = writeln!(
        r,
        "### Round lengths\n\nCompleted rounds (a round cut by the time limit is not \
         counted), seconds.\n\n| method | completed rounds | median | 95th percentile | \
         longest | rounds started per trial |\n|---|---|---|---|---|---|"
    );
    for s in &a.rounds {
        if s.completed == 0 {
            let _ = writeln!(r, "| {} | 0 | n/a | n/a | n/a | n/a |", s.label);
            continue;
        }
        let _ = writeln!(
            r,
            "| {} | {} | {} | {} | {} | {} |",
            s.label,
            s.completed,
            num(s.median_s),
            num(s.p95_s),
            num(s.longest_s),
            num(s.started_per_trial)
        );
    }
    r.push('\n');
}

fn failures(r: &mut String, input: &ReportInput<'_>) {
    let failures = &input.outcome.cells[input.cell].failures;
    if failures.is_empty() {
        return;
    }
    let _ = writeln!(r, "## Failed trials\n");
    let _ = writeln!(
        r,
        "These trials are missing from the tables above; `usar sweep --resume` reruns them.\n"
    );
    for f in failures {
        let _ = writeln!(
            r,
            "- {} trial {} (seed {}): {}",
            f.method, f.trial, f.seed, f.message
        );
    }
    r.push('\n');
}

fn timings(r: &mut String, input: &ReportInput<'_>) {
    let o = input.outcome;
    let c = &o.cells[input.cell];
    let _ = writeln!(r, "## Timings (this invocation)\n");
    if c.ran == 0 {
        let _ = writeln!(
            r,
            "No trial was run: all {} came from the journal of an earlier run.",
            c.reused
        );
        return;
    }
    if input.grid_cell.is_some() {
        let _ = writeln!(
            r,
            "{} trials of this cell run ({} taken from the journal of an earlier run); mean \
             wall time per trial {:.3} s. The whole grid ran {} trials in {:.2} s wall-clock on \
             {} thread(s).",
            c.ran,
            c.reused,
            c.trial_wall_sum_s / c.ran as f64,
            o.ran,
            o.wall_s,
            o.threads
        );
        return;
    }
    let rate = o.simulated_s() / o.wall_s.max(1e-9);
    let _ = writeln!(
        r,
        "{} trials run in {:.2} s wall-clock on {} thread(s) ({} taken from the journal of an \
         earlier run): {:.0} simulated seconds per wall-clock second, {:.0} per thread; mean \
         wall time per trial {:.3} s.",
        o.ran,
        o.wall_s,
        o.threads,
        o.reused,
        rate,
        rate / o.threads as f64,
        o.trial_wall_sum_s / o.ran as f64
    );
}
