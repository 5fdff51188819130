//! The whole picture of `usar render` (header, map, robots, paths, legend), written or returned
//! as SVG, and the bare map the replay page draws over, with its frame.

use std::path::Path;

use crate::error::Result;
use plotters::prelude::*;
use usar_sim::scenario::Scenario;

use crate::render::canvas::{Area, draw_err, font};
use crate::render::layout::{DESCRIPTION_CHAR_PX, Layout, wrap};
use crate::render::legend::{LEGEND_PX, LEGEND_ROW_PX, draw_legend, legend_entries};
use crate::render::map::draw_static;
use crate::render::robots::{Trace, draw_ends, draw_paths, draw_robots};
use usar_sweep::atomic::write_atomic;

/// Draws `scenario` top-down as SVG and writes it to `out` with [`write_atomic`] (atomically
/// for a regular file, through a symlink, directly to a FIFO or character device).
///
/// Shows the walls, debris (brown), radiation zones (shaded by dose rate factor: the weakest
/// yellow, the strongest orange, labelled `x<factor>` when the factors differ), both search
/// areas with their rescuees, goal points (crosses), drop-offs, the rest station, robots at
/// their start positions by kind (colour by role, see [`kind_color`](crate::render::kind_color); aerial robots with a
/// ring; labelled by id in teams of up to [`MAX_LABELLED_ROBOTS`](crate::render::MAX_LABELLED_ROBOTS)), a legend and a scale bar,
/// and, when `traces` is given (indexed by robot id), the path each robot took with a hollow
/// disc where it ended.
///
/// # Errors
/// If drawing or writing the file fails.
pub fn render_svg(scenario: &Scenario, traces: Option<&[Trace]>, out: &Path) -> Result<()> {
    let svg = render_svg_string(scenario, traces)?;
    Ok(write_atomic(out, svg.as_bytes())?)
}

/// Same as [`render_svg`] but returns the SVG text.
///
/// # Errors
/// If plotters fails to draw (it should not for a valid scenario).
pub fn render_svg_string(scenario: &Scenario, traces: Option<&[Trace]>) -> Result<String> {
    let l = Layout::new(scenario);
    let total_w = l.map_w + LEGEND_PX;
    let description = wrap(
        scenario.description(),
        ((f64::from(total_w) - 16.0) / DESCRIPTION_CHAR_PX) as usize,
    );
    let header_px = 30 + 16 * description.len() as u32;
    let legend = legend_entries(scenario, traces.is_some());
    let legend_h = 16 + LEGEND_ROW_PX as u32 * (legend.len() as u32 + 2);
    let total_h = header_px + l.map_h.max(legend_h);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (total_w, total_h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (header, body) = root.split_vertically(header_px);
        draw_header(&header, scenario, &description)?;
        let (map_column, legend_area) = body.split_horizontally(l.map_w);
        let (map_area, _) = map_column.split_vertically(l.map_h);
        let mut chart = ChartBuilder::on(&map_area)
            .build_cartesian_2d(l.x0..l.x1, l.y0..l.y1)
            .map_err(draw_err)?;
        draw_static(&mut chart, scenario, true)?;
        if let Some(traces) = traces {
            draw_paths(&mut chart, scenario, traces)?;
        }
        draw_robots(&mut chart, scenario)?;
        if let Some(traces) = traces {
            draw_ends(&mut chart, scenario, traces)?;
        }
        draw_legend(&legend_area, &legend, l.px_per_m)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

/// Where the map of [`render_map_svg`] lies: pixel `(0, 0)` is the field's top-left corner
/// `(x0_m, y1_m)` and one metre is `px_per_m` pixels on both axes (y grows upwards in the
/// world, downwards in the picture).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct MapFrame {
    /// World x of the picture's left edge, metres (the wall's outer side minus a 1 m margin).
    pub x0_m: f64,
    /// World x of the right edge, metres.
    pub x1_m: f64,
    /// World y of the bottom edge, metres.
    pub y0_m: f64,
    /// World y of the top edge, metres.
    pub y1_m: f64,
    /// Scale, pixels per metre, in `[4, 40]` (the longer side about 960 px where that fits).
    pub px_per_m: f64,
    /// Picture width, pixels.
    pub width_px: u32,
    /// Picture height, pixels.
    pub height_px: u32,
}

/// The map alone, as `usar render` draws it (walls, search areas, drop-offs, radiation by dose,
/// debris, the rest station, goal points and labels) but without rescuees, robots, header or
/// legend, as SVG text, with the frame that maps world metres to its pixels. The replay page
/// draws rescuees and robots over it.
///
/// # Errors
/// If plotters fails to draw (it should not for a valid scenario).
pub fn render_map_svg(scenario: &Scenario) -> Result<(String, MapFrame)> {
    let l = Layout::new(scenario);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (l.map_w, l.map_h)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let mut chart = ChartBuilder::on(&root)
            .build_cartesian_2d(l.x0..l.x1, l.y0..l.y1)
            .map_err(draw_err)?;
        draw_static(&mut chart, scenario, false)?;
        root.present().map_err(draw_err)?;
    }
    let frame = MapFrame {
        x0_m: l.x0,
        x1_m: l.x1,
        y0_m: l.y0,
        y1_m: l.y1,
        px_per_m: l.px_per_m,
        width_px: l.map_w,
        height_px: l.map_h,
    };
    Ok((svg, frame))
}

pub(crate) fn draw_header(area: &Area<'_>, s: &Scenario, description: &[String]) -> Result<()> {
    let title = ("sans-serif", 16)
        .into_font()
        .style(FontStyle::Bold)
        .into_text_style(area);
    area.draw(&Text::new(
        format!(
            "{} ({} m x {} m, {} robots)",
            s.name(),
            s.arena().width_m,
            s.arena().height_m,
            s.robots().len()
        ),
        (8, 6),
        title,
    ))
    .map_err(draw_err)?;
    for (i, line) in description.iter().enumerate() {
        area.draw(&Text::new(line.clone(), (8, 28 + 16 * i as i32), font(12)))
            .map_err(draw_err)?;
    }
    Ok(())
}
