//! Per-round yields (issue 55): `--rounds-csv FILE` of `usar run` and `usar sweep`, one row
//! per trial x round x task, and a summary per task of what ended the trips and the rounds
//! (`docs/calibration.md`, "Per-round yields").
//!
//! A row's columns: `cell` (the grid cell, 0 without `--vary`), `method`, `trial`, `seed`,
//! `round` (from 0), `task`, `start_s`, `end_s`, `completed` (every grouped robot back before
//! the time limit), `group_size` (robots grouped to the task at the round's start),
//! `rescued`, `left_area_s` and `left_because` (when and why the group was sent out of its
//! search area: `resources_used`, `capacity_full`, `nothing_left`, `search_budget` or `round_timer`; empty if
//! it never was), `deliveries` and `empty_deliveries` (trips that ended at the drop-off, and
//! those that brought no one), `left_for_rest` (members that left the group for their needs),
//! `back_s` (when its last member still in the group got back to its start; empty if not all
//! were) and `wait_s` (`end_s - back_s`: how long the group waited for the round to end).
//! Times in seconds since the trial start. Trials journaled before these figures existed have
//! empty trip cells.

use crate::error::{ReportError, Result};
use usar_sim::mission::{RoundRecord, TrialResult};

/// `--rounds-csv`: the rows of every result of every cell (`(cell index, results)`), in the
/// given order, rounds and tasks in theirs.
///
/// # Errors
/// A CSV serialisation error (not expected).
pub fn rounds_csv(cells: &[(usize, &[TrialResult])]) -> Result<Vec<u8>> {
    let mut w = csv::Writer::from_writer(Vec::new());
    w.write_record([
        "cell",
        "method",
        "trial",
        "seed",
        "round",
        "task",
        "start_s",
        "end_s",
        "completed",
        "group_size",
        "rescued",
        "left_area_s",
        "left_because",
        "deliveries",
        "empty_deliveries",
        "left_for_rest",
        "back_s",
        "wait_s",
    ])?;
    let opt = |v: Option<f64>| v.map_or(String::new(), |x| x.to_string());
    for (cell, results) in cells {
        for r in *results {
            for (i, round) in r.rounds.iter().enumerate() {
                for (t, task) in r.tasks.iter().enumerate() {
                    let trip = Trip::of(round, t);
                    w.write_record([
                        cell.to_string(),
                        r.method.clone(),
                        r.trial.to_string(),
                        r.seed.to_string(),
                        i.to_string(),
                        task.clone(),
                        round.start_s.to_string(),
                        round.end_s.to_string(),
                        round.completed.to_string(),
                        round.groups.get(t).map_or(0, Vec::len).to_string(),
                        round.rescued.get(t).copied().unwrap_or(0).to_string(),
                        opt(trip.left_area_s),
                        trip.left_because.unwrap_or_default().to_owned(),
                        trip.deliveries.map_or(String::new(), |n| n.to_string()),
                        trip.empty.map_or(String::new(), |n| n.to_string()),
                        trip.left_for_rest.map_or(String::new(), |n| n.to_string()),
                        opt(trip.back_s),
                        opt(trip.back_s.map(|b| round.end_s - b)),
                    ])?;
                }
            }
        }
    }
    w.into_inner()
        .map_err(ReportError::finish("writing rounds.csv"))
}

/// One task's trip figures in one round (`None` where the round has none recorded).
struct Trip {
    left_area_s: Option<f64>,
    left_because: Option<&'static str>,
    deliveries: Option<u32>,
    empty: Option<u32>,
    left_for_rest: Option<u32>,
    back_s: Option<f64>,
}

impl Trip {
    fn of(round: &RoundRecord, t: usize) -> Self {
        Self {
            left_area_s: round.left_area_s.get(t).copied().flatten(),
            left_because: round
                .left_because
                .get(t)
                .copied()
                .flatten()
                .map(|c| c.as_str()),
            deliveries: round.deliveries.get(t).copied(),
            empty: round.empty_deliveries.get(t).copied(),
            left_for_rest: round.left_for_rest.get(t).copied(),
            back_s: round.back_s.get(t).copied().flatten(),
        }
    }
}

