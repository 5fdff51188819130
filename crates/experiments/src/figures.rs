//! The sweep's figures in the manner of the paper's Fig. 3: grouped bar charts (groups = hard,
//! easy, total; one bar per method) of the mean over trials with 95 % confidence-interval error
//! bars. SVG via plotters; text is plain SVG `<text>`, so no fonts are needed to write them.

use crate::analysis::CellAnalysis;
use crate::stats::Summary;
use anyhow::{Result, anyhow};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Width and height of each figure, pixels.
pub const FIGURE_SIZE: (u32, u32) = (820, 440);
/// Width of the legend strip at the right of each figure, pixels.
const LEGEND_W: u32 = 110;

/// One figure: file name, title, y-axis label and the metric shown for hard, easy and total.
#[derive(Debug, Clone, Copy)]
pub struct FigureSpec {
    /// File name in the output folder.
    pub file: &'static str,
    /// Title drawn above the chart.
    pub title: &'static str,
    /// Y-axis label.
    pub y_label: &'static str,
    /// Metric names for the hard, easy and total groups.
    pub metrics: [&'static str; 3],
}

/// The three figures of a sweep: (a) rescuees, (b) energy cost per rescuee, (c) HP cost per
/// rescuee.
pub const FIGURES: [FigureSpec; 3] = [
    FigureSpec {
        file: "fig3a_rescuees.svg",
        title: "(a) Rescuees per trial",
        y_label: "rescuees",
        metrics: ["rescued_hard", "rescued_easy", "rescued_total"],
    },
    FigureSpec {
        file: "fig3b_energy_per_rescuee.svg",
        title: "(b) Energy cost per rescuee",
        y_label: "energy per rescuee (% points)",
        metrics: [
            "energy_per_hard_rescuee_pct",
            "energy_per_easy_rescuee_pct",
            "energy_per_rescuee_pct",
        ],
    },
    FigureSpec {
        file: "fig3c_hp_per_rescuee.svg",
        title: "(c) HP cost per rescuee",
        y_label: "HP per rescuee (% points)",
        metrics: [
            "hp_per_hard_rescuee_pct",
            "hp_per_easy_rescuee_pct",
            "hp_per_rescuee_pct",
        ],
    },
];

const GROUPS: [&str; 3] = ["hard task", "easy task", "total"];

/// Colour of the `i`-th method's bars (colour-blind-safe palette, Okabe-Ito).
pub fn method_color(i: usize) -> RGBColor {
    const PALETTE: [RGBColor; 8] = [
        RGBColor(0, 114, 178),
        RGBColor(230, 159, 0),
        RGBColor(0, 158, 115),
        RGBColor(204, 121, 167),
        RGBColor(86, 180, 233),
        RGBColor(213, 94, 0),
        RGBColor(240, 228, 66),
        RGBColor(0, 0, 0),
    ];
    PALETTE[i % PALETTE.len()]
}

pub(crate) fn draw_err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("drawing a figure: {e:?}")
}

/// Draws `spec` from a cell's analysis (methods in sweep order) and returns the SVG text.
///
/// # Errors
/// If plotters fails to draw.
pub fn figure_svg(spec: &FigureSpec, cell: &CellAnalysis) -> Result<String> {
    let methods: Vec<&str> = cell.methods.iter().map(|m| m.method.as_str()).collect();
    // stats[method][group]
    let stats: Vec<[Summary; 3]> = (0..methods.len())
        .map(|i| spec.metrics.map(|name| cell.summary(i, name)))
        .collect();
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
        .fold(0.0f64, f64::max);
    let y_max = if top > 0.0 { top * 1.12 } else { 1.0 };

    let n = methods.len().max(1) as f64;
    let group_w = 0.8;
    let bar_w = group_w / n;
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
            .build_cartesian_2d(-0.5f64..2.5f64, 0.0..y_max)
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

        for (i, (name, per_group)) in methods.iter().zip(&stats).enumerate() {
            let color = method_color(i);
            let offset = -group_w / 2.0 + bar_w * (i as f64 + 0.5);
            let bars = per_group
                .iter()
                .enumerate()
                .filter(|(_, s)| s.mean.is_finite())
                .map(|(g, s)| {
                    let x = g as f64 + offset;
                    Rectangle::new(
                        [(x - bar_w * 0.42, 0.0), (x + bar_w * 0.42, s.mean)],
                        color.filled(),
                    )
                });
            chart.draw_series(bars).map_err(draw_err)?;
            let y = 60 + 26 * i as i32;
            legend_area
                .draw(&Rectangle::new([(8, y - 7), (24, y + 7)], color.filled()))
                .map_err(draw_err)?;
            legend_area
                .draw(&Text::new(
                    *name,
                    (32, y),
                    ("sans-serif", 15)
                        .into_font()
                        .color(&BLACK)
                        .pos(Pos::new(HPos::Left, VPos::Center)),
                ))
                .map_err(draw_err)?;
            let errors = per_group
                .iter()
                .enumerate()
                .filter(|(_, s)| s.mean.is_finite() && s.ci95.is_finite())
                .flat_map(|(g, s)| {
                    let x = g as f64 + offset;
                    let (lo, hi) = (s.ci_low().max(0.0), s.ci_high());
                    let cap = bar_w * 0.18;
                    [
                        PathElement::new(vec![(x, lo), (x, hi)], BLACK.stroke_width(1)),
                        PathElement::new(vec![(x - cap, lo), (x + cap, lo)], BLACK.stroke_width(1)),
                        PathElement::new(vec![(x - cap, hi), (x + cap, hi)], BLACK.stroke_width(1)),
                    ]
                });
            chart.draw_series(errors).map_err(draw_err)?;
        }
        let label_style = ("sans-serif", 15)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Center, VPos::Top));
        for (g, name) in GROUPS.iter().enumerate() {
            let (px, py) = chart.backend_coord(&(g as f64, 0.0));
            root.draw(&Text::new(*name, (px, py + 8), label_style.clone()))
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
