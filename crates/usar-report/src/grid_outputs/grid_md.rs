//! `grid.md`: a grid's set-up, its cells, one table (and figure) per chosen metric and the
//! failed trials; when asked (the analysis's [`crate::calibration::ReportOptions`]), each
//! cell's pooled statistics against a targets file and the claims of a claims file per cell. It holds
//! no timings, so it is the same on any thread count.

use std::fmt::Write as _;
use std::path::Path;

use crate::analysis::Analysis;
use crate::claims::Claims;
use crate::report::software_version;
use crate::table::num;
use usar_sweep::grid::Grid;
use usar_sweep::metrics::Metric;
use usar_sweep::sweep::{SweepOutcome, simulated_length_s};

/// What [`grid_md`] needs.
#[derive(Debug)]
pub struct GridReportInput<'a> {
    /// Where the base scenario was loaded from.
    pub scenario_path: &'a Path,
    /// The grid.
    pub grid: &'a Grid,
    /// The sweep.
    pub outcome: &'a SweepOutcome,
    /// Its analysis.
    pub analysis: &'a Analysis,
    /// The chosen metrics.
    pub metrics: &'a [Metric],
    /// File names of the grid figures written, one per chosen metric (none for more than two
    /// varied fields).
    pub figures: &'a [String],
}

/// The text of `grid.md`: set-up, cells, the pooled statistics (only with targets), the
/// chosen metrics, the claims (only with a claims file; a line says how to ask for what is
/// left out) and the failed trials.
pub fn grid_md(input: &GridReportInput<'_>) -> String {
    let mut r = String::new();
    let options = &input.analysis.report;
    let _ = writeln!(r, "# Grid report: {}\n", input.outcome.header.scenario);
    setup(&mut r, input);
    cells(&mut r, input);
    if let Some(targets) = &options.targets {
        pooled(&mut r, input, targets.origin());
    }
    for (i, m) in input.metrics.iter().enumerate() {
        metric_section(&mut r, input, *m, input.figures.get(i));
    }
    if let Some(c) = &options.claims {
        claims(&mut r, input, c);
    }
    if let Some(line) = options.how_to_ask() {
        let _ = writeln!(r, "{line}\n");
    }
    failures(&mut r, input);
    r
}

fn setup(r: &mut String, input: &GridReportInput<'_>) {
    let o = input.outcome;
    let h = &o.header;
    let _ = writeln!(r, "## Set-up\n");
    let _ = writeln!(
        r,
        "- Base scenario: `{}` from `{}`.",
        h.scenario,
        input.scenario_path.display()
    );
    let _ = writeln!(r, "- Varied fields (the first varies slowest):");
    for v in &input.grid.varies {
        let values: Vec<&str> = v.values.iter().map(|x| x.text.as_str()).collect();
        let _ = writeln!(r, "  - `{}`: {}", v.path, values.join(", "));
    }
    let _ = writeln!(
        r,
        "- Cells: {}, each in its own folder with `trials.csv`, `summary.csv`, `report.md`, \
         the figures and `scenario.ron` (the cell's scenario as a file: `usar check` on it \
         shows the cell's scenario hash).",
        h.grid.cells.len()
    );
    let _ = writeln!(r, "- Methods: {}.", h.methods.join(", "));
    let mut durations: Vec<f64> = h
        .grid
        .cells
        .iter()
        .zip(&input.grid.cells)
        .map(|(c, g)| simulated_length_s(c.duration_s, g.scenario.sim().dt_s.get()))
        .collect();
    durations.dedup();
    let mut asked: Vec<f64> = h.grid.cells.iter().map(|c| c.duration_s).collect();
    asked.dedup();
    let each = match (durations.as_slice(), asked.as_slice()) {
        ([d], _) => format!("{d} s of simulated time each"),
        (_, [a]) => format!("of {a} s in whole steps of each cell's `sim.dt_s` (see the cells)"),
        _ => "of each cell's `mission.duration_s` (see the cells)".to_string(),
    };
    let _ = writeln!(r, "- Trials: {} per method and cell, {each}.", h.trials);
    let _ = writeln!(
        r,
        "- Seeds: base seed {}; trial k of every method in every cell starts from the team \
         drawn with seed `trial_seed({}, k)` (common random numbers across methods and \
         cells).",
        h.base_seed, h.base_seed
    );
    let _ = writeln!(r, "- Software: {}.", software_version());
    let failed = o.failures().count();
    let finished: usize = o.cells.iter().map(|c| c.results.len()).sum();
    let _ = writeln!(
        r,
        "- Trials finished: {finished} of {}{}.\n",
        o.expected_trials(),
        if failed == 0 {
            String::new()
        } else {
            format!(", {failed} failed (see below)")
        }
    );
}

/// `| cell | field 1 | ... |` and its separator.
fn table_head(r: &mut String, fields: &[String], rest: &[String]) {
    let _ = write!(r, "| cell |");
    for f in fields.iter().chain(rest) {
        let _ = write!(r, " {f} |");
    }
    let _ = write!(r, "\n|---|");
    for _ in fields.iter().chain(rest) {
        let _ = write!(r, "---|");
    }
    r.push('\n');
}

fn cell_start(r: &mut String, index: usize, values: &[String]) {
    let _ = write!(r, "| {index} |");
    for v in values {
        let _ = write!(r, " `{v}` |");
    }
}

