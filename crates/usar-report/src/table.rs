//! Plain-text number and matrix formatting shared by the commands.

use std::fmt::Write as _;

use crate::stats::Summary;

/// The widest padding a table column gets: `u16::MAX` characters. Rust's formatter panics
/// ("Formatting argument out of range") on a width above it, and a name or label may be
/// longer (a scenario's task or kind name, a `--vary` value).
pub const MAX_COLUMN_WIDTH: usize = u16::MAX as usize;

/// A column's padding width for cells up to `widest` characters wide, capped at
/// [`MAX_COLUMN_WIDTH`] (a longer cell is printed whole, unpadded, and its column no longer
/// lines up). Use it for every `{:w$}` width that comes from input.
pub fn column_width(widest: usize) -> usize {
    widest.min(MAX_COLUMN_WIDTH)
}

/// Formats `x` with 6 significant digits below `1e6` (`0.00372546`, `0.000504443`,
/// `12.3457`); from `1e6` to `1e9` as a whole number (up to 9 digits); `0` for zero, `inf`
/// for infinity; scientific notation below `1e-6` or from `1e9` up.
pub fn sig6(x: f64) -> String {
    if x == 0.0 {
        return "0".to_string();
    }
    if !x.is_finite() {
        return if x.is_nan() {
            "NaN".into()
        } else if x > 0.0 {
            "inf".into()
        } else {
            "-inf".into()
        };
    }
    let magnitude = x.abs().log10().floor() as i32;
    if !(-6..9).contains(&magnitude) {
        return format!("{x:.5e}");
    }
    let decimals = (5 - magnitude).max(0) as usize;
    format!("{x:.decimals$}")
}

