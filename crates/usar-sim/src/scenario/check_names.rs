//! The rules for names: the scenario's, every kind's and every task's name is one non-blank
//! line of text, and no task name clashes with the tables' columns.
//!
//! The names end up in report tables, CSV headers and console lines, so a line break, a
//! control character or a task named like a column of all tasks (`total`,
//! `per_rescuee`, `per_<task>_rescuee`) would break them.

use super::context::{Ctx, R};
use super::spec::TaskSpec;

/// The name no task may have: the tables name the sum over all tasks `total`
/// (`rescued_total`, `energy_total_pct`, the `total` rows of `summary.csv`), so a task of
/// that name would give two columns of one name.
pub const RESERVED_TASK_NAME: &str = "total";

/// Whose energy per rescuee the tables' columns of a task named `name` would stand for: the
/// columns `energy_<task>_pct` and `hp_<task>_pct` of a task `per_rescuee` are those of all
/// tasks' cost per rescuee (`energy_per_rescuee_pct`), and of a task `per_<other>_rescuee`
/// those of task `other` (`energy_per_<other>_rescuee_pct`). `None` when there is no clash.
pub(crate) fn per_rescuee_clash(name: &str, tasks: &[TaskSpec]) -> Option<String> {
    let inner = name.strip_prefix("per_")?.strip_suffix("rescuee")?;
    if inner.is_empty() {
        return Some("all tasks".into());
    }
    let other = inner.strip_suffix('_')?;
    tasks
        .iter()
        .any(|o| o.name == other)
        .then(|| format!("task {other:?}"))
}

/// Checks `name`, the `what` at `field`: not blank, and one line of text without control
/// characters or the Unicode line and paragraph separators (a line break or tab would break
/// the reports' tables, the CSV headers that carry task names, and the console's lines).
pub(crate) fn check_name(ctx: &Ctx<'_>, field: String, what: &str, name: &str) -> R<()> {
    if name.trim().is_empty() {
        return Err(ctx.err(field, format!("expected a non-empty {what}")));
    }
    let breaks_lines = |c: char| c.is_control() || matches!(c, '\u{2028}' | '\u{2029}');
    if let Some(c) = name.chars().find(|&c| breaks_lines(c)) {
        // At most 60 characters of the name are quoted, so the message stays short.
        let quoted: String = name.chars().take(60).collect();
        let more = if quoted.len() < name.len() { "..." } else { "" };
        let kind = if c.is_control() {
            "the control character"
        } else {
            "the line-breaking character"
        };
        return Err(ctx.err(
            field,
            format!("{what} {quoted:?}{more} holds {kind} {c:?}; a name is one line of text"),
        ));
    }
    Ok(())
}
