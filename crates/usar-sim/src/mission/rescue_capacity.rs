//! Which tasks no group can rescue from, whatever the grouping method: a check of a valid
//! scenario before it runs.
//!
//! Every method fills a task's group from the kinds' quotas (`docs/mission-model.md`), and
//! only ground members with free carrying capacity claim rescuees, each pick-up drawing one
//! unit from the group's pool of rescuing resources. So a task whose quotas hold no robot, no
//! ground robot with `carrying_capacity > 0` (aerial robots fly over the area and never pick
//! anyone up, whatever their role) or no `rescuing_resources` yields nothing in any trial. Such
//! a scenario is valid (a task may be meant to stay idle), so this is a warning, not an error.

use std::fmt;

use crate::scenario::{Locomotion, Scenario};

/// Why a task's groups can rescue no one: the first that holds, in this order.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoRescue {
    /// No kind has a quota for the task: its group is always empty, and it is never worked.
    NoRobots,
    /// The kinds with a quota for the task are aerial or have `carrying_capacity: 0`.
    NoGroundCapacity {
        /// Some of those kinds are aerial with `carrying_capacity > 0` (their capacity is
        /// unused: aerial robots do not rescue).
        aerial_capacity: bool,
    },
    /// The kinds with a quota for the task have `rescuing_resources: 0`.
    NoResources,
}

/// A task of the scenario whose groups can rescue no one ([`tasks_without_rescue`]).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TaskWithoutRescue {
    /// The task's scenario field, `tasks.<name>`.
    pub field: String,
    /// Why its groups rescue no one.
    pub reason: NoRescue,
}

impl fmt::Display for TaskWithoutRescue {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let why = match self.reason {
            NoRescue::NoRobots => "no kind has a quota for it; the task is never worked",
            NoRescue::NoGroundCapacity {
                aerial_capacity: true,
            } => {
                "no ground robot with carrying_capacity > 0 in its quotas (aerial robots do not \
                 rescue); its groups can rescue no one"
            }
            NoRescue::NoGroundCapacity {
                aerial_capacity: false,
            } => {
                "no ground robot with carrying_capacity > 0 in its quotas; its groups can \
                 rescue no one"
            }
            NoRescue::NoResources => {
                "no rescuing_resources in its quotas; its groups can rescue no one"
            }
        };
        write!(f, "{}: {why}", self.field)
    }
}

/// The tasks of `s` whose groups can rescue no one at full quotas, in task order; empty when
/// every task has a group that can. A group of an `Available` round holds at most its
/// quotas, so such a task yields nothing in any round of any trial, for every grouping method.
/// Cost: `O(K x kinds)`, no world is built.
pub fn tasks_without_rescue(s: &Scenario) -> Vec<TaskWithoutRescue> {
    let mut out = Vec::new();
    for (t, task) in s.tasks.iter().enumerate() {
        let members = || s.kinds.iter().filter(move |k| k.quota[t] > 0);
        let reason = if members().next().is_none() {
            NoRescue::NoRobots
        } else if !members().any(|k| k.locomotion == Locomotion::Ground && k.carrying_capacity > 0)
        {
            NoRescue::NoGroundCapacity {
                aerial_capacity: members().any(|k| k.carrying_capacity > 0),
            }
        } else if members().all(|k| k.rescuing_resources == 0) {
            NoRescue::NoResources
        } else {
            continue;
        };
        out.push(TaskWithoutRescue {
            field: format!("tasks.{}", task.name),
            reason,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::from_str;

    const PAPER: &str = include_str!("../../../../scenarios/paper.ron");

    fn paper_with(edits: &[(&str, &str)]) -> Scenario {
        let mut text = PAPER.to_string();
        for (from, to) in edits {
            assert_eq!(text.matches(from).count(), 1, "{from}");
            text = text.replacen(from, to, 1);
        }
        from_str(&text, "paper.ron").unwrap()
    }

    #[test]
    fn the_shipped_paper_scenario_has_rescuers_for_every_task() {
        assert_eq!(tasks_without_rescue(&paper_with(&[])), vec![]);
    }

    #[test]
    fn aerial_carriers_and_empty_suppliers_leave_both_tasks_without_rescue() {
        let s = paper_with(&[
            (
                "role: Carrier,\n            locomotion: Ground",
                "role: Carrier,\n            locomotion: Aerial",
            ),
            ("carrying_capacity: 1,", "carrying_capacity: 0,"),
        ]);
        let found = tasks_without_rescue(&s);
        let fields: Vec<&str> = found.iter().map(|f| f.field.as_str()).collect();
        assert_eq!(fields, ["tasks.hard", "tasks.easy"]);
        let aerial = NoRescue::NoGroundCapacity {
            aerial_capacity: true,
        };
        assert!(found.iter().all(|f| f.reason == aerial));
        assert!(
            found[0]
                .to_string()
                .starts_with("tasks.hard: no ground robot with carrying_capacity > 0")
        );
    }

    #[test]
    fn tasks_without_quotas_capacity_or_resources_are_named() {
        let s = paper_with(&[
            ("quota: (easy: 3, hard: 3)", "quota: (hard: 6)"),
            ("quota: (easy: 2, hard: 2)", "quota: (hard: 4)"),
            ("quota: (easy: 1, hard: 1)", "quota: (hard: 2)"),
        ]);
        let found = tasks_without_rescue(&s);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].field, "tasks.easy");
        assert_eq!(found[0].reason, NoRescue::NoRobots);

        // Ground kinds without capacity: no mention of aerial robots.
        let s = paper_with(&[
            ("carrying_capacity: 6,", "carrying_capacity: 0,"),
            ("carrying_capacity: 1,", "carrying_capacity: 0,"),
        ]);
        let found = tasks_without_rescue(&s);
        assert_eq!(found.len(), 2);
        let ground = NoRescue::NoGroundCapacity {
            aerial_capacity: false,
        };
        assert!(found.iter().all(|f| f.reason == ground));
        assert!(!found[0].to_string().contains("aerial"), "{}", found[0]);

        let s = paper_with(&[
            ("rescuing_resources: 1,", "rescuing_resources: 0,"),
            ("rescuing_resources: 10,", "rescuing_resources: 0,"),
        ]);
        let found = tasks_without_rescue(&s);
        assert_eq!(found.len(), 2);
        assert!(found.iter().all(|f| f.reason == NoRescue::NoResources));
    }
}
