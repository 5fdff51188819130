//! Same scenario, same inputs: identical trajectories bit for bit, run twice and inside rayon
//! pools of 1 and 2 threads.

use crate::common;

use common::{corridor, swap_goals};
use usar_sim::scenario::Scenario;
use usar_sim::world::{ControlClock, World};

/// `scenarios/corridor.ron` with 4 robots at each end.
fn corridor_8() -> Scenario {
    corridor(4)
}

/// f32 bit patterns of every robot's position at every step of the 8-robot corridor swap.
fn trajectory(s: &Scenario) -> Vec<u32> {
    let goals = swap_goals(s);
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(s, &clock);
    for (id, g) in goals.iter().enumerate() {
        w.set_goal(id, Some(*g)).unwrap();
        w.set_priority_key(id, (id * 7 % 5) as f64).unwrap();
    }
    let mut bits = Vec::new();
    for _ in 0..1500 {
        w.step(&clock);
        for r in w.robots() {
            bits.push((r.position.x as f32).to_bits());
            bits.push((r.position.y as f32).to_bits());
        }
    }
    bits
}

#[test]
fn trajectories_are_bit_identical() {
    let s = corridor_8();
    let a = trajectory(&s);
    let b = trajectory(&s);
    assert!(a == b, "two runs differ");
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        // Two worlds at once on the pool's threads.
        let (c, d) = pool.install(|| rayon::join(|| trajectory(&s), || trajectory(&s)));
        assert!(a == c && a == d, "runs on a {threads}-thread pool differ");
    }
}
