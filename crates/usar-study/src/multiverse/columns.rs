//! The fixed columns of `multiverse.csv` (long form, one row per universe, per universe x
//! method x metric, and per universe x claim; `docs/multiverse.md` documents each). Between
//! `universe` and `admissible` come one column per axis (named by the axis), between `loss`
//! and `row` one per free field (named by its path): so no axis may be named like a fixed
//! column ([`is_fixed_column`]), which the axes file's checks refuse.

/// The columns before the axes: the universe's folder name (`u007`).
pub const LEADING: [&str; 1] = ["universe"];

/// The columns between the axes and the free fields.
pub const MIDDLE: [&str; 2] = ["admissible", "loss"];

/// The columns after the free fields, in order.
pub const TRAILING: [&str; 15] = [
    "status", "row", "method", "metric", "n", "mean", "sd", "claim", "verdict", "effect", "ci_low",
    "ci_high", "p", "rival", "message",
];

/// Whether `name` is one of the fixed columns (compared as written, and trimmed).
pub fn is_fixed_column(name: &str) -> bool {
    let name = name.trim();
    LEADING
        .iter()
        .chain(&MIDDLE)
        .chain(&TRAILING)
        .any(|c| *c == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fixed_columns_are_recognised_and_others_are_not() {
        for c in ["universe", "loss", "verdict", " p ", "message"] {
            assert!(is_fixed_column(c), "{c}");
        }
        for c in ["hp effect", "Loss", "mission.pickup_s", ""] {
            assert!(!is_fixed_column(c), "{c}");
        }
    }
}
