//! The picture's legend: an entry per robot kind, path, debris, radiation dose, task, rescuee,
//! goal point and rest station, then a scale bar.

use crate::error::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use usar_sim::scenario::{Locomotion, Scenario};

use crate::render::canvas::{Area, draw_err, font};
use crate::render::palette::{
    DEBRIS, RADIATION_ALPHA, RESCUEE, REST, dose_levels, kind_color, over_white, radiation_color,
    task_color,
};

/// Width of the legend column, pixels.
pub(crate) const LEGEND_PX: u32 = 200;

/// Height of one legend entry, pixels.
pub(crate) const LEGEND_ROW_PX: i32 = 20;

/// What a legend entry shows left of its text.
pub(crate) enum Swatch {
    /// A filled square.
    Square(RGBColor),
    /// A filled square with an outline of the second colour.
    Outlined(RGBColor, RGBColor),
    /// A robot: a disc, ringed for aerial robots.
    Robot(RGBColor, bool),
    /// A hollow disc (where a traced robot ended).
    Hollow(RGBColor),
    /// A small dot (a rescuee).
    Dot(RGBColor),
    /// A cross (a goal point).
    Cross,
    /// A line (a path).
    Line(RGBColor),
}

pub(crate) fn legend_entries(s: &Scenario, traced: bool) -> Vec<(Swatch, String)> {
    let mut v: Vec<(Swatch, String)> = s
        .kinds()
        .iter()
        .enumerate()
        .map(|(i, k)| {
            let aerial = k.locomotion == Locomotion::Aerial;
            let how = if aerial { "aerial" } else { "ground" };
            (
                Swatch::Robot(kind_color(s, i), aerial),
                format!("{} x{} ({how})", k.name, k.count),
            )
        })
        .collect();
    if traced {
        v.push((
            Swatch::Line(RGBColor(120, 120, 120)),
            "path (colour by kind)".into(),
        ));
        v.push((
            Swatch::Hollow(RGBColor(120, 120, 120)),
            "where it ended".into(),
        ));
    }
    if !s.debris().is_empty() {
        v.push((Swatch::Square(DEBRIS), "debris".into()));
    }
    let doses = dose_levels(s);
    let (lo, hi) = (
        doses.first().copied().unwrap_or(1.0),
        doses.last().copied().unwrap_or(1.0),
    );
    for f in &doses {
        let c = radiation_color(*f, lo, hi);
        v.push((
            Swatch::Outlined(over_white(c, RADIATION_ALPHA), c),
            format!("radiation, dose x{f}"),
        ));
    }
    for (t, task) in s.tasks().iter().enumerate() {
        v.push((
            Swatch::Square(task_color(s, t)),
            format!("{} task: area, drop-off", task.name),
        ));
    }
    v.push((Swatch::Dot(RESCUEE), "rescuee".into()));
    v.push((Swatch::Cross, "task goal point".into()));
    v.push((Swatch::Square(REST), "rest station".into()));
    v
}

pub(crate) fn draw_legend(
    area: &Area<'_>,
    entries: &[(Swatch, String)],
    px_per_m: f64,
) -> Result<()> {
    let mut y = 16;
    for (swatch, label) in entries {
        let (cx, cy) = (14, y);
        match swatch {
            Swatch::Square(c) => area
                .draw(&Rectangle::new([(8, cy - 6), (20, cy + 6)], c.filled()))
                .map_err(draw_err)?,
            Swatch::Outlined(fill, line) => {
                area.draw(&Rectangle::new([(8, cy - 6), (20, cy + 6)], fill.filled()))
                    .map_err(draw_err)?;
                area.draw(&Rectangle::new(
                    [(8, cy - 6), (20, cy + 6)],
                    line.stroke_width(1),
                ))
                .map_err(draw_err)?;
            }
            Swatch::Robot(c, ring) => {
                area.draw(&Circle::new((cx, cy), 5, c.filled()))
                    .map_err(draw_err)?;
                if *ring {
                    area.draw(&Circle::new((cx, cy), 8, c.stroke_width(1)))
                        .map_err(draw_err)?;
                }
            }
            Swatch::Hollow(c) => area
                .draw(&Circle::new((cx, cy), 5, c.stroke_width(2)))
                .map_err(draw_err)?,
            Swatch::Dot(c) => area
                .draw(&Circle::new((cx, cy), 2, c.filled()))
                .map_err(draw_err)?,
            Swatch::Cross => area
                .draw(&Cross::new((cx, cy), 6, BLACK.stroke_width(2)))
                .map_err(draw_err)?,
            Swatch::Line(c) => area
                .draw(&PathElement::new(
                    vec![(6, cy + 4), (12, cy - 3), (16, cy + 2), (22, cy - 5)],
                    c.stroke_width(2),
                ))
                .map_err(draw_err)?,
        }
        area.draw(&Text::new(
            label.clone(),
            (28, cy),
            font(12).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(draw_err)?;
        y += LEGEND_ROW_PX;
    }
    // Scale bar: the longest round length that fits in the legend column.
    let len_m = [100.0, 50.0, 20.0, 10.0, 5.0, 2.0, 1.0, 0.5]
        .into_iter()
        .find(|m| m * px_per_m <= f64::from(LEGEND_PX) - 40.0)
        .unwrap_or(0.5);
    let len_px = (len_m * px_per_m).round() as i32;
    let by = y + LEGEND_ROW_PX / 2;
    area.draw(&PathElement::new(
        vec![(8, by - 4), (8, by), (8 + len_px, by), (8 + len_px, by - 4)],
        BLACK.stroke_width(2),
    ))
    .map_err(draw_err)?;
    area.draw(&Text::new(
        format!("{len_m} m"),
        (8 + len_px / 2, by + 3),
        font(11).pos(Pos::new(HPos::Center, VPos::Top)),
    ))
    .map_err(draw_err)?;
    Ok(())
}