/// One task's per-round figures over a set of trials (the rounds in which it had a group).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TaskRounds {
    /// The task's name.
    pub task: String,
    /// Rounds in which the task had a group.
    pub rounds: usize,
    /// Mean rescuees per such round.
    pub mean_yield: f64,
    /// Standard deviation of a round's rescuees around its trial's mean (pooled within
    /// trials, `n - 1` per trial), rescuees; NaN without two rounds in some trial.
    pub within_trial_sd: f64,
    /// Trips that ended at the drop-off.
    pub deliveries: u32,
    /// Share of `deliveries` that brought no one, in `[0, 1]` (NaN without deliveries).
    pub empty_share: f64,
    /// Why the group left its search area, counts in [`LeaveCause`] order
    /// (`resources_used`, `capacity_full`, `nothing_left`, `search_budget`, `round_timer`), then the
    /// rounds it
    /// never left (cut by the time limit).
    ///
    /// [`LeaveCause`]: usar_sim::mission::LeaveCause
    pub left_because: [usize; 6],
    /// Members that left the group for their needs, per round.
    pub left_for_rest_per_round: f64,
    /// Mean time the group waited at the start for the round to end, seconds, over the rounds
    /// in which all its members got back.
    pub mean_wait_s: f64,
}

/// The per-task summary of [`rounds_csv`]'s rows, for `results`' tasks (those of the first
/// result; every result of a sweep has the same).
pub fn task_rounds(results: &[TrialResult]) -> Vec<TaskRounds> {
    use usar_sim::mission::LeaveCause::*;
    let Some(first) = results.first() else {
        return Vec::new();
    };
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    first
        .tasks
        .iter()
        .enumerate()
        .map(|(t, name)| {
            let mut s = TaskRounds {
                task: name.clone(),
                ..TaskRounds::default()
            };
            let (mut yields, mut waits, mut rests, mut empty) = (vec![], vec![], 0u32, 0u32);
            let (mut ss, mut dof) = (0.0, 0usize);
            for r in results {
                let trial: Vec<f64> = r
                    .rounds
                    .iter()
                    .filter(|round| round.groups.get(t).is_some_and(|g| !g.is_empty()))
                    .map(|round| {
                        let trip = Trip::of(round, t);
                        s.deliveries += trip.deliveries.unwrap_or(0);
                        empty += trip.empty.unwrap_or(0);
                        rests += trip.left_for_rest.unwrap_or(0);
                        let cause = round.left_because.get(t).copied().flatten();
                        let slot = match cause {
                            Some(ResourcesUsed) => 0,
                            Some(CapacityFull) => 1,
                            Some(NothingLeft) => 2,
                            Some(SearchBudget) => 3,
                            Some(RoundTimer) => 4,
                            None => 5,
                        };
                        s.left_because[slot] += 1;
                        if let Some(b) = trip.back_s {
                            waits.push(round.end_s - b);
                        }
                        f64::from(round.rescued.get(t).copied().unwrap_or(0))
                    })
                    .collect();
                if trial.len() >= 2 {
                    let m = mean(&trial);
                    ss += trial.iter().map(|y| (y - m).powi(2)).sum::<f64>();
                    dof += trial.len() - 1;
                }
                yields.extend(trial);
            }
            s.rounds = yields.len();
            s.mean_yield = mean(&yields);
            s.within_trial_sd = if dof > 0 {
                (ss / dof as f64).sqrt()
            } else {
                f64::NAN
            };
            s.empty_share = f64::from(empty) / f64::from(s.deliveries);
            s.left_for_rest_per_round = f64::from(rests) / yields.len() as f64;
            s.mean_wait_s = mean(&waits);
            s
        })
        .collect()
}

