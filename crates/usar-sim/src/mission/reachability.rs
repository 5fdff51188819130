//! Which of the mission's shared goals the robots cannot reach from their starts: a check of
//! a valid scenario before it runs.
//!
//! Validation checks that each goal point keeps its clearance from nearby debris, not that a
//! path leads there: debris may wall a goal in, or wall the starts off from it. A robot sent to
//! a goal it cannot reach stands still (`docs/mission-model.md`; counted in its
//! `unreachable_goals`), and a group that waits for it never completes its round. This finds
//! such goals before a trial, with the planner every trial uses ([`World::is_goal_reachable`]).

use std::fmt;

use crate::scenario::{Locomotion, PointM, Scenario};
use crate::world::{ControlClock, World};

/// A mission goal that some robots cannot reach from their start positions.
#[derive(Debug, Clone, PartialEq)]
pub struct UnreachableGoal {
    /// The goal's scenario field: `tasks.<name>.goal_m`, `tasks.<name>.drop_off` (its
    /// centre), `rest_station` (one station) or `rest_station[*]` (several: none reachable).
    pub field: String,
    /// The goal point, metres, world frame (a station list gives its first centre).
    pub goal: PointM,
    /// Ids of the robots that cannot reach it from their starts, ascending, at least one.
    pub robots: Vec<usize>,
}

impl fmt::Display for UnreachableGoal {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        const SHOWN: usize = 5;
        let ids: Vec<String> = self
            .robots
            .iter()
            .take(SHOWN)
            .map(usize::to_string)
            .collect();
        let more = if self.robots.len() > SHOWN {
            ", ..."
        } else {
            ""
        };
        let then = if self.field.starts_with("rest_station") {
            "a robot that leaves to recharge stands still"
        } else {
            "a robot sent there stands still and its group's round cannot complete"
        };
        write!(
            f,
            "{} ({:.1}, {:.1}): no path from the start of {} robot(s) (id {}{more}); {then}",
            self.field,
            self.goal.x,
            self.goal.y,
            self.robots.len(),
            ids.join(", ")
        )
    }
}

