//! `usar check`'s short summary of a scenario with many tasks (more than `TASKS_TABLE_MAX` of
//! `shared/table_limits.rs`, without `--tasks`): per kind its quota range over the tasks instead of
//! a column per task, the tasks summarised with their first and last few rows, the starts'
//! distance to the nearest and to any goal instead of a column per task, and radiation zones
//! and rest stations as ranges; every line stays short.

use std::collections::BTreeMap;
use std::io::Write;

use anyhow::Result;

use usar_report::scenario_summary::{ScenarioSummary, TaskSummary};
use usar_report::table::column_width;

use super::check_numbers::{decimals, metres, metres_range, short};

/// Tasks listed from the start and from the end of the file in the short summary (the rest
/// are counted; `--tasks` lists every one).
pub const TASK_ROWS_SHOWN: usize = 3;

/// Lists of radiation zones' dose factors or of rest stations longer than this are given as
/// ranges in the short summary.
pub const LIST_MAX: usize = 6;

/// Width at which the short summary wraps the scenario's description (the description alone
/// runs longer than a terminal).
pub const WRAP_AT: usize = 150;

/// `text` cut at spaces into lines of at most [`WRAP_AT`] characters (a longer word stays
/// whole), every line after the first indented by two spaces.
pub fn wrapped(text: &str) -> String {
    let mut lines: Vec<String> = vec![String::new()];
    for word in text.split(' ') {
        let line = lines.last_mut().expect("one line at least");
        if !line.trim().is_empty() && line.chars().count() + 1 + word.chars().count() > WRAP_AT {
            lines.push(format!("  {word}"));
        } else if line.is_empty() {
            line.push_str(word);
        } else {
            line.push(' ');
            line.push_str(word);
        }
    }
    lines.join("\n")
}

/// `lo` when `lo == hi`, else `lo..hi`.
fn count_range(values: impl Iterator<Item = usize>) -> String {
    let (lo, hi) = values.fold((usize::MAX, 0), |(lo, hi), v| (lo.min(v), hi.max(v)));
    match (lo, hi) {
        (usize::MAX, _) => "-".to_string(),
        (lo, hi) if lo == hi => lo.to_string(),
        (lo, hi) => format!("{lo}..{hi}"),
    }
}

/// The least and greatest of `values` (None without any).
fn extent(values: impl Iterator<Item = f64>) -> Option<(f64, f64)> {
    values.fold(None, |acc, v| match acc {
        None => Some((v, v)),
        Some((lo, hi)) => Some((lo.min(v), hi.max(v))),
    })
}

/// `rows` (the first one the header) as lines of columns separated by two spaces, each as
/// wide as its widest cell: the first `left` columns (text) left-aligned, the others
/// right-aligned.
fn table_lines(rows: &[Vec<String>], left: usize) -> Vec<String> {
    let columns = rows.iter().map(Vec::len).max().unwrap_or(0);
    let widths: Vec<usize> = (0..columns)
        .map(|c| {
            rows.iter()
                .filter_map(|r| r.get(c))
                .map(|cell| column_width(cell.chars().count()))
                .max()
                .unwrap_or(0)
        })
        .collect();
    rows.iter()
        .map(|row| {
            let cells: Vec<String> = row
                .iter()
                .zip(&widths)
                .enumerate()
                .map(|(c, (cell, &w))| {
                    if c < left {
                        format!("{cell:<w$}")
                    } else {
                        format!("{cell:>w$}")
                    }
                })
                .collect();
            cells.join("  ").trim_end().to_string()
        })
        .collect()
}

/// Writes [`table_lines`] of `rows`.
fn table(rows: &[Vec<String>], left: usize, out: &mut dyn Write) -> Result<()> {
    for line in table_lines(rows, left) {
        writeln!(out, "{line}")?;
    }
    Ok(())
}

