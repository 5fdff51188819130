//! Where a scenario file sets a field, as an error's context: `paper.ron:208:13:
//! report.claims`, so a file the scenario names (its claims, its targets) is blamed on the
//! scenario's line and not on a flag that was not given.

use std::path::Path;

use usar_sim::scenario::{field_line_col, path_text, read_source};

/// `path:line:col: field` for the scenario file at `scenario_path` and a field path such as
/// `report.claims`: where the file writes the field (or its nearest ancestor it writes), as
/// `usar check` places its errors; `path: field` when the file cannot be read again.
pub fn scenario_field(scenario_path: &Path, field: &str) -> String {
    let at = read_source(scenario_path)
        .ok()
        .and_then(|src| field_line_col(&src, field));
    match at {
        Some((line, col)) => format!("{}:{line}:{col}: {field}", path_text(scenario_path)),
        None => format!("{}: {field}", path_text(scenario_path)),
    }
}
