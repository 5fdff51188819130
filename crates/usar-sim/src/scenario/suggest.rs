//! The nearest valid name for a misspelt one: "did you mean ...?" after an unknown field,
//! variant or task name.
//!
//! Similarity is the Jaro-Winkler similarity of `strsim` (1 for equal strings, 0 for nothing in
//! common); a valid name is suggested when it is the most similar one and at least
//! [`SUGGEST_SIMILARITY`] similar, as clap suggests subcommands (its threshold is 0.7).
//!
//! # Reference
//! W. E. Winkler, "String Comparator Metrics and Enhanced Decision Rules in the Fellegi-Sunter
//! Model of Record Linkage", Proc. Section on Survey Research Methods, ASA, 1990.

/// Least Jaro-Winkler similarity, in `[0, 1]`, at which a valid name is suggested: 0.8.
pub const SUGGEST_SIMILARITY: f64 = 0.8;

/// The name of `valid` most similar to `found`, if it is at least [`SUGGEST_SIMILARITY`]
/// similar (the first of equally similar ones).
pub fn nearest_name<'a>(found: &str, valid: impl IntoIterator<Item = &'a str>) -> Option<&'a str> {
    let mut best: Option<(&str, f64)> = None;
    for name in valid {
        let score = strsim::jaro_winkler(found, name);
        if score >= SUGGEST_SIMILARITY && best.is_none_or(|(_, b)| score > b) {
            best = Some((name, score));
        }
    }
    best.map(|(name, _)| name)
}

/// `"; did you mean `name`?"` for [`nearest_name`], or nothing.
pub fn did_you_mean<'a>(found: &str, valid: impl IntoIterator<Item = &'a str>) -> String {
    nearest_name(found, valid)
        .map(|n| format!("; did you mean `{n}`?"))
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_typo_gets_the_nearest_name_and_a_stranger_none() {
        let fields = ["max_speed_m_per_s", "sensing_range_m", "observing_range_m"];
        assert_eq!(
            nearest_name("max_sped_m_per_s", fields),
            Some("max_speed_m_per_s")
        );
        assert_eq!(
            nearest_name("observe_range_m", fields),
            Some("observing_range_m")
        );
        assert_eq!(nearest_name("colour", fields), None);
        assert_eq!(did_you_mean("colour", fields), "");
        assert_eq!(
            did_you_mean("sensing_rang_m", fields),
            "; did you mean `sensing_range_m`?"
        );
    }
}