/// The kinds table with, in place of a quota column per task, each kind's quota per task (one
/// number when every task has the same, else its range) and the tasks with a non-zero quota
/// of the kind.
pub fn kinds_table(s: &ScenarioSummary, out: &mut dyn Write) -> Result<()> {
    let mut rows = vec![
        [
            "kind",
            "role",
            "moves",
            "count",
            "quota per task",
            "tasks with quota",
            "speed",
            "sense",
            "observe",
            "radius",
            "cap",
            "res",
        ]
        .map(String::from)
        .to_vec(),
    ];
    for k in &s.kinds {
        rows.push(vec![
            k.name.clone(),
            k.role.clone(),
            k.locomotion.to_string(),
            k.count.to_string(),
            count_range(k.quota.iter().map(|(_, q)| *q)),
            format!(
                "{} of {}",
                k.quota.iter().filter(|(_, q)| *q > 0).count(),
                k.quota.len()
            ),
            short(k.max_speed_m_per_s),
            short(k.sensing_range_m),
            short(k.observing_range_m),
            short(k.body_radius_m),
            k.carrying_capacity.to_string(),
            k.rescuing_resources.to_string(),
        ]);
    }
    writeln!(out)?;
    table(&rows, 3, out)?;
    writeln!(
        out,
        "(quota per task: robots of the kind each task asks for, one number when all tasks ask \
         the same; speed m/s; ranges and radius m)"
    )?;
    Ok(())
}

/// One task's row: name, difficulty, rank from the hardest, rescuees, search area, goal,
/// drop-off and the robots' distances from their starts to its goal.
fn task_row(s: &ScenarioSummary, task: &TaskSummary) -> Vec<String> {
    let m = |v: f64| metres(v, decimals(s));
    let ((ax0, ay0), (ax1, ay1)) = task.search_area_m;
    let (gx, gy) = task.goal_m;
    let ((dx, dy), dr) = task.drop_off;
    let (lo, hi, mean) = task.start_to_goal_m;
    vec![
        task.name.clone(),
        task.difficulty.to_string(),
        format!("{} of {}", task.rank + 1, s.tasks.len()),
        task.rescuees.to_string(),
        format!("[{}, {}]-[{}, {}]", m(ax0), m(ay0), m(ax1), m(ay1)),
        format!("({}, {})", m(gx), m(gy)),
        format!("({}, {}) r {dr}", m(dx), m(dy)),
        format!("{}-{} (mean {})", m(lo), m(hi), m(mean)),
    ]
}

/// The tasks in a few lines: how many, of which difficulties, their rescuees and the range of
/// start-to-goal distances over all of them, then the first and last [`TASK_ROWS_SHOWN`] as
/// rows of a table and how to list them all.
pub fn tasks_summary(s: &ScenarioSummary, out: &mut dyn Write) -> Result<()> {
    let d = decimals(s);
    let mut by_difficulty: BTreeMap<u32, usize> = BTreeMap::new();
    for t in &s.tasks {
        *by_difficulty.entry(t.difficulty).or_default() += 1;
    }
    let difficulties: Vec<String> = by_difficulty
        .iter()
        .rev()
        .map(|(difficulty, n)| format!("{difficulty} x{n}"))
        .collect();
    let rescuees: usize = s.tasks.iter().map(|t| t.rescuees).sum();
    writeln!(
        out,
        "\n{} tasks; difficulty (hardest first) {}; rescuees per task {} ({rescuees} in all)",
        s.tasks.len(),
        difficulties.join(", "),
        count_range(s.tasks.iter().map(|t| t.rescuees)),
    )?;
    let reached: Vec<&TaskSummary> = s
        .tasks
        .iter()
        .filter(|t| t.start_to_goal_m.0.is_finite())
        .collect();
    let nearest = extent(reached.iter().map(|t| t.start_to_goal_m.0));
    let farthest = extent(reached.iter().map(|t| t.start_to_goal_m.1));
    if let (Some((lo, _)), Some((_, hi))) = (nearest, farthest) {
        writeln!(
            out,
            "start->goal over all tasks {}-{} m (each task's nearest start {} m, its farthest {} m)",
            metres(lo, d),
            metres(hi, d),
            metres_range(nearest.expect("some"), d),
            metres_range(farthest.expect("some"), d),
        )?;
    }
    let header = [
        "task",
        "difficulty",
        "from the hardest",
        "rescuees",
        "search area (m)",
        "goal (m)",
        "drop-off (m)",
        "start->goal (m)",
    ]
    .map(String::from)
    .to_vec();
    let n = s.tasks.len();
    let (head, tail) = if n > 2 * TASK_ROWS_SHOWN {
        (TASK_ROWS_SHOWN, n - TASK_ROWS_SHOWN)
    } else {
        (n, n)
    };
    let mut rows = vec![header];
    rows.extend(s.tasks[..head].iter().map(|t| task_row(s, t)));
    rows.extend(s.tasks[tail..].iter().map(|t| task_row(s, t)));
    let lines = table_lines(&rows, 1);
    for line in &lines[..=head] {
        writeln!(out, "{line}")?;
    }
    if tail > head {
        writeln!(
            out,
            "... {} more tasks (every task's line: --tasks)",
            tail - head
        )?;
    }
    for line in &lines[head + 1..] {
        writeln!(out, "{line}")?;
    }
    Ok(())
}

