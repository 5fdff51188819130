//! The band a statistic must fall in: `PlusMinus(w)` around the target's value, or
//! `Between(low, high)`; boundaries included.

use std::fmt;

use serde::{Deserialize, Serialize};

/// Where a statistic is accepted, as written in a targets file.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Band {
    /// `value ± w`: `|x - value| <= w`; `w` finite and > 0.
    PlusMinus(f64),
    /// `low <= x <= high`, whatever the target's value (which must lie inside); both finite,
    /// `low < high`.
    Between(f64, f64),
}

impl Band {
    /// Half the band's width: `w`, or `(high - low) / 2` (the unit of the loss, see
    /// [`super::loss()`]).
    pub fn half_width(&self) -> f64 {
        match *self {
            Band::PlusMinus(w) => w,
            Band::Between(lo, hi) => (hi - lo) / 2.0,
        }
    }

    /// How far `x` lies outside the band around `value` (0 inside, boundaries included; NaN
    /// for a NaN `x`, infinite for an infinite one). `PlusMinus` measures `|x - value| - w`, so
    /// that `x` holds exactly when `|x - value| <= w` in floating point.
    pub fn distance_outside(&self, value: f64, x: f64) -> f64 {
        if x.is_nan() {
            return f64::NAN;
        }
        match *self {
            Band::PlusMinus(w) => ((x - value).abs() - w).max(0.0),
            Band::Between(lo, hi) => (lo - x).max(x - hi).max(0.0),
        }
    }

    /// Whether `x` lies in the band around `value` (never for NaN).
    pub fn holds(&self, value: f64, x: f64) -> bool {
        self.distance_outside(value, x) == 0.0
    }

    /// Lowest and highest accepted value around `value`.
    pub fn bounds(&self, value: f64) -> (f64, f64) {
        match *self {
            Band::PlusMinus(w) => (value - w, value + w),
            Band::Between(lo, hi) => (lo, hi),
        }
    }

    /// Why the band is not usable for a target of `value`, if it is not: a width that is not
    /// finite and > 0, bounds that are not finite or not increasing, or (for `Between`) a
    /// value outside the band.
    pub fn problem(&self, value: f64) -> Option<String> {
        match *self {
            Band::PlusMinus(w) if !(w.is_finite() && w > 0.0) => Some(format!(
                "PlusMinus({w}): the half-width must be a finite number > 0"
            )),
            Band::Between(lo, hi) if !(lo.is_finite() && hi.is_finite()) => Some(format!(
                "Between({lo}, {hi}): both bounds must be finite numbers"
            )),
            Band::Between(lo, hi) if lo >= hi => Some(format!(
                "Between({lo}, {hi}): the low bound must be below the high one"
            )),
            Band::Between(lo, hi) if !(lo..=hi).contains(&value) => Some(format!(
                "the target's value {value} lies outside its own band Between({lo}, {hi})"
            )),
            _ => None,
        }
    }
}

impl fmt::Display for Band {
    /// `± 0.6` or `[3, 7]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Band::PlusMinus(w) => write!(f, "± {w}"),
            Band::Between(lo, hi) => write!(f, "[{lo}, {hi}]"),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bands_include_their_boundaries() {
        let pm = Band::PlusMinus(0.6);
        assert!(pm.holds(6.2, 6.8) && pm.holds(6.2, 5.61) && !pm.holds(6.2, 6.81));
        // In floating point |5.6 - 6.2| is 0.6000000000000005: just outside, as the nine
        // targets' old `holds` judged it.
        assert!(!pm.holds(6.2, 5.6));
        assert!((pm.distance_outside(6.2, 7.4) - 0.6).abs() < 1e-12);
        let between = Band::Between(3.0, 7.0);
        assert!(between.holds(4.69, 3.0) && between.holds(4.69, 7.0));
        assert_eq!(between.distance_outside(4.69, 8.0), 1.0);
        assert_eq!(between.distance_outside(4.69, 1.0), 2.0);
        assert_eq!(between.half_width(), 2.0);
        assert!(between.distance_outside(4.69, f64::NAN).is_nan());
        assert!(!between.holds(4.69, f64::NAN));
        assert_eq!(between.distance_outside(4.69, f64::INFINITY), f64::INFINITY);
        assert_eq!(pm.bounds(1.0), (0.4, 1.6));
        assert_eq!(pm.to_string(), "± 0.6");
        assert_eq!(between.to_string(), "[3, 7]");
    }

    #[test]
    fn unusable_bands_say_why() {
        assert_eq!(Band::PlusMinus(0.5).problem(1.0), None);
        assert_eq!(Band::Between(3.0, 7.0).problem(4.69), None);
        for (band, says) in [
            (Band::PlusMinus(0.0), "PlusMinus(0): the half-width must be"),
            (
                Band::PlusMinus(-1.0),
                "PlusMinus(-1): the half-width must be",
            ),
            (Band::PlusMinus(f64::NAN), "PlusMinus(NaN): the half-width"),
            (
                Band::Between(3.0, 3.0),
                "Between(3, 3): the low bound must be below",
            ),
            (
                Band::Between(f64::NEG_INFINITY, 3.0),
                "both bounds must be finite",
            ),
            (
                Band::Between(5.0, 7.0),
                "the target's value 4.69 lies outside its own band",
            ),
        ] {
            let p = band.problem(4.69).unwrap();
            assert!(p.starts_with(says) || p.contains(says), "{p}");
        }
    }
}
