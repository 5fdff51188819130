//! `World::step_beside`: every robot is handed over once a step, either to the work beside the
//! step (under `sim.physics: NearBodies`, the robots far from any contact, beside Rapier's step
//! on a parallel team) or after it (`World::read_back_rest`), each with its state of that step;
//! and the world steps as `World::step` does.

use usar_sim::scenario::{PhysicsStepping, PointM, Scenario};
use usar_sim::world::{ControlClock, World};

fn scenario(file: &str) -> Scenario {
    let path = format!("{}/../../scenarios/{file}", env!("CARGO_MANIFEST_DIR"));
    usar_sim::scenario::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// Each robot's position and velocity as bits.
fn bits(w: &World) -> Vec<[u64; 4]> {
    (w.robots().iter())
        .map(|r| {
            let (p, v) = (r.position, r.velocity);
            [p.x.to_bits(), p.y.to_bits(), v.x.to_bits(), v.y.to_bits()]
        })
        .collect()
}

/// Steps two worlds of `s` side by side for `steps` steps, every robot sent to one of two
/// points across the arena: one with `World::step`, one with `World::step_beside`. Checks that
/// each step hands every robot over exactly once, with the state the step leaves it in, and
/// that both worlds move alike; returns how many robots were handed over after the step.
fn hand_over(s: &Scenario, steps: usize) -> usize {
    let clock = ControlClock::of(s.sim());
    let (mut plain, mut split) = (World::new(s, &clock), World::new(s, &clock));
    let (w, h) = (s.arena().width_m.get(), s.arena().height_m.get());
    let goals = [PointM::new(0.3 * w, 0.7 * h), PointM::new(0.7 * w, 0.6 * h)];
    for id in 0..s.robots().len() {
        let goal = Some(goals[id % 2]);
        let _ = (plain.set_goal(id, goal), split.set_goal(id, goal));
    }
    let n = s.robots().len();
    // Five pairs of robots side by side, their bodies almost touching: near a contact.
    for k in 0..5 {
        let (a, b) = (2 * k, 2 * k + 1);
        let p = plain.robot(a).position;
        let gap = plain.robot(a).radius_m + plain.robot(b).radius_m + 0.05;
        let q = PointM::new(p.x + gap, p.y);
        for world in [&mut plain, &mut split] {
            world.teleport(b, q).expect("in the arena");
        }
    }
    let mut after_total = 0;
    for step in 0..steps {
        plain.step(&clock);
        assert!(
            (0..n).all(|id| plain.read_back_rest().covers(id)),
            "after step() every robot is left to read_back_rest"
        );
        let mut seen: Vec<Option<[u64; 4]>> = vec![None; n];
        split.step_beside(&clock, |read| {
            for (id, r) in read.robots().iter().enumerate() {
                if read.covers(id) {
                    let (p, v) = (r.position, r.velocity);
                    seen[id] = Some([p.x.to_bits(), p.y.to_bits(), v.x.to_bits(), v.y.to_bits()]);
                }
            }
        });
        let now = bits(&split);
        let rest = split.read_back_rest();
        for id in 0..n {
            let after = rest.covers(id);
            assert_ne!(
                seen[id].is_some(),
                after,
                "step {step}, robot {id}: handed over once"
            );
            if let Some(b) = seen[id] {
                assert_eq!(b, now[id], "step {step}, robot {id}: its state of the step");
            }
            after_total += usize::from(after);
        }
        // The shortcuts a pass over the rest takes: the near robots listed, or nobody left.
        if let Some(ids) = rest.near_ids() {
            let listed: Vec<usize> = ids.collect();
            let covered: Vec<usize> = (0..n).filter(|&id| rest.covers(id)).collect();
            assert_eq!(
                listed, covered,
                "step {step}: near_ids lists the robots left"
            );
        }
        if rest.covers_none() {
            assert!(
                (0..n).all(|id| !rest.covers(id)),
                "step {step}: nobody left"
            );
        }
        let physics = s.sim().physics;
        assert_eq!(
            rest.covers_none(),
            physics != PhysicsStepping::NearBodies,
            "step {step}: nobody is left but after NearBodies' step ({physics:?})"
        );
        assert_eq!(
            rest.near_ids().is_some(),
            physics == PhysicsStepping::NearBodies
        );
        assert_eq!(bits(&plain), now, "step {step}: the same bits as step()");
    }
    after_total
}

#[test]
fn step_beside_hands_every_robot_over_once_with_its_state() {
    let s = scenario("swarm-1000.ron");
    assert_eq!(s.sim().physics, PhysicsStepping::NearBodies);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let near = pool.install(|| hand_over(&s, 150));
    assert!(
        near > 0,
        "some robots came near a contact and were read back after the step"
    );
    // Another stepping: the whole read-back is handed over after it, nothing is left.
    let every = s
        .edit(|spec| spec.sim.physics = PhysicsStepping::EveryStep)
        .unwrap();
    assert_eq!(pool.install(|| hand_over(&every, 20)), 0);
}

/// Every robot's dose factor is the factor at its position after every step: for a robot that
/// drives into a radiation zone (its factor recomputed as it moves), for one standing still
/// inside a zone (whose factor the read-back keeps rather than recomputes) and for one moved
/// there between steps.
#[test]
fn each_dose_factor_is_the_factor_at_the_robots_position() {
    let s = scenario("swarm-1000.ron");
    let zone = s.radiation_zones()[0].area;
    let (c, r) = (zone.center, zone.radius_m);
    let clock = ControlClock::of(s.sim());
    let mut world = World::new(&s, &clock);
    let (w, h) = (s.arena().width_m.get(), s.arena().height_m.get());
    for id in 3..s.robots().len() {
        let _ = world.set_goal(id, Some(PointM::new(0.5 * w, 0.5 * h)));
    }
    // Robot 0 just outside the zone's rim, sent to its centre; robot 1 standing inside it.
    world
        .teleport(0, PointM::new(c.x - r - 0.5, c.y))
        .expect("in the arena");
    world
        .set_goal(0, Some(c))
        .expect("the zone's centre is reachable");
    world.teleport(1, c).expect("in the arena");
    assert_eq!(
        world.radiation_factor(0),
        0.0,
        "robot 0 starts outside the zone"
    );
    let check = |world: &World, step: usize| {
        for (id, r) in world.robots().iter().enumerate() {
            let want = world.radiation_factor_at(&r.position);
            assert_eq!(
                world.radiation_factor(id).to_bits(),
                want.to_bits(),
                "step {step}, robot {id} at {:?}",
                r.position
            );
        }
    };
    for step in 0..150 {
        world.step(&clock);
        check(&world, step);
        if step == 30 {
            // Robot 2 moved into the zone between steps, then standing still there.
            world
                .teleport(2, PointM::new(c.x + 1.0, c.y))
                .expect("in the arena");
        }
    }
    assert!(
        world.radiation_factor(0) > 0.0,
        "robot 0 drove into the zone"
    );
    assert!(
        world.radiation_factor(1) > 0.0,
        "robot 1 stands in the zone"
    );
    assert!(
        world.radiation_factor(2) > 0.0,
        "robot 2 stands in the zone"
    );
}
