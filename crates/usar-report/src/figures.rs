//! The sweep's figures in the manner of the paper's Fig. 3: grouped bar charts (one group per
//! task, in the scenario's order, then the total; one bar per method) of the mean over trials
//! with 95 % confidence-interval error bars. SVG via plotters; text is plain SVG `<text>`, so
//! no fonts are needed to write them.

use crate::analysis::CellAnalysis;
use crate::chart::{AXIS_LIMIT, draw_err, legend_entry, plotted};
pub use crate::chart::{FIGURE_SIZE, method_color};
use crate::error::Result;
use crate::stats::Summary;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
pub use usar_sweep::data::figure_list::{FIGURES, FigureSpec};
use usar_sweep::metrics::{Metric, Quantity, Scope};

/// Width of the legend strip at the right of each figure, pixels.
const LEGEND_W: u32 = 110;

/// The groups of a figure for `tasks` (`<name> task` each, then `total`) and their metrics.
fn groups(quantity: Quantity, tasks: &[String]) -> Vec<(String, Metric)> {
    tasks
        .iter()
        .enumerate()
        .map(|(t, name)| {
            (
                format!("{name} task"),
                Metric::new(quantity, Scope::Task(t)),
            )
        })
        .chain(std::iter::once((
            "total".to_string(),
            Metric::new(quantity, Scope::Total),
        )))
        .collect()
}

/// Top of the y axis: 12 % above the highest upper whisker (or mean), at least 1; values
/// past [`AXIS_LIMIT`] count as that bound (so the top cannot overflow).
fn y_max(stats: &[Vec<Summary>]) -> f64 {
    let top = stats
        .iter()
        .flatten()
        .map(|s| {
            if s.ci95.is_finite() {
                s.ci_high()
            } else {
                s.mean
            }
        })
        .filter(|x| x.is_finite())
        .map(|x| x.min(AXIS_LIMIT))
        .fold(0.0f64, f64::max);
    if top > 0.0 { top * 1.12 } else { 1.0 }
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// One method's bars and whiskers, `offset` from each group's centre, `bar_w` wide.
fn draw_method(
    chart: &mut Chart<'_, '_>,
    color: RGBColor,
    per_group: &[Summary],
    offset: f64,
    bar_w: f64,
) -> Result<()> {
    let bars = per_group
        .iter()
        .enumerate()
        .filter(|(_, s)| s.mean.is_finite())
        .map(|(g, s)| {
            let x = g as f64 + offset;
            Rectangle::new(
                [(x - bar_w * 0.42, 0.0), (x + bar_w * 0.42, plotted(s.mean))],
                color.filled(),
            )
        });
    chart.draw_series(bars).map_err(draw_err)?;
    let errors = per_group
        .iter()
        .enumerate()
        .filter(|(_, s)| s.mean.is_finite() && s.ci95.is_finite())
        .flat_map(|(g, s)| {
            let x = g as f64 + offset;
            let (lo, hi) = (plotted(s.ci_low().max(0.0)), plotted(s.ci_high()));
            let cap = bar_w * 0.18;
            [
                PathElement::new(vec![(x, lo), (x, hi)], BLACK.stroke_width(1)),
                PathElement::new(vec![(x - cap, lo), (x + cap, lo)], BLACK.stroke_width(1)),
                PathElement::new(vec![(x - cap, hi), (x + cap, hi)], BLACK.stroke_width(1)),
            ]
        });
    chart.draw_series(errors).map_err(draw_err)?;
    Ok(())
}

/// Draws `spec` from a cell's analysis (methods in sweep order; a group per task of the cell,
/// then the total) and returns the SVG text.
///
/// # Errors
/// If plotters fails to draw.
pub fn figure_svg(spec: &FigureSpec, cell: &CellAnalysis) -> Result<String> {
    let groups = groups(spec.quantity, &cell.tasks);
    // stats[method][group]
    let stats: Vec<Vec<Summary>> = (0..cell.methods.len())
        .map(|i| {
            groups
                .iter()
                .map(|(_, m)| cell.summary(i, *m).unwrap_or_else(|| Summary::of(&[])))
                .collect()
        })
        .collect();
    let n = cell.methods.len().max(1) as f64;
    let (group_w, bar_w) = (0.8, 0.8 / n);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, FIGURE_SIZE).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (plot_area, legend_area) = root.split_horizontally(FIGURE_SIZE.0 - LEGEND_W);
        let mut chart = ChartBuilder::on(&plot_area)
            .caption(spec.title, ("sans-serif", 20))
            .margin(12)
            .x_label_area_size(36)
            .y_label_area_size(64)
            .build_cartesian_2d(-0.5f64..(groups.len() as f64 - 0.5), 0.0..y_max(&stats))
            .map_err(draw_err)?;
        chart
            .configure_mesh()
            .disable_x_mesh()
            .x_labels(0)
            .y_label_style(("sans-serif", 13))
            .y_desc(spec.y_label)
            .axis_desc_style(("sans-serif", 15))
            .light_line_style(RGBColor(238, 238, 238))
            .y_max_light_lines(1)
            .draw()
            .map_err(draw_err)?;
        for (i, (m, per_group)) in cell.methods.iter().zip(&stats).enumerate() {
            let offset = -group_w / 2.0 + bar_w * (i as f64 + 0.5);
            draw_method(&mut chart, method_color(i), per_group, offset, bar_w)?;
            legend_entry(&legend_area, i, &m.method, method_color(i))?;
        }
        let label_style = ("sans-serif", 15)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Top));
        for (g, (name, _)) in groups.iter().enumerate() {
            let (px, py) = chart.backend_coord(&(g as f64, 0.0));
            root.draw(&Text::new(name.as_str(), (px, py + 8), label_style.clone()))
                .map_err(draw_err)?;
        }
        root.draw(&Text::new(
            "bars: mean over trials; whiskers: 95 % confidence interval (t)",
            (16, FIGURE_SIZE.1 as i32 - 16),
            ("sans-serif", 12).into_font().color(&RGBColor(90, 90, 90)),
        ))
        .map_err(draw_err)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}
