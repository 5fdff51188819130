//! `sim.physics: NearContacts` and `NearBodies` ([`crate::scenario::PhysicsStepping`]):
//! whether a contact may begin or go on within the next step, for the team
//! ([`ContactGate::near_contact`]) or robot by robot ([`ContactGate::mark_near_bodies`], in
//! parallel for a large team; the World calls both through its thin methods of the same
//! names); the straight move
//! of every body on a step without one ([`PhysicsScene::move_free`]); and the bodies enabled
//! in Rapier only while their robots are near a contact ([`PhysicsScene::gate_bodies`]).

use parry2d::math::Vector as Vec2;

use rayon::prelude::*;

use super::bodies::PhysicsScene;
use super::clearance_grid::ClearanceGrid;
use super::nav_state::{Nav, for_each_near};
use super::neighbour_lists::NeighbourLists;
use super::neighbours::NeighbourIndex;
use super::per_robot::CHUNK_ROBOTS;
use crate::scenario::Locomotion;

/// What a body must keep beyond Rapier's contact prediction distance and what the two bodies
/// can close in one step at their commanded speeds for a step to go without Rapier, metres
/// (0.05): a slack for the rounding of positions and for Rapier's fattened boxes.
pub const NEAR_CONTACT_MARGIN_M: f32 = 0.05;

/// What [`PhysicsScene::static_within`] adds to the reach before it skips an obstacle by its
/// bounding box, and the gate to half a cell's diagonal before it trusts the clearance grid's
/// bound, metres (1 mm): far above the rounding of a box's distance or of a cell's clearance,
/// so a skipped obstacle is one the exact distance would have found out of reach too.
const BOX_SKIP_MARGIN_M: f32 = 1e-3;

/// What the gate adds to a robot's query radius, relative, before it skips a robot by its
/// indexed position (1e-5, with [`BOX_SKIP_MARGIN_M`]): far above the rounding of a distance,
/// so a skipped robot is one the exact test would have found out of reach too.
const PAIR_SKIP_REL: f32 = 1e-5;

/// Skin of the gate's neighbour lists (`sim.physics: NearBodies`), metres (0.5): the lists
/// hold every robot within the gate's largest query radius plus this of a robot, and stay
/// valid until some robot has moved about half of it (`neighbour_lists.rs`); a larger skin
/// means longer lists and fewer rebuilds. Any skin gives the same answers.
pub const GATE_LIST_SKIN_M: f32 = 0.5;

/// What the gate's lists add to the largest query radius, metres (1 mm): a robot's own
/// radius and speed are at most its layer's largest and the team's fastest, and this covers
/// the rounding of the distances the lists are built and kept on.
const GATE_LIST_MARGIN_M: f32 = 1e-3;

/// The state the contact gate reads on one step, borrowed from the world: the robots'
/// navigation states (by id), the clearance grid, the physics scene (bodies and statics), each
/// layer's largest body radius (ground, aerial; metres) and the step (seconds).
pub(super) struct GateInputs<'a> {
    pub(super) nav: &'a [Nav],
    pub(super) grid: &'a ClearanceGrid,
    pub(super) scene: &'a PhysicsScene,
    pub(super) max_radius_m: [f64; 2],
    pub(super) dt_s: f64,
}

/// The contact gate's stage (`sim.physics: NearContacts` and `NearBodies`): it owns only
/// what it keeps between steps (its neighbour lists, each robot's last clearance reading) and
/// its scratch, and reads the world through [`GateInputs`] (the shape of Rapier's
/// `PhysicsPipeline::step`, which takes the sets it works on as arguments).
#[derive(Debug, Clone)]
pub(super) struct ContactGate {
    /// Each robot's disc and speed on this step, by id.
    discs: Vec<GateDisc>,
    /// Where each robot last read the clearance grid and what it read there, metres, by id.
    clearance: Vec<(Vec2, f32)>,
    /// The gate's neighbour lists, kept over several steps.
    lists: NeighbourLists,
    /// Both robots of each pair found near whose lower id is in the chunk, for each chunk of
    /// [`CHUNK_ROBOTS`] robots, by chunk.
    partners: Vec<Vec<usize>>,
}

impl Default for ContactGate {
    fn default() -> Self {
        Self {
            discs: Vec::new(),
            clearance: Vec::new(),
            lists: NeighbourLists::with_skin(GATE_LIST_SKIN_M),
            partners: Vec::new(),
        }
    }
}

