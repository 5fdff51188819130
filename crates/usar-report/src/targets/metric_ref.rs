//! A metric named in a targets file: a `trials.csv` column name ([`usar_sweep::metrics::Metric`])
//! such as `rounds`, `rescued_total` or `energy_hard_pct`, checked for its shape when the file
//! is read and resolved against a scenario's task names when a calibration starts.

use std::fmt;

use serde::{Deserialize, Serialize};
use usar_sim::mission::TrialResult;

use usar_sweep::metrics::Metric;

/// The per-task column names as `(prefix, suffix)` around the task's name, longest first
/// (`energy_per_hard_rescuee_pct` is a cost per rescuee, not the energy of a task named
/// `per_hard_rescuee`). Only used to find the task a name speaks of; [`Metric::parse`]
/// decides whether the name is a metric.
const TASK_PATTERNS: [(&str, &str); 5] = [
    ("energy_per_", "_rescuee_pct"),
    ("hp_per_", "_rescuee_pct"),
    ("energy_", "_pct"),
    ("hp_", "_pct"),
    ("rescued_", ""),
];

/// A metric by its `trials.csv` column name, e.g. `rescued_hard`. The name says which task it
/// is about (if any); whether a scenario has that task is decided by [`MetricRef::resolve`].
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(transparent)]
pub struct MetricRef(pub String);

impl MetricRef {
    /// The task the name speaks of (`hard` in `hp_per_hard_rescuee_pct`), `None` for a metric
    /// over all tasks or per trial (`rescued_total`, `rounds`).
    ///
    /// # Errors
    /// A name that is no metric for any task names, with the list of the metrics there are
    /// ([`metric_names_help`]).
    pub fn task(&self) -> Result<Option<&str>, String> {
        let name = self.0.as_str();
        if Metric::parse(name, &[]).is_some() {
            return Ok(None);
        }
        for (prefix, suffix) in TASK_PATTERNS {
            let task = name
                .strip_prefix(prefix)
                .and_then(|rest| rest.strip_suffix(suffix))
                .filter(|t| !t.is_empty());
            if let Some(task) = task
                && Metric::parse(name, &[task.to_string()]).is_some()
            {
                return Ok(Some(task));
            }
        }
        Err(format!(
            "unknown metric {name:?} (metrics: {})",
            metric_names_help()
        ))
    }

    /// The metric for a scenario with task names `tasks` (by task id).
    ///
    /// # Errors
    /// A malformed name ([`MetricRef::task`]), or one naming a task not in `tasks` (the
    /// message lists the tasks).
    pub fn resolve(&self, tasks: &[String]) -> Result<Metric, String> {
        let task = self.task()?;
        Metric::parse(&self.0, tasks).ok_or_else(|| {
            format!(
                "metric {:?} is about task {:?}, which the scenario does not have (its tasks: \
                 {})",
                self.0,
                task.unwrap_or_default(),
                tasks.join(", ")
            )
        })
    }

    /// The value of the metric in trial `r` (resolved against the trial's own task names);
    /// `None` when it is undefined there (a cost per rescuee without rescuees) or names a
    /// task the trial does not have.
    pub fn value(&self, r: &TrialResult) -> Option<f64> {
        Metric::parse(&self.0, &r.tasks)?.value(r)
    }
}

impl fmt::Display for MetricRef {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.0)
    }
}

/// Every metric name a targets file may use, `<task>` standing for a task's name, in
/// `trials.csv` column order: `rescued_total, rescued_<task>, energy_<task>_pct, ...`.
pub fn metric_names_help() -> String {
    let tasks = ["<task>".to_string()];
    Metric::all(1)
        .iter()
        .map(|m| m.name(&tasks))
        .collect::<Vec<_>>()
        .join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tasks() -> Vec<String> {
        vec!["hard".into(), "easy".into()]
    }

    #[test]
    fn every_column_name_finds_its_task() {
        let t = tasks();
        for m in Metric::all(2) {
            let name = MetricRef(m.name(&t));
            assert_eq!(name.resolve(&t), Ok(m), "{name}");
        }
        assert_eq!(MetricRef("rounds".into()).task(), Ok(None));
        assert_eq!(
            MetricRef("energy_per_hard_rescuee_pct".into()).task(),
            Ok(Some("hard"))
        );
        assert_eq!(
            MetricRef("hp_my_task_pct".into()).task(),
            Ok(Some("my_task"))
        );
        assert_eq!(
            MetricRef("rescued_medium".into()).task(),
            Ok(Some("medium"))
        );
    }

    #[test]
    fn unknown_names_and_missing_tasks_are_named() {
        let e = MetricRef("rescuees".into()).task().unwrap_err();
        assert!(
            e.starts_with("unknown metric \"rescuees\" (metrics: rescued_total, rescued_<task>, "),
            "{e}"
        );
        assert!(e.ends_with("mean_round_s)"), "{e}");
        for bad in ["rescued_", "energy__pct", "hp_pct", ""] {
            assert!(MetricRef(bad.into()).task().is_err(), "{bad:?}");
        }
        let e = MetricRef("rescued_medium".into())
            .resolve(&tasks())
            .unwrap_err();
        assert_eq!(
            e,
            "metric \"rescued_medium\" is about task \"medium\", which the scenario does not \
             have (its tasks: hard, easy)"
        );
    }
}
