//! `sim.control_period_s`: robots decide every control period and hold their commands in
//! between; a period of one step is the default, bit for bit.

use crate::common;

use common::{corridor, swap_goals};
use usar_sim::scenario::{Positive, Scenario};
use usar_sim::world::{ControlClock, Motion, World};

/// `corridor(per_side)` with a control period of `steps` steps (`None`: no period).
fn with_period(per_side: usize, steps: Option<u32>) -> Scenario {
    corridor(per_side)
        .edit(|s| {
            s.sim.control_period_s =
                steps.map(|k| Positive::new(f64::from(k) * s.sim.dt_s.get()).expect("positive"));
        })
        .unwrap_or_else(|e| panic!("{e}"))
}

/// [`fnv`] of the 8-robot corridor swap's first 1,500 steps ([`trajectory`]) without a control
/// period. Changed (from 15_994_870_929_765_887_161) when robots began to keep their steering
/// side and to stop at the rim of a goal a robot standing still has taken (issue 70: a
/// robot's path no longer depends on the step length).
const GOLDEN_CORRIDOR_SWAP: u64 = 5_521_727_075_073_380_223;

/// f32 bit patterns of every robot's position and velocity at every step of the corridor swap.
fn trajectory(s: &Scenario, steps: usize) -> Vec<u32> {
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(s, &clock);
    for (id, g) in swap_goals(s).iter().enumerate() {
        w.set_goal(id, Some(*g)).expect("goal plans");
        w.set_priority_key(id, (id * 7 % 5) as f64).expect("key");
    }
    let mut bits = Vec::new();
    for _ in 0..steps {
        w.step(&clock);
        for r in w.robots() {
            for v in [r.position.x, r.position.y, r.velocity.x, r.velocity.y] {
                bits.push((v as f32).to_bits());
            }
        }
    }
    bits
}

