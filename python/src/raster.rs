//! `usar.gym`'s `rgb_array` frames: an SVG picture (`usar.render`'s) rasterised with resvg
//! into RGB bytes, composited over white. Built without resvg's text support (no fonts are
//! loaded): the picture's labels are left out of the frame.

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyBytes;
use resvg::{tiny_skia, usvg};

/// The largest side of a frame, pixels.
const MAX_SIDE: u32 = 8192;

/// Rasterises the SVG text `svg` to `width` pixels wide (default: the picture's own width,
/// one pixel per SVG unit), the height in proportion. Returns `(height, width, rgb)`: `rgb`
/// holds `height * width * 3` bytes, rows top to bottom, each pixel's red, green and blue,
/// the picture composited over white.
///
/// # Errors
/// `ValueError` naming `svg` for text that is not an SVG picture, or `width` for a width of
/// 0 or a frame side above 8192 pixels.
#[pyfunction]
#[pyo3(signature = (svg, width = None))]
pub fn rasterize_svg<'py>(
    py: Python<'py>,
    svg: &str,
    width: Option<u32>,
) -> PyResult<(u32, u32, Bound<'py, PyBytes>)> {
    let tree = usvg::Tree::from_str(svg, &usvg::Options::default())
        .map_err(|e| PyValueError::new_err(format!("svg: not an SVG picture: {e}")))?;
    let size = tree.size();
    let w = width.unwrap_or(size.width().ceil() as u32);
    if w == 0 || w > MAX_SIDE {
        return Err(PyValueError::new_err(format!(
            "width: expected 1 to {MAX_SIDE} pixels, found {w}"
        )));
    }
    let scale = w as f32 / size.width();
    let h = ((size.height() * scale).round() as u32).max(1);
    if h > MAX_SIDE {
        return Err(PyValueError::new_err(format!(
            "width: {w} pixels make the frame {h} pixels high, above {MAX_SIDE}"
        )));
    }
    let mut pixmap = tiny_skia::Pixmap::new(w, h)
        .ok_or_else(|| PyValueError::new_err(format!("width: no frame of {w} x {h} pixels")))?;
    pixmap.fill(tiny_skia::Color::WHITE);
    resvg::render(
        &tree,
        tiny_skia::Transform::from_scale(scale, scale),
        &mut pixmap.as_mut(),
    );
    // Over an opaque white background every pixel is opaque: premultiplied = straight.
    let rgb: Vec<u8> = pixmap
        .data()
        .chunks_exact(4)
        .flat_map(|p| [p[0], p[1], p[2]])
        .collect();
    Ok((h, w, PyBytes::new(py, &rgb)))
}
