//! The cross-crate integration tests of the workspace, one test binary (each file a module):
//! the mission's behaviour and rules, pinned rescuee counts, the calibration bands, teams of
//! 1,000 and 10,000 robots, and the architecture test. The long checks are `#[ignore]`d with
//! their reason; `just test-all` (and CI, in release) runs them.

mod architecture;
mod authors_clock;
mod body_overlap;
mod calibration;
mod congestion;
mod mission_behaviour;
mod mission_golden;
mod mission_invariants;
mod mission_rules;
mod mission_stalls;
mod open_choices;
mod paper_v0;
mod paper_v1;
mod paper_v2;
mod paper_v3;
mod parallel_trial;
mod round_trips;
mod scenario_api;
mod scenario_fuzz;
mod step_length;
mod swarm;
mod tasks;
