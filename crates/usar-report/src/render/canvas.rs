//! The SVG canvas the pictures are drawn on: the chart and area types, fonts, centred labels
//! and plotters' drawing errors.

use plotters::coord::Shift;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use crate::error::ReportError;

pub(crate) type Chart<'a, 'b> =
    ChartContext<'a, SVGBackend<'b>, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

pub(crate) type Area<'a> = DrawingArea<SVGBackend<'a>, Shift>;

/// A plotters drawing error as a [`ReportError::Picture`] (`drawing the SVG failed: ...`).
pub(crate) fn draw_err<E: std::fmt::Display>(e: E) -> ReportError {
    ReportError::Picture {
        problem: e.to_string(),
    }
}

pub(crate) fn font(size: u32) -> TextStyle<'static> {
    ("sans-serif", size).into_font().into()
}

/// A label centred on `(x, y)` horizontally, hanging below it (`VPos::Top`) or sitting on it.
pub(crate) fn label_at(
    text: String,
    x: f64,
    y: f64,
    size: u32,
    v: VPos,
) -> Text<'static, (f64, f64), String> {
    Text::new(text, (x, y), font(size).pos(Pos::new(HPos::Center, v)))
}
