//! Same scenario, same inputs: identical trajectories bit for bit, run twice and inside rayon
//! pools of 1 and 2 threads.

use usar_sim::world::{World, fixtures};

/// f32 bit patterns of every robot's position at every step of the 8-robot corridor swap.
fn trajectory() -> Vec<u32> {
    let s = fixtures::corridor(4);
    let goals = fixtures::corridor_goals(&s);
    let mut w = World::new(&s);
    for (id, g) in goals.iter().enumerate() {
        w.set_goal(id, Some(*g)).unwrap();
        w.set_priority_key(id, (id * 7 % 5) as f64).unwrap();
    }
    let mut bits = Vec::new();
    for _ in 0..1500 {
        w.step();
        for r in w.robots() {
            bits.push((r.position.x as f32).to_bits());
            bits.push((r.position.y as f32).to_bits());
        }
    }
    bits
}

#[test]
fn trajectories_are_bit_identical() {
    let a = trajectory();
    let b = trajectory();
    assert!(a == b, "two runs differ");
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        // Two worlds at once on the pool's threads.
        let (c, d) = pool.install(|| rayon::join(trajectory, trajectory));
        assert!(a == c && a == d, "runs on a {threads}-thread pool differ");
    }
}
