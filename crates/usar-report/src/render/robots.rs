//! The robots on the map: at their start positions by kind, and the paths traced robots took
//! with where they ended.

use crate::error::Result;
use plotters::prelude::*;
use plotters::style::text_anchor::VPos;
use usar_sim::scenario::{Circle as Disc, Locomotion, PointM, Scenario};

use crate::render::canvas::{Chart, draw_err, label_at};
use crate::render::palette::kind_color;
use crate::render::shapes::{disc_outline, disc_polygon};

/// The path one robot took: its positions in the world frame, metres, in time order.
pub type Trace = Vec<PointM>;

pub(crate) fn draw_paths(chart: &mut Chart<'_, '_>, s: &Scenario, traces: &[Trace]) -> Result<()> {
    for (id, trace) in traces.iter().enumerate().take(s.robots().len()) {
        let color = kind_color(s, s.robots()[id].kind);
        chart
            .draw_series([PathElement::new(
                trace.iter().map(|p| (p.x, p.y)).collect::<Vec<_>>(),
                color.mix(0.6).stroke_width(1),
            )])
            .map_err(draw_err)?;
    }
    Ok(())
}

/// Where each traced robot ended: hollow discs of the body's size, on top of everything.
pub(crate) fn draw_ends(chart: &mut Chart<'_, '_>, s: &Scenario, traces: &[Trace]) -> Result<()> {
    for (id, trace) in traces.iter().enumerate().take(s.robots().len()) {
        let kind = s.kind_of(id);
        let Some(end) = trace.last() else { continue };
        let body = Disc {
            center: *end,
            radius_m: kind.body_radius_m,
        };
        chart
            .draw_series([Polygon::new(disc_polygon(&body), WHITE.filled())])
            .map_err(draw_err)?;
        chart
            .draw_series([PathElement::new(
                disc_outline(&body),
                kind_color(s, s.robots()[id].kind).stroke_width(2),
            )])
            .map_err(draw_err)?;
    }
    Ok(())
}

pub(crate) fn draw_robots(chart: &mut Chart<'_, '_>, s: &Scenario) -> Result<()> {
    for (id, robot) in s.robots().iter().enumerate() {
        let kind = &s.kinds()[robot.kind];
        let body = Disc {
            center: robot.start_in_world,
            radius_m: kind.body_radius_m,
        };
        let color = kind_color(s, robot.kind);
        chart
            .draw_series([Polygon::new(disc_polygon(&body), color.filled())])
            .map_err(draw_err)?;
        let mut reach = kind.body_radius_m;
        if kind.locomotion == Locomotion::Aerial {
            reach *= 1.8;
            let ring = Disc {
                radius_m: reach,
                ..body
            };
            chart
                .draw_series([PathElement::new(disc_outline(&ring), color.stroke_width(1))])
                .map_err(draw_err)?;
        }
        if s.robots().len() <= MAX_LABELLED_ROBOTS {
            chart
                .draw_series([label_at(
                    id.to_string(),
                    body.center.x,
                    body.center.y - reach,
                    9,
                    VPos::Top,
                )])
                .map_err(draw_err)?;
        }
    }
    Ok(())
}

/// Teams of more robots than this are drawn without id labels (they would cover each other).
pub const MAX_LABELLED_ROBOTS: usize = 100;
