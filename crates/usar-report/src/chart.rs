//! Chart basics every SVG figure shares: the figure size, the methods' colours, a legend entry,
//! axis ranges that cannot overflow or be empty, tick labels, and plotters' drawing errors.

use crate::error::{ReportError, Result};
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

/// The largest magnitude an axis reaches: values beyond are drawn at this bound, so that an
/// axis's width (at most `2e300`) and its padding stay finite; `1e300`.
pub const AXIS_LIMIT: f64 = 1e300;

/// The narrowest axis, relative to the largest magnitude on it (`1e-9`): below this the
/// ticks of an axis around 1e16 would not advance in floating point (plotters' tick loop would
/// never end). An axis around 0 is at least `1e-200` wide.
const MIN_RELATIVE_WIDTH: f64 = 1e-9;

/// An axis range `(low, high)` with `low < high`, both finite, that covers every finite value
/// of `values` (each clamped to ±[`AXIS_LIMIT`]), with `pad` (a fraction of the width, `0.08`
/// for 8 %) of room on each side. Non-finite values are left out; none at all gives `0..1`;
/// a single value `x` gives `x ± max(|x| / 20, 1)` (no further room); a range narrower than a billionth of its
/// magnitude is widened around its middle. Never overflows, never empty: every figure's axes
/// come from here, so that plotters' tick loop always ends.
pub fn axis_range(values: impl IntoIterator<Item = f64>, pad: f64) -> (f64, f64) {
    let (lo, hi) = values
        .into_iter()
        .filter(|x| x.is_finite())
        .map(|x| x.clamp(-AXIS_LIMIT, AXIS_LIMIT))
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), x| {
            (l.min(x), h.max(x))
        });
    if lo > hi {
        return (0.0, 1.0);
    }
    let magnitude = lo.abs().max(hi.abs());
    if hi == lo {
        let half = (magnitude / 20.0).max(1.0);
        return (lo - half, hi + half);
    }
    let min_width = (magnitude * MIN_RELATIVE_WIDTH).max(1e-200);
    let (lo, hi) = if hi - lo < min_width {
        let mid = lo / 2.0 + hi / 2.0;
        (mid - min_width / 2.0, mid + min_width / 2.0)
    } else {
        (lo, hi)
    };
    let room = (hi - lo) * pad.clamp(0.0, 1.0);
    (lo - room, hi + room)
}

/// `v` as drawn: clamped to ±[`AXIS_LIMIT`] (NaN stays NaN). Every coordinate a figure
/// draws from data goes through it: its axis ([`axis_range`]) covers the clamped values, so
/// no point lands millions of axis widths away, past what plotters' pixel arithmetic holds.
pub fn plotted(v: f64) -> f64 {
    v.clamp(-AXIS_LIMIT, AXIS_LIMIT)
}

/// A tick label of `v` with `decimals` digits after the point, or in scientific notation
/// (`1.20e9`) when `|v|` is at least a million or below a thousandth (but not 0), so that a
/// label never runs to hundreds of digits.
pub fn tick_label(v: f64, decimals: usize) -> String {
    let a = v.abs();
    if a >= 1e6 || (a > 0.0 && a < 1e-3) {
        format!("{v:.2e}")
    } else {
        format!("{v:.decimals$}")
    }
}

/// Draws a figure with `draw`, or, when it fails or panics, warns on standard error (naming
/// `what`) and returns `None`: a figure that cannot be drawn never costs a run its data.
pub fn figure_or_warn<T, E: std::error::Error + 'static>(
    what: &str,
    draw: impl FnOnce() -> Result<T, E>,
) -> Option<T> {
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(draw)) {
        Ok(Ok(figure)) => Some(figure),
        Ok(Err(e)) => {
            let why = rne_core::error_line(&e);
            tracing::warn!("{what} not drawn: {why}");
            None
        }
        Err(_) => {
            tracing::warn!("{what} not drawn: the plotting library panicked");
            None
        }
    }
}

/// A plotters drawing error as a [`ReportError::Figure`] (`drawing a figure: ...`).
pub fn draw_err<E: std::fmt::Debug>(e: E) -> ReportError {
    ReportError::Figure {
        problem: format!("{e:?}"),
    }
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_ranges_are_finite_and_never_empty() {
        assert_eq!(axis_range([], 0.08), (0.0, 1.0));
        assert_eq!(axis_range([f64::NAN, f64::INFINITY], 0.08), (0.0, 1.0));
        assert_eq!(axis_range([3.0], 0.08), (2.0, 4.0));
        let (lo, hi) = axis_range([0.0, 10.0], 0.1);
        assert!((lo + 1.0).abs() < 1e-12 && (hi - 11.0).abs() < 1e-12);
        for values in [
            vec![-1.7e308, 1.7e308],
            vec![f64::MAX],
            vec![1e16, 1e16 + 2.0],
            vec![5.0, 1.7e308],
            vec![1e-300, 2e-300],
            vec![-f64::MIN_POSITIVE, 0.0],
        ] {
            let (lo, hi) = axis_range(values.iter().copied(), 0.08);
            assert!(
                lo.is_finite() && hi.is_finite() && lo < hi,
                "{values:?}: {lo}..{hi}"
            );
            assert!((hi - lo).is_finite(), "{values:?}");
            let step = (hi - lo) / 10.0;
            assert!(
                lo + step > lo && hi - step < hi,
                "{values:?}: ticks advance"
            );
        }
    }

    #[test]
    fn tick_labels_stay_short() {
        assert_eq!(tick_label(1.5, 3), "1.500");
        assert_eq!(tick_label(0.0, 1), "0.0");
        assert_eq!(tick_label(1.7e308, 3), "1.70e308");
        assert_eq!(tick_label(-2.5e-7, 3), "-2.50e-7");
    }
}
