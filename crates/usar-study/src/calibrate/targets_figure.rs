//! Small multiples of target statistics: one panel per target, its statistic at each point
//! (dots: blue in the band, grey out of it) against the point's index, with the target's
//! band shaded and one point ringed. A calibration draws it over its evaluations
//! (`statistics.svg`: which targets a search reaches and which it never does; two targets
//! never in their bands at the same evaluation conflict under the free fields searched), a
//! multiverse over its universes (plotters, plain SVG text, as the other figures).

use plotters::coord::Shift;
use plotters::prelude::*;
use usar_report::error::Result;

use super::outcome::CalibrationOutcome;
use usar_report::chart::{axis_range, draw_err, plotted, tick_label};
use usar_report::targets::file::Target;

/// Panels per row.
const COLUMNS: usize = 4;
/// Size of one panel, pixels.
const PANEL: (u32, u32) = (300, 190);

/// The SVG text of `statistics.svg` for `o`: [`targets_svg`] over its evaluations, the best
/// ringed.
///
/// # Errors
/// If plotters fails to draw.
pub fn statistics_svg(o: &CalibrationOutcome) -> Result<String> {
    let values: Vec<Vec<f64>> = (0..o.header.targets.len())
        .map(|k| o.evaluations.iter().map(|e| e.statistics[k]).collect())
        .collect();
    targets_svg(
        &format!(
            "Calibration of {}: each target's statistic per evaluation (band shaded, best \
             ringed)",
            o.header.scenario
        ),
        &o.header.targets,
        &values,
        Some(o.best),
    )
}

/// A panel per target of `targets` (in order), titled `title`: `values[k][i]` is target `k`'s
/// statistic at point `i` (NaN and infinite values are left out); point `ring`, if any, is
/// ringed in every panel.
///
/// # Errors
/// If plotters fails to draw.
///
/// # Panics
/// If `values` has fewer rows than `targets` (a programming error).
pub fn targets_svg(
    title: &str,
    targets: &[Target],
    values: &[Vec<f64>],
    ring: Option<usize>,
) -> Result<String> {
    let rows = targets.len().div_ceil(COLUMNS).max(1);
    let size = (PANEL.0 * COLUMNS as u32, PANEL.1 * rows as u32 + 40);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (head, body) = root.split_vertically(40);
        head.titled(title, ("sans-serif", 17)).map_err(draw_err)?;
        let panels = body.split_evenly((rows, COLUMNS));
        for (k, (target, area)) in targets.iter().zip(&panels).enumerate() {
            panel(area, target, &values[k], ring)?;
        }
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// The y range of a panel ([`axis_range`], 8 % room): every finite value and the target's
/// value, and each band edge that is finite and lies within one data span of them (a band
/// edge far away, or open, is left out; the band's shading is cut at the axis).
fn y_range(target: &Target, values: &[f64]) -> (f64, f64) {
    let plotted = || {
        values
            .iter()
            .copied()
            .filter(|x| x.is_finite())
            .chain(std::iter::once(target.value))
    };
    let (lo, hi) = axis_range(plotted(), 0.0);
    let span = hi - lo;
    let (b0, b1) = target.band.bounds(target.value);
    let near = [b0, b1]
        .into_iter()
        .filter(|b| b.is_finite() && *b >= lo - span && *b <= hi + span);
    axis_range(plotted().chain(near), 0.08)
}

/// One target's panel on `area`.
fn panel(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    target: &Target,
    values: &[f64],
    ring: Option<usize>,
) -> Result<()> {
    let n = values.len().max(1) as f64;
    let (y0, y1) = y_range(target, values);
    let mut chart = ChartBuilder::on(area)
        .caption(&target.name, ("sans-serif", 13))
        .margin(6)
        .x_label_area_size(18)
        .y_label_area_size(44)
        .build_cartesian_2d(-0.5f64..(n - 0.5), y0..y1)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .x_labels(4)
        .y_labels(4)
        .x_label_formatter(&|x| format!("{x:.0}"))
        .y_label_formatter(&|y| tick_label(*y, 3))
        .label_style(("sans-serif", 10))
        .disable_mesh()
        .draw()
        .map_err(draw_err)?;
    let (lo, hi) = target.band.bounds(target.value);
    let band = RGBColor(0, 158, 115).mix(0.18);
    chart
        .draw_series(std::iter::once(Rectangle::new(
            [(-0.5, lo.clamp(y0, y1)), (n - 0.5, hi.clamp(y0, y1))],
            band.filled(),
        )))
        .map_err(draw_err)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            vec![
                (-0.5, plotted(target.value)),
                (n - 0.5, plotted(target.value)),
            ],
            RGBColor(0, 158, 115),
        )))
        .map_err(draw_err)?;
    let dots = values
        .iter()
        .enumerate()
        .filter(|(_, x)| x.is_finite())
        .map(|(i, &x)| {
            let c = if target.holds(x) {
                RGBColor(0, 114, 178)
            } else {
                RGBColor(150, 150, 150)
            };
            Circle::new((i as f64, plotted(x)), 2, c.filled())
        });
    chart.draw_series(dots).map_err(draw_err)?;
    if let Some((i, &x)) = ring.and_then(|i| values.get(i).map(|x| (i, x))) {
        if !x.is_finite() {
            return Ok(());
        }
        chart
            .draw_series(std::iter::once(Circle::new(
                (i as f64, plotted(x)),
                5,
                RGBColor(213, 94, 0).stroke_width(2),
            )))
            .map_err(draw_err)?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::calibrate::{Band, Statistic};
    use usar_report::targets::metric_ref::MetricRef;

    #[test]
    fn a_panel_spans_its_band_and_every_finite_value() {
        let t = Target {
            name: "t".into(),
            statistic: Statistic::Mean(MetricRef("rounds".into())),
            value: 6.0,
            band: Band::PlusMinus(1.0),
            report_only: false,
        };
        let (lo, hi) = y_range(&t, &[f64::NAN, 2.0, f64::INFINITY, 6.5]);
        assert!(lo < 2.0 && hi > 7.0 && hi < 8.0, "{lo}..{hi}");
        let (lo, hi) = y_range(&t, &[]);
        assert!(lo < 5.0 && hi > 7.0, "{lo}..{hi}");
    }

    /// A band reaching 1.7e308 once spun plotters' tick loop forever: the axis spans the
    /// values and leaves a far or open band edge out.
    #[test]
    fn a_far_or_open_band_edge_is_left_out() {
        for band in [
            Band::Between(5.0, 1.7e308),
            Band::AtLeast(5.0),
            Band::Between(-1e308, 1e308),
        ] {
            let t = Target {
                name: "t".into(),
                statistic: Statistic::Mean(MetricRef("rounds".into())),
                value: 6.0,
                band,
                report_only: false,
            };
            let (lo, hi) = y_range(&t, &[5.5, 6.5]);
            assert!(lo > -10.0 && hi < 10.0, "{band:?}: {lo}..{hi}");
            let svg =
                targets_svg("t", std::slice::from_ref(&t), &[vec![5.5, 6.5]], Some(0)).unwrap();
            assert!(svg.contains("<svg"));
        }
    }
}
