//! `convergence.svg`: the loss of each evaluation (dots; +inf as triangles along the top)
//! and the best loss so far (a step line) against the evaluation index, on a `log10(1 +
//! loss)` axis so that a loss of 0 is shown (plotters, plain SVG text, as the sweep's
//! figures).

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use usar_report::error::Result;

use super::outcome::CalibrationOutcome;
use usar_report::chart::{FIGURE_SIZE, draw_err};

/// The axis value of `loss`: `log10(1 + loss)` (0 for 0).
fn axis(loss: f64) -> f64 {
    loss.ln_1p() / std::f64::consts::LN_10
}

/// A tick's label: `0`, `1`, `10`, ..., `1e6` from a million on.
fn num_tick(l: f64) -> String {
    if l >= 1e6 {
        format!("{l:e}")
    } else {
        format!("{l}")
    }
}

/// A chart on an SVG string with numeric axes.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// The SVG text of `convergence.svg`.
///
/// # Errors
/// If plotters fails to draw.
pub fn convergence_svg(o: &CalibrationOutcome) -> Result<String> {
    let losses: Vec<f64> = o.evaluations.iter().map(|e| e.loss).collect();
    losses_svg(&o.header.scenario, &losses, o.best)
}

/// The convergence figure of a calibration of `scenario` with these `losses` (in evaluation
/// order; any values, +inf drawn as a triangle at the top) and the best at index `best`.
///
/// # Errors
/// If plotters fails to draw.
pub(crate) fn losses_svg(scenario: &str, losses: &[f64], best: usize) -> Result<String> {
    let top = losses
        .iter()
        .filter(|l| l.is_finite())
        .map(|&l| axis(l))
        .fold(0.0f64, f64::max);
    let y_max = if top > 0.0 { top * 1.12 } else { 1.0 };
    let n = losses.len().max(1) as f64;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, FIGURE_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let mut chart = ChartBuilder::on(&root)
            .caption(
                format!("Calibration of {scenario}: loss per evaluation"),
                ("sans-serif", 20),
            )
            .margin(16)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d(-0.5f64..(n - 0.5), 0.0..y_max)
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .x_desc("evaluation")
            .y_desc("loss (axis: log of 1 + loss)")
            .x_label_formatter(&|x| format!("{x:.0}"))
            .y_labels(0)
            .disable_y_mesh()
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 15))
            .light_line_style(RGBColor(238, 238, 238))
            .draw()
            .map_err(draw_err)?;
        ticks(&mut chart, &root, y_max, n)?;
        points(&mut chart, losses, y_max)?;
        best_line(&mut chart, losses, best)?;
        root.draw(&Text::new(
            "dots: each evaluation; line: best so far; ring: the best; triangles at the top: +inf \
             (a failed trial, a broken rule or an undefined statistic)",
            (16, FIGURE_SIZE.1 as i32 - 14),
            ("sans-serif", 12).into_font().color(&RGBColor(90, 90, 90)),
        ))
        .map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// Horizontal lines and labels at a loss of 0 and the powers of ten below `y_max` (axis
/// units), across `n` evaluations: what a reader compares losses by.
fn ticks(
    chart: &mut Chart<'_, '_>,
    root: &DrawingArea<SVGBackend<'_>, Shift>,
    y_max: f64,
    n: f64,
) -> Result<()> {
    let levels = std::iter::once(0.0)
        .chain((0..12).map(|k| 10f64.powi(k)))
        .filter(|&l| axis(l) <= y_max);
    for l in levels {
        let y = axis(l);
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(-0.5, y), (n - 0.5, y)],
                RGBColor(220, 220, 220),
            )))
            .map_err(draw_err)?;
        let (px, py) = chart.backend_coord(&(-0.5, y));
        root.draw(&Text::new(
            num_tick(l),
            (px - 8, py),
            ("sans-serif", 13)
                .into_font()
                .color(&BLACK)
                .pos(Pos::new(HPos::Right, VPos::Center)),
        ))
        .map_err(draw_err)?;
    }
    Ok(())
}

/// A dot per finite loss, a triangle along the top (at `y_max`) per infinite one.
fn points(chart: &mut Chart<'_, '_>, losses: &[f64], y_max: f64) -> Result<()> {
    let finite = losses
        .iter()
        .enumerate()
        .filter(|(_, l)| l.is_finite())
        .map(|(i, &l)| Circle::new((i as f64, axis(l)), 3, RGBColor(150, 150, 150).filled()));
    chart.draw_series(finite).map_err(draw_err)?;
    let failed = losses
        .iter()
        .enumerate()
        .filter(|(_, l)| !l.is_finite())
        .map(|(i, _)| {
            TriangleMarker::new((i as f64, y_max * 0.97), 5, RGBColor(213, 94, 0).filled())
        });
    chart.draw_series(failed).map_err(draw_err)?;
    Ok(())
}

/// The best loss so far as a step line (from the first finite loss on), and a ring around
/// evaluation `best`.
fn best_line(chart: &mut Chart<'_, '_>, losses: &[f64], best: usize) -> Result<()> {
    let mut so_far = f64::INFINITY;
    let mut steps: Vec<(f64, f64)> = Vec::new();
    for (i, &l) in losses.iter().enumerate() {
        so_far = so_far.min(l);
        if so_far.is_finite() {
            if let Some(&(_, y)) = steps.last() {
                steps.push((i as f64, y));
            }
            steps.push((i as f64, axis(so_far)));
        }
    }
    let blue = RGBColor(0, 114, 178);
    chart
        .draw_series(LineSeries::new(steps, blue.stroke_width(2)))
        .map_err(draw_err)?;
    if let Some(&l) = losses.get(best).filter(|l| l.is_finite()) {
        chart
            .draw_series(std::iter::once(Circle::new(
                (best as f64, axis(l)),
                6,
                blue.stroke_width(2),
            )))
            .map_err(draw_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_axis_shows_zero_and_ticks_read_plainly() {
        assert_eq!(axis(0.0), 0.0);
        assert!((axis(9.0) - 1.0).abs() < 1e-12);
        assert!((axis(99.0) - 2.0).abs() < 1e-12);
        assert_eq!(num_tick(0.0), "0");
        assert_eq!(num_tick(1000.0), "1000");
        assert_eq!(num_tick(1e7), "1e7");
    }
}
