//! Top-down SVG picture of a scenario, optionally with the paths robots took (`usar render`).

use std::path::Path;

use anyhow::{Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use usar_sim::scenario::{Circle as Disc, Debris, Locomotion, PointM, Role, Scenario, TaskLevel};

use crate::atomic::write_atomic;

/// Pixels per metre of the picture.
const PX_PER_M: f64 = 12.0;
/// Vertices used to draw a circle as a polygon in world coordinates.
const CIRCLE_VERTICES: usize = 40;

/// The path one robot took: its positions in the world frame, metres, in time order.
pub type Trace = Vec<PointM>;

/// Colour of a robot by role: carriers blue, suppliers green, observers red.
pub fn role_color(role: Role) -> RGBColor {
    match role {
        Role::Carrier => RGBColor(31, 119, 180),
        Role::Supplier => RGBColor(44, 160, 44),
        Role::Observer => RGBColor(214, 39, 40),
    }
}

/// Draws `scenario` top-down as SVG and writes it atomically to `out`.
///
/// Shows the walls, debris (brown), radiation zones (shaded by dose rate factor, the strongest
/// zone darkest), both search areas with their rescuees, goal points (crosses), drop-offs,
/// the rest station, start positions and robots by kind (aerial robots with a ring), and,
/// when `traces` is given (indexed by robot id), the path each robot took.
///
/// # Errors
/// If drawing or writing the file fails.
pub fn render_svg(scenario: &Scenario, traces: Option<&[Trace]>, out: &Path) -> Result<()> {
    let svg = render_svg_string(scenario, traces)?;
    write_atomic(out, svg.as_bytes()).with_context(|| format!("writing {}", out.display()))
}

/// Same as [`render_svg`] but returns the SVG text.
///
/// # Errors
/// If plotters fails to draw (it should not for a valid scenario).
pub fn render_svg_string(scenario: &Scenario, traces: Option<&[Trace]>) -> Result<String> {
    let a = scenario.arena;
    let pad = a.wall_thickness_m + 1.0;
    let (x0, x1) = (-pad, a.width_m + pad);
    let (y0, y1) = (-pad, a.height_m + pad);
    let legend_px = 150u32;
    let w_px = ((x1 - x0) * PX_PER_M).round() as u32;
    let h_px = ((y1 - y0) * PX_PER_M).round() as u32 + 30;
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (w_px + legend_px, h_px)).into_drawing_area();
        root.fill(&WHITE).map_err(draw_err)?;
        let (map_area, legend_area) = root.split_horizontally(w_px);
        let mut chart = ChartBuilder::on(&map_area)
            .caption(
                format!("{}: {}", scenario.name, scenario.description),
                ("sans-serif", 14),
            )
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(draw_err)?;
        draw_static(&mut chart, scenario)?;
        if let Some(traces) = traces {
            for (id, trace) in traces.iter().enumerate().take(scenario.robots.len()) {
                let color = role_color(scenario.kind_of(id).role).mix(0.6);
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        trace.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>(),
                        color.stroke_width(1),
                    )))
                    .map_err(draw_err)?;
            }
        }
        draw_robots(&mut chart, scenario)?;
        draw_legend(&legend_area, scenario)?;
        root.present().map_err(draw_err)?;
    }
    Ok(svg)
}

type Chart<'a, 'b> = ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

fn draw_err<E: std::fmt::Display>(e: E) -> anyhow::Error {
    anyhow::anyhow!("drawing the SVG failed: {e}")
}

fn disc_polygon(c: &Disc) -> Vec<(f64, f64)> {
    (0..CIRCLE_VERTICES)
        .map(|i| {
            let t = i as f64 / CIRCLE_VERTICES as f64 * std::f64::consts::TAU;
            (
                c.center.x + c.radius_m * t.cos(),
                c.center.y + c.radius_m * t.sin(),
            )
        })
        .collect()
}

