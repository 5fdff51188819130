//! The grid's figures, one SVG per chosen metric (plotters, plain SVG text, no fonts needed):
//!
//! - one varied field: the metric's mean against the field's value, one line per method with
//!   its 95 % confidence interval as a shaded band; the x axis is numeric when every value is
//!   a number, else categorical (values in `--vary` order);
//! - two varied fields: a heat map per method (first field across, second up), coloured by
//!   the mean on one scale shared by all methods (viridis), each cell labelled with its mean;
//! - more fields: no figure (`grid.md` has the tables).

use crate::error::Result;
use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::colors::colormaps::ViridisRGB;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::analysis::Analysis;
use crate::chart::{FIGURE_SIZE, axis_range, draw_err, legend_entry, method_color, plotted};
use crate::stats::Summary;
use crate::table::num;
use usar_sweep::journal::SweepHeader;
use usar_sweep::metrics::Metric;

/// A chart on an SVG string with numeric axes.
type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Width of the legend strip at the right of a line chart, pixels.
const LEGEND_W: u32 = 110;
/// Width of one heat-map panel, pixels.
const PANEL_W: u32 = 380;
/// Width of the colour bar strip at the right of the heat maps, pixels.
const COLORBAR_W: u32 = 100;

/// File name of the grid figure of `metric` (for tasks `tasks`): `grid_<metric name>.svg`.
pub fn figure_file(metric: Metric, tasks: &[String]) -> String {
    format!("grid_{}.svg", metric.name(tasks))
}

/// The grid figure of `metric`, or `None` when more than two fields are varied.
///
/// # Errors
/// If plotters fails to draw.
pub fn grid_figure_svg(
    header: &SweepHeader,
    analysis: &Analysis,
    metric: Metric,
) -> Result<Option<String>> {
    let fields = &header.grid.fields;
    let tasks = analysis.cells.first().map_or(&[][..], |c| &c.tasks[..]);
    let label = metric.label(tasks);
    let stats = |method: usize| -> Vec<Summary> {
        analysis
            .cells
            .iter()
            .map(|c| c.summary(method, metric).unwrap_or_default())
            .collect()
    };
    let per_method: Vec<Vec<Summary>> = (0..header.methods.len()).map(stats).collect();
    let values = |f: usize| -> Vec<String> {
        header
            .grid
            .cells
            .iter()
            .map(|c| c.values[f].clone())
            .collect()
    };
    match fields.len() {
        1 => line_chart(&fields[0], &values(0), &header.methods, &per_method, &label).map(Some),
        2 => {
            let (xs, ys) = (distinct(&values(0)), distinct(&values(1)));
            heat_maps(&fields[..2], &xs, &ys, &header.methods, &per_method, &label).map(Some)
        }
        _ => Ok(None),
    }
}

/// The distinct values in first-seen order (a field's values in `--vary` order).
fn distinct(values: &[String]) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for v in values {
        if !out.contains(v) {
            out.push(v.clone());
        }
    }
    out
}