/// Formats a positive rate or size `x` for a one-line summary with 3 significant digits, in
/// fixed notation without trailing zeros (`2.94`, `0.704`, `10`, `1250`: whole numbers keep
/// all their digits) from `1e-3` to below `1e6`, in scientific notation outside (`1.67e-5`,
/// `1.20e-5`); `0`, `inf`, `NaN` as [`sig6`] writes them.
pub fn sig3(x: f64) -> String {
    if x == 0.0 || !x.is_finite() {
        return sig6(x);
    }
    let magnitude = x.abs().log10().floor() as i32;
    if !(-3..6).contains(&magnitude) {
        return format!("{x:.2e}");
    }
    let decimals = (2 - magnitude).max(0) as usize;
    let s = format!("{x:.decimals$}");
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// Renders a labelled matrix. `values[r][c]` is shown with [`sig6`]; a cell gets a `*` when
/// `marked(r, c)` is true. `row_labels.len() == values.len()`,
/// `col_labels.len() == values[r].len()`.
pub fn matrix(
    row_labels: &[String],
    col_labels: &[String],
    values: &[Vec<f64>],
    marked: impl Fn(usize, usize) -> bool,
) -> String {
    let cells: Vec<Vec<String>> = values
        .iter()
        .enumerate()
        .map(|(r, row)| {
            row.iter()
                .enumerate()
                .map(|(c, v)| format!("{}{}", sig6(*v), if marked(r, c) { "*" } else { " " }))
                .collect()
        })
        .collect();
    let label_w = column_width(row_labels.iter().map(String::len).max().unwrap_or(0));
    let col_w = column_width(
        cells
            .iter()
            .flatten()
            .map(String::len)
            .chain(col_labels.iter().map(|l| l.len() + 1))
            .max()
            .unwrap_or(1),
    );
    let mut s = format!("  {:label_w$}", "");
    for l in col_labels {
        let _ = write!(s, "  {:>w$}", format!("{l} "), w = col_w);
    }
    s.push('\n');
    for (label, row) in row_labels.iter().zip(&cells) {
        let _ = write!(s, "  {label:label_w$}");
        for cell in row {
            let _ = write!(s, "  {cell:>col_w$}");
        }
        s.push('\n');
    }
    s
}

/// Indices of the minimum of `row` ignoring `skip` (e.g. the diagonal); empty if nothing
/// remains. All tied minima are returned.
pub fn row_minima(row: &[f64], skip: Option<usize>) -> Vec<usize> {
    let min = row
        .iter()
        .enumerate()
        .filter(|(c, _)| Some(*c) != skip)
        .map(|(_, v)| *v)
        .fold(f64::INFINITY, f64::min);
    row.iter()
        .enumerate()
        .filter(|(c, v)| Some(*c) != skip && **v == min)
        .map(|(c, _)| c)
        .collect()
}

/// Formats a number for tables: 3 significant decimals for small values, fewer for large.
pub fn num(x: f64) -> String {
    if !x.is_finite() {
        return "n/a".to_string();
    }
    let a = x.abs();
    if a >= 100.0 {
        format!("{x:.1}")
    } else if a >= 1.0 {
        format!("{x:.2}")
    } else if a >= 0.01 || a == 0.0 {
        format!("{x:.3}")
    } else {
        format!("{x:.2e}")
    }
}

/// Formats a p-value for reading: three decimals (`0.044`), `< 0.001` below that (also for an
/// exact 0, which a degenerate test can give; it was printed `0.0e0`), `n/a` when undefined.
pub fn pval(p: f64) -> String {
    if !p.is_finite() {
        "n/a".to_string()
    } else if p < 0.001 {
        "< 0.001".to_string()
    } else {
        format!("{p:.3}")
    }
}

/// `mean ± sd` of a summary, the mean alone when the sd is undefined (n = 1), `n/a` for no
/// values.
pub fn mean_sd(s: &Summary) -> String {
    if s.n == 0 {
        "n/a".to_string()
    } else if s.sd.is_finite() {
        format!("{} ± {}", num(s.mean), num(s.sd))
    } else {
        num(s.mean)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_matrix_prints_labels_longer_than_the_widest_padding_whole() {
        let long: String = "r".repeat(MAX_COLUMN_WIDTH + 1);
        let labels = [long.clone(), "b".to_string()];
        let text = matrix(
            &labels,
            &labels,
            &[vec![0.0, 1.0], vec![2.0, 3.0]],
            |_, _| false,
        );
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "a header and two rows");
        assert!(
            lines[1].starts_with(&format!("  {long}  ")),
            "the row label whole"
        );
        assert!(lines[2].starts_with("  b "), "the short label padded");
        assert_eq!(column_width(7), 7);
        assert_eq!(column_width(usize::MAX), MAX_COLUMN_WIDTH);
    }

    #[test]
    fn p_values_read_as_three_decimals_or_below_a_thousandth() {
        assert_eq!(pval(0.0), "< 0.001");
        assert_eq!(pval(1.1e-4), "< 0.001");
        assert_eq!(pval(0.001), "0.001");
        assert_eq!(pval(0.0443), "0.044");
        assert_eq!(pval(1.0), "1.000");
        assert_eq!(pval(f64::NAN), "n/a");
    }

    #[test]
    fn six_significant_digits() {
        assert_eq!(sig6(0.003_725_460_66), "0.00372546");
        assert_eq!(sig6(0.000_504_442_6), "0.000504443");
        assert_eq!(sig6(12.345_678), "12.3457");
        assert_eq!(sig6(0.0), "0");
        assert_eq!(sig6(f64::INFINITY), "inf");
        assert_eq!(sig6(1.5e-9), "1.50000e-9");
    }

    #[test]
    fn three_significant_digits_without_trailing_zeros() {
        assert_eq!(sig3(1.0 / 0.34), "2.94");
        assert_eq!(sig3(1.0 / 1.42), "0.704");
        assert_eq!(sig3(10.0), "10");
        assert_eq!(sig3(50.000_000_000_001), "50");
        assert_eq!(sig3(1250.0), "1250");
        assert_eq!(sig3(1.0 / 60_000.0), "1.67e-5");
        assert_eq!(sig3(0.0), "0");
    }

    #[test]
    fn minima_skip_the_diagonal() {
        assert_eq!(row_minima(&[0.0, 2.0, 1.0], Some(0)), vec![2]);
        assert_eq!(row_minima(&[0.0], Some(0)), Vec::<usize>::new());
    }
}