/// [`task_rounds`] as the lines `usar run` and `usar sweep` print after writing the file.
pub fn summary_lines(rows: &[TaskRounds]) -> Vec<String> {
    let mut lines = vec![format!(
        "{:<10} {:>6} {:>7} {:>8} {:>6} {:>6}  {:<40} {:>6} {:>7}",
        "task",
        "rounds",
        "yield",
        "sd in tr",
        "trips",
        "empty",
        "left because (res/full/none/budget/timer/never)",
        "rest/r",
        "wait s"
    )];
    for r in rows {
        lines.push(format!(
            "{:<10} {:>6} {:>7.2} {:>8.2} {:>6} {:>5.1}%  {:<40} {:>6.2} {:>7.1}",
            r.task,
            r.rounds,
            r.mean_yield,
            r.within_trial_sd,
            r.deliveries,
            100.0 * r.empty_share,
            r.left_because
                .iter()
                .map(usize::to_string)
                .collect::<Vec<_>>()
                .join("/"),
            r.left_for_rest_per_round,
            r.mean_wait_s
        ));
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;
    use usar_sim::mission::LeaveCause;

    fn round(rescued: [u32; 2], end_s: f64, back_s: [Option<f64>; 2]) -> RoundRecord {
        RoundRecord {
            start_s: 0.0,
            end_s,
            completed: true,
            groups: vec![vec![0, 1], vec![2]],
            rescued: rescued.to_vec(),
            left_area_s: vec![Some(10.0), None],
            left_because: vec![Some(LeaveCause::CapacityFull), None],
            deliveries: vec![2, 1],
            empty_deliveries: vec![1, 0],
            left_for_rest: vec![0, 1],
            back_s: back_s.to_vec(),
        }
    }

    fn trial(trial: u32, rounds: Vec<RoundRecord>) -> TrialResult {
        TrialResult {
            scenario: "s".into(),
            method: "RNE".into(),
            trial,
            seed: 7,
            duration_s: 100.0,
            tasks: vec!["hard".into(), "easy".into()],
            rescued: vec![0, 0],
            energy_spent_pct: vec![0.0, 0.0],
            hp_lost_pct: vec![0.0, 0.0],
            rounds,
            robots: vec![],
        }
    }

    #[test]
    fn the_summary_is_the_hand_computed_one() {
        // hard yields 4, 8 in trial 0 and 6 in trial 1: mean 6, within-trial SD sqrt(8 / 1).
        let results = [
            trial(
                0,
                vec![
                    round([4, 1], 50.0, [Some(40.0), None]),
                    round([8, 2], 90.0, [Some(80.0), Some(90.0)]),
                ],
            ),
            trial(1, vec![round([6, 3], 50.0, [Some(45.0), None])]),
        ];
        let s = task_rounds(&results);
        let hard = &s[0];
        assert_eq!(hard.rounds, 3);
        assert!((hard.mean_yield - 6.0).abs() < 1e-12);
        assert!((hard.within_trial_sd - 8f64.sqrt()).abs() < 1e-12);
        assert_eq!(hard.deliveries, 6);
        assert!((hard.empty_share - 0.5).abs() < 1e-12);
        assert_eq!(hard.left_because, [0, 3, 0, 0, 0, 0]);
        assert!((hard.mean_wait_s - (10.0 + 10.0 + 5.0) / 3.0).abs() < 1e-12);
        let easy = &s[1];
        assert_eq!(easy.left_because, [0, 0, 0, 0, 0, 3]);
        assert!((easy.left_for_rest_per_round - 1.0).abs() < 1e-12);
        assert!((easy.mean_wait_s - 0.0).abs() < 1e-12);
    }

    #[test]
    fn the_csv_has_a_row_per_round_and_task_and_leaves_unknown_figures_empty() {
        let mut old = round([1, 1], 5.0, [None, None]);
        (old.left_area_s, old.left_because, old.deliveries) = (vec![], vec![], vec![]);
        (old.empty_deliveries, old.left_for_rest, old.back_s) = (vec![], vec![], vec![]);
        let results = [trial(0, vec![round([4, 1], 50.0, [Some(40.0), None]), old])];
        let text = String::from_utf8(rounds_csv(&[(3, &results)]).unwrap()).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 1 + 2 * 2);
        assert_eq!(
            lines[1],
            "3,RNE,0,7,0,hard,0,50,true,2,4,10,capacity_full,2,1,0,40,10"
        );
        assert_eq!(lines[2], "3,RNE,0,7,0,easy,0,50,true,1,1,,,1,0,1,,");
        assert_eq!(lines[3], "3,RNE,0,7,1,hard,0,5,true,2,1,,,,,,,");
    }
}
