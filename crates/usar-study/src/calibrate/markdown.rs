//! `calibration.md`: the set-up, the command, the result (every statistic at the best values
//! against its target and band), the best values, the convergence figure and the statistics
//! on unseen trials.

use std::fmt::Write;

use super::outcome::{
    CalibrationOutcome, FIGURE_FILE, STATISTICS_FIGURE_FILE, TRACE_CSV_FILE, TargetCheck,
};
use super::progress::loss_text;
use usar_report::table::num;

/// The text of `calibration.md`.
pub fn calibration_md(o: &CalibrationOutcome) -> String {
    let h = &o.header;
    let mut r = String::new();
    let _ = writeln!(r, "# Calibration: {}\n", h.scenario);
    let _ = writeln!(r, "## Set-up\n");
    let _ = writeln!(
        r,
        "- base scenario: `{}` (scenario hash `{}`)\n- targets: `{}` ({} targets)\n- trials \
         per evaluation: {}, statistics pooled over methods\n- free values rounded to {} \
         significant digits; search: {}\n- budget of this run: {} evaluations; build: `{}`; \
         written {} (UTC)\n",
        o.origin,
        h.scenario_hash,
        o.targets_origin,
        h.targets.len(),
        o.trials_text(),
        h.digits,
        h.search,
        o.max_evals,
        if h.build.is_empty() {
            "unrecorded"
        } else {
            &h.build
        },
        o.date
    );
    let _ = writeln!(r, "```sh\n{}\n```\n", o.command);
    let best = o.best();
    let _ = writeln!(r, "## Result\n");
    let _ = writeln!(
        r,
        "{} evaluations ({} run now, {} from the trace of an earlier run) in {:.1} s on {} \
         thread(s); the search stopped because {}. Best: evaluation #{} with loss {}: {}.\n",
        o.evaluations.len(),
        o.ran,
        o.reused,
        o.wall_s,
        o.threads,
        o.stop,
        best.index,
        loss_text(o.loss),
        if o.admissible {
            "every statistic lies in its band"
        } else {
            "**not every statistic lies in its band**"
        }
    );
    if let Some(m) = &best.message {
        let _ = writeln!(r, "Its evaluation failed: {m}\n");
    }
    table(&mut r, &o.statistics);
    if let Some((a, b)) = super::tradeoff_figure::tradeoff_pair(o) {
        let _ = writeln!(
            r,
            "Figures: `convergence.svg` (the loss per evaluation), `statistics.svg` (each \
             target's statistic per evaluation) and `tradeoff.svg` ({} against {}, the two \
             farthest outside their bands at the best point, with the Pareto front).\n",
            o.header.targets[a].name, o.header.targets[b].name
        );
    }
    let _ = writeln!(r, "## Best values\n");
    let _ = writeln!(
        r,
        "| field | value | range | scale | start |\n|---|---|---|---|---|"
    );
    for ((f, x), s) in h.free.iter().zip(&best.values).zip(&o.starts) {
        let _ = writeln!(
            r,
            "| `{}`{} | {x} | {} to {} | {} | {s} |",
            f.field,
            if f.factor { " (factor)" } else { "" },
            f.lo,
            f.hi,
            if f.log { "log" } else { "linear" }
        );
    }
    let _ = writeln!(
        r,
        "\n`calibrated.ron` is the base scenario with these values. Every evaluation is in \
         `{TRACE_CSV_FILE}`.\n"
    );
    let _ = writeln!(r, "## Convergence\n\n![Best loss so far]({FIGURE_FILE})\n");
    let _ = writeln!(
        r,
        "Each target's statistic at every evaluation, its band shaded (a target never in its \
         band while the others are conflicts with them under these free fields):\n\n\
         ![Statistics per evaluation]({STATISTICS_FIGURE_FILE})\n"
    );
    unseen(&mut r, o);
    r
}

/// The statistics on unseen trials, or why there are none.
fn unseen(r: &mut String, o: &CalibrationOutcome) {
    let _ = writeln!(r, "## Unseen trials\n");
    let Some(c) = &o.check else {
        let _ = writeln!(r, "Skipped (`--check-trials 0`).");
        return;
    };
    let _ = writeln!(
        r,
        "The calibrated scenario once more, on {} trials per method from base seed {} (trials \
         the calibration never saw):\n",
        c.trials, c.seed
    );
    table(r, &c.statistics);
    if !c.failures.is_empty() {
        let _ = writeln!(r, "Failed trials (left out): {}\n", c.failures.join("; "));
    }
}

/// A table of statistics against their targets.
fn table(r: &mut String, rows: &[TargetCheck]) {
    let _ = writeln!(
        r,
        "| statistic | value | target | band | in band |\n|---|---|---|---|---|"
    );
    for c in rows {
        let _ = writeln!(
            r,
            "| {} (`{}`) | {} | {} | {} | {} |",
            c.target.name,
            c.target.statistic,
            num(c.value),
            c.target.value,
            c.target.band,
            match (c.holds, c.target.report_only) {
                (true, false) => "in",
                (false, false) => "**out**",
                (true, true) => "in (reported only)",
                (false, true) => "**out** (reported only)",
            }
        );
    }
    r.push('\n');
}
