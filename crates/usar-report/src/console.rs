//! The terminal summary of `usar sweep`, rendered from the sweep's analysis: what ran, a table
//! of the main metrics per method (per cell and chosen metric for a grid), when asked
//! ([`crate::calibration::ReportOptions`]) how many pooled statistics lie in their target
//! bands and the claims (without a grid; a grid has them per cell in `grid.md`), and
//! the files written.

use std::io::Write;
use std::path::PathBuf;

use crate::error::Result;

use crate::analysis::{Analysis, CellAnalysis};
use crate::claims::{ClaimCheck, Test};
use crate::table::{column_width, mean_sd, pval, sig3};
use usar_sweep::data::config::SweepConfig;
use usar_sweep::data::outcome::{JournalUse, SweepOutcome};
use usar_sweep::metrics::{Metric, Quantity, Scope};

/// Columns of the one-cell table: rescuees in total and per task, then the energy and HP cost
/// per rescuee of the hardest task; each with its heading.
fn columns(a: &CellAnalysis) -> Vec<(Metric, String)> {
    let mut out = vec![(Metric::new(Quantity::Rescued, Scope::Total), "total".into())];
    out.extend(
        a.tasks
            .iter()
            .enumerate()
            .map(|(t, name)| (Metric::new(Quantity::Rescued, Scope::Task(t)), name.clone())),
    );
    if let Some(&hardest) = a.hardest_first.first() {
        let name = &a.tasks[hardest];
        out.push((
            Metric::new(Quantity::EnergyPerRescuee, Scope::Task(hardest)),
            format!("eng/{name}"),
        ));
        out.push((
            Metric::new(Quantity::HpPerRescuee, Scope::Task(hardest)),
            format!("hp/{name}"),
        ));
    }
    out
}

/// Writes the summary of a finished sweep to `out`.
///
/// # Errors
/// An I/O error writing to `out`.
pub fn print_sweep(
    out: &mut dyn Write,
    cfg: &SweepConfig,
    o: &SweepOutcome,
    analysis: &Analysis,
    grid_metrics: &[Metric],
    files: &[PathBuf],
) -> Result<()> {
    let h = &o.header;
    if o.journal == JournalUse::Reused {
        writeln!(
            out,
            "{} holds this very sweep (same parameters): continuing it as with --resume",
            usar_sweep::journal::Journal::path_in(&cfg.out_dir).display()
        )?;
    }
    let mut durations: Vec<f64> = cfg
        .cell_scenarios()
        .into_iter()
        .map(|s| cfg.simulated_length_of(s))
        .collect();
    durations.dedup();
    let length = match (durations.as_slice(), cfg.duration_s) {
        ([d], _) => format!("{d} s"),
        (_, Some(d)) => format!("--duration {d} s in whole steps of each cell's sim.dt_s"),
        _ => "each cell's mission.duration_s".to_string(),
    };
    let grid = match &cfg.grid {
        Some(g) => format!(
            " over a grid of {} cells ({})",
            g.cells.len(),
            h.grid.fields.join(" x ")
        ),
        None => String::new(),
    };
    writeln!(
        out,
        "sweep {}{grid}: {} x {} trials x {length}, base seed {}",
        h.scenario,
        h.methods.join(","),
        h.trials,
        h.base_seed
    )?;
    ran_line(out, o)?;
    match &cfg.grid {
        None => {
            method_table(out, &analysis.cells[0])?;
            pooled(out, analysis)?;
            if let Some(c) = &analysis.report.claims {
                claims(out, &analysis.cells[0], c.origin())?;
            }
            writeln!(out, "\nwrote:")?;
            for f in files {
                writeln!(out, "  {}", f.display())?;
            }
        }
        Some(g) => {
            for m in grid_metrics {
                grid_table(out, o, analysis, *m)?;
            }
            pooled(out, analysis)?;
            writeln!(out, "\nwrote:")?;
            for f in files
                .iter()
                .filter(|f| f.parent() == Some(cfg.out_dir.as_path()))
            {
                writeln!(out, "  {}", f.display())?;
            }
            writeln!(
                out,
                "  and {} cell folders in {} ({} .. {}), each with trials.csv, summary.csv, \
                 report.md, figures and scenario.ron",
                g.cells.len(),
                cfg.out_dir.display(),
                g.cells.first().map_or("", |c| c.dir.as_str()),
                g.cells.last().map_or("", |c| c.dir.as_str())
            )?;
        }
    }
    Ok(())
}

/// A speed (simulated seconds per wall-clock second) for the terminal: whole numbers from 10
/// up (`1153`), three significant digits below ([`sig3`]: `2.47`, `0.442`, `1.20e-5`), so a
/// run slower than real time does not print as `0`.
pub fn speed(sim_s_per_wall_s: f64) -> String {
    let x = sim_s_per_wall_s;
    if !x.is_finite() || x >= 10.0 {
        format!("{x:.0}")
    } else {
        sig3(x)
    }
}

fn ran_line(out: &mut dyn Write, o: &SweepOutcome) -> Result<()> {
    if o.ran == 0 {
        writeln!(out, "all {} trials came from the journal", o.reused)?;
        return Ok(());
    }
    let rate = o.simulated_s() / o.wall_s.max(1e-9);
    writeln!(
        out,
        "ran {} trials in {:.2} s on {} thread(s): {} sim-s per wall-s ({} per thread){}",
        o.ran,
        o.wall_s,
        o.threads,
        speed(rate),
        speed(rate / o.threads as f64),
        if o.reused > 0 {
            format!("; {} from the journal", o.reused)
        } else {
            String::new()
        }
    )?;
    Ok(())
}

