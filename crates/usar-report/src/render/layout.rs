//! The picture's geometry: the field's extent in metres, the scale, the map's size in pixels,
//! and the text sizes and wrapping that the header and labels use.

use usar_sim::scenario::Scenario;

/// Length of the longer side of the drawn field (arena plus walls and a margin), pixels; the
/// scale is clamped to [`MIN_PX_PER_M`, `MAX_PX_PER_M`].
pub(crate) const MAP_TARGET_PX: f64 = 960.0;

/// Smallest scale, pixels per metre.
pub(crate) const MIN_PX_PER_M: f64 = 4.0;

/// Largest scale, pixels per metre (a narrow corridor is drawn large, not huge).
pub(crate) const MAX_PX_PER_M: f64 = 40.0;

/// Approximate width of one character of the 12 px description font, pixels (for wrapping).
pub(crate) const DESCRIPTION_CHAR_PX: f64 = 6.6;

/// The drawing's geometry: field extent in metres and the scale.
pub(crate) struct Layout {
    pub(crate) x0: f64,
    pub(crate) x1: f64,
    pub(crate) y0: f64,
    pub(crate) y1: f64,
    pub(crate) px_per_m: f64,
    pub(crate) map_w: u32,
    pub(crate) map_h: u32,
}

impl Layout {
    pub(crate) fn new(s: &Scenario) -> Self {
        let (w, h) = (s.arena().width(), s.arena().height());
        let pad = drawn_wall_m(s) + 1.0;
        let (x0, x1) = (-pad, w + pad);
        let (y0, y1) = (-pad, h + pad);
        let px_per_m = (MAP_TARGET_PX / (x1 - x0).max(y1 - y0)).clamp(MIN_PX_PER_M, MAX_PX_PER_M);
        Self {
            x0,
            x1,
            y0,
            y1,
            px_per_m,
            map_w: ((x1 - x0) * px_per_m).round() as u32,
            map_h: ((y1 - y0) * px_per_m).round() as u32,
        }
    }
}

/// Splits `text` into lines of at most `width` characters at spaces.
pub(crate) fn wrap(text: &str, width: usize) -> Vec<String> {
    let mut lines = Vec::new();
    let mut line = String::new();
    for word in text.split_whitespace() {
        if !line.is_empty() && line.len() + 1 + word.len() > width {
            lines.push(std::mem::take(&mut line));
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(word);
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

/// The walls' drawn thickness, metres: `arena.wall_thickness_m`, but at most a tenth of the
/// arena's longer side, so that thick walls (up to 10 km) do not shrink the arena in the
/// picture to a dot.
pub(crate) fn drawn_wall_m(s: &Scenario) -> f64 {
    let longer_side_m = s.arena().width().max(s.arena().height());
    s.arena().wall_thickness_m.get().min(0.1 * longer_side_m)
}
