//! `sim.physics: NearContacts` ([`crate::scenario::PhysicsStepping`]): whether a contact may
//! begin or go on within the next step ([`World::near_contact`]), and the straight move of every
//! body on a step without one ([`PhysicsScene::move_free`]).

use parry2d::math::Vector as Vec2;
use rapier2d::prelude::RigidBodyHandle;

use super::bodies::PhysicsScene;
use super::world::World;
use crate::scenario::Locomotion;

/// What a body must keep beyond Rapier's contact prediction distance and what the two bodies
/// can close in one step at their commanded speeds for a step to go without Rapier, metres
/// (0.05): a slack for the rounding of positions and for Rapier's fattened boxes.
pub const NEAR_CONTACT_MARGIN_M: f32 = 0.05;

impl World {
    /// Whether some robot may touch a wall, debris (ground robots) or another robot of its
    /// layer within the next step: its gap (distance between the surfaces, negative when they
    /// overlap) is at most what the two can close in a step at their bodies' velocities, plus
    /// Rapier's prediction distance and [`NEAR_CONTACT_MARGIN_M`]. Statics by the clearance
    /// grid first (a cell's clearance less half a diagonal bounds the distance from below), then
    /// exactly; robots through the neighbour index. Stops at the first robot near a contact.
    pub(super) fn near_contact(&self) -> bool {
        let dt = self.dt as f32;
        let bodies = &self.scene.physics.bodies;
        let speed = |body: RigidBodyHandle| bodies[body].linvel().length();
        let slack = self
            .scene
            .physics
            .integration_parameters
            .prediction_distance()
            + NEAR_CONTACT_MARGIN_M;
        let fastest = self
            .nav
            .iter()
            .map(|n| speed(n.body))
            .fold(0.0f32, f32::max);
        let half_diagonal = self.grid.cell_m() * std::f32::consts::SQRT_2;
        for (i, a) in self.nav.iter().enumerate() {
            let va = speed(a.body);
            let reach = va * dt + slack;
            let ground = a.layer == Locomotion::Ground;
            let grid_gap = self.grid.clearance_at(a.pos) - half_diagonal - a.radius;
            if (!ground || grid_gap <= reach)
                && self.scene.static_distance(a.pos, ground) - a.radius <= reach
            {
                return true;
            }
            let others = self.max_radius_m[usize::from(!ground)] as f32;
            let radius = a.radius + others + (va + fastest) * dt + slack;
            let mut near = false;
            self.for_each_near(a.layer, a.pos, radius, |j| {
                let b = &self.nav[j];
                let gap = (b.pos - a.pos).length() - a.radius - b.radius;
                near |= j != i && gap <= (va + speed(b.body)) * dt + slack;
            });
            if near {
                return true;
            }
        }
        false
    }
}

impl PhysicsScene {
    /// Moves every robot's body straight at its velocity for one step (`dt` seconds), as Rapier
    /// moves a body with no contact in reach, without stepping Rapier: the new positions are
    /// written to the bodies (Rapier takes them up at its next step).
    pub fn move_free(&mut self, dt: f32) {
        for &h in &self.robot_bodies {
            let body = &mut self.physics.bodies[h];
            let p: Vec2 = body.translation() + body.linvel() * dt;
            body.set_translation(p, false);
        }
    }

    /// Distance from `p` to the nearest wall, or wall or debris when `with_debris`, metres (0
    /// inside one).
    pub fn static_distance(&self, p: Vec2, with_debris: bool) -> f32 {
        self.statics
            .iter()
            .filter(|o| with_debris || o.is_wall)
            .map(|o| o.distance_to_point(p))
            .fold(f32::INFINITY, f32::min)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scenario::PhysicsStepping;

    fn paper(physics: PhysicsStepping) -> crate::scenario::Scenario {
        let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../../scenarios/paper.ron");
        let mut spec =
            crate::scenario::parse_spec(&std::fs::read_to_string(path).unwrap(), path).unwrap();
        spec.sim.physics = physics;
        spec.validate(path).unwrap()
    }

    /// The robots start in a line at rest, a little apart and away from everything: no contact
    /// is near; one driven at another, or at a wall, is.
    #[test]
    fn a_contact_is_near_only_within_a_steps_closing() {
        let s = paper(PhysicsStepping::NearContacts);
        let mut w = World::new(&s);
        assert!(!w.near_contact(), "robots at rest at their starts");
        let (a, b) = (w.nav[0].clone(), w.nav[1].clone());
        let gap = (b.pos - a.pos).length() - a.radius - b.radius;
        assert!(gap > 0.0);
        // Robot 0 drives at robot 1 fast enough to close the gap within a step.
        let v = (b.pos - a.pos).normalize() * (gap / w.dt as f32 + 0.1);
        w.scene.physics.bodies[a.body].set_linvel(v, true);
        assert!(w.near_contact());
        // Slowly: the gap stays open this step.
        let slow = (b.pos - a.pos).normalize() * 0.01;
        w.scene.physics.bodies[a.body].set_linvel(slow, true);
        let prediction = w.scene.physics.integration_parameters.prediction_distance();
        let reach = 0.01 * w.dt as f32 + prediction + NEAR_CONTACT_MARGIN_M;
        assert_eq!(w.near_contact(), gap <= reach, "gap {gap}, reach {reach}");
    }

    /// With no contact in reach a robot's straight move is Rapier's up to rounding: one robot
    /// driven 1 m across open ground in 100 steps ends within 0.1 mm of where Rapier's 400
    /// substeps of `f32` positions put it (they differ by 0.024 mm).
    #[test]
    fn a_free_move_is_rapiers_up_to_rounding() {
        let mut ends = Vec::new();
        for physics in [PhysicsStepping::EveryStep, PhysicsStepping::NearContacts] {
            let mut w = World::new(&paper(physics));
            let body = w.nav[0].body;
            for _ in 0..100 {
                w.scene.physics.bodies[body].set_linvel(Vec2::new(0.0, 0.5), true);
                if physics == PhysicsStepping::NearContacts && !w.near_contact() {
                    w.scene.move_free(w.dt as f32);
                } else {
                    w.scene.step();
                }
            }
            ends.push(w.scene.physics.bodies[body].translation());
        }
        assert!((ends[0] - ends[1]).length() < 1e-4, "{ends:?}");
        let start = World::new(&paper(PhysicsStepping::EveryStep)).nav[0].pos;
        assert!(
            (ends[1].y - start.y - 1.0).abs() < 1e-4,
            "{start:?} {ends:?}"
        );
    }
}