/// The goals robots of `s` are sent to that some of them cannot reach from their starts,
/// in the order tasks (each: goal, then drop-off), then rest stations; empty when every goal
/// is reachable. Checked for each ground robot whose kind has a quota for the task (every
/// member goes to the task's goal and, when the group leaves, to its drop-off centre) and,
/// for the rest stations, for every ground robot (with several stations a robot goes to a
/// reachable one, so only robots that reach none are listed). Aerial robots fly straight.
///
/// Builds the trial's world ([`World::new`]) and plans with the same planner as a trial,
/// from the starts, before any robot moves; other robots are not obstacles to the plan. Cost:
/// one lookup per robot and goal in the grid's regions, labelled once per clearance class in
/// one pass over the grid (a path exists exactly when the planner's A* or shared distance
/// field would find one; no field is made, so many shared goals on a large grid cost no
/// memory per goal).
pub fn unreachable_goals(s: &Scenario) -> Vec<UnreachableGoal> {
    let mut world = World::new(s, &ControlClock::of(&s.sim));
    // Every robot and goal is checked from the grid's regions (`World::is_goal_reachable`).
    // Robots go by body radius, so each
    // clearance class's regions are labelled once even when more classes than the planner
    // keeps labels for take turns.
    let mut ground: Vec<usize> = (0..s.robots.len())
        .filter(|&id| s.kind_of(id).locomotion == Locomotion::Ground)
        .collect();
    ground.sort_by(|&a, &b| {
        (s.kind_of(a)
            .body_radius_m
            .total_cmp(&s.kind_of(b).body_radius_m))
        .then(a.cmp(&b))
    });
    // Robots cut off from each task's goal and drop-off, and from every rest station.
    let mut cut_off = vec![[Vec::new(), Vec::new()]; s.tasks.len()];
    let mut stranded = Vec::new();
    for &id in &ground {
        for (t, task) in s.tasks.iter().enumerate() {
            if s.kind_of(id).quota[t] == 0 {
                continue;
            }
            for (k, goal) in [task.goal, task.drop_off.center].into_iter().enumerate() {
                if !world.is_goal_reachable(id, goal) {
                    cut_off[t][k].push(id);
                }
            }
        }
        if !s
            .rest_stations
            .iter()
            .any(|c| world.is_goal_reachable(id, c.center))
        {
            stranded.push(id);
        }
    }
    let mut out = Vec::new();
    for (task, lists) in s.tasks.iter().zip(cut_off) {
        let goals = [("goal_m", task.goal), ("drop_off", task.drop_off.center)];
        for ((what, goal), mut robots) in goals.into_iter().zip(lists) {
            if !robots.is_empty() {
                robots.sort_unstable();
                out.push(UnreachableGoal {
                    field: format!("tasks.{}.{what}", task.name),
                    goal,
                    robots,
                });
            }
        }
    }
    if let (false, Some(first)) = (stranded.is_empty(), s.rest_stations.first()) {
        stranded.sort_unstable();
        let field = if s.rest_stations.len() == 1 {
            "rest_station"
        } else {
            "rest_station[*]"
        };
        out.push(UnreachableGoal {
            field: field.to_string(),
            goal: first.center,
            robots: stranded,
        });
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::from_str;

    const PAPER: &str = include_str!("../../../../scenarios/paper.ron");

    /// Two rovers right of a wall across the whole arena; the hard task is left of it.
    const SPLIT: &str = include_str!("../../tests/data/split-arena.ron");

    #[test]
    fn a_wall_across_the_arena_cuts_the_starts_off_from_one_task() {
        let s = from_str(SPLIT, "split.ron").unwrap();
        let found = unreachable_goals(&s);
        let fields: Vec<&str> = found.iter().map(|u| u.field.as_str()).collect();
        assert_eq!(fields, ["tasks.hard.goal_m", "tasks.hard.drop_off"]);
        assert!(found.iter().all(|u| u.robots == [0, 1]), "{found:?}");
        assert_eq!(found[0].goal, PointM::new(6.0, 16.0));
        let line = found[0].to_string();
        assert!(
            line.starts_with("tasks.hard.goal_m (6.0, 16.0): no path"),
            "{line}"
        );
        // With A* for every plan: the same robots (the regions answer, not one search per
        // robot; only the first robot of each kind was listed before).
        let astar = SPLIT.replace(
            "    debris: [",
            "    navigation: (shared_goal_fields: false),\n    debris: [",
        );
        assert_ne!(astar, SPLIT);
        let found = unreachable_goals(&from_str(&astar, "astar.ron").unwrap());
        let robots: Vec<&[usize]> = found.iter().map(|u| u.robots.as_slice()).collect();
        assert_eq!(robots, [[0, 1], [0, 1]], "{found:?}");
        // A gap in the wall (a shorter wall) opens the way: nothing to report.
        let open = SPLIT.replace("size_m: (0.5, 20.0)", "size_m: (0.5, 12.0)");
        assert_eq!(unreachable_goals(&from_str(&open, "open.ron").unwrap()), []);
        // The rest station walled off instead: every ground robot is listed.
        let fenced = SPLIT.replace(
            "debris: [Rect(center_m: (12.0, 10.0), size_m: (0.5, 20.0))]",
            "debris: [Rect(center_m: (22.0, 5.0), size_m: (0.5, 10.0)), \
             Rect(center_m: (26.0, 10.0), size_m: (8.0, 0.5))]",
        );
        let found = unreachable_goals(&from_str(&fenced, "fenced.ron").unwrap());
        let fields: Vec<&str> = found.iter().map(|u| u.field.as_str()).collect();
        assert_eq!(fields, ["tasks.easy.drop_off", "rest_station"], "{found:?}");
    }

    #[test]
    fn the_shipped_paper_scenario_has_no_unreachable_goal() {
        let s = from_str(PAPER, "paper.ron").unwrap();
        assert_eq!(unreachable_goals(&s), []);
    }
}