fn cells(r: &mut String, input: &GridReportInput<'_>) {
    let h = &input.outcome.header;
    let _ = writeln!(r, "## Cells\n");
    let rest = [
        "folder",
        "scenario hash",
        "trial length (s)",
        "trials finished",
    ]
    .map(String::from);
    table_head(r, &h.grid.fields, &rest);
    let per_cell = h.methods.len() * h.trials as usize;
    for ((cell, c), o) in input
        .grid
        .cells
        .iter()
        .zip(&h.grid.cells)
        .zip(&input.outcome.cells)
    {
        cell_start(r, cell.index, &c.values);
        let _ = writeln!(
            r,
            " [`{}`]({}/report.md) | `{}` | {} | {} of {per_cell} |",
            cell.dir,
            cell.dir,
            c.scenario_hash,
            c.duration_s,
            o.results.len()
        );
    }
    r.push('\n');
}

/// Every cell's statistics pooled over its trials of all methods against the targets of
/// `origin`
/// (`docs/calibration.md`); a value outside its band is marked with `!`, a value that is n/a
/// is not.
fn pooled(r: &mut String, input: &GridReportInput<'_>, origin: &str) {
    let h = &input.outcome.header;
    let _ = writeln!(
        r,
        "## Pooled statistics\n\nPer cell, over all trials of all methods (means, ratios of \
         means and pooled within-method standard deviations), against the targets of `{origin}` \
         (see `docs/calibration.md`). The targets are in the header; `!` marks a value outside \
         its band.\n"
    );
    let first = input.analysis.cells.first();
    let labels: Vec<String> = first
        .map_or(&[][..], |c| &c.pooled[..])
        .iter()
        .map(|(t, _)| format!("{} ({})", t.name, t.describe()))
        .collect();
    table_head(r, &h.grid.fields, &labels);
    for (index, (c, a)) in h.grid.cells.iter().zip(&input.analysis.cells).enumerate() {
        cell_start(r, index, &c.values);
        for (t, x) in &a.pooled {
            let mark = if !x.is_finite() || t.holds(*x) {
                ""
            } else {
                " !"
            };
            let _ = write!(r, " {}{mark} |", num(*x));
        }
        r.push('\n');
    }
    r.push('\n');
}

fn metric_section(
    r: &mut String,
    input: &GridReportInput<'_>,
    metric: Metric,
    figure: Option<&String>,
) {
    let h = &input.outcome.header;
    let tasks = input
        .analysis
        .cells
        .first()
        .map_or(&[][..], |c| &c.tasks[..]);
    let label = metric.label(tasks);
    let _ = writeln!(r, "## {label} (`{}`)\n", metric.name(tasks));
    let _ = writeln!(
        r,
        "Mean over trials [95 % confidence interval of the mean]; n shown when fewer trials \
         define the metric than finished. Every metric is in `grid.csv`.\n"
    );
    table_head(r, &h.grid.fields, &h.methods);
    for (index, (c, a)) in h.grid.cells.iter().zip(&input.analysis.cells).enumerate() {
        cell_start(r, index, &c.values);
        for (i, m) in a.methods.iter().enumerate() {
            let s = a.summary(i, metric).unwrap_or_default();
            let mut text = num(s.mean);
            if s.ci95.is_finite() {
                let _ = write!(text, " [{}, {}]", num(s.ci_low()), num(s.ci_high()));
            }
            if s.n != m.trials {
                let _ = write!(text, " (n = {})", s.n);
            }
            let _ = write!(r, " {text} |");
        }
        r.push('\n');
    }
    r.push('\n');
    match figure {
        Some(f) => {
            let _ = writeln!(r, "![{label} across the grid]({f})\n");
        }
        None => {
            let _ = writeln!(
                r,
                "No figure: {} fields are varied (figures are drawn for one or two).\n",
                h.grid.fields.len()
            );
        }
    }
}

fn claims(r: &mut String, input: &GridReportInput<'_>, claims: &Claims) {
    let h = &input.outcome.header;
    let _ = writeln!(r, "## Claims per cell\n");
    let _ = writeln!(
        r,
        "The claims of `{}`, with verdicts as in each cell's `report.md`:\n",
        claims.origin()
    );
    for c in claims.claims() {
        let _ = writeln!(r, "- ({}) {} ({})", c.id, c.sentence, c.test_words());
    }
    r.push('\n');
    let ids: Vec<String> = claims
        .claims()
        .iter()
        .map(|c| format!("({})", c.id))
        .collect();
    table_head(r, &h.grid.fields, &ids);
    for (index, (c, a)) in h.grid.cells.iter().zip(&input.analysis.cells).enumerate() {
        cell_start(r, index, &c.values);
        for check in &a.claims {
            let _ = write!(r, " {} |", check.verdict.words());
        }
        r.push('\n');
    }
    r.push('\n');
}

fn failures(r: &mut String, input: &GridReportInput<'_>) {
    let o = input.outcome;
    if o.failures().next().is_none() {
        return;
    }
    let _ = writeln!(r, "## Failed trials\n");
    let _ = writeln!(
        r,
        "These trials are missing from the tables above; `usar sweep --resume` reruns them.\n"
    );
    for f in o.failures() {
        let _ = writeln!(
            r,
            "- cell {} ({}): {} trial {} (seed {}): {}",
            f.cell, input.grid.cells[f.cell].dir, f.method, f.trial, f.seed, f.message
        );
    }
    r.push('\n');
}
