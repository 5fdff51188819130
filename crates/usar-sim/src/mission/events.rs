//! [`MissionEvent`]: what happened in the mission during one step (rounds starting and ending,
//! pick-ups, deliveries, robots leaving for and coming back from the rest station), for
//! observers such as a replay recorder. Recording events changes no result.

/// What happened (see [`MissionEvent`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MissionEventKind {
    /// A round started: the available robots were grouped (paper, section VI.B).
    RoundStarted {
        /// The round's index in [`crate::mission::Simulation::rounds`] (0-based).
        round: usize,
    },
    /// The open round ended.
    RoundEnded {
        /// The round's index (0-based).
        round: usize,
        /// Every grouped robot got back to its start (`false`: cut by the time limit).
        completed: bool,
    },
    /// The robot picked up a rescuee of its task.
    PickedUp {
        /// The rescuee's index in its task's rescuees.
        rescuee: usize,
    },
    /// The robot delivered its load at its task's drop-off.
    Delivered {
        /// Rescuees delivered (0 when it arrived with an empty load).
        rescuees: u32,
    },
    /// The robot left its task for the rest station: its energy or HP fell below
    /// `mission.low_energy_pct` / `mission.low_hp_pct`.
    LeftForRest {
        /// Energy was below its threshold.
        low_energy: bool,
        /// HP was below its threshold.
        low_hp: bool,
    },
    /// The robot's stay at the rest station ended (it heads back to its start).
    Recharged,
}

/// One event of the mission: when, which robot and task it concerns, and what happened.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MissionEvent {
    /// Simulated time, seconds since the trial start: the end of the step it happened in
    /// (a round starts before the step's physics, at the step's start time).
    pub time_s: f64,
    /// The robot it concerns (`None` for round events).
    pub robot: Option<usize>,
    /// The task (id) it concerns, if any: the robot's task, or `None` for rounds, rests and
    /// recharges.
    pub task: Option<usize>,
    /// What happened.
    pub kind: MissionEventKind,
}

impl MissionEvent {
    /// An event of robot `robot` (and task `task`) at `time_s`.
    pub fn of_robot(
        time_s: f64,
        robot: usize,
        task: Option<usize>,
        kind: MissionEventKind,
    ) -> Self {
        Self {
            time_s,
            robot: Some(robot),
            task,
            kind,
        }
    }

    /// A round event at `time_s`.
    pub fn of_round(time_s: f64, kind: MissionEventKind) -> Self {
        Self {
            time_s,
            robot: None,
            task: None,
            kind,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mission::Simulation;
    use crate::scenario;

    /// Runs 200 s of trial 0 of `scenarios/paper.ron` with RNE and checks the events against
    /// the trial's own metrics: every round start and end, pick-up, delivery and recharge
    /// counted by the recorder is an event, in time order, at the step's time.
    #[test]
    fn events_match_the_trials_metrics() {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
        let s = scenario::load(path).expect("paper.ron loads");
        let mut sim = Simulation::builder(&s)
            .method_named("rne")
            .duration_s(200.0)
            .build()
            .expect("trial builds");
        let mut events: Vec<MissionEvent> = Vec::new();
        let dt = s.sim.dt_s.get();
        let mut observe = |sim: &Simulation| {
            for e in sim.events() {
                // Round starts happen before the step's physics, at its start time.
                assert!(e.time_s <= sim.time_s() + 1e-9 && e.time_s >= sim.time_s() - dt - 1e-9);
            }
            events.extend_from_slice(sim.events());
        };
        let result = sim.run_observed(&mut observe).expect("trial runs");
        let count =
            |f: &dyn Fn(&MissionEventKind) -> bool| events.iter().filter(|e| f(&e.kind)).count();
        let started = count(&|k| matches!(k, MissionEventKind::RoundStarted { .. }));
        let ended = count(&|k| matches!(k, MissionEventKind::RoundEnded { .. }));
        assert_eq!(started, result.rounds.len());
        assert_eq!(
            ended,
            result.rounds.len(),
            "the last round is closed at the end"
        );
        let picked: u32 = result.robots.iter().map(|r| r.picked_up).sum();
        assert!(picked > 0, "200 s of the paper's mission rescue someone");
        assert_eq!(
            count(&|k| matches!(k, MissionEventKind::PickedUp { .. })),
            picked as usize
        );
        let delivered: u32 = events
            .iter()
            .map(|e| match e.kind {
                MissionEventKind::Delivered { rescuees } => rescuees,
                _ => 0,
            })
            .sum();
        assert_eq!(delivered, result.rescued.iter().sum::<u32>());
        let recharges: u32 = result.robots.iter().map(|r| r.recharges).sum();
        assert_eq!(
            count(&|k| matches!(k, MissionEventKind::Recharged)),
            recharges as usize
        );
        assert!(events.windows(2).all(|w| w[0].time_s <= w[1].time_s));
        for (i, r) in result.rounds.iter().enumerate() {
            let start = events
                .iter()
                .find(|e| e.kind == MissionEventKind::RoundStarted { round: i })
                .expect("round start event");
            assert!((start.time_s - r.start_s).abs() < 1e-12);
        }
    }
}