/// FNV-1a 64 of `bits` (little-endian bytes).
fn fnv(bits: &[u32]) -> u64 {
    bits.iter()
        .flat_map(|b| b.to_le_bytes())
        .fold(0xcbf2_9ce4_8422_2325, |h, b| {
            (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
        })
}

/// The corridor swap without a control period, as the world steps it (this checksum), and an
/// explicit period of one step the same.
#[test]
fn a_period_of_one_step_is_the_model_without_a_period() {
    let none = with_period(4, None);
    let one = with_period(4, Some(1));
    assert_eq!(ControlClock::of(one.sim()).period_steps(), 1);
    let reference = trajectory(&none, 1500);
    assert_eq!(
        fnv(&reference),
        GOLDEN_CORRIDOR_SWAP,
        "the corridor swap without a control period moved"
    );
    assert!(
        reference == trajectory(&one, 1500),
        "a control period of one step changed the corridor swap"
    );
    assert!(
        trajectory(&none, 600) != trajectory(&with_period(4, Some(5)), 600),
        "a control period of five steps changed nothing: the test cannot tell periods apart"
    );
}

#[test]
fn a_goal_set_between_control_steps_is_driven_to_from_the_next_one() {
    for period in [1u64, 5] {
        let s = with_period(1, Some(period as u32));
        let clock = ControlClock::of(s.sim());
        let mut w = World::new(&s, &clock);
        assert_eq!(clock.period_steps(), period);
        let goal = swap_goals(&s)[0];
        w.step(&clock); // step 0 is a control step: no goal yet
        w.set_goal(0, Some(goal)).expect("goal plans");
        let start = w.robot(0).position;
        // Until the next control step the robot keeps its command (standing still).
        while !clock.is_control_step(w.steps()) {
            w.step(&clock);
            assert_eq!(w.robot(0).position, start, "period {period}: moved early");
            assert_eq!(w.robot(0).motion, Motion::Idle, "period {period}");
        }
        assert_eq!(w.stats().steps, period, "period {period}");
        w.step(&clock);
        assert!(
            (w.robot(0).position - start).norm() > 1e-3,
            "period {period}: did not set off at the control step"
        );
        assert_eq!(w.robot(0).motion, Motion::Moving, "period {period}");
    }
}

#[test]
fn commands_change_only_at_control_steps() {
    let s = with_period(4, Some(5));
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(&s, &clock);
    for (id, g) in swap_goals(&s).iter().enumerate() {
        w.set_goal(id, Some(*g)).expect("goal plans");
    }
    let mut last: Vec<(Motion, bool, bool)> = Vec::new();
    let mut changes_between = 0;
    let mut changes_at = 0;
    for _ in 0..1500 {
        let control = clock.is_control_step(w.steps());
        w.step(&clock);
        let now: Vec<(Motion, bool, bool)> = w
            .robots()
            .iter()
            .map(|r| (r.motion, r.held, r.goal_reached))
            .collect();
        if !last.is_empty() && now != last {
            if control {
                changes_at += 1;
            } else {
                changes_between += 1;
            }
        }
        last = now;
    }
    assert_eq!(
        changes_between, 0,
        "a robot's decision changed between control steps"
    );
    assert!(
        changes_at > 5,
        "only {changes_at} control steps changed a decision"
    );
    assert!(
        w.robots().iter().all(|r| r.goal_reached),
        "the corridor swap did not finish with a control period of 0.1 s"
    );
}

#[test]
fn a_goal_is_not_overshot_on_the_last_leg_with_a_control_period() {
    for period in [1u32, 5, 25] {
        let s = with_period(1, Some(period));
        let clock = ControlClock::of(s.sim());
        let mut w = World::new(&s, &clock);
        let start = w.robot(0).position;
        // 3.37 m straight ahead along the corridor, reached within 1 mm.
        let goal = usar_sim::scenario::PointM::new(start.x + 3.37, start.y);
        w.set_goal_within(0, goal, 1e-3).expect("goal plans");
        let mut closest = f64::INFINITY;
        for _ in 0..2000 {
            w.step(&clock);
            let d = (w.robot(0).position - goal).norm();
            closest = closest.min(d);
            // Never past the goal along x (beyond the 1 mm tolerance and f32 rounding).
            assert!(
                w.robot(0).position.x <= goal.x + 1e-3,
                "period {period}: overshot to x = {}",
                w.robot(0).position.x
            );
            if w.robot(0).goal_reached {
                break;
            }
        }
        assert!(
            w.robot(0).goal_reached,
            "period {period}: not reached, closest {closest} m"
        );
        assert!(closest <= 1e-3 + 1e-5, "period {period}: {closest} m");
    }
}

#[test]
fn spot_queries_between_control_steps_see_where_robots_are_now() {
    // 100 steps per control period: at 1.5 m/s robot 0 drives about 3 m before the neighbour
    // index is rebuilt, farther than a cell of the index (2.26 m here) plus its 0.4 m radius,
    // so an index of the positions at the control step would no longer find it near where it
    // stands.
    let s = with_period(1, Some(100));
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(&s, &clock);
    w.set_goal(0, Some(swap_goals(&s)[0])).expect("goal plans");
    let start = w.robot(0).position;
    let radius = w.robot(0).radius_m;
    w.step(&clock); // the control step: robot 0 sets off
    let mut moved = 0.0;
    while !clock.is_control_step(w.steps()) {
        w.step(&clock);
        let here = w.robot(0).position;
        moved = (here - start).norm();
        assert!(
            !w.is_spot_clear(&here, usize::MAX, 0.0),
            "step {}: robot 0's own spot is clear",
            w.stats().steps
        );
        assert_eq!(
            w.is_spot_clear(&start, usize::MAX, 0.0),
            moved > radius,
            "step {}: moved {moved} m",
            w.stats().steps
        );
    }
    assert!(
        moved > 2.26 + radius,
        "moved only {moved} m: the test shows nothing"
    );
}