impl ContactGate {
    /// Whether some robot may touch a wall, debris (ground robots) or another robot of its
    /// layer within the next step ([`GateView::robot_near_contact`] of each robot, by id).
    /// The robots near each robot come from the gate's neighbour lists, as for
    /// [`ContactGate::mark_near_bodies`] (`neighbours` is rebuilt for them when they are
    /// rebuilt and `index_fresh` is false, which it then sets): the same answer as a scan of
    /// every robot, in time linear in the team. Stops at the first robot near a contact.
    pub(super) fn near_contact(
        &mut self,
        w: &GateInputs,
        neighbours: &mut NeighbourIndex,
        index_fresh: &mut bool,
    ) -> bool {
        let gate = self.gate(w, false);
        self.refresh_lists(w, &gate, neighbours, index_fresh, false);
        let view = GateView::new(w, &gate, Some(&self.lists), None);
        let near = (0..w.nav.len()).any(|i| {
            let mut clearance = UNREAD;
            view.robot_near_contact(i, &mut clearance, |_| {})
        });
        self.discs = gate.discs;
        near
    }

    /// `sim.physics: NearBodies`: marks in `near[id]` whether robot `id` may touch a wall,
    /// debris or another robot within the next step ([`GateView::robot_near_contact`]; both
    /// robots of a pair found near from either side are marked); returns whether any may.
    /// `near` holds one flag per robot. Each robot first writes whether it is near a static
    /// ([`GateView::near_static`]); then each pair of robots is tested once, by its lower id,
    /// with the answers of both sides ([`GateView::pairs_above`]), its two robots listed in
    /// their chunk's list, and the lists are marked in chunk order. These are the flags of a
    /// test of every robot from its own side, marked with its partners, at half the pair
    /// tests. With `parallel` both passes run on the calling rayon pool: the same flags on any
    /// number of threads (each robot writes its own static flag; the marking only sets
    /// flags). The robots near each robot come from the gate's neighbour lists
    /// ([`ContactGate::refresh_lists`]; `neighbours` is rebuilt for them when they are
    /// rebuilt and `index_fresh` is false, which it then sets).
    pub(super) fn mark_near_bodies(
        &mut self,
        w: &GateInputs,
        neighbours: &mut NeighbourIndex,
        index_fresh: &mut bool,
        parallel: bool,
        near: &mut [bool],
    ) -> bool {
        let gate = self.gate(w, parallel);
        self.refresh_lists(w, &gate, neighbours, index_fresh, parallel);
        let chunks = near.len().div_ceil(CHUNK_ROBOTS).max(1);
        let mut partners = std::mem::take(&mut self.partners);
        if partners.len() < chunks {
            partners.resize_with(chunks, Vec::new);
        }
        let mut cache = std::mem::take(&mut self.clearance);
        cache.resize(near.len(), UNREAD);
        let view = GateView::new(w, &gate, Some(&self.lists), None);
        // First each robot's statics, then each pair once, by its lower id, reading both
        // robots' statics flags.
        type Chunk<'a> = (usize, (&'a mut [bool], &'a mut [(Vec2, f32)]));
        let statics_chunk = |(c, (out, cached)): Chunk<'_>| {
            for (k, (o, cached)) in out.iter_mut().zip(cached).enumerate() {
                *o = view.near_static(c * CHUNK_ROBOTS + k, cached);
            }
        };
        if parallel {
            near.par_chunks_mut(CHUNK_ROBOTS)
                .zip(cache.par_chunks_mut(CHUNK_ROBOTS))
                .enumerate()
                .with_max_len(1)
                .for_each(statics_chunk);
        } else {
            near.chunks_mut(CHUNK_ROBOTS)
                .zip(cache.chunks_mut(CHUNK_ROBOTS))
                .enumerate()
                .for_each(statics_chunk);
        }
        let static_near: &[bool] = near;
        let pairs_chunk = |(c, found): (usize, &mut Vec<usize>)| {
            found.clear();
            let robots = c * CHUNK_ROBOTS..((c + 1) * CHUNK_ROBOTS).min(static_near.len());
            for i in robots {
                if view.pairs_above(i, &self.lists, static_near, |j| found.push(j)) {
                    found.push(i);
                }
            }
        };
        let used = &mut partners[..chunks];
        if parallel {
            used.par_iter_mut()
                .enumerate()
                .with_max_len(1)
                .for_each(pairs_chunk);
        } else {
            used.iter_mut().enumerate().for_each(pairs_chunk);
        }
        for &j in partners.iter().take(chunks).flatten() {
            near[j] = true;
        }
        let any = near.contains(&true);
        self.partners = partners;
        self.clearance = cache;
        self.discs = gate.discs;
        any
    }

    /// Makes the gate's neighbour lists valid for every robot's query radius this step, the
    /// largest being a robot of its layer's largest radius at the team's fastest speed (plus
    /// [`GATE_LIST_MARGIN_M`]): rebuilt from `neighbours` (rebuilt first unless
    /// `index_fresh`) only when some robot has moved too far since the last rebuild
    /// (`neighbour_lists.rs`), on the rayon pool when `parallel`.
    fn refresh_lists(
        &mut self,
        w: &GateInputs,
        gate: &Gate,
        neighbours: &mut NeighbourIndex,
        index_fresh: &mut bool,
        parallel: bool,
    ) {
        let closing_m = (gate.fastest_m_per_s + gate.fastest_m_per_s) * w.dt_s as f32;
        let query_m = w.max_radius_m.map(|r| {
            let r = r as f32;
            let radius = r + r + closing_m + gate.slack_m;
            radius * (1.0 + PAIR_SKIP_REL) + BOX_SKIP_MARGIN_M + GATE_LIST_MARGIN_M
        });
        self.lists.set_parallel(parallel);
        if self.lists.stale(w.nav, query_m) {
            if !*index_fresh {
                neighbours.rebuild(w.nav.iter().map(|n| (n.layer, n.pos)), parallel);
                *index_fresh = true;
            }
            self.lists.rebuild(w.nav, neighbours);
        }
    }

    /// What every robot's gate shares on one step: each robot's disc and speed, the fastest,
    /// and the slack every gap is allowed (Rapier's prediction distance and
    /// [`NEAR_CONTACT_MARGIN_M`]). A robot's speed is the larger of its command's and its
    /// body's: with `NearContacts` the bodies were driven at the commands before the gate, so
    /// the two are one; with `NearBodies` a body Rapier pushed last step may still move faster
    /// than its command. The discs are filled in parallel when `parallel`.
    fn gate(&mut self, w: &GateInputs, parallel: bool) -> Gate {
        let mut discs = std::mem::take(&mut self.discs);
        discs.resize(w.nav.len(), GateDisc::default());
        let disc = |(d, n): (&mut GateDisc, &Nav)| {
            *d = GateDisc {
                pos: n.pos,
                radius_m: n.radius,
                speed_m_per_s: n.command.length().max(n.body_speed_m_per_s),
            };
        };
        if parallel {
            discs
                .par_iter_mut()
                .zip(w.nav)
                .with_min_len(CHUNK_ROBOTS)
                .with_max_len(CHUNK_ROBOTS)
                .for_each(disc);
        } else {
            discs.iter_mut().zip(w.nav).for_each(disc);
        }
        Gate {
            slack_m: w.scene.physics.integration_parameters.prediction_distance()
                + NEAR_CONTACT_MARGIN_M,
            fastest_m_per_s: discs.iter().map(|d| d.speed_m_per_s).fold(0.0f32, f32::max),
            discs,
        }
    }
}

