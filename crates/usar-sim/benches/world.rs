//! World step cost: the 12-robot paper-like world (`scenarios/paper.ron`: 80 m x 60 m, 6
//! carriers + 4 suppliers on the ground, 2 aerial observers) with goals far away, against the
//! same bodies and colliders stepped by bare Rapier (no navigation, no resolver).

use std::hint::black_box;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use usar_sim::scenario::{self, Scenario};
use usar_sim::world::bodies::{PhysicsScene, to_vec2};
use usar_sim::world::{ControlClock, World};

fn paper() -> Scenario {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
    scenario::load(path).expect("scenarios/paper.ron loads")
}

/// Far goal of robot `id` at a given leg: alternate between the two tasks' goals.
fn far_goal(s: &Scenario, id: usize, leg: usize) -> usar_sim::scenario::PointM {
    s.tasks()[(id + leg) % 2].goal
}

fn bench(c: &mut Criterion) {
    let s = paper();
    let mut group = c.benchmark_group("world_step_12_robots");
    group.throughput(Throughput::Elements(1));

    let clock = ControlClock::of(s.sim());
    let mut world = World::new(&s, &clock);
    let mut legs = vec![0usize; s.robots().len()];
    for id in 0..s.robots().len() {
        world.set_goal(id, Some(far_goal(&s, id, 0))).unwrap();
    }
    group.bench_function("world_with_logic", |b| {
        b.iter(|| {
            world.step(&clock);
            for (id, leg) in legs.iter_mut().enumerate() {
                if world.robot(id).goal_reached {
                    *leg += 1;
                    let _ = world.set_goal(id, Some(far_goal(&s, id, *leg)));
                }
            }
            black_box(world.robot(0).position);
        })
    });

    let mut bare = PhysicsScene::new(&s);
    for (id, r) in s.robots().iter().enumerate() {
        let v = to_vec2(&far_goal(&s, id, 0)) - to_vec2(&r.start_in_world);
        let speed = s.kinds()[r.kind].max_speed_m_per_s as f32;
        let body = &mut bare.physics.bodies[bare.robot_bodies[id]];
        body.set_linvel(v.normalize() * speed, true);
    }
    group.bench_function("bare_rapier", |b| {
        b.iter(|| {
            bare.step();
            black_box(bare.physics.bodies[bare.robot_bodies[0]].translation());
        })
    });
    // Floor: the same bodies at rest (no contacts at all).
    let mut rest = PhysicsScene::new(&s);
    group.bench_function("bare_rapier_at_rest", |b| {
        b.iter(|| {
            rest.step();
            black_box(rest.physics.bodies[rest.robot_bodies[0]].translation());
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
