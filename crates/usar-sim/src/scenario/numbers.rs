//! Validated numbers of scenario fields ("parse, don't validate"): each type can only hold a
//! value in its range, so a field typed [`Positive`] is > 0 wherever it is read, whether it came
//! from a file (deserialisation checks it and ron reports the value's line and column) or from
//! code ([`Positive::new`] checks it).
//!
//! All are `f64` underneath, serialise as plain numbers, and reject NaN and infinities.

// The range checks also run in the `const fn known`, where `RangeInclusive::contains` cannot.
#![allow(clippy::manual_range_contains)]

use std::fmt;

use serde::{Deserialize, Serialize};

/// A number outside its field's range; the message says what was expected and what was found,
/// e.g. `expected a finite number > 0, found -5`.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RangeError(pub String);

impl fmt::Display for RangeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for RangeError {}

macro_rules! bounded {
    ($(#[$doc:meta])* $name:ident, $expect:literal, |$v:ident| $ok:expr) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, PartialOrd, Serialize, Deserialize)]
        #[serde(try_from = "f64", into = "f64")]
        pub struct $name(f64);

        impl $name {
            #[doc = concat!("Checks `value`: ", $expect, ".")]
            ///
            /// # Errors
            /// [`RangeError`] naming the range and the value.
            pub fn new(value: f64) -> Result<Self, RangeError> {
                let $v = value;
                if $v.is_finite() && $ok {
                    Ok(Self(value))
                } else {
                    Err(RangeError(format!(
                        concat!("expected ", $expect, ", found {}"),
                        rne_core::number_text(value)
                    )))
                }
            }

            /// The value.
            pub const fn get(self) -> f64 {
                self.0
            }

            /// A value known to be in range (defaults written in the code); checked in debug
            /// builds.
            pub(crate) const fn known(value: f64) -> Self {
                let $v = value;
                debug_assert!($v.is_finite() && $ok);
                Self(value)
            }
        }

        impl TryFrom<f64> for $name {
            type Error = RangeError;
            fn try_from(value: f64) -> Result<Self, RangeError> {
                Self::new(value)
            }
        }

        impl From<$name> for f64 {
            fn from(x: $name) -> f64 {
                x.0
            }
        }

        impl PartialEq<f64> for $name {
            fn eq(&self, other: &f64) -> bool {
                self.0 == *other
            }
        }

        impl PartialOrd<f64> for $name {
            fn partial_cmp(&self, other: &f64) -> Option<std::cmp::Ordering> {
                self.0.partial_cmp(other)
            }
        }

        impl fmt::Display for $name {
            fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                fmt::Display::fmt(&self.0, f)
            }
        }
    };
}

bounded!(
    /// Any finite number.
    Finite,
    "a finite number",
    |v| true
);

bounded!(
    /// A finite number `> 0`.
    Positive,
    "a finite number > 0",
    |v| v > 0.0
);

bounded!(
    /// A finite number `>= 0`.
    NonNegative,
    "a finite number >= 0",
    |v| v >= 0.0
);

bounded!(
    /// A percentage in `[0, 100]`.
    Percent,
    "a number in [0, 100]",
    |v| v >= 0.0 && v <= 100.0
);

bounded!(
    /// A fraction in `[0, 1]`.
    Fraction,
    "a number in [0, 1]",
    |v| v >= 0.0 && v <= 1.0
);

bounded!(
    /// A factor in `(0, 1]`: a reduction that never reaches zero.
    Factor,
    "a number in (0, 1]",
    |v| v > 0.0 && v <= 1.0
);

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ranges_and_messages() {
        assert_eq!(Positive::new(2.5).map(Positive::get), Ok(2.5));
        assert_eq!(
            Positive::new(0.0).unwrap_err().to_string(),
            "expected a finite number > 0, found 0"
        );
        assert!(Positive::new(f64::NAN).is_err());
        assert!(Finite::new(f64::INFINITY).is_err());
        assert!(NonNegative::new(0.0).is_ok() && NonNegative::new(-1e-300).is_err());
        assert!(Percent::new(100.0).is_ok() && Percent::new(100.5).is_err());
        assert!(Fraction::new(0.0).is_ok() && Fraction::new(1.01).is_err());
        assert!(Factor::new(1.0).is_ok() && Factor::new(0.0).is_err());
    }

    #[test]
    fn deserialisation_checks_and_serialisation_is_a_plain_number() {
        let p: Positive = serde_json::from_str("3.5").unwrap();
        assert_eq!(serde_json::to_string(&p).unwrap(), "3.5");
        let e = serde_json::from_str::<Positive>("-2")
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("expected a finite number > 0, found -2"),
            "{e}"
        );
    }
}
