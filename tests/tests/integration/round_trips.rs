//! The per-round trip figures of `RoundRecord` (`left_area_s`, `left_because`, `deliveries`,
//! `empty_deliveries`, `left_for_rest`, `back_s`; `usar run --rounds-csv`) agree with the
//! mission's events and with the round's own times, for every built-in method on a full
//! paper.ron trial, and a scenario without a search time budget never names it as a cause.

use integration_tests::{method, paper, paper_with};
use usar_sim::mission::{LeaveCause, MissionEventKind, Simulation};
use usar_sim::scenario::{ResourceStock, Scenario};

/// Per round, per task: (deliveries, empty deliveries, left for rest), counted from events.
type Counts = Vec<Vec<(u32, u32, u32)>>;

fn check(s: &Scenario, name: &str) -> Vec<Option<LeaveCause>> {
    let tasks = s.task_names().len();
    let mut sim = Simulation::for_trial(s, method(name, s), 1);
    let mut counts: Counts = Vec::new();
    while !sim.is_finished() {
        sim.step().expect("built-in methods do not fail");
        for e in sim.events() {
            let carries = |id: usize| s.kind_of(id).carrying_capacity > 0;
            match (e.kind, e.robot, e.task) {
                (MissionEventKind::RoundStarted { .. }, _, _) => {
                    counts.push(vec![(0, 0, 0); tasks]);
                }
                (MissionEventKind::Delivered { rescuees }, Some(id), Some(t)) if carries(id) => {
                    let c = &mut counts.last_mut().expect("a round is open")[t];
                    c.0 += 1;
                    c.1 += u32::from(rescuees == 0);
                }
                (MissionEventKind::LeftForRest { .. }, Some(_), Some(t)) => {
                    counts.last_mut().expect("a round is open")[t].2 += 1;
                }
                _ => {}
            }
        }
    }
    let result = sim.result();
    assert_eq!(result.rounds.len(), counts.len(), "{name}");
    let mut causes = Vec::new();
    for (i, (round, c)) in result.rounds.iter().zip(&counts).enumerate() {
        for (t, counted) in c.iter().enumerate() {
            let at = format!("{name}, round {i}, task {t}");
            assert_eq!(
                (
                    round.deliveries[t],
                    round.empty_deliveries[t],
                    round.left_for_rest[t]
                ),
                *counted,
                "{at}"
            );
            assert!(round.empty_deliveries[t] <= round.deliveries[t], "{at}");
            // A non-empty delivery brings someone: at most one rescuee-less trip per rescuee
            // short of the deliveries.
            let full_trips = round.deliveries[t] - round.empty_deliveries[t];
            assert!(full_trips <= round.rescued[t], "{at}");
            assert_eq!(
                round.left_area_s[t].is_some(),
                round.left_because[t].is_some(),
                "{at}"
            );
            if let Some(left) = round.left_area_s[t] {
                assert!(
                    (round.start_s..=round.end_s).contains(&left),
                    "{at}: {left}"
                );
            }
            if let Some(back) = round.back_s[t] {
                assert!(
                    (round.start_s..=round.end_s).contains(&back),
                    "{at}: {back}"
                );
                assert!(round.left_area_s[t].is_none_or(|l| l <= back), "{at}");
            }
            if round.completed && !round.groups[t].is_empty() && round.back_s[t].is_none() {
                // Every member left for its needs: none is still in the group.
                assert!(
                    round.left_for_rest[t] as usize >= round.groups[t].len(),
                    "{at}"
                );
            }
            causes.push(round.left_because[t]);
        }
    }
    let by_rounds: Vec<u32> = (0..tasks)
        .map(|t| result.rounds.iter().map(|r| r.rescued[t]).sum())
        .collect();
    assert_eq!(by_rounds, result.rescued, "{name}");
    causes
}

#[test]
fn trip_figures_agree_with_the_events_for_every_method() {
    let s = paper();
    let mut seen = Vec::new();
    for name in ["rne", "dis", "eng", "hp_dis"] {
        seen.extend(check(&s, name));
    }
    // paper.ron's groups leave by their search budget, and when the team's stock of rescuing
    // resources for the round is spent.
    assert!(seen.contains(&Some(LeaveCause::SearchBudget)));
    assert!(seen.contains(&Some(LeaveCause::ResourcesUsed)));
}

#[test]
fn groups_with_their_own_resources_also_leave_when_full() {
    // Each member refilled per round (paper-v2.ron's rule): a group's 23 units outlast its
    // capacity, so some groups leave full.
    let s = paper_with(|s| s.mission.resource_stock = ResourceStock::PerRound);
    let mut seen = Vec::new();
    for name in ["rne", "dis", "eng", "hp_dis"] {
        seen.extend(check(&s, name));
    }
    assert!(seen.contains(&Some(LeaveCause::CapacityFull)));
    assert!(!seen.contains(&Some(LeaveCause::ResourcesUsed)));
}

#[test]
fn without_a_search_budget_no_group_leaves_for_it() {
    let s = paper_with(|s| s.mission.search_time_budget_s = None);
    let causes = check(&s, "rne");
    assert!(causes.iter().flatten().count() > 0);
    assert!(!causes.contains(&Some(LeaveCause::SearchBudget)));
}
