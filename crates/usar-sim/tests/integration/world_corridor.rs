//! Corridor head-on meetings in `scenarios/corridor.ron` (24 m x 3.4 m): the priority resolver
//! (paper, section V, Algorithm 5) lets 2, 4 and 8 ground robots swap ends safely; without it
//! the same meeting stays stuck.

use crate::common;

use common::{corridor, swap_goals};
use usar_sim::scenario::Steering;
use usar_sim::world::{ControlClock, World};

/// Every robot must reach its goal within this simulated time, seconds.
const BOUND_S: f64 = 90.0;
/// Largest allowed penetration between bodies, or of a body into a wall, at any step, metres.
const OVERLAP_TOLERANCE_M: f64 = 0.05;

struct Outcome {
    all_arrived_at_s: Option<f64>,
    arrived: usize,
    max_penetration_m: f64,
    deadlocks: u64,
    resolved: u64,
    lists_joined: u64,
    steps_held: u64,
}

fn run(per_side: usize, enabled: bool, keys: Option<&[f64]>) -> Outcome {
    run_steering(per_side, enabled, keys, Steering::KeepSide)
}

/// [`run`] with `collision.steering` set to `steering`.
fn run_steering(
    per_side: usize,
    enabled: bool,
    keys: Option<&[f64]>,
    steering: Steering,
) -> Outcome {
    let s = corridor(per_side)
        .edit(|s| {
            s.collision.enabled = enabled;
            s.collision.steering = steering;
        })
        .unwrap_or_else(|e| panic!("{e}"));
    let goals = swap_goals(&s);
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(&s, &clock);
    for (id, g) in goals.iter().enumerate() {
        w.set_goal(id, Some(*g))
            .expect("corridor goals are reachable");
        if let Some(k) = keys {
            w.set_priority_key(id, k[id]).unwrap();
        }
    }
    let mut max_pen = 0.0f64;
    let mut all_arrived_at_s = None;
    let steps = (BOUND_S / s.sim().dt_s.get()).round() as u64;
    for _ in 0..steps {
        w.step(&clock);
        max_pen = max_pen.max(w.max_penetration_m());
        if w.robots().iter().all(|r| r.goal_reached) {
            all_arrived_at_s = Some(w.time_s());
            break;
        }
    }
    let rs = w.robots();
    Outcome {
        all_arrived_at_s,
        arrived: rs.iter().filter(|r| r.goal_reached).count(),
        max_penetration_m: max_pen,
        deadlocks: rs.iter().map(|r| r.counters.deadlocks_detected).sum(),
        resolved: rs.iter().map(|r| r.counters.deadlocks_resolved).sum(),
        lists_joined: rs.iter().map(|r| r.counters.lists_joined).sum(),
        steps_held: rs.iter().map(|r| r.counters.steps_held).sum(),
    }
}

fn report(name: &str, o: &Outcome) {
    println!(
        "{name}: all arrived at {:?} s, arrived {}, max penetration {:.4} m, deadlocks {} (resolved {}), lists joined {}, steps held {}",
        o.all_arrived_at_s,
        o.arrived,
        o.max_penetration_m,
        o.deadlocks,
        o.resolved,
        o.lists_joined,
        o.steps_held
    );
}

#[test]
fn two_four_eight_robots_swap_ends_with_the_resolver() {
    for per_side in [1, 2, 4] {
        let o = run(per_side, true, None);
        report(&format!("{} robots", 2 * per_side), &o);
        assert!(
            o.all_arrived_at_s.is_some(),
            "{} robots: only {} arrived within {BOUND_S} s",
            2 * per_side,
            o.arrived
        );
        assert!(
            o.max_penetration_m <= OVERLAP_TOLERANCE_M,
            "penetration {} m",
            o.max_penetration_m
        );
        assert!(
            o.lists_joined > 0,
            "a head-on meeting forms a collision list"
        );
    }
}

/// With the steering before issue 70 (`collision.steering: Memoryless`) the 8 robots jam, and
/// the resolver's deadlock rotation (Algorithm 5's `Swap`) clears it. (With today's default
/// the turned headings keep clear of moving robots too, and the same swap needs no rotation.)
#[test]
fn eight_robots_that_jam_are_freed_by_the_deadlock_rotation() {
    let o = run_steering(4, true, None, Steering::Memoryless);
    report("8 robots, memoryless steering", &o);
    assert!(o.all_arrived_at_s.is_some(), "only {} arrived", o.arrived);
    assert!(o.deadlocks > 0, "8 robots jam: deadlocks are detected");
    assert!(o.resolved > 0, "and resolved");
}

#[test]
fn without_the_resolver_the_head_on_meeting_stays_stuck() {
    for per_side in [1, 2, 4] {
        let o = run(per_side, false, None);
        report(&format!("{} robots, resolver off", 2 * per_side), &o);
        assert!(
            o.all_arrived_at_s.is_none(),
            "resolver off must not solve it"
        );
        assert!(o.arrived < 2 * per_side);
        assert_eq!(o.lists_joined, 0);
    }
}

#[test]
fn the_shipped_corridor_lets_a_robot_pass_a_held_one() {
    let s = corridor(4);
    let r = s.kinds()[0].body_radius_m;
    // Lateral offset to pass a robot standing on the centre line, plus what the planner keeps
    // from the wall: 1.0 m + 0.625 m on each side of the centre line.
    let pass = 2.0 * r + s.collision().safety_margin_m.get();
    let to_wall = r + s.navigation().clearance_m.get() + s.navigation().grid_cell_m.get() / 2.0;
    let needed = 2.0 * (pass + to_wall);
    assert!(
        s.arena().height_m.get() >= needed,
        "corridor {} m wide, passing needs {needed} m",
        s.arena().height_m.get()
    );
    // Everyone starts on the centre line, the groups facing each other, 1 m apart in a row.
    let y = s.arena().height_m.get() / 2.0;
    assert!(s.robots().iter().all(|p| p.start_in_world.y == y));
    let goals = swap_goals(&s);
    let xs: Vec<f64> = goals.iter().map(|g| g.x).collect();
    assert_eq!(xs, [22.5, 21.0, 19.5, 18.0, 1.5, 3.0, 4.5, 6.0]);
    assert!(goals.iter().all(|g| g.y == y));
}