fn method_table(out: &mut dyn Write, a: &CellAnalysis) -> Result<()> {
    let columns = columns(a);
    write!(out, "\n{:<8}", "method")?;
    for (_, heading) in &columns {
        write!(out, " {heading:>16}")?;
    }
    writeln!(out)?;
    for (i, m) in a.methods.iter().enumerate() {
        write!(out, "{:<8}", m.method)?;
        for (metric, _) in &columns {
            let s = a.summary(i, *metric).unwrap_or_default();
            write!(out, " {:>16}", mean_sd(&s))?;
        }
        writeln!(out)?;
    }
    Ok(())
}

/// With targets: per cell, how many pooled statistics lie in their bands, and without a
/// grid the ones outside with their value and target (`report.md` and `grid.md` have the
/// tables). Nothing without targets.
fn pooled(out: &mut dyn Write, analysis: &Analysis) -> Result<()> {
    let Some(targets) = &analysis.report.targets else {
        return Ok(());
    };
    let count = |a: &CellAnalysis| {
        let held = a.pooled.iter().filter(|(t, x)| t.holds(*x)).count();
        let undefined = a.pooled.iter().filter(|(_, x)| !x.is_finite()).count();
        let na = if undefined > 0 {
            format!(", {undefined} n/a")
        } else {
            String::new()
        };
        format!("{held} of {} in their bands{na}", a.pooled.len())
    };
    if let [a] = analysis.cells.as_slice() {
        let outside: Vec<String> = a
            .pooled
            .iter()
            .filter(|(t, x)| x.is_finite() && !t.holds(*x))
            .map(|(t, x)| format!("{} {} ({} {})", t.name, sig3(*x), t.value, t.band))
            .collect();
        let out_text = if outside.is_empty() {
            String::new()
        } else {
            format!("; out: {}", outside.join(", "))
        };
        writeln!(
            out,
            "\npooled statistics against {}: {}{out_text}",
            targets.origin(),
            count(a)
        )?;
        return Ok(());
    }
    let cells: Vec<String> = analysis
        .cells
        .iter()
        .enumerate()
        .map(|(i, a)| format!("cell {i}: {}", count(a)))
        .collect();
    writeln!(
        out,
        "\npooled statistics against {} (grid.md): {}",
        targets.origin(),
        cells.join("; ")
    )?;
    Ok(())
}

fn claims(out: &mut dyn Write, a: &CellAnalysis, origin: &str) -> Result<()> {
    writeln!(out, "\nclaims of {origin}:")?;
    for chk in &a.claims {
        match &chk.reason {
            None => writeln!(
                out,
                "  ({}) {}: {} ({}, {})",
                chk.claim.id,
                chk.claim.sentence,
                chk.verdict.words(),
                chk.test_run_words(),
                max_p_text(chk)
            )?,
            Some(why) => writeln!(
                out,
                "  ({}) {}: not tested ({why})",
                chk.claim.id, chk.claim.sentence
            )?,
        }
    }
    Ok(())
}

/// One chosen metric of a grid: a row per cell (index and values), a column per method.
fn grid_table(out: &mut dyn Write, o: &SweepOutcome, analysis: &Analysis, m: Metric) -> Result<()> {
    let h = &o.header;
    let digits = h
        .grid
        .cells
        .len()
        .saturating_sub(1)
        .to_string()
        .len()
        .max(2);
    let labels: Vec<String> = h
        .grid
        .cells
        .iter()
        .enumerate()
        .map(|(i, c)| format!("c{i:0digits$} {}", c.values.join(", ")))
        .collect();
    let w = column_width(labels.iter().map(String::len).max().unwrap_or(4).max(4));
    let tasks = analysis.cells.first().map_or(&[][..], |a| &a.tasks[..]);
    writeln!(out, "\n{} ({}), mean ± sd:", m.label(tasks), m.name(tasks))?;
    write!(out, "{:<w$}", "cell")?;
    for method in &h.methods {
        write!(out, " {method:>16}")?;
    }
    writeln!(out)?;
    for (label, a) in labels.iter().zip(&analysis.cells) {
        write!(out, "{label:<w$}")?;
        for i in 0..a.methods.len() {
            let s = a.summary(i, m).unwrap_or_default();
            write!(out, " {:>16}", mean_sd(&s))?;
        }
        writeln!(out)?;
    }
    Ok(())
}

/// `max p = ...` of a claim (its test's, after its correction), or why there is none: with
/// fewer than two trials of a method, Welch's test has no variance to work with (`max p = n/a`
/// said nothing of the cause).
fn max_p_text(chk: &ClaimCheck) -> String {
    let p = chk.worst_p();
    let fewest = chk
        .comparisons
        .iter()
        .map(|c| c.other_summary.n)
        .chain([chk.subject_summary.n])
        .min()
        .unwrap_or(0);
    if p.is_nan() && fewest < 2 && chk.claim.test == Test::Welch {
        "no p: Welch's test needs at least 2 trials per method".to_string()
    } else if p.is_nan() {
        format!(
            "no p: the {} test is undefined here",
            chk.claim.test.words()
        )
    } else {
        format!("max p = {}", pval(p))
    }
}

#[cfg(test)]
mod tests {
    #[test]
    fn speeds_below_one_are_not_zero() {
        assert_eq!(super::speed(1153.4), "1153");
        assert_eq!(super::speed(2.4661), "2.47");
        assert_eq!(super::speed(0.44166), "0.442");
        assert_eq!(super::speed(1.2e-5), "1.20e-5");
    }
}
