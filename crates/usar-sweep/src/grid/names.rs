//! Names of the cell folders of a grid: readable and safe on any file system, e.g.
//! `c00_hp_pct_per_step_in_radiation=0.003` or `c05_kinds-0.max_speed_m_per_s=1.5`.
//!
//! A name is `c` + the cell index (zero-padded to the same width for every cell, so folders
//! sort in cell order) + one `_label=value` per varied field. A field's label is the shortest
//! tail of its path that tells it apart from the other varied fields (`max_speed_m_per_s`, or
//! `kinds-0.max_speed_m_per_s` when `kinds[1].max_speed_m_per_s` is varied too); `[i]` is
//! written `-i` and `[*]` `-all`. Labels and values keep ASCII letters, digits, `.`, `+` and
//! `-` (and `_` in labels); any other run of characters becomes one `_`. A name longer than
//! [`MAX_NAME`] characters (many varied fields) is cut there, so it stays within the 255
//! bytes file systems allow; the index alone makes names unique, and each cell's
//! `scenario.ron` and the grid's tables give its values in full.

use crate::vary::{FieldPath, Step};

/// Longest label or value part kept in a folder name, characters.
const MAX_PART: usize = 40;

/// Longest folder name, characters (ASCII, so bytes): below the 255 bytes of a file name on
/// Linux, macOS and Windows file systems, with room for a temporary suffix.
pub const MAX_NAME: usize = 200;

/// One label per path: the shortest tail of its components (a name with its indices) that no
/// other path shares, sanitised.
pub fn field_labels(paths: &[&FieldPath]) -> Vec<String> {
    let comps: Vec<Vec<String>> = paths.iter().map(|p| components(p)).collect();
    let tail = |c: &[String], k: usize| c[c.len().saturating_sub(k)..].join(".");
    comps
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let k = (1..=c.len())
                .find(|&k| {
                    comps
                        .iter()
                        .enumerate()
                        .all(|(j, other)| j == i || tail(other, k) != tail(c, k))
                })
                .unwrap_or(c.len());
            clip(&sanitise(&tail(c, k), true))
        })
        .collect()
}

/// A path's components: each field name followed by its indices (`kinds-0`, `zones-all`).
fn components(p: &FieldPath) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for step in p.steps() {
        match step {
            Step::Field(name) => out.push(name.clone()),
            Step::Index(i) => push_suffix(&mut out, &format!("-{i}")),
            Step::All => push_suffix(&mut out, "-all"),
        }
    }
    out
}

fn push_suffix(out: &mut Vec<String>, suffix: &str) {
    match out.last_mut() {
        Some(last) => last.push_str(suffix),
        None => out.push(suffix.to_string()),
    }
}

/// The folder name of cell `index` of `n_cells`, from the field labels and the cell's values
/// (as written).
pub fn cell_dir(index: usize, n_cells: usize, labels: &[String], values: &[&str]) -> String {
    let width = n_cells.saturating_sub(1).to_string().len().max(2);
    let mut name = format!("c{index:0width$}");
    for (label, value) in labels.iter().zip(values) {
        name.push('_');
        name.push_str(label);
        name.push('=');
        name.push_str(&clip(&sanitise(value, false)));
    }
    if name.len() > MAX_NAME {
        name.truncate(MAX_NAME);
        let kept = name.trim_end_matches(['_', '=', '.']).len();
        name.truncate(kept);
    }
    name
}

/// Keeps `[A-Za-z0-9.+-]` (and `_` when `underscore`); other runs become one `_`; no `_` at
/// either end; `v` if nothing is left.
pub fn sanitise(text: &str, underscore: bool) -> String {
    let mut out = String::new();
    for c in text.chars() {
        let keep =
            c.is_ascii_alphanumeric() || matches!(c, '.' | '+' | '-') || (underscore && c == '_');
        if keep {
            out.push(c);
        } else if !out.ends_with('_') {
            out.push('_');
        }
    }
    let trimmed = out.trim_matches('_');
    if trimmed.is_empty() || trimmed.chars().all(|c| c == '.') {
        "v".to_string()
    } else {
        trimmed.to_string()
    }
}

fn clip(s: &str) -> String {
    s.chars().take(MAX_PART).collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn labels(paths: &[&str]) -> Vec<String> {
        let parsed: Vec<FieldPath> = paths.iter().map(|p| FieldPath::parse(p).unwrap()).collect();
        field_labels(&parsed.iter().collect::<Vec<_>>())
    }

    #[test]
    fn labels_are_the_shortest_distinguishing_tails() {
        assert_eq!(
            labels(&["mission.hp_pct_per_step_in_radiation", "sim.dt_s"]),
            ["hp_pct_per_step_in_radiation", "dt_s"]
        );
        assert_eq!(
            labels(&[
                "kinds[0].max_speed_m_per_s",
                "kinds[1].max_speed_m_per_s",
                "radiation_zones[*].dose_rate_factor"
            ]),
            [
                "kinds-0.max_speed_m_per_s",
                "kinds-1.max_speed_m_per_s",
                "dose_rate_factor"
            ]
        );
        assert_eq!(
            labels(&["tasks.easy.goal_m", "tasks.hard.goal_m"]),
            ["easy.goal_m", "hard.goal_m"]
        );
        assert_eq!(labels(&["tasks.easy.rescuees[2]"]), ["rescuees-2"]);
    }

    #[test]
    fn names_are_padded_and_safe() {
        let l = vec!["goal_m".to_string(), "role".to_string()];
        assert_eq!(
            cell_dir(3, 12, &l, &["(10.0, 50.0)", "\"a/b\""]),
            "c03_goal_m=10.0_50.0_role=a_b"
        );
        assert_eq!(cell_dir(7, 150, &l[..1], &["-5"]), "c007_goal_m=-5");
        assert_eq!(sanitise("Some(3)", false), "Some_3");
        assert_eq!(sanitise("..", false), "v");
        assert_eq!(sanitise("/", false), "v");
        assert_eq!(sanitise("a_b", false), "a_b");
        assert_eq!(clip(&"x".repeat(100)).len(), MAX_PART);
    }

    /// Regression: thirteen varied fields made a name of over 255 bytes, and the sweep failed
    /// with "File name too long (os error 36)".
    #[test]
    fn names_of_many_fields_are_cut_to_a_file_name() {
        let l: Vec<String> = (0..13)
            .map(|i| format!("field_number_{i:02}_with_a_long_name"))
            .collect();
        let values = ["0.5"; 13];
        let name = cell_dir(1, 2, &l, &values);
        assert!(name.len() <= MAX_NAME, "{} characters", name.len());
        assert!(
            name.starts_with("c01_field_number_00_with_a_long_name=0.5_"),
            "{name}"
        );
        assert!(!name.ends_with(['_', '=', '.']), "{name}");
        // Shorter names are as before.
        assert_eq!(cell_dir(1, 2, &l[..2], &values[..2]).len(), 4 + 2 * 36 + 1);
    }
}
