//! The map: everything in a scenario that does not move (walls, search areas and rescuees,
//! drop-offs, radiation zones, debris, the rest station, goal points and their labels).

use crate::error::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use usar_sim::scenario::{Rect, Scenario};

use crate::render::canvas::{Chart, draw_err, font, label_at};
use crate::render::layout::{DESCRIPTION_CHAR_PX, Layout, drawn_wall_m};
use crate::render::palette::{
    DEBRIS, RADIATION_ALPHA, RESCUEE, REST, WALL, dose_levels, radiation_color, task_color,
};
use crate::render::shapes::{debris_polygon, disc_outline, disc_polygon};

/// Draws everything that does not move: walls, search areas (with their rescuees when
/// `rescuees`), drop-offs, radiation zones, debris, the rest station, goal points and labels.
pub(crate) fn draw_static(chart: &mut Chart<'_, '_>, s: &Scenario, rescuees: bool) -> Result<()> {
    draw_walls(chart, s)?;
    // Search areas and rescuees first: radiation, debris and labels go on top.
    draw_task_areas(chart, s, rescuees)?;
    draw_hazards(chart, s)?;
    draw_rest_stations(chart, s)?;
    // Labels last so nothing covers them.
    draw_task_labels(chart, s)?;
    draw_rest_station_labels(chart, s)
}

/// Draws the four walls around the arena of `s`, each as thick as drawn (`drawn_wall_m`).
fn draw_walls(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    let (w, h) = (s.arena().width(), s.arena().height());
    let t = drawn_wall_m(s);
    let walls = [
        [(-t, -t), (w + t, 0.0)],
        [(-t, h), (w + t, h + t)],
        [(-t, 0.0), (0.0, h)],
        [(w, 0.0), (w + t, h)],
    ];
    chart
        .draw_series(walls.iter().map(|r| Rectangle::new(*r, WALL.filled())))
        .map_err(draw_err)?;
    Ok(())
}

/// Draws each task's search area (with its rescuees when `rescuees`) and its drop-off disc
/// with an outline, in the task's colour.
fn draw_task_areas(chart: &mut Chart<'_, '_>, s: &Scenario, rescuees: bool) -> Result<()> {
    for (t, task) in s.tasks().iter().enumerate() {
        let r = task.search_area;
        chart
            .draw_series([Rectangle::new(
                [(r.min.x, r.min.y), (r.max.x, r.max.y)],
                task_color(s, t).filled(),
            )])
            .map_err(draw_err)?;
        if rescuees {
            chart
                .draw_series(
                    task.rescuees
                        .iter()
                        .map(|p| Circle::new((p.x, p.y), 1, RESCUEE.filled())),
                )
                .map_err(draw_err)?;
        }
        chart
            .draw_series([Polygon::new(
                disc_polygon(&task.drop_off),
                task_color(s, t).filled(),
            )])
            .map_err(draw_err)?;
        chart
            .draw_series([PathElement::new(
                disc_outline(&task.drop_off),
                task_color(s, t).mix(1.0).stroke_width(1),
            )])
            .map_err(draw_err)?;
    }
    Ok(())
}

/// Draws the radiation zones (coloured by dose rate between the lowest and highest dose
/// levels), the debris over them, then each zone's dose-rate factor (`x2`) when the zones
/// have more than one dose level.
fn draw_hazards(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    let doses = dose_levels(s);
    let (lo, hi) = (
        doses.first().copied().unwrap_or(1.0),
        doses.last().copied().unwrap_or(1.0),
    );
    for z in s.radiation_zones() {
        let c = radiation_color(z.dose_rate_factor, lo, hi);
        chart
            .draw_series([Polygon::new(
                disc_polygon(&z.area),
                c.mix(RADIATION_ALPHA).filled(),
            )])
            .map_err(draw_err)?;
        chart
            .draw_series([PathElement::new(disc_outline(&z.area), c.stroke_width(1))])
            .map_err(draw_err)?;
    }
    chart
        .draw_series(
            s.debris()
                .iter()
                .map(|d| Polygon::new(debris_polygon(d), DEBRIS.filled())),
        )
        .map_err(draw_err)?;
    if doses.len() > 1 {
        chart
            .draw_series(s.radiation_zones().iter().map(|z| {
                label_at(
                    format!("x{}", z.dose_rate_factor),
                    z.area.center.x,
                    z.area.center.y,
                    10,
                    VPos::Center,
                )
            }))
            .map_err(draw_err)?;
    }
    Ok(())
}

/// Draws each rest station as a translucent disc.
fn draw_rest_stations(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    chart
        .draw_series(
            s.rest_stations()
                .iter()
                .map(|rs| Polygon::new(disc_polygon(rs), REST.mix(0.6).filled())),
        )
        .map_err(draw_err)?;
    Ok(())
}

/// Labels each task's search area (name and rescuee count) and drop-off, and marks its goal
/// point with a cross.
fn draw_task_labels(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    for task in s.tasks() {
        let r = task.search_area;
        let text = format!(
            "{} search area ({} rescuees)",
            task.name,
            task.rescuees.len()
        );
        draw_area_label(chart, s, &r, text)?;
        let d = task.drop_off;
        chart
            .draw_series([label_at(
                format!("{} drop-off", task.name),
                d.center.x,
                d.center.y - d.radius_m,
                11,
                VPos::Top,
            )])
            .map_err(draw_err)?;
        chart
            .draw_series([Cross::new(
                (task.goal.x, task.goal.y),
                6,
                BLACK.stroke_width(2),
            )])
            .map_err(draw_err)?;
    }
    Ok(())
}

/// Labels each rest station "rest station", the text hanging from the disc's lowest point.
fn draw_rest_station_labels(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    chart
        .draw_series(s.rest_stations().iter().map(|rs| {
            label_at(
                "rest station".into(),
                rs.center.x,
                rs.center.y - rs.radius_m,
                11,
                VPos::Top,
            )
        }))
        .map_err(draw_err)?;
    Ok(())
}

/// Labels a search area above its top-left corner; where the wall leaves no room, below it,
/// else inside its top edge on a white band. Right-aligned when it would run past the arena.
pub(crate) fn draw_area_label(
    chart: &mut Chart<'_, '_>,
    s: &Scenario,
    r: &Rect,
    text: String,
) -> Result<()> {
    let px_per_m = Layout::new(s).px_per_m;
    let w_m = text.len() as f64 * DESCRIPTION_CHAR_PX / px_per_m;
    let h_m = 10.0 / px_per_m;
    let (y, v, inside) = if r.max.y + h_m <= s.arena().height() {
        (r.max.y, VPos::Bottom, false)
    } else if r.min.y - h_m >= 0.0 {
        (r.min.y, VPos::Top, false)
    } else {
        (r.max.y, VPos::Top, true)
    };
    let (x, h) = if r.min.x + w_m > s.arena().width() {
        (r.max.x, HPos::Right)
    } else {
        (r.min.x, HPos::Left)
    };
    if inside {
        let (bx0, bx1) = match h {
            HPos::Right => (r.max.x - w_m, r.max.x),
            _ => (r.min.x, r.min.x + w_m),
        };
        chart
            .draw_series([Rectangle::new(
                [(bx0, r.max.y - h_m), (bx1, r.max.y)],
                WHITE.mix(0.8).filled(),
            )])
            .map_err(draw_err)?;
    }
    chart
        .draw_series([Text::new(text, (x, y), font(12).pos(Pos::new(h, v)))])
        .map_err(draw_err)?;
    Ok(())
}
