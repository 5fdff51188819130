//! The files at the top of a multiverse's output folder, made from its plan and records and
//! written as one [`FileSet`] (every file staged in a temporary file, then all renamed):
//! `multiverse.csv`, one `spec_curve_<claim>.svg` per claim, `targets.svg` (each target's
//! statistic per universe, over the comparison's trials) and `multiverse.md`.

use std::path::{Path, PathBuf};

use usar_report::error::Result;

use super::csv::multiverse_csv;
use super::emulator_md::design_section;
use super::markdown::{TARGETS_FIGURE_FILE, multiverse_md};
use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use super::sensitivity_figure::{sensitivity_file, sensitivity_svg};
use super::spec_curve::{spec_curve_file, spec_curve_svg};
use crate::calibrate::targets_figure::targets_svg;
use usar_report::chart::figure_or_warn;
use usar_report::claims::Claim;
use usar_sweep::atomic::FileSet;

/// The long-form table.
pub const CSV_FILE: &str = "multiverse.csv";
/// The report.
pub const REPORT_FILE: &str = "multiverse.md";

/// The names of every file [`write_outputs`] writes for a multiverse checking `claims`, in
/// that order.
pub fn output_files(claims: &[Claim]) -> Vec<String> {
    let mut out = vec![CSV_FILE.to_string()];
    out.extend(claims.iter().map(spec_curve_file));
    out.extend(claims.iter().map(sensitivity_file));
    out.push(TARGETS_FIGURE_FILE.to_string());
    out.push(REPORT_FILE.to_string());
    out
}

/// Writes `multiverse.csv`, the specification curves and `multiverse.md` of `records` (every
/// universe of the plan, in universe order) into `dir`; returns their paths.
///
/// # Errors
/// An I/O error or a path that cannot be written; no file is changed then. A figure that
/// cannot be drawn is left out with a warning ([`figure_or_warn`]).
pub fn write_outputs(
    plan: &MultiversePlan,
    records: &[UniverseRecord],
    dir: &Path,
) -> Result<Vec<PathBuf>> {
    let mut files = FileSet::new();
    files.stage(&dir.join(CSV_FILE), &multiverse_csv(plan, records)?)?;
    for c in &plan.identity.claims {
        let name = spec_curve_file(c);
        if let Some(svg) = figure_or_warn(&name, || spec_curve_svg(plan, records, c)) {
            files.stage(&dir.join(name), svg.as_bytes())?;
        }
    }
    for c in &plan.identity.claims {
        let name = sensitivity_file(c);
        if let Some(svg) = figure_or_warn(&name, || sensitivity_svg(plan, records, c)) {
            files.stage(&dir.join(name), svg.as_bytes())?;
        }
    }
    if let Some(svg) = figure_or_warn(TARGETS_FIGURE_FILE, || targets_figure(plan, records)) {
        files.stage(&dir.join(TARGETS_FIGURE_FILE), svg.as_bytes())?;
    }
    let mut md = multiverse_md(plan, records);
    if let Some(section) = design_section(plan, records, dir) {
        md.push_str(&section);
    }
    files.stage(&dir.join(REPORT_FILE), md.as_bytes())?;
    Ok(files.commit()?)
}

/// `targets.svg`: a panel per target, its statistic over each compared universe's trials (in
/// universe order; NaN for a universe not compared), its band shaded.
///
/// # Errors
/// If plotters fails to draw.
fn targets_figure(plan: &MultiversePlan, records: &[UniverseRecord]) -> Result<String> {
    let targets = &plan.identity.targets;
    let values: Vec<Vec<f64>> = (0..targets.len())
        .map(|k| {
            records
                .iter()
                .map(|r| {
                    r.comparison
                        .as_ref()
                        .and_then(|c| c.targets.get(k).copied())
                        .unwrap_or(f64::NAN)
                })
                .collect()
        })
        .collect();
    targets_svg(
        &format!(
            "Multiverse of {}: each target's statistic per universe (x: universe in order; \
             comparison trials, calibrated values)",
            plan.identity.scenario
        ),
        targets,
        &values,
        None,
    )
}
