//! Chart basics every SVG figure shares: the figure size, the methods' colours, a legend entry
//! and plotters' drawing errors.

use anyhow::{Result, anyhow};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

/// Width and height of each figure, pixels.
pub const FIGURE_SIZE: (u32, u32) = (820, 440);

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

/// A plotters drawing error as an [`anyhow::Error`] (`drawing a figure: ...`).
pub(crate) fn draw_err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("drawing a figure: {e:?}")
}

/// The `i`-th legend entry (top left of `area`, one line each): a `color` swatch and `name`.
pub(crate) fn legend_entry(
    area: &DrawingArea<SVGBackend<'_>, Shift>,
    i: usize,
    name: &str,
    color: RGBColor,
) -> Result<()> {
    let y = 60 + 26 * i as i32;
    area.draw(&Rectangle::new([(8, y - 7), (24, y + 7)], color.filled()))
        .map_err(draw_err)?;
    area.draw(&Text::new(
        name,
        (32, y),
        ("sans-serif", 15)
            .into_font()
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Center)),
    ))
    .map_err(draw_err)
}
