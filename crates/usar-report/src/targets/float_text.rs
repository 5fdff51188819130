//! Serde for numbers that may not be finite (a statistic that is NaN, a loss of +inf): a
//! finite number as a JSON number, the others as the strings `"NaN"`, `"inf"` and `"-inf"`
//! (JSON has no such numbers). Used with `#[serde(with = "float_text")]`, and
//! `float_text::vec` for a list.

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// `x` as text for people and for RON: Rust's shortest round-trip form (`0.0055`, `14`,
/// `inf`), in scientific notation (`1e300`, `1.7e308`, `2.5e-12`) when `|x|` is at least 1e16
/// or below 1e-9 (but not 0), where the plain form runs to hundreds of digits. Reads back as
/// the same `f64`.
pub fn short(x: f64) -> String {
    let a = x.abs();
    if a.is_finite() && (a >= 1e16 || (a > 0.0 && a < 1e-9)) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// A number as written: finite, or one of the three words.
#[derive(Serialize, Deserialize)]
#[serde(untagged)]
enum Text {
    Number(f64),
    Word(String),
}

fn to_text(x: f64) -> Text {
    if x.is_finite() {
        Text::Number(x)
    } else if x.is_nan() {
        Text::Word("NaN".into())
    } else if x > 0.0 {
        Text::Word("inf".into())
    } else {
        Text::Word("-inf".into())
    }
}

fn from_text<E: serde::de::Error>(t: Text) -> Result<f64, E> {
    match t {
        Text::Number(x) => Ok(x),
        Text::Word(w) => match w.as_str() {
            "NaN" => Ok(f64::NAN),
            "inf" => Ok(f64::INFINITY),
            "-inf" => Ok(f64::NEG_INFINITY),
            other => Err(E::custom(format!(
                "expected a number, NaN, inf or -inf, found {other:?}"
            ))),
        },
    }
}

/// Serialises `x` (see the module documentation).
///
/// # Errors
/// The serializer's.
pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
    to_text(*x).serialize(s)
}

/// Reads a number written by [`serialize`].
///
/// # Errors
/// Neither a number nor one of the three words.
pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
    from_text(Text::deserialize(d)?)
}

/// NaN: the serde default of an optional number written only when known
/// (`#[serde(default = "float_text::nan", skip_serializing_if = "float_text::is_nan")]`).
pub fn nan() -> f64 {
    f64::NAN
}

/// Whether `x` is NaN (an optional number not known: not written).
pub fn is_nan(x: &f64) -> bool {
    x.is_nan()
}

/// The same for a list of numbers.
pub mod vec {
    use super::*;

    /// Serialises every number of `xs`.
    ///
    /// # Errors
    /// The serializer's.
    pub fn serialize<S: Serializer>(xs: &[f64], s: S) -> Result<S::Ok, S::Error> {
        xs.iter()
            .map(|&x| to_text(x))
            .collect::<Vec<_>>()
            .serialize(s)
    }

    /// Reads a list written by [`serialize`].
    ///
    /// # Errors
    /// An item that is neither a number nor one of the three words.
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        Vec::<Text>::deserialize(d)?
            .into_iter()
            .map(from_text)
            .collect()
    }
}

#[cfg(test)]
mod tests {
    #[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    struct Row {
        #[serde(with = "super")]
        loss: f64,
        #[serde(with = "super::vec")]
        stats: Vec<f64>,
    }

    #[test]
    fn non_finite_numbers_survive_json() {
        let row = Row {
            loss: f64::INFINITY,
            stats: vec![0.1 + 0.2, f64::NAN, f64::NEG_INFINITY, 1e-300],
        };
        let json = serde_json::to_string(&row).unwrap();
        assert_eq!(
            json,
            r#"{"loss":"inf","stats":[0.30000000000000004,"NaN","-inf",1e-300]}"#
        );
        let back: Row = serde_json::from_str(&json).unwrap();
        assert_eq!(back.loss, f64::INFINITY);
        assert_eq!(back.stats[0], 0.1 + 0.2);
        assert!(back.stats[1].is_nan());
        assert_eq!(back.stats[2..], [f64::NEG_INFINITY, 1e-300]);
        let e = serde_json::from_str::<Row>(r#"{"loss":"big","stats":[]}"#).unwrap_err();
        assert!(e.to_string().contains("found \"big\""), "{e}");
    }

    #[test]
    fn short_text_reads_back_and_stays_short() {
        for (x, text) in [
            (0.0055, "0.0055"),
            (14.0, "14"),
            (1e300, "1e300"),
            (-1.7e308, "-1.7e308"),
            (2.5e-12, "2.5e-12"),
            (0.0, "0"),
            (1e15, "1000000000000000"),
        ] {
            assert_eq!(super::short(x), text);
            assert_eq!(text.parse::<f64>().unwrap(), x);
        }
    }
}