/// Every value as a finite number, or `None` if one is not.
fn numeric(values: &[String]) -> Option<Vec<f64>> {
    values
        .iter()
        .map(|v| v.parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect()
}

/// Lowest and highest of the band ends (or means where the band is undefined), padded.
/// Whether positive numeric axis values span at least a factor of 10 (then the axis is drawn
/// on a log scale, as for a rate varied over a decade).
fn spans_a_decade(v: &[f64]) -> bool {
    let lo = v.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    lo > 0.0 && hi / lo >= 10.0 - 1e-9
}

/// The y axis: every band end (or mean where the band is undefined), with 8 % room
/// ([`axis_range`]: finite and never empty, whatever the values).
fn y_range(per_method: &[Vec<Summary>]) -> (f64, f64) {
    let ends = per_method.iter().flatten().flat_map(|s| {
        if s.ci95.is_finite() {
            [s.ci_low(), s.ci_high()]
        } else {
            [s.mean, s.mean]
        }
    });
    axis_range(ends, 0.08)
}

/// A line chart of one varied `field` (its `values`, numeric or not): per method, the mean
/// and its 95 % band at each value (`per_method[method][cell]`), titled with `label`.
pub(crate) fn line_chart(
    field: &str,
    values: &[String],
    methods: &[String],
    per_method: &[Vec<Summary>],
    label: &str,
) -> Result<String> {
    let categorical = numeric(values).is_none();
    let log_x = numeric(values).is_some_and(|v| spans_a_decade(&v));
    let xs: Vec<f64> = match numeric(values) {
        Some(v) if log_x => v.iter().map(|x| x.log10()).collect(),
        Some(v) => v,
        None => (0..values.len()).map(|i| i as f64).collect(),
    };
    let (x_lo, x_hi) = if categorical {
        (-0.5, xs.len() as f64 - 0.5)
    } else {
        axis_range(xs.iter().copied(), 0.05)
    };
    let (y_lo, y_hi) = y_range(per_method);
    // Points in increasing x, so lines and bands run left to right.
    let mut order: Vec<usize> = (0..xs.len()).collect();
    order.sort_by(|a, b| xs[*a].total_cmp(&xs[*b]));
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, FIGURE_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (plot_area, legend_area) = root.split_horizontally(FIGURE_SIZE.0 - LEGEND_W);
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(format!("{label} vs {field}"), ("sans-serif", 18))
            .margin(12)
            .margin_bottom(30)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d(x_lo..x_hi, y_lo..y_hi)
            .map_err(draw_err)?;
        let x_desc = if log_x {
            format!("{field} (log scale)")
        } else {
            field.to_string()
        };
        chart
            .configure_mesh()
            // Categorical and log axes are labelled at the varied values (below).
            .x_labels(if categorical || log_x { 0 } else { 8 })
            .x_desc(x_desc)
            .y_desc(label)
            .label_style(("sans-serif", 13))
            .axis_desc_style(("sans-serif", 15))
            .light_line_style(RGBColor(238, 238, 238))
            .max_light_lines(1)
            .draw()
            .map_err(draw_err)?;
        for (i, (name, stats)) in methods.iter().zip(per_method).enumerate() {
            draw_method(&mut chart, method_color(i), &xs, &order, stats)?;
            legend_entry(&legend_area, i, name, method_color(i))?;
        }
        if categorical || log_x {
            let style = ("sans-serif", 13)
                .into_font()
                .color(&BLACK)
                .pos(Pos::new(HPos::Center, VPos::Top));
            for (k, v) in values.iter().enumerate() {
                let (px, py) = chart.backend_coord(&(xs[k], y_lo));
                root.draw(&Text::new(v.as_str(), (px, py + 6), style.clone()))
                    .map_err(draw_err)?;
            }
        }
        footnote(
            &root,
            "lines: mean over trials; bands: 95 % confidence interval of the mean (t)",
        )?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// One method's band, line and points; `order` lists the points in increasing x.
fn draw_method(
    chart: &mut Chart<'_, '_>,
    color: RGBColor,
    xs: &[f64],
    order: &[usize],
    stats: &[Summary],
) -> Result<()> {
    for run in band_runs(order, stats) {
        let at = |k: usize, y: f64| (plotted(xs[k]), plotted(y));
        let mut poly: Vec<(f64, f64)> = run.iter().map(|&k| at(k, stats[k].ci_high())).collect();
        poly.extend(run.iter().rev().map(|&k| at(k, stats[k].ci_low())));
        chart
            .draw_series(std::iter::once(Polygon::new(
                poly,
                color.mix(0.18).filled(),
            )))
            .map_err(draw_err)?;
    }
    let line: Vec<(f64, f64)> = order
        .iter()
        .filter(|&&k| stats[k].mean.is_finite())
        .map(|&k| (plotted(xs[k]), plotted(stats[k].mean)))
        .collect();
    chart
        .draw_series(line.iter().map(|p| Circle::new(*p, 3, color.filled())))
        .map_err(draw_err)?;
    chart
        .draw_series(std::iter::once(PathElement::new(
            line,
            color.stroke_width(2),
        )))
        .map_err(draw_err)?;
    Ok(())
}

/// Runs of consecutive points (in x order) whose confidence interval is defined.
fn band_runs(order: &[usize], stats: &[Summary]) -> Vec<Vec<usize>> {
    let mut runs: Vec<Vec<usize>> = Vec::new();
    let mut run = Vec::new();
    for &k in order {
        if stats[k].ci95.is_finite() && stats[k].mean.is_finite() {
            run.push(k);
        } else if !run.is_empty() {
            runs.push(std::mem::take(&mut run));
        }
    }
    if !run.is_empty() {
        runs.push(run);
    }
    runs
}

fn footnote(root: &DrawingArea<SVGBackend<'_>, Shift>, text: &str) -> Result<()> {
    let (_, h) = root.dim_in_pixel();
    root.draw(&Text::new(
        text,
        (16, h as i32 - 16),
        ("sans-serif", 12).into_font().color(&RGBColor(90, 90, 90)),
    ))
    .map_err(draw_err)
}

/// One heat map per method over two varied `fields` (`xs` by `ys`, cells in grid order),
/// coloured by the mean of `per_method[method][cell]`, titled with `label`.
pub(crate) fn heat_maps(
    fields: &[String],
    xs: &[String],
    ys: &[String],
    methods: &[String],
    per_method: &[Vec<Summary>],
    label: &str,
) -> Result<String> {
    let means = per_method
        .iter()
        .flatten()
        .map(|s| s.mean)
        .filter(|m| m.is_finite());
    let (lo, hi) = means.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), x| {
        (a.min(x), b.max(x))
    });
    let (lo, hi) = if !lo.is_finite() {
        (0.0, 1.0)
    } else if (hi - lo).is_finite() && hi - lo >= 1e-12 && hi - lo >= lo.abs().max(hi.abs()) * 1e-9
    {
        (lo, hi)
    } else {
        // One value (or nearly): an axis that is not empty ([`axis_range`]).
        axis_range([lo, hi], 0.0)
    };
    let size = (
        PANEL_W * methods.len().max(1) as u32 + COLORBAR_W,
        FIGURE_SIZE.1 + 20,
    );
    let mut svg = String::new();
    {
        let base = SVGBackend::with_string(&mut svg, size).into_drawing_area();
        base.fill(&WHITE).map_err(draw_err)?;
        let root = base
            .titled(&format!("{label}: mean over trials"), ("sans-serif", 18))
            .map_err(draw_err)?;
        let (panels, bar) = root.split_horizontally(size.0 - COLORBAR_W);
        for (area, (name, stats)) in panels
            .split_evenly((1, methods.len().max(1)))
            .iter()
            .zip(methods.iter().zip(per_method))
        {
            heat_panel(&base, area, name, fields, (xs, ys), stats, (lo, hi))?;
        }
        color_bar(&bar, lo, hi)?;
        footnote(
            &root,
            "cells: mean over trials (n/a: no trial defines the metric)",
        )?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// One method's heat map in `area` (`base`: the whole figure, for labels placed in absolute
/// pixels); `stats[cell]`, cells in grid order (first field slowest).
fn heat_panel(
    base: &DrawingArea<SVGBackend<'_>, Shift>,
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    method: &str,
    fields: &[String],
    (xs, ys): (&[String], &[String]),
    stats: &[Summary],
    (lo, hi): (f64, f64),
) -> Result<()> {
    let (nx, ny) = (xs.len(), ys.len());
    let mut chart = ChartBuilder::on(area)
        .caption(method, ("sans-serif", 16))
        .margin(10)
        .margin_bottom(30)
        .x_label_area_size(40)
        .y_label_area_size(70)
        .build_cartesian_2d(0f64..nx as f64, 0f64..ny as f64)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(0)
        .y_labels(0)
        .x_desc(fields[0].as_str())
        .y_desc(fields[1].as_str())
        .axis_desc_style(("sans-serif", 13))
        .draw()
        .map_err(draw_err)?;
    for (cell, s) in stats.iter().enumerate() {
        let (i, j) = (cell / ny, cell % ny);
        let (x, y) = (i as f64, j as f64);
        let t = if hi > lo {
            (s.mean - lo) / (hi - lo)
        } else {
            0.5
        };
        let fill = if s.mean.is_finite() {
            ViridisRGB::get_color_normalized(s.mean, lo, hi)
        } else {
            RGBColor(200, 200, 200)
        };
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x, y), (x + 1.0, y + 1.0)],
                fill.filled(),
            )))
            .map_err(draw_err)?;
        let text_color = if s.mean.is_finite() && t < 0.6 {
            WHITE
        } else {
            BLACK
        };
        let label = if s.mean.is_finite() {
            num(s.mean)
        } else {
            "n/a".into()
        };
        chart
            .draw_series(std::iter::once(Text::new(
                label,
                (x + 0.5, y + 0.5),
                ("sans-serif", 13)
                    .into_font()
                    .color(&text_color)
                    .pos(Pos::new(HPos::Center, VPos::Center)),
            )))
            .map_err(draw_err)?;
    }
    axis_values(base, &chart, xs, ys)
}