/// Per kind: the count, the extent of the start positions, and in place of a column per task
/// the range over the kind's robots of the distance from a start to the nearest task's goal
/// and the range over all tasks of the distance from a start to a goal (straight line, m).
pub fn starts_by_kind(s: &ScenarioSummary, out: &mut dyn Write) -> Result<()> {
    let d = decimals(s);
    writeln!(
        out,
        "\nstarts by kind ({} robots; the per-robot table: --robots; per task: --tasks)",
        s.robots.len()
    )?;
    let mut rows = vec![
        [
            "kind",
            "count",
            "x range (m)",
            "y range (m)",
            "->nearest goal (m)",
            "->any goal (m)",
        ]
        .map(String::from)
        .to_vec(),
    ];
    let range = |r: Option<(f64, f64)>| r.map_or_else(|| "-".to_string(), |r| metres_range(r, d));
    for k in &s.starts_by_kind {
        let nearest = extent(
            s.robots
                .iter()
                .filter(|r| r.kind == k.kind)
                .filter_map(|r| {
                    r.distance_to_goal_m
                        .iter()
                        .map(|(_, m)| *m)
                        .reduce(f64::min)
                }),
        );
        let lo = extent(k.to_goal_m.iter().map(|t| t.0)).map(|r| r.0);
        let hi = extent(k.to_goal_m.iter().map(|t| t.1)).map(|r| r.1);
        rows.push(vec![
            k.kind.clone(),
            k.count.to_string(),
            metres_range(k.x_range_m, d),
            metres_range(k.y_range_m, d),
            range(nearest),
            range(lo.zip(hi)),
        ]);
    }
    table(&rows, 1, out)?;
    writeln!(
        out,
        "(->nearest goal: from each robot's start to the nearest task's goal, least and greatest \
         over the kind; ->any goal: over all tasks)"
    )?;
    Ok(())
}

/// `dose factors a, b, c` for up to [`LIST_MAX`] zones, else `dose factors lo..hi`.
pub fn dose_factors(factors: &[f64]) -> String {
    if factors.len() <= LIST_MAX {
        let all: Vec<String> = factors.iter().map(ToString::to_string).collect();
        return format!("dose factors {}", all.join(", "));
    }
    let (lo, hi) = extent(factors.iter().copied()).expect("more than LIST_MAX factors");
    format!("dose factors {lo}..{hi}")
}

/// For more than [`LIST_MAX`] rest stations, `N rest stations (r lo..hi m at x lo..hi m,
/// y lo..hi m)`; None for fewer (listed as usual).
pub fn rest_stations(s: &ScenarioSummary) -> Option<String> {
    let list = &s.rest_stations;
    if list.len() <= LIST_MAX {
        return None;
    }
    let d = decimals(s);
    let r = extent(list.iter().map(|(_, r)| *r))?;
    let x = extent(list.iter().map(|((x, _), _)| *x))?;
    let y = extent(list.iter().map(|((_, y), _)| *y))?;
    let radii = if r.0 == r.1 {
        r.0.to_string()
    } else {
        format!("{}..{}", r.0, r.1)
    };
    Some(format!(
        "{} rest stations (r {radii} m at x {} m, y {} m)",
        list.len(),
        metres_range(x, d),
        metres_range(y, d)
    ))
}

#[cfg(test)]
mod tests {
    use super::{WRAP_AT, count_range, wrapped};

    #[test]
    fn quotas_print_as_one_number_or_a_range() {
        assert_eq!(count_range([625, 625].into_iter()), "625");
        assert_eq!(count_range([417, 416, 417].into_iter()), "416..417");
        assert_eq!(count_range(std::iter::empty()), "-");
    }

    #[test]
    fn a_long_description_wraps_at_spaces() {
        let text = "word ".repeat(100);
        let w = wrapped(text.trim_end());
        assert!(w.lines().count() > 3);
        assert!(w.lines().all(|l| l.len() <= WRAP_AT), "{w}");
        assert!(w.lines().skip(1).all(|l| l.starts_with("  word")), "{w}");
        assert_eq!(w.split_whitespace().count(), 100);
        assert_eq!(wrapped("short line"), "short line");
    }
}
