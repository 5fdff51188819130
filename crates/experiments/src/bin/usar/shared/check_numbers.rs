//! How `usar check`'s summary writes numbers: positions and distances with as many decimals
//! as the arena's scale needs, table columns rounded short.

use usar_report::scenario_summary::ScenarioSummary;

/// Decimals of the positions and distances the summary prints: 1 in an arena whose shorter
/// side is 10 m or more, one more per factor of ten below that (3 for a 0.5 m arena, 4 for
/// 8 cm), so that points a tenth of the arena's scale apart never print alike.
pub fn decimals(s: &ScenarioSummary) -> usize {
    decimals_for_side(s.arena.width_m.min(s.arena.height_m))
}

/// [`decimals`] of an arena whose shorter side is `side_m` metres (> 0).
fn decimals_for_side(side_m: f64) -> usize {
    if side_m >= 10.0 {
        1
    } else {
        1 + (10.0 / side_m).log10().ceil().clamp(0.0, 15.0) as usize
    }
}

/// `v` metres with the summary's [`decimals`].
pub fn metres(v: f64, decimals: usize) -> String {
    format!("{v:.decimals$}")
}

/// `lo..hi` metres with `decimals`.
pub fn metres_range((lo, hi): (f64, f64), decimals: usize) -> String {
    format!("{}..{}", metres(lo, decimals), metres(hi, decimals))
}

/// `x` rounded to 4 decimals, as short as Rust writes it (`2.5`, `1.6667`), for table columns.
pub fn short(x: f64) -> String {
    ((x * 1e4).round() / 1e4).to_string()
}

#[cfg(test)]
mod tests {
    use super::{decimals_for_side, metres};

    #[test]
    fn small_arenas_print_positions_with_more_decimals() {
        assert_eq!(decimals_for_side(80.0), 1);
        assert_eq!(decimals_for_side(10.0), 1);
        assert_eq!(decimals_for_side(9.9), 2);
        assert_eq!(decimals_for_side(1.0), 2);
        assert_eq!(decimals_for_side(0.5), 3);
        assert_eq!(decimals_for_side(0.08), 4);
        // Millimetre positions in an 8 cm arena print apart (they printed (0.0, 0.0)).
        let d = decimals_for_side(0.08);
        assert_eq!(metres(0.002, d), "0.0020");
        assert_ne!(metres(0.002, d), metres(0.003, d));
        assert_eq!(metres(32.5, decimals_for_side(80.0)), "32.5");
    }
}
