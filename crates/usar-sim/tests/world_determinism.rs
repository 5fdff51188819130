//! Same scenario, same inputs: identical trajectories bit for bit, run twice and inside rayon
//! pools of 1 and 2 threads.

use usar_sim::scenario::{self, PointM, Scenario, TaskLevel};
use usar_sim::world::World;

/// The shipped corridor scenario.
const CORRIDOR: &str = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/corridor.ron");

/// `scenarios/corridor.ron` with 4 robots at each end.
fn corridor_8() -> Scenario {
    let src = std::fs::read_to_string(CORRIDOR).expect("scenarios/corridor.ron");
    let mut spec = scenario::parse_spec(&src, CORRIDOR).unwrap_or_else(|e| panic!("{e}"));
    for k in &mut spec.kinds {
        k.count = 4;
    }
    spec.kinds[0].quota.easy = 4;
    spec.kinds[1].quota.hard = 4;
    spec.validate("corridor.ron (4 per end)")
        .unwrap_or_else(|e| panic!("{e}"))
}

/// Swap goals 1.5 m apart at the far ends, front robot deepest (as in `world_corridor.rs`).
fn swap_goals(s: &Scenario) -> Vec<PointM> {
    let easy = s.task(TaskLevel::Easy).goal;
    let hard = s.task(TaskLevel::Hard).goal;
    let mut seen = [0usize; 2];
    s.robots
        .iter()
        .map(|r| {
            let k = seen[r.kind] as f64;
            seen[r.kind] += 1;
            match r.kind {
                0 => PointM::new(easy.x - 1.5 * k, easy.y),
                _ => PointM::new(hard.x + 1.5 * k, hard.y),
            }
        })
        .collect()
}

/// f32 bit patterns of every robot's position at every step of the 8-robot corridor swap.
fn trajectory(s: &Scenario) -> Vec<u32> {
    let goals = swap_goals(s);
    let mut w = World::new(s);
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
