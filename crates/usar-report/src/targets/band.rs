//! The band a statistic must fall in: `PlusMinus(w)` around the target's value,
//! `Between(low, high)`, or one-sided, `AtLeast(low)` and `AtMost(high)`; boundaries included.

use std::fmt;

use serde::{Deserialize, Serialize};

use super::float_text::short;

/// Where a statistic is accepted, as written in a targets file.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Band {
    /// `value ± w`: `|x - value| <= w`; `w` finite and > 0, `value ± w` finite.
    PlusMinus(f64),
    /// `low <= x <= high`, whatever the target's value (which must lie inside); both finite,
    /// `low < high`.
    Between(f64, f64),
    /// `x >= low` ("at least"): `low` finite, below the target's value.
    AtLeast(f64),
    /// `x <= high` ("at most"): `high` finite, above the target's value.
    AtMost(f64),
}

impl Band {
    /// The unit of the loss (see `calibrate::loss`), always finite and > 0 for a usable band:
    /// half the band's width (`w`, or `high / 2 - low / 2`); for a one-sided band, the
    /// distance from its bound to the target's `value`.
    pub fn half_width(&self, value: f64) -> f64 {
        match *self {
            Band::PlusMinus(w) => w,
            Band::Between(lo, hi) => hi / 2.0 - lo / 2.0,
            Band::AtLeast(lo) => value - lo,
            Band::AtMost(hi) => hi - value,
        }
    }

    /// How far `x` lies outside the band around `value` (0 inside, boundaries included; NaN
    /// for a NaN `x`, infinite for an infinite one outside). `PlusMinus` measures
    /// `|x - value| - w`, so that `x` holds exactly when `|x - value| <= w` in floating point.
    pub fn distance_outside(&self, value: f64, x: f64) -> f64 {
        if x.is_nan() {
            return f64::NAN;
        }
        match *self {
            Band::PlusMinus(w) => ((x - value).abs() - w).max(0.0),
            Band::Between(lo, hi) => (lo - x).max(x - hi).max(0.0),
            Band::AtLeast(lo) => (lo - x).max(0.0),
            Band::AtMost(hi) => (x - hi).max(0.0),
        }
    }

    /// Whether `x` lies in the band around `value` (never for NaN).
    pub fn holds(&self, value: f64, x: f64) -> bool {
        self.distance_outside(value, x) == 0.0
    }

    /// Lowest and highest accepted value around `value`; an open side is infinite.
    pub fn bounds(&self, value: f64) -> (f64, f64) {
        match *self {
            Band::PlusMinus(w) => (value - w, value + w),
            Band::Between(lo, hi) => (lo, hi),
            Band::AtLeast(lo) => (lo, f64::INFINITY),
            Band::AtMost(hi) => (f64::NEG_INFINITY, hi),
        }
    }

    /// Why the band is not usable for a target of `value`, if it is not: a width that is not
    /// finite and > 0 (or reaches past the largest number), bounds that are not finite or not
    /// increasing, a value outside the band, or a one-sided band whose bound is the value.
    pub fn problem(&self, value: f64) -> Option<String> {
        match *self {
            Band::PlusMinus(w) if !(w.is_finite() && w > 0.0) => Some(format!(
                "PlusMinus({w}): the half-width must be a finite number > 0"
            )),
            Band::PlusMinus(w) if !((value - w).is_finite() && (value + w).is_finite()) => {
                Some(format!(
                    "PlusMinus({w}): the band around {value} reaches past the largest number; \
                     write AtLeast or AtMost for a band open on one side"
                ))
            }
            Band::Between(lo, hi) if !(lo.is_finite() && hi.is_finite()) => Some(format!(
                "Between({lo}, {hi}): both bounds must be finite numbers (AtLeast and AtMost \
                 are open on one side)"
            )),
            Band::Between(lo, hi) if lo >= hi => Some(format!(
                "Between({lo}, {hi}): the low bound must be below the high one"
            )),
            Band::Between(lo, hi) if !(lo..=hi).contains(&value) => Some(format!(
                "the target's value {value} lies outside its own band Between({lo}, {hi})"
            )),
            Band::AtLeast(lo) if !lo.is_finite() => {
                Some(format!("AtLeast({lo}): the bound must be a finite number"))
            }
            Band::AtMost(hi) if !hi.is_finite() => {
                Some(format!("AtMost({hi}): the bound must be a finite number"))
            }
            Band::AtLeast(lo) if !(value > lo && (value - lo).is_finite()) => Some(format!(
                "AtLeast({lo}): the target's value {value} must lie above the bound (their \
                 distance is the loss's unit)"
            )),
            Band::AtMost(hi) if !(value < hi && (hi - value).is_finite()) => Some(format!(
                "AtMost({hi}): the target's value {value} must lie below the bound (their \
                 distance is the loss's unit)"
            )),
            _ => None,
        }
    }
}

impl fmt::Display for Band {
    /// `± 0.6`, `[3, 7]`, `[5, ∞)` or `(-∞, 7]`.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Band::PlusMinus(w) => write!(f, "± {}", short(w)),
            Band::Between(lo, hi) => write!(f, "[{}, {}]", short(lo), short(hi)),
            Band::AtLeast(lo) => write!(f, "[{}, ∞)", short(lo)),
            Band::AtMost(hi) => write!(f, "(-∞, {}]", short(hi)),
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
        assert_eq!(between.half_width(4.69), 2.0);
        let at_least = Band::AtLeast(5.0);
        assert!(
            at_least.holds(6.0, 5.0) && at_least.holds(6.0, 1e308) && !at_least.holds(6.0, 4.9)
        );
        assert_eq!(at_least.distance_outside(6.0, 3.0), 2.0);
        assert_eq!(at_least.half_width(6.0), 1.0);
        assert_eq!(at_least.bounds(6.0), (5.0, f64::INFINITY));
        let at_most = Band::AtMost(7.0);
        assert!(at_most.holds(6.0, -1e308) && !at_most.holds(6.0, 7.5));
        assert_eq!(at_most.half_width(6.0), 1.0);
        assert_eq!(at_least.to_string(), "[5, ∞)");
        assert_eq!(at_most.to_string(), "(-∞, 7]");
        // A very wide band's half-width does not overflow.
        assert_eq!(Band::Between(-1e308, 1e308).half_width(0.0), 1e308);
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
        assert_eq!(Band::AtLeast(5.0).problem(6.0), None);
        assert_eq!(Band::AtMost(1.7e308).problem(6.0), None);
        assert_eq!(Band::Between(-1e308, 1e308).problem(6.0), None);
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
            (Band::PlusMinus(1e308), "reaches past the largest number"),
            (
                Band::AtLeast(f64::NAN),
                "AtLeast(NaN): the bound must be a finite",
            ),
            (Band::AtLeast(4.69), "must lie above the bound"),
            (Band::AtMost(-1.7e308), "must lie below the bound"),
            (
                Band::AtMost(1.7e308 + 1.7e308),
                "AtMost(inf): the bound must be a finite",
            ),
        ] {
            let value = if matches!(band, Band::PlusMinus(w) if w > 1e300) {
                1e308
            } else {
                4.69
            };
            let p = band.problem(value).unwrap();
            assert!(p.starts_with(says) || p.contains(says), "{p}");
        }
    }
}