/// The values of the two fields written under the columns and left of the rows, on `base`
/// (the whole figure: the chart gives absolute pixel positions).
fn axis_values(
    base: &DrawingArea<SVGBackend<'_>, Shift>,
    chart: &Chart<'_, '_>,
    xs: &[String],
    ys: &[String],
) -> Result<()> {
    let below = ("sans-serif", 12)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Top));
    for (i, v) in xs.iter().enumerate() {
        let (px, py) = chart.backend_coord(&(i as f64 + 0.5, 0.0));
        base.draw(&Text::new(v.as_str(), (px, py + 4), below.clone()))
            .map_err(draw_err)?;
    }
    let left = ("sans-serif", 12)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Right, VPos::Center));
    for (j, v) in ys.iter().enumerate() {
        let (px, py) = chart.backend_coord(&(0.0, j as f64 + 0.5));
        base.draw(&Text::new(v.as_str(), (px - 4, py), left.clone()))
            .map_err(draw_err)?;
    }
    Ok(())
}

/// A vertical viridis bar from `lo` (bottom) to `hi` (top), labelled at both ends.
fn color_bar(area: &DrawingArea<SVGBackend<'_>, Shift>, lo: f64, hi: f64) -> Result<()> {
    let (top, bottom, left, width) = (70i32, 360i32, 14i32, 22i32);
    let steps = 48;
    for k in 0..steps {
        let f0 = f64::from(k) / f64::from(steps);
        let y1 = bottom - ((bottom - top) as f64 * f0) as i32;
        let y0 = bottom - ((bottom - top) as f64 * (f64::from(k + 1) / f64::from(steps))) as i32;
        let c = ViridisRGB::get_color_normalized(f0, 0.0, 1.0);
        area.draw(&Rectangle::new(
            [(left, y0), (left + width, y1)],
            c.filled(),
        ))
        .map_err(draw_err)?;
    }
    let style = ("sans-serif", 12)
        .into_font()
        .color(&BLACK)
        .pos(Pos::new(HPos::Left, VPos::Center));
    area.draw(&Text::new(num(hi), (left + width + 6, top), style.clone()))
        .map_err(draw_err)?;
    area.draw(&Text::new(num(lo), (left + width + 6, bottom), style))
        .map_err(draw_err)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn log_axis_for_positive_values_over_a_decade() {
        assert!(spans_a_decade(&[0.00174, 0.0055, 0.0174]));
        assert!(!spans_a_decade(&[1.0, 9.0]));
        assert!(!spans_a_decade(&[0.0, 1.0, 100.0]));
    }

    #[test]
    fn numeric_axis_only_when_every_value_is_a_number() {
        assert_eq!(numeric(&["0.1".into(), "-2".into()]), Some(vec![0.1, -2.0]));
        assert_eq!(numeric(&["0.1".into(), "Linear".into()]), None);
        assert_eq!(numeric(&["inf".into()]), None);
        assert_eq!(distinct(&["a".into(), "b".into(), "a".into()]), ["a", "b"]);
    }

    #[test]
    fn bands_skip_undefined_intervals() {
        let s = |ci: f64| Summary {
            n: 2,
            mean: 1.0,
            sd: 1.0,
            ci95: ci,
            floor: f64::NEG_INFINITY,
        };
        let stats = [s(1.0), s(f64::NAN), s(1.0), s(1.0)];
        assert_eq!(band_runs(&[0, 1, 2, 3], &stats), vec![vec![0], vec![2, 3]]);
        assert_eq!(y_range(&[vec![s(f64::NAN)]]), (0.0, 2.0));
    }
}
