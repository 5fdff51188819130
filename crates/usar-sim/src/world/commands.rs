//! Commanded velocities replayed: the write rule of the velocity each robot's body was driven
//! at in the last step ([`World::commanded_velocities`](super::World::commanded_velocities),
//! in `world.rs`) for a bare [`PhysicsScene`], so a trial's motion can be replayed on bare
//! Rapier (the scaling bench's baseline, `crates/usar-sim/benches/scale`).
//!
//! Not in the paper; nothing here changes a result (it writes only the bare scene it is given).

use parry2d::math::Vector as Vec2;

use super::bodies::PhysicsScene;

/// Drives the robot bodies of `scene` at `commands` (m/s, one per robot in id order, as
/// [`World::commanded_velocities`](super::World::commanded_velocities) gives them) with
/// [`World::step`](super::World::step)'s write rule: a body's
/// velocity is written only where it differs from the command (a write queues the body for
/// Rapier's pass over user-modified bodies). Robots beyond the shorter of the two lists are
/// left as they are. Call [`PhysicsScene::step`] after it.
pub fn drive_bodies(scene: &mut PhysicsScene, commands: &[Vec2]) {
    for (i, &command) in commands.iter().enumerate().take(scene.robot_bodies.len()) {
        scene.drive_body(scene.robot_bodies[i], command);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::{self, PointM, Scenario};
    use crate::world::bodies::to_point;
    use crate::world::{ControlClock, World};

    /// `scenarios/corridor.ron` (two pairs of ground robots that must pass each other in a
    /// 3.4 m wide corridor) with the given control period.
    fn corridor(control_period_s: Option<f64>) -> Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/corridor.ron");
        let src = std::fs::read_to_string(path).expect("corridor.ron");
        let mut spec = scenario::parse_spec(&src, path).expect("parses");
        spec.sim.control_period_s =
            control_period_s.map(|p| scenario::Positive::new(p).expect("> 0"));
        spec.validate(path).expect("valid")
    }

    #[test]
    fn no_velocity_is_commanded_before_the_first_step() {
        let s = corridor(None);
        let w = World::new(&s, &ControlClock::of(&s.sim));
        assert_eq!(w.commanded_velocities().len(), 4);
        assert!(w.commanded_velocities().all(|v| v == Vec2::ZERO));
    }

    /// The corridor's robots drive to the far ends through each other (the resolver holds and
    /// steers them, Rapier pushes them apart); a bare scene driven by the recorded commands
    /// has every body at the world's position, bit for bit, after every step, at every step
    /// and at a 0.1 s control period.
    #[test]
    fn replayed_commands_move_a_bare_scene_as_the_world() {
        for period in [None, Some(0.1)] {
            let s = corridor(period);
            let clock = ControlClock::of(&s.sim);
            let mut w = World::new(&s, &clock);
            let mut bare = PhysicsScene::new(&s);
            for id in 0..4 {
                let x = if id < 2 { 22.5 } else { 1.5 };
                w.set_goal(id, Some(PointM::new(x, 1.7))).expect("plans");
            }
            let (mut commands, mut moving, mut stopped) = (Vec::new(), 0, 0);
            for step in 0..800 {
                w.step(&clock);
                commands.clear();
                commands.extend(w.commanded_velocities());
                moving += commands.iter().filter(|v| v.length() > 0.5).count();
                stopped += commands.iter().filter(|v| **v == Vec2::ZERO).count();
                drive_bodies(&mut bare, &commands);
                bare.step();
                for (id, &body) in bare.robot_bodies.iter().enumerate() {
                    let p = to_point(bare.physics.bodies[body].translation());
                    assert_eq!(
                        p,
                        w.robot(id).position,
                        "robot {id}, step {step}, {period:?}"
                    );
                }
            }
            // The replay covered real motion: robots drove, and some were held or arrived.
            assert!(
                moving > 1000 && stopped > 0,
                "{moving} {stopped} {period:?}"
            );
            assert!(
                w.robots()[..2].iter().all(|r| r.position.x > 12.0),
                "{period:?}"
            );
        }
    }
}
