//! A targets or claims file, checked against the scenario's tasks as soon as it is read, so
//! that a metric about a task the scenario lacks is blamed on the setting that named the file,
//! as `usar sweep` blames it: `--targets: t.ron:6:31: targets[2].statistic: ...; scenario:
//! scenarios/paper.ron`.

use std::fmt::Display;

use anyhow::{Context, Result, anyhow};
use usar_sim::scenario::ScenarioSpec;

/// Runs `check` (a file's task check, such as `Targets::check_tasks`) on the task names of
/// `base` (read from `origin`); its error gets `; scenario: ORIGIN` and the context `setting`
/// (the flag, such as `--targets`, or where the scenario names the file).
///
/// # Errors
/// The error of `check`. A scenario that does not validate is left to the command's own
/// check, which reports it: nothing is checked here then.
pub fn check_file_tasks<E: Display>(
    setting: &str,
    base: &ScenarioSpec,
    origin: &str,
    check: impl FnOnce(&[String]) -> Result<(), E>,
) -> Result<()> {
    let Ok(scenario) = base.validate(origin) else {
        return Ok(());
    };
    check(&scenario.task_names())
        .map_err(|e| anyhow!("{e}; scenario: {origin}"))
        .with_context(|| setting.to_owned())
}