fn debris_polygon(d: &Debris) -> Vec<(f64, f64)> {
    match d {
        Debris::Circle(c) => disc_polygon(c),
        Debris::Rect {
            center,
            half_extents_m: h,
            rotation_rad,
        } => {
            let (s, c) = rotation_rad.sin_cos();
            [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                .iter()
                .map(|(sx, sy)| {
                    let (lx, ly) = (sx * h.x, sy * h.y);
                    (center.x + c * lx - s * ly, center.y + s * lx + c * ly)
                })
                .collect()
        }
    }
}

fn draw_static(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    let a = s.arena;
    let t = a.wall_thickness_m;
    let wall = RGBColor(60, 60, 60).filled();
    let walls = [
        [(-t, -t), (a.width_m + t, 0.0)],
        [(-t, a.height_m), (a.width_m + t, a.height_m + t)],
        [(-t, 0.0), (0.0, a.height_m)],
        [(a.width_m, 0.0), (a.width_m + t, a.height_m)],
    ];
    chart
        .draw_series(walls.iter().map(|r| Rectangle::new(*r, wall)))
        .map_err(draw_err)?;

    for level in TaskLevel::ALL {
        let task = s.task(level);
        let fill = match level {
            TaskLevel::Easy => RGBColor(198, 219, 239),
            TaskLevel::Hard => RGBColor(253, 208, 162),
        };
        let r = task.search_area;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(r.min.x, r.min.y), (r.max.x, r.max.y)],
                fill.filled(),
            )))
            .map_err(draw_err)?;
        chart
            .draw_series(
                task.rescuees
                    .iter()
                    .map(|p| Circle::new((p.x, p.y), 1, RGBColor(90, 90, 90).filled())),
            )
            .map_err(draw_err)?;
        let label = format!(
            "{} search area ({} rescuees)",
            level.name(),
            task.rescuees.len()
        );
        chart
            .draw_series(std::iter::once(Text::new(
                label,
                (r.min.x, r.max.y + 0.8),
                ("sans-serif", 12),
            )))
            .map_err(draw_err)?;
        chart
            .draw_series(std::iter::once(Polygon::new(
                disc_polygon(&task.drop_off),
                fill.mix(0.9).filled(),
            )))
            .map_err(draw_err)?;
        chart
            .draw_series(std::iter::once(Text::new(
                format!("{} drop-off", level.name()),
                (
                    task.drop_off.center.x - task.drop_off.radius_m,
                    task.drop_off.center.y,
                ),
                ("sans-serif", 11),
            )))
            .map_err(draw_err)?;
        chart
            .draw_series(std::iter::once(Cross::new(
                (task.goal.x, task.goal.y),
                6,
                BLACK.stroke_width(2),
            )))
            .map_err(draw_err)?;
    }

    let max_dose = s
        .radiation_zones
        .iter()
        .map(|z| z.dose_rate_factor)
        .fold(0.0_f64, f64::max);
    for z in &s.radiation_zones {
        let shade = 0.15 + 0.45 * (z.dose_rate_factor / max_dose.max(f64::MIN_POSITIVE));
        chart
            .draw_series(std::iter::once(Polygon::new(
                disc_polygon(&z.area),
                RGBColor(230, 200, 0).mix(shade).filled(),
            )))
            .map_err(draw_err)?;
    }
    chart
        .draw_series(
            s.debris
                .iter()
                .map(|d| Polygon::new(debris_polygon(d), RGBColor(140, 100, 60).filled())),
        )
        .map_err(draw_err)?;
    chart
        .draw_series(std::iter::once(Polygon::new(
            disc_polygon(&s.rest_station),
            RGBColor(180, 140, 220).mix(0.6).filled(),
        )))
        .map_err(draw_err)?;
    chart
        .draw_series(std::iter::once(Text::new(
            "rest station",
            (
                s.rest_station.center.x - s.rest_station.radius_m,
                s.rest_station.center.y,
            ),
            ("sans-serif", 11),
        )))
        .map_err(draw_err)?;
    Ok(())
}

fn draw_robots(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    for robot in &s.robots {
        let kind = &s.kinds[robot.kind];
        let body = Disc {
            center: robot.start_in_world,
            radius_m: kind.body_radius_m,
        };
        let color = role_color(kind.role);
        chart
            .draw_series(std::iter::once(Polygon::new(
                disc_polygon(&body),
                color.filled(),
            )))
            .map_err(draw_err)?;
        if kind.locomotion == Locomotion::Aerial {
            let ring = Disc {
                radius_m: kind.body_radius_m * 1.8,
                ..body
            };
            let mut pts = disc_polygon(&ring);
            pts.push(pts[0]);
            chart
                .draw_series(std::iter::once(PathElement::new(
                    pts,
                    color.stroke_width(1),
                )))
                .map_err(draw_err)?;
        }
    }
    Ok(())
}

fn draw_legend(
    area: &DrawingArea<SVGBackend<'_>, plotters::coord::Shift>,
    s: &Scenario,
) -> Result<()> {
    let mut y = 40;
    let font = ("sans-serif", 12).into_font();
    let mut entry = |label: String, color: RGBColor| -> Result<()> {
        area.draw(&Rectangle::new([(8, y - 9), (20, y + 3)], color.filled()))
            .map_err(draw_err)?;
        area.draw(&Text::new(label, (26, y - 8), font.clone()))
            .map_err(draw_err)?;
        y += 20;
        Ok(())
    };
    for kind in &s.kinds {
        entry(
            format!("{} x{}", kind.name, kind.count),
            role_color(kind.role),
        )?;
    }
    entry("debris".into(), RGBColor(140, 100, 60))?;
    entry("radiation zone".into(), RGBColor(230, 200, 0))?;
    entry("easy task".into(), RGBColor(198, 219, 239))?;
    entry("hard task".into(), RGBColor(253, 208, 162))?;
    entry("rest station".into(), RGBColor(180, 140, 220))?;
    entry("goal point (x)".into(), BLACK)?;
    Ok(())
}
