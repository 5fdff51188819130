//! The terminal summary of a calibration (what `usar calibrate` prints at its end): what ran,
//! the statistics at the best values against their targets, the best values, the loss, the
//! statistics on unseen trials and where the files are.

use std::fmt::Write;

use super::outcome::{CalibrationOutcome, TargetCheck};
use super::progress::loss_text;
use usar_report::table::num;
use usar_report::targets::float_text::short;

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

/// Rows `statistic value target band in/OUT`, aligned. The names are padded by hand: a
/// width given to `format!` above 65,535 panics.
fn table(r: &mut String, rows: &[TargetCheck]) {
    let width = rows
        .iter()
        .map(|c| c.target.name.chars().count())
        .max()
        .unwrap_or(0)
        .max("statistic".len());
    let padded = |name: &str| {
        let pad = width.saturating_sub(name.chars().count());
        format!("{name}{}", " ".repeat(pad))
    };
    let _ = writeln!(
        r,
        "{}  {:>10}  {:>10}  {:<14}  in band",
        padded("statistic"),
        "value",
        "target",
        "band"
    );
    for c in rows {
        let _ = writeln!(
            r,
            "{}  {:>10}  {:>10}  {:<14}  {}",
            padded(&c.target.name),
            num(c.value),
            short(c.target.value),
            c.target.band.to_string(),
            c.target.mark(c.value)
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use usar_report::targets::{Band, MetricRef, Statistic, Target};

    /// Regression (issue 70): a target name longer than 65,535 characters made the padding
    /// panic ("Formatting argument out of range") after the calibration wrote its files.
    #[test]
    fn a_name_of_any_length_is_padded_without_panicking() {
        let target = |name: String| Target {
            name,
            statistic: Statistic::Mean(MetricRef("rounds".into())),
            value: 1e300,
            band: Band::PlusMinus(1.0),
            report_only: false,
        };
        let long = "n".repeat(70_000);
        let rows = vec![
            TargetCheck {
                target: target(long.clone()),
                value: 2.0,
                holds: false,
            },
            TargetCheck {
                target: target("short".into()),
                value: 2.0,
                holds: false,
            },
        ];
        let mut r = String::new();
        table(&mut r, &rows);
        let lines: Vec<&str> = r.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines[1].starts_with(&format!("{long}  ")), "row 1");
        let short_row = format!("short{}  ", " ".repeat(70_000 - 5));
        assert!(lines[2].starts_with(&short_row), "row 2 padded");
        // A huge target value is written short, not in 301 digits.
        assert!(lines[2].contains("  1e300  "), "{}", &lines[2][70_000..]);
    }
}
