//! The section of `multiverse.md` about a design shared by the universes (`--design N`):
//! the emulator's cross-validated error per target against the target's band, and how its
//! predictions compare with the universes' own calibrations. Made from the plan, the design's
//! point files and the records, so a merged multiverse writes the same section.

use std::fmt::Write as _;
use std::path::Path;

use super::design_run::read_design;
use super::emulator::Emulator;
use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use usar_report::targets::float_text::short;

/// The section, or `None` for a multiverse without a design.
pub fn design_section(
    plan: &MultiversePlan,
    records: &[UniverseRecord],
    dir: &Path,
) -> Option<String> {
    let id = &plan.identity;
    if id.design == 0 {
        return None;
    }
    let mut r = String::new();
    let _ = writeln!(r, "\n## The design shared by the universes\n");
    let _ = writeln!(
        r,
        "Before any universe, {} design evaluations ({} trials per method each) spread over the \
         universes and the free ranges (a Latin hypercube, docs/multiverse.md) were fitted by a \
         ridge-regression emulator of each target's statistic; each universe's calibration then \
         started where the emulator predicts its least loss. The universes' own evaluations decide \
         admissibility, never the emulator.\n",
        id.design, id.calibration_trials
    );
    let points = match read_design(plan, dir) {
        Ok(p) => p,
        Err(missing) => {
            let _ = writeln!(
                r,
                "The design is not complete: {} points missing.",
                missing.len()
            );
            return Some(r);
        }
    };
    let sizes: Vec<usize> = id.axes.axes.iter().map(|a| a.alternatives.len()).collect();
    let e = Emulator::fit(&points, &sizes, &id.free, id.targets.len());
    let ran = points.iter().filter(|p| p.message.is_none()).count();
    let _ = writeln!(
        r,
        "{ran} of {} design points ran every trial. The emulator's error by target (5-fold \
         cross-validated root-mean-square error, in the statistic's unit, against the band's \
         half-width; an error near or above the half-width means the emulator can only start a \
         search near the band):\n",
        points.len()
    );
    let _ = writeln!(
        r,
        "| target | band | points | penalty | SD over the design | CV error | error / half-width |\n|---|---|---:|---:|---:|---:|---:|"
    );
    for (t, fit) in id.targets.iter().zip(&e.fits) {
        let half = t.band.half_width(t.value);
        match fit {
            Some(f) => {
                let _ = writeln!(
                    r,
                    "| {} | {} | {} | {} | {} | {} | {} |",
                    t.name,
                    t.describe(),
                    f.points,
                    short(f.lambda),
                    sig(f.sd),
                    sig(f.cv_rmse),
                    if half.is_finite() && half > 0.0 {
                        sig(f.cv_rmse / half)
                    } else {
                        "-".into()
                    }
                );
            }
            None => {
                let _ = writeln!(
                    r,
                    "| {} | {} | too few | - | - | - | - |",
                    t.name,
                    t.describe()
                );
            }
        }
    }
    let calibrated: Vec<(f64, f64)> = records
        .iter()
        .filter_map(|u| u.calibration.as_ref())
        .map(|c| (c.predicted_loss, c.loss))
        .filter(|(p, _)| !p.is_nan())
        .collect();
    let predicted = calibrated.iter().filter(|(p, _)| *p == 0.0).count();
    let both = calibrated
        .iter()
        .filter(|(p, l)| *p == 0.0 && *l == 0.0)
        .count();
    let only = calibrated
        .iter()
        .filter(|(p, l)| *p > 0.0 && *l == 0.0)
        .count();
    let _ = writeln!(
        r,
        "\nOf {} calibrated universes, the emulator predicted {predicted} in every band at their \
         start, and {both} of those were admissible; {only} admissible universes were not \
         predicted so.",
        calibrated.len()
    );
    Some(r)
}

/// `x` to four significant digits.
fn sig(x: f64) -> String {
    short(crate::calibrate::round_significant(x, 4))
}
