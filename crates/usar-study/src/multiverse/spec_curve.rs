//! `spec_curve_<claim id>.svg`: a specification curve in the manner of Simonsohn, Simmons &
//! Nelson (2020, "Specification curve analysis", Nature Human Behaviour 4:1208).
//!
//! Top panel: the claim's effect ([`super::effect`]) in every admissible universe, sorted
//! ascending (ties by universe index), with its 95 % confidence interval as a bar, coloured
//! by verdict (holds, not significant, does not hold; the sweep figures' Okabe-Ito palette),
//! and the zero line. Bottom panel, on the same horizontal order: one row per alternative of
//! each axis (grouped by axis, labelled `axis: alternative`), a dark dot where the universe
//! takes it. Universes that are not admissible, and admissible ones without an effect (the
//! comparison did not run, the claim was not tested), are left out; the caption says how
//! many. Plain SVG text (plotters), as the sweep's figures.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use usar_report::error::Result;

use super::plan::MultiversePlan;
use super::record::UniverseRecord;
use usar_report::chart::{axis_range, draw_err, method_color, plotted};
use usar_report::claims::{Claim, Verdict};

/// Width of the figure, pixels.
const WIDTH: u32 = 900;
/// Height of the title strip, the effect panel and the caption strip, pixels.
const TITLE_H: u32 = 56;
const TOP_H: u32 = 300;
const CAPTION_H: u32 = 44;
/// Height of one row of the dot matrix, pixels.
const ROW_H: u32 = 16;
/// Width of the label area left of both panels, pixels.
const LABEL_W: u32 = 230;

/// Width of the effect axis's ticks and title, pixels (the rest of [`LABEL_W`] is margin, so
/// that both panels' plotting areas start at the same x).
const TICKS_W: u32 = 80;
/// Longest row label of the dot matrix, characters: what fits in [`LABEL_W`] at 12 px.
const LABEL_CHARS: usize = 34;

/// `text` cut to `max` characters, the last one an ellipsis when it is cut.
fn short(text: &str, max: usize) -> String {
    if text.chars().count() <= max {
        return text.to_string();
    }
    let head: String = text.chars().take(max.saturating_sub(1)).collect();
    format!("{head}…")
}

/// The file name of the figure of `claim`: `spec_curve_<id>.svg`.
pub fn spec_curve_file(claim: &Claim) -> String {
    format!("spec_curve_{}.svg", claim.id)
}

/// The colour of a verdict (in words): holds green, not significant orange, does not hold
/// vermillion, anything else grey.
fn verdict_color(words: &str) -> RGBColor {
    if words == Verdict::Holds.words() {
        method_color(2)
    } else if words == Verdict::NotSignificant.words() {
        method_color(1)
    } else if words == Verdict::DoesNotHold.words() {
        method_color(5)
    } else {
        RGBColor(150, 150, 150)
    }
}

/// One point of the curve.
struct Point<'a> {
    record: &'a UniverseRecord,
    effect: f64,
    low: f64,
    high: f64,
    verdict: &'a str,
}

/// The admissible universes with an effect for `claim`, sorted by effect then index.
fn points<'a>(records: &'a [UniverseRecord], claim: &Claim) -> Vec<Point<'a>> {
    let mut pts: Vec<Point<'a>> = records
        .iter()
        .filter(|r| r.admissible())
        .filter_map(|r| {
            let c = r.claim(&claim.id)?;
            c.effect.is_finite().then_some(Point {
                record: r,
                effect: c.effect,
                low: c.ci_low,
                high: c.ci_high,
                verdict: c.verdict.as_str(),
            })
        })
        .collect();
    pts.sort_by(|a, b| {
        a.effect
            .total_cmp(&b.effect)
            .then(a.record.index.cmp(&b.record.index))
    });
    pts
}

