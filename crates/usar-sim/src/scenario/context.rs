//! The validation context: errors positioned at a field path, and the checks of single numbers,
//! points, rectangles and circles that every validation step shares.
//!
//! [`Ctx`] carries the origin (file path or name) and, when the spec was read from text, its
//! source map, so that an error at a field path gets the line and column of that field. The
//! message helpers ([`fmt_pt`], [`fmt_arena`]) write numbers the way all scenario errors do.

use nalgebra::Point2;

use super::error::{ScenarioError, SourceLocation};
use super::locate::SourceMap;
use super::model::{Circle, PointM, Rect, number_text};
use super::params::Arena;
use super::spec::{CircleSpec, RectSpec, XyM};

/// The result of a validation step: the value, or the first rule broken.
pub(crate) type R<T> = Result<T, ScenarioError>;

/// Error context: the origin name and, when validating a file's text, its source map.
pub(crate) struct Ctx<'a> {
    pub(crate) origin: &'a str,
    pub(crate) map: Option<&'a SourceMap>,
}

impl Ctx<'_> {
    /// An [`ScenarioError::Invalid`] at `field` (positioned at the field or its nearest
    /// ancestor in the source).
    pub(crate) fn err(
        &self,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> ScenarioError {
        let field = field.into();
        ScenarioError::Invalid {
            location: SourceLocation {
                origin: self.origin.to_owned(),
                line_col: self.map.and_then(|m| m.line_col_of(&field)),
            },
            field,
            message: message.into(),
        }
    }

    /// `v` if finite, else an error at `field`.
    pub(crate) fn finite(&self, field: &str, v: f64) -> R<f64> {
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.err(field, format!("expected a finite number, found {v}")))
        }
    }

    /// `v` if finite and `>= 0`, else an error at `field`.
    pub(crate) fn non_negative(&self, field: &str, v: f64) -> R<f64> {
        if v.is_finite() && v >= 0.0 {
            Ok(v)
        } else {
            Err(self.err(
                field,
                format!("expected a finite number >= 0, found {}", number_text(v)),
            ))
        }
    }

    /// `v` if finite and in `[lo, hi]`, else an error at `field`.
    pub(crate) fn in_range(&self, field: &str, v: f64, lo: f64, hi: f64) -> R<f64> {
        if v.is_finite() && v >= lo && v <= hi {
            Ok(v)
        } else {
            Err(self.err(
                field,
                format!(
                    "expected a number in [{}, {}], found {}",
                    number_text(lo),
                    number_text(hi),
                    number_text(v)
                ),
            ))
        }
    }

    /// The point `xy` (metres) if both coordinates are finite, else an error at `field`.
    pub(crate) fn point(&self, field: &str, xy: &XyM) -> R<PointM> {
        if xy.iter().all(|v| v.is_finite()) {
            Ok(Point2::new(xy[0], xy[1]))
        } else {
            Err(self.err(
                field,
                format!("expected finite coordinates, found ({}, {})", xy[0], xy[1]),
            ))
        }
    }

    /// The point `xy` (metres) if finite and inside the arena, else an error at `field`.
    pub(crate) fn point_in_arena(&self, field: &str, xy: &XyM, arena: &Arena) -> R<PointM> {
        let p = self.point(field, xy)?;
        if arena.contains(&p) {
            Ok(p)
        } else {
            Err(self.err(
                field,
                format!(
                    "point {} is outside the arena {}",
                    fmt_pt(&p),
                    fmt_arena(arena)
                ),
            ))
        }
    }

    /// The rectangle of `spec` if its corners are finite, ordered (`max_m > min_m`) and inside
    /// the arena, else an error at `field` (or at its `min_m` / `max_m`).
    pub(crate) fn rect_in_arena(&self, field: &str, spec: &RectSpec, arena: &Arena) -> R<Rect> {
        let min = self.point(&format!("{field}.min_m"), &spec.min_m)?;
        let max = self.point(&format!("{field}.max_m"), &spec.max_m)?;
        if !(max.x > min.x && max.y > min.y) {
            return Err(self.err(
                field,
                format!(
                    "expected max_m > min_m in both coordinates, found min_m {} and max_m {}",
                    fmt_pt(&min),
                    fmt_pt(&max)
                ),
            ));
        }
        if !(arena.contains(&min) && arena.contains(&max)) {
            return Err(self.err(
                field,
                format!(
                    "rectangle {} - {} is not inside the arena {}",
                    fmt_pt(&min),
                    fmt_pt(&max),
                    fmt_arena(arena)
                ),
            ));
        }
        Ok(Rect { min, max })
    }

    /// The circle of `spec` if its centre is finite and the whole disc is inside the arena,
    /// else an error at `field` (or at its `center_m`).
    pub(crate) fn circle_in_arena(
        &self,
        field: &str,
        spec: &CircleSpec,
        arena: &Arena,
    ) -> R<Circle> {
        let center = self.point(&format!("{field}.center_m"), &spec.center_m)?;
        let radius_m = spec.radius_m.get();
        if !disc_inside(arena, &center, radius_m) {
            return Err(self.err(
                field,
                format!(
                    "circle at {} with radius {} m is not inside the arena {}",
                    fmt_pt(&center),
                    number_text(radius_m),
                    fmt_arena(arena)
                ),
            ));
        }
        Ok(Circle { center, radius_m })
    }
}

/// A point as messages write it: `(x, y)` in the shortest exact number text.
pub(crate) fn fmt_pt(p: &PointM) -> String {
    format!("({}, {})", number_text(p.x), number_text(p.y))
}

/// The arena as messages write it: `[0, width] x [0, height] m`.
pub(crate) fn fmt_arena(a: &Arena) -> String {
    format!(
        "[0, {}] x [0, {}] m",
        number_text(a.width()),
        number_text(a.height())
    )
}

/// `true` if the disc of radius `r` (metres) at `c` lies wholly inside the arena.
pub(crate) fn disc_inside(arena: &Arena, c: &PointM, r: f64) -> bool {
    c.x - r >= 0.0 && c.y - r >= 0.0 && c.x + r <= arena.width() && c.y + r <= arena.height()
}
