//! `sensitivity_<claim>.svg`: per claim, the share of its effect's variance each axis, the
//! interaction of the two strongest and each calibrated value explains
//! ([`super::decompose`]), a bar each (largest first), with the share's chance level as a
//! black tick and, for an axis, its total-order share as an outlined bar; one panel over the
//! admissible universes, one over every compared universe.

use plotters::prelude::*;
use usar_report::error::Result;

use super::decompose::{Decomposition, Scope, Share, decompose_over};
use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use usar_report::chart::{draw_err, method_color};
use usar_report::claims::Claim;

/// The file name of `claim`'s figure: `sensitivity_<id>.svg`.
pub fn sensitivity_file(claim: &Claim) -> String {
    format!("sensitivity_{}.svg", claim.id)
}

/// Row height, pixels.
const ROW: u32 = 22;

/// The width of one panel, pixels.
const PANEL_W: u32 = 760;

/// The SVG text of `claim`'s sensitivity figure over `records` of `plan`: two panels, the
/// decomposition over the admissible universes (left) and over every compared universe,
/// admissible or not (right, [`Scope::Compared`]); a panel with nothing to split (fewer than
/// 3 universes with an effect, or one that does not vary) says so.
///
/// # Errors
/// If plotters fails to draw.
pub fn sensitivity_svg(
    plan: &MultiversePlan,
    records: &[UniverseRecord],
    claim: &Claim,
) -> Result<String> {
    let panels: Vec<(Scope, Option<Decomposition>)> = [Scope::Admissible, Scope::Compared]
        .into_iter()
        .map(|s| (s, decompose_over(plan, records, claim, s)))
        .collect();
    let rows_max = panels
        .iter()
        .map(|(_, d)| d.as_ref().map_or(1, |d| rows_of(d).0.len().max(1)))
        .max()
        .unwrap_or(1);
    let height = 110 + ROW * rows_max as u32;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (2 * PANEL_W, height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let title = format!(
            "Claim {}: {} - share of the effect's variance",
            claim.id, claim.sentence
        );
        let body = root.titled(&title, ("sans-serif", 15)).map_err(draw_err)?;
        let (left, right) = body.split_horizontally(PANEL_W);
        for ((scope, d), area) in panels.iter().zip([left, right]) {
            draw_panel(&area, *scope, d.as_ref())?;
        }
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// A panel's rows, strongest axis first: (label, share).
type Rows<'a> = Vec<(String, &'a Share)>;

/// The rows of a panel, strongest axis first (label, share), and the rows with a
/// total-order share (row, share).
fn rows_of(d: &Decomposition) -> (Rows<'_>, Vec<(usize, f64)>) {
    let mut rows: Rows = Vec::new();
    let mut totals: Vec<(usize, f64)> = Vec::new();
    for a in d.strongest() {
        if let Some(t) = &d.total[a] {
            totals.push((rows.len(), t.share));
        }
        rows.push((format!("axis: {}", d.axes[a].name), &d.axes[a]));
    }
    if let Some((_, _, i)) = &d.interaction {
        rows.push((format!("interaction: {}", i.name), i));
    }
    for f in &d.free {
        rows.push((format!("calibrated: {}", f.name), f));
    }
    (rows, totals)
}

/// One panel: a bar per input, the chance level as a black tick, an axis's total-order share
/// outlined.
fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    scope: Scope,
    d: Option<&Decomposition>,
) -> Result<()> {
    let (rows, totals) = d.map(rows_of).unwrap_or_default();
    let caption = match d {
        Some(d) => format!("over {} {}", d.n, scope.noun()),
        None => format!("over the {}: nothing to split", scope.noun()),
    };
    let n = rows.len().max(1);
    let mut chart = ChartBuilder::on(area)
        .caption(caption, ("sans-serif", 13))
        .margin(10)
        .x_label_area_size(30)
        .y_label_area_size(330)
        .build_cartesian_2d(0f64..1f64, (0..n).into_segmented())
        .map_err(draw_err)?;
    let labels: Vec<String> = rows.iter().map(|(l, _)| l.clone()).collect();
    chart
        .configure_mesh()
        .disable_y_mesh()
        .x_desc("share (outline: total-order share; black tick: chance level)")
        .x_label_formatter(&|x| format!("{:.0} %", 100.0 * x))
        .y_label_formatter(&|y| match y {
            SegmentValue::CenterOf(i) => labels.get(*i).cloned().unwrap_or_default(),
            _ => String::new(),
        })
        .label_style(("sans-serif", 11))
        .draw()
        .map_err(draw_err)?;
    let bar = method_color(0).filled();
    chart
        .draw_series(rows.iter().enumerate().map(|(i, (_, s))| {
            Rectangle::new(
                [
                    (0.0, SegmentValue::Exact(i)),
                    (s.share.clamp(0.0, 1.0), SegmentValue::Exact(i + 1)),
                ],
                bar,
            )
        }))
        .map_err(draw_err)?;
    chart
        .draw_series(totals.iter().map(|&(i, t)| {
            Rectangle::new(
                [
                    (0.0, SegmentValue::Exact(i)),
                    (t.clamp(0.0, 1.0), SegmentValue::Exact(i + 1)),
                ],
                method_color(1).stroke_width(2),
            )
        }))
        .map_err(draw_err)?;
    chart
        .draw_series(rows.iter().enumerate().map(|(i, (_, s))| {
            PathElement::new(
                vec![
                    (s.chance.clamp(0.0, 1.0), SegmentValue::Exact(i)),
                    (s.chance.clamp(0.0, 1.0), SegmentValue::Exact(i + 1)),
                ],
                BLACK.stroke_width(2),
            )
        }))
        .map_err(draw_err)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::tests::record;

    #[test]
    fn a_figure_names_its_claim_and_every_input() {
        let records: Vec<_> = (0..6u64)
            .map(|i| {
                let mut r = record(i, &[(i % 2) as usize, (i % 3) as usize], 0.0);
                if let Some(c) = r.comparison.as_mut() {
                    c.claims[0].effect = (i % 3) as f64;
                }
                r
            })
            .collect();
        let claim = &usar_report::claims::paper_claims().claims()[0];
        assert_eq!(sensitivity_file(claim), "sensitivity_1.svg");
        let svg = sensitivity_svg(&plan(), &records, claim).unwrap();
        assert!(svg.starts_with("<svg"));
        for part in [
            "Claim 1: RNE rescues the most",
            "over 6 admissible universes",
            "over 6 compared universes",
            "axis: b",
            "interaction: b x a",
            "calibrated: mission.energy_pct_per_m",
            "total-order share",
        ] {
            assert!(svg.contains(part), "{part}");
        }
        // Two axes: two outlined total-order bars (orange, #E69F00); none for an axis in which
        // no two universes differ alone (a, among (0, 0), (0, 1), (0, 2)).
        let outlined = |svg: &str| {
            svg.lines()
                .filter(|l| l.contains("<rect") && l.contains("#E69F00"))
                .count()
        };
        assert_eq!(outlined(&svg), 4, "two in each panel: {svg}");
        let alone = [records[0].clone(), records[4].clone(), records[2].clone()];
        assert_eq!(
            outlined(&sensitivity_svg(&plan(), &alone, claim).unwrap()),
            2
        );
        // Two admissible of six compared: nothing to split among the admissible, the six
        // compared split as before.
        let mut loose = records.clone();
        for r in &mut loose[2..] {
            if let Some(c) = r.calibration.as_mut() {
                c.loss = 1.5;
            }
        }
        let split = sensitivity_svg(&plan(), &loose, claim).unwrap();
        assert!(
            split.contains("over the admissible universes: nothing to split"),
            "{split}"
        );
        assert!(split.contains("over 6 compared universes"), "{split}");
        assert!(split.contains("axis: b"), "{split}");
        let empty = sensitivity_svg(&plan(), &records[..2], claim).unwrap();
        assert!(empty.contains("over the compared universes: nothing to split"));
    }
}
