//! The JSON of one trial that `usar run --json` writes: the [`TrialResult`]'s fields, plus each
//! task's figures under its name and their totals (schema: `docs/schema/trial.schema.json`).

use indexmap::IndexMap;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use usar_sim::mission::TrialResult;

/// One task's figures in a trial, or their totals over all tasks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TaskFigures {
    /// Rescuees delivered.
    pub rescued: u32,
    /// Energy spent by robots while in the task's group, percent points summed over robots.
    pub energy_spent_pct: f64,
    /// HP lost by robots while in the task's group, percent points summed over robots.
    pub hp_lost_pct: f64,
}

/// What `usar run --json FILE` writes. It reads back as a [`TrialResult`] (the extra fields
/// are ignored), and a reader can ask for `by_task.hard.rescued` without knowing the order of
/// the tasks.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TrialJson {
    /// The trial's result, its fields at the top level.
    #[serde(flatten)]
    pub result: TrialResult,
    /// Each task's figures by task name, in the scenario's task order.
    pub by_task: IndexMap<String, TaskFigures>,
    /// The figures over all tasks (sums in task order).
    pub total: TaskFigures,
}

impl TrialJson {
    /// The JSON record of `result`.
    pub fn of(result: &TrialResult) -> Self {
        let by_task = result
            .tasks
            .iter()
            .enumerate()
            .map(|(t, name)| {
                let figures = TaskFigures {
                    rescued: result.rescued[t],
                    energy_spent_pct: result.energy_spent_pct[t],
                    hp_lost_pct: result.hp_lost_pct[t],
                };
                (name.clone(), figures)
            })
            .collect();
        let total = TaskFigures {
            rescued: result.rescued_total(),
            energy_spent_pct: result.energy_total_pct(),
            hp_lost_pct: result.hp_total_pct(),
        };
        Self {
            result: result.clone(),
            by_task,
            total,
        }
    }
}
