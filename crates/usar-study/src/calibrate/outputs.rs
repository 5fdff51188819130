//! The files a calibration writes at its end, as one set through [`usar_sweep::atomic::FileSet`]
//! (every file complete or none changed): `calibrated.ron` (the base scenario with the best
//! values, [`usar_sweep::spec_ron::spec_to_ron`], after a header comment), `trace.csv` (one row per
//! evaluation), `calibration.md` (`super::markdown`), `convergence.svg` (`super::figure`),
//! `statistics.svg` (`super::targets_figure`) and `tradeoff.svg` (`super::tradeoff_figure`;
//! with at least two fitted targets).

use std::path::{Path, PathBuf};

use super::figure::convergence_svg;
use super::free::FreeField;
use super::markdown::calibration_md;
use super::outcome::{
    CALIBRATED_FILE, CalibrationOutcome, FIGURE_FILE, OUTPUT_FILES, REPORT_FILE,
    STATISTICS_FIGURE_FILE, TRACE_CSV_FILE, TRADEOFF_FIGURE_FILE,
};
use super::targets_figure::statistics_svg;
use super::tradeoff_figure::tradeoff_svg;
use usar_report::chart::figure_or_warn;
use usar_report::error::{ReportError, Result};
use usar_sweep::atomic::FileSet;
use usar_sweep::spec_ron::spec_to_ron;

/// Writes the outputs of `o` into `dir` as one set; returns their paths.
///
/// # Errors
/// A path that cannot be written (a folder in the way, a full disk): no file of the set
/// changes then. A figure that cannot be drawn is left out with a warning
/// ([`figure_or_warn`]); the other files are written.
pub fn write_outputs(o: &CalibrationOutcome, dir: &Path) -> Result<Vec<PathBuf>> {
    let mut set = FileSet::new();
    set.stage(&dir.join(CALIBRATED_FILE), calibrated_ron(o)?.as_bytes())?;
    set.stage(&dir.join(TRACE_CSV_FILE), trace_csv(o)?.as_bytes())?;
    set.stage(&dir.join(REPORT_FILE), calibration_md(o).as_bytes())?;
    if let Some(svg) = figure_or_warn(FIGURE_FILE, || convergence_svg(o)) {
        set.stage(&dir.join(FIGURE_FILE), svg.as_bytes())?;
    }
    if let Some(svg) = figure_or_warn(STATISTICS_FIGURE_FILE, || statistics_svg(o)) {
        set.stage(&dir.join(STATISTICS_FIGURE_FILE), svg.as_bytes())?;
    }
    if let Some(Some(svg)) = figure_or_warn(TRADEOFF_FIGURE_FILE, || tradeoff_svg(o)) {
        set.stage(&dir.join(TRADEOFF_FIGURE_FILE), svg.as_bytes())?;
    }
    Ok(set.commit()?)
}

/// `--overwrite` of a calibration's folder: removes its trace, the files [`write_outputs`]
/// writes and the temporary files killed runs left; the lock, the owner manifest and every
/// other file stay. Call it only while holding the folder's lock.
///
/// # Errors
/// An I/O error removing a file.
pub fn clear(dir: &Path) -> Result<()> {
    usar_sweep::atomic::remove_named(dir, &[super::trace::TRACE_FILE])?;
    usar_sweep::atomic::remove_named(dir, &OUTPUT_FILES)?;
    usar_sweep::atomic::remove_stale_temps(dir)?;
    Ok(())
}

/// A free value, or a statistic, as the files write it: Rust's shortest round-trip form
/// (`0.0055`, `14`, `NaN`, `inf`).
fn exact(x: f64) -> String {
    format!("{x}")
}

/// The text of `calibrated.ron`: a header comment (the command, the date, the base scenario
/// and targets, the search's end, the best values and every statistic with its band and
/// whether it holds), then the scenario.
///
/// # Errors
/// A spec ron cannot write (not expected).
pub fn calibrated_ron(o: &CalibrationOutcome) -> Result<String> {
    let h = &o.header;
    let best = o.best();
    let mut c = vec![
        format!("Calibrated by usar calibrate on {} (UTC):", o.date),
        format!("  {}", o.command),
        format!(
            "Base scenario: {} (scenario hash {}); targets: {}",
            o.origin, h.scenario_hash, o.targets_origin
        ),
        format!(
            "Search: {} evaluations, stopped because {}; best: evaluation #{}, loss {}{}",
            o.evaluations.len(),
            o.stop,
            best.index,
            exact(o.loss),
            if o.admissible {
                " (every statistic in its band)"
            } else {
                " (NOT every statistic in its band)"
            }
        ),
        "Free fields (value; range):".into(),
    ];
    for (f, x) in h.free.iter().zip(&best.values) {
        let scale = match (f.log, f.factor) {
            (true, true) => ", log scale, a factor of the base scenario's value(s)",
            (false, true) => ", a factor of the base scenario's value(s)",
            (true, false) => ", log scale",
            (false, false) => "",
        };
        c.push(format!(
            "  {} = {} ({}..{}{scale})",
            f.field,
            exact(*x),
            f.lo,
            f.hi
        ));
    }
    c.push(format!(
        "Statistics at these values ({}, pooled over methods):",
        o.trials_text()
    ));
    for s in &o.statistics {
        c.push(format!(
            "  {}: {} (target {}): {}",
            s.target.name,
            exact(s.value),
            s.target.describe(),
            s.target.mark(s.value)
        ));
    }
    Ok(spec_to_ron(&o.best_spec, &c)?)
}

/// The text of `trace.csv`: columns `index`, each free field, each target's name, `loss`,
/// `message`; one row per evaluation in order; numbers in their shortest round-trip form.
///
/// # Errors
/// A CSV error (not expected).
pub fn trace_csv(o: &CalibrationOutcome) -> Result<String> {
    let mut w = csv::Writer::from_writer(Vec::new());
    let mut head = vec!["index".to_string()];
    head.extend(o.header.free.iter().map(FreeField::label));
    head.extend(o.header.targets.iter().map(|t| t.name.clone()));
    head.extend(["loss".to_string(), "message".to_string()]);
    w.write_record(&head)?;
    for e in &o.evaluations {
        let mut row = vec![e.index.to_string()];
        row.extend(e.values.iter().map(|&x| exact(x)));
        row.extend(e.statistics.iter().map(|&x| exact(x)));
        row.push(exact(e.loss));
        row.push(e.message.clone().unwrap_or_default());
        w.write_record(&row)?;
    }
    let bytes = w
        .into_inner()
        .map_err(ReportError::finish("writing trace.csv"))?;
    // The writer wrote only `String`s: the bytes are UTF-8.
    Ok(String::from_utf8_lossy(&bytes).into_owned())
}
