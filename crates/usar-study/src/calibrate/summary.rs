//! The terminal summary of a calibration (what `usar calibrate` prints at its end): what ran,
//! the statistics at the best values against their targets, the best values, the loss, the
//! statistics on unseen trials and where the files are.

use std::fmt::Write;

use super::outcome::{CalibrationOutcome, TargetCheck};
use super::progress::loss_text;
use usar_report::table::num;

/// The summary's text, lines ending in `\n`.
pub fn summary_text(o: &CalibrationOutcome) -> String {
    let mut r = String::new();
    let _ = writeln!(
        r,
        "calibration of {}: {} evaluations ({} run now, {} from the trace) in {:.2} s on {} \
         thread(s); stopped because {}\n",
        o.header.scenario,
        o.evaluations.len(),
        o.ran,
        o.reused,
        o.wall_s,
        o.threads,
        o.stop
    );
    table(&mut r, &o.statistics);
    let values: Vec<String> = o
        .header
        .free
        .iter()
        .zip(o.best_values())
        .map(|(f, x)| f.assignment(*x))
        .collect();
    let _ = writeln!(r, "\nbest values: {}", values.join(" "));
    let _ = writeln!(
        r,
        "loss: {} (evaluation #{}); every statistic in its band: {}",
        loss_text(o.loss),
        o.best().index,
        if o.admissible { "yes" } else { "no" }
    );
    if let Some(c) = &o.check {
        let _ = writeln!(
            r,
            "\nunseen trials ({} per method from base seed {}):\n",
            c.trials, c.seed
        );
        table(&mut r, &c.statistics);
        if !c.failures.is_empty() {
            let _ = writeln!(r, "failed trials (left out): {}", c.failures.join("; "));
        }
    }
    let _ = writeln!(r);
    for f in &o.files {
        let _ = writeln!(r, "wrote {}", f.display());
    }
    r
}

/// Rows `statistic value target band in/OUT`, aligned.
fn table(r: &mut String, rows: &[TargetCheck]) {
    let width = rows
        .iter()
        .map(|c| c.target.name.chars().count())
        .max()
        .unwrap_or(0)
        .max("statistic".len());
    let _ = writeln!(
        r,
        "{:width$}  {:>10}  {:>10}  {:<14}  in band",
        "statistic", "value", "target", "band"
    );
    for c in rows {
        let _ = writeln!(
            r,
            "{:width$}  {:>10}  {:>10}  {:<14}  {}",
            c.target.name,
            num(c.value),
            c.target.value,
            c.target.band.to_string(),
            c.target.mark(c.value)
        );
    }
}