/// The effect axis: from the lowest to the highest of 0, effects and interval ends, with 8 %
/// room ([`axis_range`]: finite and never empty); `-1..1` when they are all 0.
fn y_range(pts: &[Point<'_>]) -> (f64, f64) {
    let values = pts
        .iter()
        .flat_map(|p| [p.effect, p.low, p.high])
        .chain(std::iter::once(0.0));
    if values.clone().filter(|x| x.is_finite()).all(|x| x == 0.0) {
        return (-1.0, 1.0);
    }
    axis_range(values, 0.08)
}

/// The SVG text of the specification curve of `claim` over `records`.
///
/// # Errors
/// If plotters fails to draw.
pub fn spec_curve_svg(
    plan: &MultiversePlan,
    records: &[UniverseRecord],
    claim: &Claim,
) -> Result<String> {
    let axes = &plan.identity.axes.axes;
    let rows: usize = axes.iter().map(|a| a.alternatives.len()).sum();
    let matrix_h = ROW_H * rows as u32 + 24;
    let height = TITLE_H + TOP_H + matrix_h + CAPTION_H;
    let pts = points(records, claim);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (WIDTH, height)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (title, rest) = root.split_vertically(TITLE_H);
        let (top, rest) = rest.split_vertically(TOP_H);
        let (matrix, caption) = rest.split_vertically(matrix_h);
        draw_title(&title, claim)?;
        let n = pts.len().max(1) as f64;
        draw_effects(&root, &top, &pts, n)?;
        draw_matrix(&root, &matrix, plan, &pts, n)?;
        draw_caption(&caption, records, &pts)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

fn font(size: u32) -> TextStyle<'static> {
    ("sans-serif", size).into_font().color(&BLACK)
}

/// The claim in words and the legend of the verdict colours.
fn draw_title(area: &Root<'_>, claim: &Claim) -> Result<()> {
    area.draw(&Text::new(
        format!("Claim {}: {}", claim.id, claim.sentence),
        (16, 20),
        font(18).pos(Pos::new(HPos::Left, VPos::Center)),
    ))
    .map_err(draw_err)?;
    let verdicts = [
        Verdict::Holds,
        Verdict::NotSignificant,
        Verdict::DoesNotHold,
    ];
    for (i, v) in verdicts.iter().enumerate() {
        let x = LABEL_W as i32 + 150 * i as i32;
        area.draw(&Circle::new((x, 44), 5, verdict_color(v.words()).filled()))
            .map_err(draw_err)?;
        area.draw(&Text::new(
            v.words(),
            (x + 10, 44),
            font(13).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(draw_err)?;
    }
    Ok(())
}

/// The whole figure, where text placed by a chart's backend coordinates is drawn.
type Root<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// The top panel (`area` of `root`): effects, intervals and the zero line over `n`
/// positions.
fn draw_effects(root: &Root<'_>, area: &Root<'_>, pts: &[Point<'_>], n: f64) -> Result<()> {
    let (lo, hi) = y_range(pts);
    let mut chart = ChartBuilder::on(area)
        .margin_right(16)
        .margin_top(6)
        .margin_left(LABEL_W - TICKS_W)
        .x_label_area_size(8)
        .y_label_area_size(TICKS_W)
        .build_cartesian_2d(-0.5f64..(n - 0.5), lo..hi)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_labels(0)
        .y_desc("effect: subject minus strongest rival")
        .label_style(("sans-serif", 12))
        .axis_desc_style(("sans-serif", 14))
        .light_line_style(RGBColor(238, 238, 238))
        .draw()
        .map_err(draw_err)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![(-0.5, 0.0), (n - 0.5, 0.0)],
            RGBColor(120, 120, 120).stroke_width(1),
        )))
        .map_err(draw_err)?;
    let bars = pts
        .iter()
        .enumerate()
        .filter(|(_, p)| p.low.is_finite() && p.high.is_finite())
        .map(|(i, p)| {
            PathElement::new(
                vec![(i as f64, plotted(p.low)), (i as f64, plotted(p.high))],
                verdict_color(p.verdict).stroke_width(2),
            )
        });
    chart.draw_series(bars).map_err(draw_err)?;
    let dots = pts.iter().enumerate().map(|(i, p)| {
        let at = (i as f64, plotted(p.effect));
        Circle::new(at, 4, verdict_color(p.verdict).filled())
    });
    chart.draw_series(dots).map_err(draw_err)?;
    if pts.is_empty() {
        let (x, y) = chart.backend_coord(&(0.0, (lo + hi) / 2.0));
        root.draw(&Text::new(
            "no admissible universe with an effect",
            (x, y),
            font(15).pos(Pos::new(HPos::Center, VPos::Center)),
        ))
        .map_err(draw_err)?;
    }
    Ok(())
}

/// The bottom panel (`area` of `root`): a row per alternative, a dot where each universe
/// takes it.
fn draw_matrix(
    root: &Root<'_>,
    area: &Root<'_>,
    plan: &MultiversePlan,
    pts: &[Point<'_>],
    n: f64,
) -> Result<()> {
    let axes = &plan.identity.axes.axes;
    let rows: usize = axes.iter().map(|a| a.alternatives.len()).sum();
    let mut chart = ChartBuilder::on(area)
        .margin_right(16)
        .margin_top(12)
        .margin_bottom(12)
        .y_label_area_size(LABEL_W)
        .build_cartesian_2d(-0.5f64..(n - 0.5), -(rows as f64) + 0.5..0.5)
        .map_err(draw_err)?;
    let mut row = 0usize;
    for (a, axis) in axes.iter().enumerate() {
        for (k, alt) in axis.alternatives.iter().enumerate() {
            let y = -(row as f64);
            let (px, py) = chart.backend_coord(&(-0.5, y));
            root.draw(&Text::new(
                short(&format!("{}: {}", axis.name, alt.name), LABEL_CHARS),
                (px - 8, py),
                font(12).pos(Pos::new(HPos::Right, VPos::Center)),
            ))
            .map_err(draw_err)?;
            let dots = pts.iter().enumerate().map(|(i, p)| {
                let taken = p.record.choices.get(a) == Some(&k);
                let (size, color) = if taken {
                    (4, RGBColor(40, 40, 40))
                } else {
                    (1, RGBColor(205, 205, 205))
                };
                Circle::new((i as f64, y), size, color.filled())
            });
            chart.draw_series(dots).map_err(draw_err)?;
            row += 1;
        }
        if a + 1 < axes.len() {
            let y = -(row as f64) + 0.5;
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(-0.5, y), (n - 0.5, y)],
                    RGBColor(225, 225, 225),
                )))
                .map_err(draw_err)?;
        }
    }
    Ok(())
}