/// What every robot's gate shares on one step (see [`GateView::robot_near_contact`]).
struct Gate {
    slack_m: f32,
    fastest_m_per_s: f32,
    /// Each robot's disc and speed this step, by id: what a robot's pair test reads of the
    /// others, packed (16 bytes a robot) rather than read from their navigation states.
    discs: Vec<GateDisc>,
}

/// A robot as the gate's pair test reads it: its centre and radius (its [`Nav`]'s, metres)
/// and its speed (the larger of its command's and its body's, m/s).
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct GateDisc {
    pos: Vec2,
    radius_m: f32,
    speed_m_per_s: f32,
}

/// A robot's last clearance reading before its first: at no position (a NaN distance from
/// it never bounds anything).
const UNREAD: (Vec2, f32) = (Vec2::NAN, 0.0);

/// What the gate allows for the rounding of a robot's distance from where it last read the
/// clearance grid, metres (1 mm).
const MOVED_MARGIN_M: f32 = 1e-3;

/// What one robot's gate reads, borrowed for one step (nothing in it is written while the
/// robots are tested, so they may be tested on any thread in any order).
struct GateView<'a> {
    /// The gate's neighbour lists, current for this step, if any: each robot's list holds
    /// every robot its test could find (then neither `index` nor a scan is used).
    lists: Option<&'a NeighbourLists>,
    nav: &'a [Nav],
    grid: &'a ClearanceGrid,
    scene: &'a PhysicsScene,
    /// The neighbour index while it holds the robots' positions, else `None` (every robot of
    /// the layer is a candidate: [`for_each_near`]).
    index: Option<&'a NeighbourIndex>,
    max_radius_m: [f64; 2],
    dt: f32,
    gate: &'a Gate,
}

