//! The timeline's marks ([`Mark`]): round starts and ends, deadlocks detected and resolved,
//! robots leaving to recharge, deliveries.

use serde::Serialize;
use usar_sim::mission::{MissionEvent, MissionEventKind};

/// What a mark on the replay's timeline stands for. The page draws one row per kind, in this
/// order, in [`MarkKind::color`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum MarkKind {
    /// A round started: the available robots were grouped (`value`: the round's index).
    RoundStart = 0,
    /// A round ended (`value`: 1 when every grouped robot got back, 0 when the time limit cut
    /// it).
    RoundEnd = 1,
    /// The collision resolver found a collision list deadlocked and rotated its priority order
    /// (paper, Algorithm 5; `robots`: the list's members whose count grew this step).
    DeadlockDetected = 2,
    /// Robots left a list whose order had been rotated: their deadlock cleared.
    DeadlockResolved = 3,
    /// A robot left its task to recharge (`value`: bit 0 low energy, bit 1 low HP).
    LeftToRecharge = 4,
    /// A robot delivered rescuees at its task's drop-off (`value`: how many).
    Delivery = 5,
}

impl MarkKind {
    /// Every kind, in row order.
    pub const ALL: [MarkKind; 6] = [
        MarkKind::RoundStart,
        MarkKind::RoundEnd,
        MarkKind::DeadlockDetected,
        MarkKind::DeadlockResolved,
        MarkKind::LeftToRecharge,
        MarkKind::Delivery,
    ];

    /// The label of the kind's row on the page.
    pub fn label(self) -> &'static str {
        match self {
            MarkKind::RoundStart => "round start",
            MarkKind::RoundEnd => "round end",
            MarkKind::DeadlockDetected => "deadlock detected",
            MarkKind::DeadlockResolved => "deadlock resolved",
            MarkKind::LeftToRecharge => "left to recharge",
            MarkKind::Delivery => "delivery",
        }
    }

    /// The kind's colour on the page, `#rrggbb`.
    pub fn color(self) -> &'static str {
        match self {
            MarkKind::RoundStart => "#2ca02c",
            MarkKind::RoundEnd => "#555555",
            MarkKind::DeadlockDetected => "#d62728",
            MarkKind::DeadlockResolved => "#ff9896",
            MarkKind::LeftToRecharge => "#9467bd",
            MarkKind::Delivery => "#1f77b4",
        }
    }
}

/// One mark on the timeline.
#[derive(Debug, Clone, PartialEq)]
pub struct Mark {
    /// Simulated time, seconds since the trial start.
    pub time_s: f64,
    /// What it stands for.
    pub kind: MarkKind,
    /// The robots it concerns (empty for rounds), ascending.
    pub robots: Vec<usize>,
    /// The task (id) it concerns, if any.
    pub task: Option<usize>,
    /// A number whose meaning depends on the kind (see [`MarkKind`]).
    pub value: u32,
}

impl Mark {
    /// The mark of a mission event, if it has one: round starts and ends, leaves for the rest
    /// station and deliveries of at least one rescuee (pick-ups and recharges have no mark).
    pub fn of_event(e: &MissionEvent) -> Option<Self> {
        let (kind, value) = match e.kind {
            MissionEventKind::RoundStarted { round } => (MarkKind::RoundStart, round as u32),
            MissionEventKind::RoundEnded { completed, .. } => {
                (MarkKind::RoundEnd, u32::from(completed))
            }
            MissionEventKind::LeftForRest { low_energy, low_hp } => (
                MarkKind::LeftToRecharge,
                u32::from(low_energy) | (u32::from(low_hp) << 1),
            ),
            MissionEventKind::Delivered { rescuees } if rescuees > 0 => {
                (MarkKind::Delivery, rescuees)
            }
            _ => return None,
        };
        Some(Self {
            time_s: e.time_s,
            kind,
            robots: e.robot.into_iter().collect(),
            task: e.task,
            value,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_with_a_mark_become_marks_and_the_others_do_not() {
        let left = MissionEvent::of_robot(
            3.5,
            7,
            Some(1),
            MissionEventKind::LeftForRest {
                low_energy: false,
                low_hp: true,
            },
        );
        let m = Mark::of_event(&left).unwrap();
        assert_eq!(m.kind, MarkKind::LeftToRecharge);
        assert_eq!(
            (m.robots.as_slice(), m.task, m.value),
            (&[7][..], Some(1), 2)
        );
        let empty =
            MissionEvent::of_robot(1.0, 2, Some(0), MissionEventKind::Delivered { rescuees: 0 });
        assert_eq!(Mark::of_event(&empty), None);
        let pick =
            MissionEvent::of_robot(1.0, 2, Some(0), MissionEventKind::PickedUp { rescuee: 4 });
        assert_eq!(Mark::of_event(&pick), None);
        let end = MissionEvent::of_round(
            9.0,
            MissionEventKind::RoundEnded {
                round: 2,
                completed: true,
            },
        );
        let m = Mark::of_event(&end).unwrap();
        assert_eq!(
            (m.kind, m.value, m.robots.len()),
            (MarkKind::RoundEnd, 1, 0)
        );
    }

    #[test]
    fn kinds_are_listed_in_row_order() {
        for (i, k) in MarkKind::ALL.iter().enumerate() {
            assert_eq!(*k as usize, i);
        }
    }
}