/// How many universes are shown and how many are left out, and what the bars are.
fn draw_caption(area: &Root<'_>, records: &[UniverseRecord], pts: &[Point<'_>]) -> Result<()> {
    let admissible = records.iter().filter(|r| r.admissible()).count();
    let lines = [
        format!(
            "{} of {} universes shown, sorted by effect; left out: {} not admissible, {} \
             admissible without an effect.",
            pts.len(),
            records.len(),
            records.len() - admissible,
            admissible - pts.len()
        ),
        "Dots: the effect; bars: its 95 % Welch confidence interval; above 0 is the claim's \
         direction."
            .to_string(),
    ];
    for (i, text) in lines.iter().enumerate() {
        area.draw(&Text::new(
            text.as_str(),
            (16, 12 + 16 * i as i32),
            ("sans-serif", 12).into_font().color(&RGBColor(90, 90, 90)),
        ))
        .map_err(draw_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::multiverse::plan::tests::plan;
    use crate::multiverse::record::tests::record;
    use usar_report::claims::paper_claims;

    #[test]
    fn only_admissible_universes_with_an_effect_are_drawn_in_effect_order() {
        let mut a = record(0, &[0, 0], 0.0);
        let mut b = record(1, &[1, 2], 0.0);
        let c = record(2, &[0, 1], 3.0); // not admissible
        if let Some(x) = a.comparison.as_mut() {
            x.claims[0].effect = 5.0;
        }
        if let Some(x) = b.comparison.as_mut() {
            x.claims[0].effect = -1.0;
            x.claims[0].verdict = "does not hold".into();
        }
        let records = [a, b, c];
        let pts = points(&records, &paper_claims().claims()[0]);
        let order: Vec<u64> = pts.iter().map(|p| p.record.index).collect();
        assert_eq!(order, [1, 0]);
        let (lo, hi) = y_range(&pts);
        assert!(lo < -1.0 && hi > 5.0);
        let svg = spec_curve_svg(&plan(), &records, &paper_claims().claims()[0]).unwrap();
        assert!(svg.starts_with("<svg"), "{}", &svg[..40]);
        assert!(svg.contains("Claim 1: RNE rescues the most in total"));
        assert!(svg.contains("a: a1") && svg.contains("b: b2"));
        assert!(svg.contains("2 of 3 universes shown"), "caption");
        assert!(svg.contains("1 not admissible"));
        assert_eq!(short("abc", 3), "abc");
        assert_eq!(short("abcd", 3), "ab…");
        // A claim no universe has an effect for still gives a figure.
        let empty = spec_curve_svg(&plan(), &records, &paper_claims().claims()[1]).unwrap();
        assert!(empty.contains("no admissible universe with an effect"));
    }
}