impl<'a> GateView<'a> {
    fn new(
        w: &GateInputs<'a>,
        gate: &'a Gate,
        lists: Option<&'a NeighbourLists>,
        index: Option<&'a NeighbourIndex>,
    ) -> Self {
        GateView {
            lists,
            nav: w.nav,
            grid: w.grid,
            scene: w.scene,
            index,
            max_radius_m: w.max_radius_m,
            dt: w.dt_s as f32,
            gate,
        }
    }
}

impl GateView<'_> {
    /// Whether robot `i` may touch a wall, debris (ground robots) or another robot of its
    /// layer within the next step: its gap (distance between the surfaces, negative when they
    /// overlap) is at most what the two can close in a step at their speeds ([`Gate`]), plus
    /// Rapier's prediction distance and [`NEAR_CONTACT_MARGIN_M`]. Statics first
    /// ([`GateView::near_static`], `clearance` the robot's last reading; a robot near one
    /// stops there), then every robot of its layer, each from this robot's side
    /// ([`GateView::pair_near`]): through the gate's lists (`NearContacts`'
    /// [`ContactGate::near_contact`]), else the neighbour index, else a scan of the layer,
    /// calling `partner(j)` for each robot `j` found near (the test of a pair is the same from
    /// both sides up to rounding). The lists hold robots of the robot's own layer only (they
    /// are built from the per-layer index). `NearBodies` tests each pair once instead
    /// ([`GateView::pairs_above`]); this is also the tests' reference for it.
    fn robot_near_contact(
        &self,
        i: usize,
        clearance: &mut (Vec2, f32),
        mut partner: impl FnMut(usize),
    ) -> bool {
        if self.near_static(i, clearance) {
            return true;
        }
        let (a, disc) = (&self.nav[i], &self.gate.discs[i]);
        let (radius, bound) = self.pair_reach(i);
        let mut near = false;
        let mut test = |j: usize, q: Vec2| {
            if j == i || (q - a.pos).length_squared() > bound * bound {
                return;
            }
            debug_assert_eq!(self.nav[j].layer, a.layer, "a list holds its own layer");
            if self.pair_near(disc, &self.gate.discs[j]) {
                near = true;
                partner(j);
            }
        };
        match (self.lists, self.index) {
            (Some(lists), _) => lists
                .of(i)
                .iter()
                .for_each(|&j| test(j, self.gate.discs[j].pos)),
            (None, Some(index)) => index.grid(a.layer).for_each_candidate(a.pos, radius, test),
            (None, None) => for_each_near(self.nav, None, a.layer, a.pos, radius, |j| {
                test(j, self.nav[j].pos)
            }),
        }
        near
    }

    /// Whether robot `i` may touch a wall or (ground robots) debris within the next step: by
    /// the clearance grid first (a cell's clearance less half a diagonal bounds the distance
    /// from below), then exactly.
    ///
    /// `clearance` is where the robot last read the (static) clearance grid and what it read
    /// there, overwritten whenever the grid is read: while the distance from there, taken off
    /// that reading, still bounds its gap to the statics above its reach, the grid is not read
    /// again (with the gate's kept readings, a robot in open ground reads it every few dozen
    /// steps instead of every step). The bound only decides whether the exact test runs, and
    /// the exact test answers "no" whenever a bound is above the reach, so the answers are
    /// those of reading the grid every step.
    fn near_static(&self, i: usize, clearance: &mut (Vec2, f32)) -> bool {
        // A point lies within half a diagonal of its cell's centre; the margin covers rounding.
        let half_diagonal =
            self.grid.cell_m() * std::f32::consts::FRAC_1_SQRT_2 + BOX_SKIP_MARGIN_M;
        let a = &self.nav[i];
        let reach = self.gate.discs[i].speed_m_per_s * self.dt + self.gate.slack_m;
        let ground = a.layer == Locomotion::Ground;
        let moved = (a.pos - clearance.0).length() + MOVED_MARGIN_M;
        // `!(x > reach)`, not `x <= reach`: a NaN (no reading yet) reads the grid.
        let open = ground && clearance.1 - half_diagonal - moved - a.radius > reach;
        if open {
            return false;
        }
        if ground {
            *clearance = (a.pos, self.grid.clearance_at(a.pos));
        }
        let grid_gap = clearance.1 - half_diagonal - a.radius;
        (!ground || grid_gap <= reach) && self.scene.static_within(a.pos, ground, a.radius, reach)
    }

    /// Robot `i`'s query radius for other robots (its radius, its layer's largest, what the two
    /// can close in a step at its speed and the team's fastest, and the slack; metres) and
    /// the distance beyond which a robot is skipped before its state is read: that radius and
    /// a margin far above rounding, so a skipped robot fails [`GateView::pair_near`] from
    /// either side too (every robot's radius is at most its layer's largest, and its speed at
    /// most the team's fastest).
    fn pair_reach(&self, i: usize) -> (f32, f32) {
        let (a, gate) = (&self.nav[i], self.gate);
        let others = self.max_radius_m[usize::from(a.layer != Locomotion::Ground)] as f32;
        let va = gate.discs[i].speed_m_per_s;
        let radius = a.radius + others + (va + gate.fastest_m_per_s) * self.dt + gate.slack_m;
        (radius, radius * (1.0 + PAIR_SKIP_REL) + BOX_SKIP_MARGIN_M)
    }

    /// Whether robot `a` (read from its own side) may touch robot `b` within the next step:
    /// their gap is at most what the two can close in a step, plus the slack.
    fn pair_near(&self, a: &GateDisc, b: &GateDisc) -> bool {
        let gap = (b.pos - a.pos).length() - a.radius_m - b.radius_m;
        gap <= (a.speed_m_per_s + b.speed_m_per_s) * self.dt + self.gate.slack_m
    }

    /// The pairs of robot `i` with the robots above it in its list, each pair tested once, by
    /// its lower id, with the answers of [`GateView::robot_near_contact`] from both sides:
    /// `static_near` holds every robot's [`GateView::near_static`], and a robot near a static
    /// tests no pair from its side (it stops there), so the pair `(i, j)` is near when `i` is
    /// not near a static and finds `j` near from its side, or `j` is not and finds `i`. Calls
    /// `partner(j)` for each `j` so found; returns whether there was one. Only `i`'s bound
    /// skips robots ([`GateView::pair_reach`]: it covers either side's test), and every pair
    /// that can pass is in the lists (both robots within the query radius of each other), so
    /// marked
    /// with `i` and its partners for every `i`, the flags are those of
    /// [`GateView::robot_near_contact`] of every robot marked with its partners, bit for bit
    /// (the two sides differ only in the order the radii are taken off the distance).
    fn pairs_above(
        &self,
        i: usize,
        lists: &NeighbourLists,
        static_near: &[bool],
        mut partner: impl FnMut(usize),
    ) -> bool {
        let discs = &self.gate.discs;
        let (a, bound) = (&discs[i], self.pair_reach(i).1);
        let mut near = false;
        for &j in lists.above(i) {
            let b = &discs[j];
            if (b.pos - a.pos).length_squared() > bound * bound {
                continue;
            }
            debug_assert_eq!(
                self.nav[j].layer, self.nav[i].layer,
                "a list holds its layer"
            );
            if (!static_near[i] && self.pair_near(a, b))
                || (!static_near[j] && self.pair_near(b, a))
            {
                near = true;
                partner(j);
            }
        }
        near
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

    /// `sim.physics: NearBodies`: the body of each robot not `near[id]` a contact is disabled
    /// in Rapier (out of its solver and broad phase; the read-back moves the robot straight at
    /// its command, `parallel.rs`); the body of each robot near one is enabled, set to the
    /// robot's position if it was disabled, and driven at its command.
    /// Whether each body is enabled is the gate's own record (`gated_enabled`), so a robot that
    /// stays far from contacts costs no look-up in Rapier's body set.
    pub(super) fn gate_bodies(&mut self, nav: &[Nav], near: &[bool]) {
        let mut enabled = std::mem::take(&mut self.gated_enabled);
        if enabled.len() != nav.len() {
            let bodies = &self.physics.bodies;
            enabled.clear();
            enabled.extend(nav.iter().map(|r| bodies[r.body].is_enabled()));
        }
        // A body enabled here is stepped by Rapier, and its robot's body speed read back after.
        for ((robot, &near), was) in nav.iter().zip(near).zip(enabled.iter_mut()) {
            match (near, *was) {
                (true, true) => self.drive_body(robot.body, robot.command),
                (true, false) => {
                    let body = &mut self.physics.bodies[robot.body];
                    body.set_enabled(true);
                    body.set_translation(robot.pos, false);
                    body.set_linvel(robot.command, false);
                }
                (false, true) => self.physics.bodies[robot.body].set_enabled(false),
                (false, false) => {}
            }
            *was = near;
        }
        self.gated_enabled = enabled;
    }

    /// Whether `static_distance(p, with_debris) - radius_m <= reach_m`, answered obstacle by
    /// obstacle (the same answer: `f32` subtraction keeps the order of the distances) and
    /// skipping an obstacle whose bounding box is farther than that by
    /// `BOX_SKIP_MARGIN_M` (a box's distance bounds its obstacle's from below), and looking
    /// only at the obstacles of the buckets near `p` (`static_buckets.rs`).
    pub fn static_within(&self, p: Vec2, with_debris: bool, radius_m: f32, reach_m: f32) -> bool {
        let box_reach = radius_m + reach_m + BOX_SKIP_MARGIN_M;
        self.static_buckets.any_near(p, box_reach, |k| {
            let (o, b) = (&self.statics[k], &self.static_boxes[k]);
            let dx = (b.mins.x - p.x).max(p.x - b.maxs.x).max(0.0);
            let dy = (b.mins.y - p.y).max(p.y - b.maxs.y).max(0.0);
            (with_debris || o.is_wall)
                && dx * dx + dy * dy <= box_reach * box_reach
                && o.distance_to_point(p) - radius_m <= reach_m
        })
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
    use crate::world::parallel::{ReadFrom, read_back_all};
    use crate::world::{ControlClock, World};

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
        let clock = ControlClock::of(&s.sim);
        let mut w = World::new(&s, &clock);
        assert!(!w.near_contact(), "robots at rest at their starts");
        let (a, b) = (w.parts().nav[0].clone(), w.parts().nav[1].clone());
        let gap = (b.pos - a.pos).length() - a.radius - b.radius;
        assert!(gap > 0.0);
        // Robot 0 drives at robot 1 fast enough to close the gap within a step.
        let v = (b.pos - a.pos).normalize() * (gap / w.dt_s() as f32 + 0.1);
        drive(&mut w, 0, v);
        assert!(w.near_contact());
        // Slowly: the gap stays open this step.
        let slow = (b.pos - a.pos).normalize() * 0.01;
        drive(&mut w, 0, slow);
        let prediction = w
            .parts()
            .scene
            .physics
            .integration_parameters
            .prediction_distance();
        let reach = 0.01 * w.dt_s() as f32 + prediction + NEAR_CONTACT_MARGIN_M;
        assert_eq!(w.near_contact(), gap <= reach, "gap {gap}, reach {reach}");
    }

    /// With no contact in reach a robot's straight move is Rapier's up to rounding: one robot
    /// driven 1 m across open ground in 100 steps ends within 0.1 mm of where Rapier's 400
    /// substeps of `f32` positions put it (they differ by 0.024 mm).
    #[test]
    fn a_free_move_is_rapiers_up_to_rounding() {
        let mut ends = Vec::new();
        for physics in [PhysicsStepping::EveryStep, PhysicsStepping::NearContacts] {
            let mut w = World::new(&paper(physics), &ControlClock::of(&paper(physics).sim));
            let body = w.parts().nav[0].body;
            for _ in 0..100 {
                drive(&mut w, 0, Vec2::new(0.0, 0.5));
                if physics == PhysicsStepping::NearContacts && !w.near_contact() {
                    let dt = w.dt_s() as f32;
                    w.parts().scene.move_free(dt);
                } else {
                    w.parts().scene.step();
                }
            }
            ends.push(w.parts().scene.physics.bodies[body].translation());
        }
        assert!((ends[0] - ends[1]).length() < 1e-4, "{ends:?}");
        let start = World::new(
            &paper(PhysicsStepping::EveryStep),
            &ControlClock::of(&paper(PhysicsStepping::EveryStep).sim),
        )
        .parts()
        .nav[0]
            .pos;
        assert!(
            (ends[1].y - start.y - 1.0).abs() < 1e-4,
            "{start:?} {ends:?}"
        );
    }

    /// Robot `id` commanded at `v` and its body driven, as a control step and `World::step` do.
    fn drive(w: &mut World, id: usize, v: Vec2) {
        w.parts().nav[id].command = v;
        let body = w.parts().nav[id].body;
        w.parts().scene.drive_body(body, v);
    }

    /// One physics step as `World::step` takes it with `NearBodies` between control steps
    /// (the neighbour index stale, the gate rebuilding it with its lists when it must);
    /// returns the near flags.
    fn gated_step(w: &mut World) -> Vec<bool> {
        w.parts().pipelines.index_fresh = false;
        let mut near = vec![false; w.parts().nav.len()];
        let any = w.mark_near_bodies(&mut near);
        let p = w.parts();
        p.scene.gate_bodies(p.nav, &near);
        if any {
            p.scene.step();
        }
        let (mut to, scene) = w.read_back_parts();
        let bodies = &scene.physics.bodies;
        read_back_all(ReadFrom::Bodies(bodies), &mut to);
        near
    }

    /// With `NearBodies` only the two robots about to touch are Rapier's: their bodies are
    /// enabled and the contact keeps them apart; every other body is disabled and its robot
    /// moves straight at its command, exactly `position + command * dt` per step.
    #[test]
    fn near_bodies_steps_only_the_robots_near_a_contact() {
        let mut w = World::new(
            &paper(PhysicsStepping::NearBodies),
            &ControlClock::of(&paper(PhysicsStepping::NearBodies).sim),
        );
        let (a, b) = (w.parts().nav[0].clone(), w.parts().nav[1].clone());
        let toward = (b.pos - a.pos).normalize();
        let sideways = Vec2::new(-toward.y, toward.x) * 0.3;
        let third = w.parts().nav[2].pos;
        for step in 0..200 {
            drive(&mut w, 0, toward * 1.0);
            drive(&mut w, 2, sideways);
            let before = w.parts().nav[2].pos;
            let near = gated_step(&mut w);
            assert_eq!(
                near[0], near[1],
                "step {step}: a pair is near from both sides"
            );
            for (id, &flag) in near.iter().enumerate() {
                let p = w.parts();
                let enabled = p.scene.physics.bodies[p.nav[id].body].is_enabled();
                assert_eq!(enabled, flag, "step {step}, robot {id}");
            }
            if !near[2] {
                let dt = w.dt_s() as f32;
                assert_eq!(w.parts().nav[2].pos, before + sideways * dt, "step {step}");
            }
            let gap = (w.parts().nav[1].pos - w.parts().nav[0].pos).length() - a.radius - b.radius;
            assert!(gap > -0.02, "step {step}: bodies overlap by {}", -gap);
        }
        assert!(w.parts().nav[1].pos != b.pos, "robot 0 pushed robot 1");
        assert!(
            (w.parts().nav[2].pos - third).length() > 1.0,
            "robot 2 drove on"
        );
    }

    /// A body disabled while its robot drove free is enabled again where the robot is, at its
    /// command: the robot driven at a wall ends against it, as Rapier stops it.
    #[test]
    fn a_body_enabled_again_starts_where_its_robot_is() {
        let mut w = World::new(
            &paper(PhysicsStepping::NearBodies),
            &ControlClock::of(&paper(PhysicsStepping::NearBodies).sim),
        );
        let mut enabled_again = false;
        for _ in 0..1500 {
            drive(&mut w, 0, Vec2::new(0.0, -0.8));
            let p = w.parts();
            let was_enabled = p.scene.physics.bodies[p.nav[0].body].is_enabled();
            let near = gated_step(&mut w);
            if near[0] && !was_enabled {
                enabled_again = true;
            }
            let p = w.parts();
            let body = &p.scene.physics.bodies[p.nav[0].body];
            if body.is_enabled() {
                assert_eq!(body.translation(), p.nav[0].pos);
            }
        }
        assert!(enabled_again, "robot 0 reached the wall");
        let p = w.parts();
        let wall_gap = p.scene.static_distance(p.nav[0].pos, true) - p.nav[0].radius;
        assert!(wall_gap.abs() < 0.02, "against the wall: gap {wall_gap}");
    }

    /// The gate's lists and open-ground readings change no flag: on every step of robots
    /// driven at each other and at the walls, with the lists kept over steps (skins of 0.5 m
    /// and 5 cm), `mark_near_bodies` marks exactly the robots that the exact test of every
    /// robot against every other of its layer, reading the grid afresh, marks (either side).
    #[test]
    fn lists_and_readings_mark_what_the_exact_test_marks() {
        for skin in [GATE_LIST_SKIN_M, 0.05] {
            let s = paper(PhysicsStepping::NearBodies);
            let mut w = World::new(&s, &ControlClock::of(&s.sim));
            w.parts().pipelines.gate.lists = NeighbourLists::with_skin(skin);
            let n = w.parts().nav.len();
            let mut marked = 0;
            for step in 0..600 {
                for i in 0..n {
                    // Robot i drives at robot i + 1 (or at the wall below), faster every turn.
                    let to = w.parts().nav[(i + 1) % n].pos - w.parts().nav[i].pos;
                    let v = if (step / 150 + i) % 3 == 0 {
                        Vec2::new(0.0, -1.5)
                    } else {
                        to.normalize_or_zero() * (0.5 + (i % 4) as f32 * 0.6)
                    };
                    drive(&mut w, i, v);
                }
                let reference = reference_flags(&mut w);
                let near = gated_step(&mut w);
                assert_eq!(near, reference, "skin {skin}, step {step}");
                marked += near.iter().filter(|&&f| f).count();
            }
            assert!(
                marked > 100,
                "skin {skin}: robots came near contacts ({marked} flags)"
            );
        }
    }

    /// The flags of every robot tested from its own side (a robot near a static stops there),
    /// marked with its partners: the reference the gate's pairs-once test must give.
    fn reference_flags(w: &mut World) -> Vec<bool> {
        let n = w.parts().nav.len();
        let (inputs, p) = w.gate_inputs();
        let gate = p.gate.gate(&inputs, false);
        let view = GateView::new(&inputs, &gate, None, None);
        let mut flags = vec![false; n];
        for i in 0..n {
            let (mut found, mut unread) = (Vec::new(), UNREAD);
            flags[i] |= view.robot_near_contact(i, &mut unread, |j| found.push(j));
            for j in found {
                flags[j] = true;
            }
        }
        flags
    }

    /// Regression (pairs tested once): two ground robots of unequal radii (0.4 m and 0.1 m to
    /// 0.3 m, either at the wall), one at rest against a wall, the other commanded at 2.5 m/s
    /// at the distances where their gaps read from the two sides (the radii taken off in the
    /// two orders) fall on either side of what they can close in a step. The robot near the
    /// wall tests no pair, so the pair is near only if the other robot's side finds it: a test
    /// of each pair once that took either side's answer would mark the free robot where the
    /// reference does not. Both ways round (the robot at the wall the lower id and the higher).
    #[test]
    fn a_pair_of_unequal_robots_at_a_wall_is_marked_as_from_each_side() {
        let s = paper(PhysicsStepping::NearBodies);
        for (at_wall, free) in [(0, 1), (1, 0)] {
            let mut w = World::new(&s, &ControlClock::of(&s.sim));
            let start = w.parts().nav[at_wall].pos;
            let slack = w
                .parts()
                .scene
                .physics
                .integration_parameters
                .prediction_distance()
                + NEAR_CONTACT_MARGIN_M;
            let speed_m_per_s = 2.5;
            w.parts().nav[free].command = Vec2::new(speed_m_per_s, 0.0);
            let reach = speed_m_per_s * w.dt_s() as f32 + slack;
            let (mut straddles, mut would_differ) = (0, 0);
            for (k, small_at_wall) in (0..200).flat_map(|k| [(k, false), (k, true)]) {
                let small = 0.1 + k as f32 * 1e-3;
                let (ra, rb) = if small_at_wall {
                    (small, 0.4)
                } else {
                    (0.4, small)
                };
                w.parts().nav[at_wall].radius = ra;
                w.parts().nav[free].radius = rb;
                // Robot `at_wall` moved down from its start until it is within half the
                // slack of the wall below.
                let mut p = start;
                while w.parts().scene.static_distance(p, true) - ra > 0.5 * slack {
                    p.y -= 1e-3;
                }
                w.parts().nav[at_wall].pos = p;
                // The free robot up and to the side, a few steps of rounding apart in each
                // coordinate (so the distance takes nearly every value near the reach).
                let side = (ra + rb + reach) * std::f32::consts::FRAC_1_SQRT_2;
                let centre = Vec2::new(p.x + side, p.y + side);
                let ulp = Vec2::new(centre.x.next_up() - centre.x, centre.y.next_up() - centre.y);
                for (kx, ky) in (0..8).flat_map(|kx| (0..8).map(move |ky| (kx, ky))) {
                    let q = centre + Vec2::new(kx as f32 - 4.0, ky as f32 - 4.0) * ulp;
                    let d = (q - p).length();
                    let (from_wall, from_free) = (d - ra - rb <= reach, d - rb - ra <= reach);
                    if from_wall == from_free {
                        continue;
                    }
                    straddles += 1;
                    w.parts().nav[free].pos = q;
                    w.parts().pipelines.index_fresh = false;
                    let mut near = vec![false; w.parts().nav.len()];
                    w.mark_near_bodies(&mut near);
                    let reference = reference_flags(&mut w);
                    assert_eq!(
                        near, reference,
                        "robot {at_wall} at the wall, {free} at {q}"
                    );
                    assert!(near[at_wall], "robot {at_wall} is near the wall");
                    assert_eq!(near[free], from_free, "only the free robot's side counts");
                    would_differ += usize::from(!from_free);
                }
            }
            // Both kinds of straddle: the free robot's side finds the pair, or only the side
            // of the robot at the wall would.
            assert!(
                would_differ > 0 && straddles > would_differ,
                "robot {at_wall} at the wall: {straddles} straddles, {would_differ} where only \
                 its side finds the pair"
            );
        }
    }
}
