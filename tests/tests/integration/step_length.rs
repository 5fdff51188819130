//! The step length `sim.dt_s` does not change a robot's path (issue 70): on the corridor and on
//! the paper's arena, at the shipped speeds and at 5 m/s, each robot's path length and energy
//! spent at dt 0.01 s lie within 1.5x of those at dt 0.02 s (RNE, trial 0).
//!
//! Before the fix (7e06364), corridor robot 0 at the shipped speed drove 28.9 m at dt 0.02 and
//! 47.2 m at dt 0.01 (1.63x), and at 5 m/s 29.1 m against 177.2 m (6.1x). A step-resolution
//! trace (`World::robots` after every step) showed why: back at its start, robot 0's goal lay
//! 0.70 m from robot 1, who stood still 0.30 m short of its own start, inside the resolver's
//! 1.0 m keep-out (r + r + safety margin). Steering (rule 5) let robot 0 only slide along the
//! keep-out's rim, and it chose the other side on every control step: it slid up and down by
//! one step's length, at full speed and charged per metre, and arrived only if a step landed in
//! the 3 mm sliver of the rim inside its 0.3 m tolerance (at dt 0.02 after 0.2 s, at dt 0.01
//! never). At 5 m/s robot 3 did the same between a parked robot and the wall. Robots now keep
//! the side they last steered to, and stop at the rim of a goal a robot standing still has
//! taken (`usar_sim::world`, docs/world-model.md).
//!
//! What stays (ratio dt 0.01 / dt 0.02 of each robot's path length; energy the same to two
//! digits): corridor 0.98-1.00 at the shipped speed and 0.83-1.30 at 5 m/s; paper 0.98-1.01 and
//! 0.98-1.14. The largest, corridor robot 3 at 5 m/s (73.4 m against 95.3 m), is the slide
//! this test is about, not yet gone in one geometry: wedged between a parked robot and the wall,
//! at dt 0.01 it still turns back and forth between a right turn towards the wall and a left
//! turn of 120 degrees away from it (the two sides' turns differ by more than the 45-degree
//! bound on keeping a side) from 5 s to 15.5 s, 36 m on the spot, where at dt 0.02 it stands
//! blocked; it leaves when a detour finds a way. Within the bound, but a known limit
//! (docs/world-model.md, "Steering side and taken goals").

use integration_tests::{load, method, scenario_path};
use usar_sim::mission::Simulation;
use usar_sim::scenario::{Positive, Scenario};

/// Ratio allowed between a robot's figure at dt 0.01 and at dt 0.02 (either way).
const MAX_RATIO: f64 = 1.5;
/// Below this a path length (m) or energy (% points) counts as this much in a ratio: a robot
/// that barely moves has no meaningful ratio.
const FLOOR: f64 = 1.0;

/// `file` with step `dt_s` and, if given, every kind's top speed `speed_m_per_s`.
fn scenario(file: &str, dt_s: f64, speed_m_per_s: Option<f64>) -> Scenario {
    load(&scenario_path(file))
        .edit(|s| {
            s.sim.dt_s = Positive::new(dt_s).expect("> 0");
            if let Some(v) = speed_m_per_s {
                for k in &mut s.kinds {
                    k.max_speed_m_per_s = Positive::new(v).expect("> 0");
                }
            }
        })
        .unwrap_or_else(|e| panic!("{file} at dt {dt_s}: {e}"))
}

/// Each robot's (path length m, energy spent % points) in RNE trial 0 of `s` over `duration_s`.
fn paths(s: &Scenario, duration_s: f64) -> Vec<(f64, f64)> {
    let result = Simulation::builder(s)
        .method(method("rne", s))
        .trial(0)
        .duration_s(duration_s)
        .build()
        .expect("builds")
        .run_to_end()
        .expect("runs");
    result
        .robots
        .iter()
        .map(|r| (r.distance_m, r.energy_spent_pct))
        .collect()
}

/// The robots of `file` whose path length or energy at dt 0.01 is off by more than
/// [`MAX_RATIO`] from dt 0.02, as text (empty: none).
fn diverging(file: &str, speed_m_per_s: Option<f64>, duration_s: f64) -> Vec<String> {
    let coarse = paths(&scenario(file, 0.02, speed_m_per_s), duration_s);
    let fine = paths(&scenario(file, 0.01, speed_m_per_s), duration_s);
    assert_eq!(coarse.len(), fine.len());
    let ratio = |a: f64, b: f64| a.max(FLOOR) / b.max(FLOOR);
    let off = |r: f64| !(1.0 / MAX_RATIO..=MAX_RATIO).contains(&r);
    coarse
        .iter()
        .zip(&fine)
        .enumerate()
        .filter(|(_, (c, f))| off(ratio(f.0, c.0)) || off(ratio(f.1, c.1)))
        .map(|(id, (c, f))| {
            format!(
                "{file} at {speed_m_per_s:?} m/s, robot {id}: {:.1} m / {:.2} % at dt 0.02, \
                 {:.1} m / {:.2} % at dt 0.01",
                c.0, c.1, f.0, f.1
            )
        })
        .collect()
}

#[test]
fn corridor_paths_do_not_depend_on_the_step_length() {
    let mut off = diverging("corridor.ron", None, 60.0);
    off.extend(diverging("corridor.ron", Some(5.0), 60.0));
    assert!(off.is_empty(), "{off:#?}");
}

#[test]
fn paper_paths_do_not_depend_on_the_step_length() {
    let mut off = diverging("paper.ron", None, 600.0);
    off.extend(diverging("paper.ron", Some(5.0), 600.0));
    assert!(off.is_empty(), "{off:#?}");
}
