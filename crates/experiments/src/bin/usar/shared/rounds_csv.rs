//! `--rounds-csv FILE` of `usar run` and `usar sweep`: the per-round yields written and
//! summarised (`usar_report::rounds_table`).

use std::io::Write;

use anyhow::{Context, Result};
use usar_sweep::atomic::write_atomic;

/// Writes `--rounds-csv` of `cells` (grid cell index, results) to `path` and prints the
/// summary per task of every result (`usar_report::rounds_table`).
///
/// # Errors
/// An I/O error writing the file or the output.
pub fn write_rounds_csv(
    path: &std::path::Path,
    cells: &[(usize, &[usar_sim::mission::TrialResult])],
    out: &mut dyn Write,
) -> Result<()> {
    use usar_report::rounds_table::{rounds_csv, summary_lines, task_rounds};
    // The error names the path; the context names the flag.
    write_atomic(path, &rounds_csv(cells)?).context("--rounds-csv")?;
    let all: Vec<_> = cells.iter().flat_map(|(_, r)| r.iter().cloned()).collect();
    writeln!(
        out,
        "\nper-round yields (rounds with a group; {} trial(s)):",
        all.len()
    )?;
    for line in summary_lines(&task_rounds(&all)) {
        writeln!(out, "  {line}")?;
    }
    writeln!(out, "wrote {}", path.display())?;
    Ok(())
}
