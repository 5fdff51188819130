//! A targets or claims file, checked against the scenario's tasks as soon as it is read, so
//! that a metric about a task the scenario lacks is blamed on the setting that named the file,
//! as `usar sweep` blames it: `--targets: t.ron:6:31: targets[2].statistic: ...; scenario:
//! scenarios/paper.ron`.

use anyhow::{Context, Result};
use usar_sim::scenario::ScenarioSpec;

/// The task names of `base` (read from `origin`), or `None` when it does not validate: the
/// command's own check reports that, and [`check_file_tasks`] then checks nothing.
pub fn scenario_tasks(base: &ScenarioSpec, origin: &str) -> Option<Vec<String>> {
    base.validate(origin).ok().map(|s| s.task_names())
}

/// Runs `check` (a file's task check against the scenario, such as
/// `Targets::check_tasks_of_scenario`, whose error names the scenario) on `tasks`, the task
/// names of the scenario ([`scenario_tasks`]; nothing is checked when `None`); its error gets
/// the context `setting` (the flag, such as `--targets`, or where the scenario names the
/// file).
///
/// # Errors
/// The error of `check`.
pub fn check_file_tasks<E: std::error::Error + Send + Sync + 'static>(
    setting: &str,
    tasks: Option<&[String]>,
    check: impl FnOnce(&[String]) -> Result<(), E>,
) -> Result<()> {
    let Some(tasks) = tasks else {
        return Ok(());
    };
    check(tasks).with_context(|| setting.to_owned())
}
