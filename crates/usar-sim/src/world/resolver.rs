//! Priority-based collision avoidance with deadlock solving (paper, section V, Algorithm 5).
//!
//! Each step, in this order:
//! 1. **About to collide.** Two *active* robots (goal set and not reached) on the same layer
//!    (ground-ground or aerial-aerial), at most `max(sensing_i, sensing_j)` apart, are about to
//!    collide when, moving with their intended velocities, they approach each other
//!    (`(p_j - p_i) . (v_j - v_i) < 0`) and their closest distance within
//!    `collision.lookahead_s` is below `r_i + r_j + collision.safety_margin_m`.
//! 2. **Collision lists** are the connected components (two or more robots) of that relation.
//!    A list is sorted by the caller's priority key (lower first, ties by id). With rotation
//!    count `R` (see 4) the head is `sorted[R mod len]`; the head moves, the others are *held*
//!    (commanded zero velocity). Under `collision.hold_rule: Yield` (not the paper's; for
//!    crowds, [`HoldRule::Yield`]) the members are taken in that order from the head on,
//!    wrapping around, and a member is held only when a member before it that moves is about
//!    to collide with it (rule 1's relation); rule 3 is then skipped.
//! 3. **Followers join** (`hold_rule: ListHead` only). An active robot that is not held and
//!    whose intended motion would hit a held robot (taken as standing still, same test as 1)
//!    joins that robot's list (repeated until no robot joins); heads are then recomputed.
//! 4. **Deadlock.** A list is deadlocked when no member has *moved*, i.e. made progress along
//!    its path (remaining path length below its best value by more than
//!    [`DEADLOCK_PROGRESS_TOLERANCE_M`]), while in a list for at least
//!    `collision.deadlock_after_s`. (Progress rather than displacement: a blocked head that
//!    jitters sideways must not hide a deadlock.) Then the list's rotation count `R` is incremented (the next
//!    robot in priority order becomes the head: Algorithm 5's `Swap(C, 0, C[i])` with `i++`)
//!    and the members' stall timers restart; this repeats while the deadlock persists. A
//!    merged list takes the largest `R` of its members; a robot in no list has `R = 0`.
//! 5. **Moving robots steer** (heads, robots in no list, and under [`HoldRule::Yield`] every
//!    list member not held): held, idle, arrived and zero-speed robots of the same layer
//!    within sensing range are obstacles standing still;
//!    the intended velocity is rotated by the smallest angle (15 degree steps up to 120 degrees,
//!    right side first) whose straight motion keeps clear of them for the look-ahead (same test
//!    as 1) and, for ground robots, does not drive into walls or debris. If no heading is clear
//!    the robot stands still this step (blocked). Under `collision.steering: KeepSide` (the
//!    default; not from the paper) a robot tries the side it last turned to first, unless the
//!    other side has a clear turn more than 45 degrees smaller, and a turned heading must also
//!    keep clear of the moving robots it senses, taken at their intended velocities
//!    (`steering::pick_turn`; `docs/world-model.md`, "Steering side and taken goals").

use std::cell::Cell;

use parry2d::math::Vector as Vec2;

use super::clearance_grid::ClearanceGrid;
pub use super::collision_course::about_to_collide;
use super::conflicts::ConflictGraph;
use super::neighbour_lists::{NeighbourLists, skin_for_control_steps};
use super::neighbours::NeighbourQuery;
pub use super::resolver_input::ResolverInput;
use super::resolver_input::layer_slot;
use super::resolver_pairs::pairs_by_chunk;
use super::resolver_reach::{self, LayerBounds};
pub use super::steering::{
    NearRobot, STEER_ANGLE_STEP_RAD, STEER_STATIC_GAP_M, STEER_STATIC_LOOKAHEAD_M,
    STEER_STEPS_PER_SIDE,
};
use super::steering::{all_clear_hinted, pick_turn};
use super::union_find::{find, union};
use crate::scenario::{CollisionParams, HoldRule, Steering};

/// Progress (decrease of the remaining path length below its best value since the stall timer
/// last restarted) below which a list member counts as "not moved" for deadlock detection,
/// metres.
pub const DEADLOCK_PROGRESS_TOLERANCE_M: f32 = 0.05;

/// The resolver's decision for one robot this step.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Decision {
    /// Member of a collision list.
    pub in_list: bool,
    /// Held (zero velocity).
    pub held: bool,
    /// Joined a list this step (was in none at the previous step).
    pub joined: bool,
    /// A deadlock was detected in its list this step (the order was rotated).
    pub deadlock_detected: bool,
    /// It left a list whose order had been rotated (its deadlock cleared).
    pub deadlock_resolved: bool,
}

#[derive(Debug, Clone, Copy, Default)]
struct Memory {
    best: f32,
    stall_s: f64,
    rotation: u32,
    in_list: bool,
}

/// The collision resolver: persistent per-robot memory plus scratch buffers (no allocation per
/// step).
#[derive(Debug, Clone)]
pub struct Resolver {
    params: CollisionParams,
    parent: Vec<usize>,
    size: Vec<usize>,
    /// The members of each component as a cycle: `next[i]` is the member after `i`.
    next: Vec<usize>,
    /// Robots whose component grew in the current follower round (rule 3).
    grown: Vec<usize>,
    held: Vec<bool>,
    members: Vec<usize>,
    /// (root, id) of every list member, sorted: the lists, each in ascending id.
    lists: Vec<(usize, usize)>,
    /// Scratch of [`Resolver::collect_lists`]: each robot's root, then each root's next slot
    /// in `lists`.
    roots: Vec<usize>,
    next_slot: Vec<usize>,
    /// Scratch of rule 5: the robots near the steering robot it tests headings against.
    near: Vec<NearRobot>,
    /// Each robot's neighbour candidates for rules 1, 3 and 5, kept over several steps and
    /// refreshed by [`Resolver::resolve`].
    neighbour_lists: NeighbourLists,
    /// Rule 3's (follower, robot it would hit) pairs of this step.
    follow: Vec<(usize, usize)>,
    /// Rule 1's pairs of this step as adjacency lists (kept under [`HoldRule::Yield`] only).
    conflicts: ConflictGraph,
    /// Under [`HoldRule::Yield`]: the members of the current list found to move so far.
    moving: Vec<bool>,
    /// Ground and aerial bounds of this step (see [`Resolver::reach`]).
    bounds: [LayerBounds; 2],
    memory: Vec<Memory>,
    decisions: Vec<Decision>,
    deadlocked_lists: u64,
    largest_list: usize,
    /// Rule 1's pairs of this step, one list per chunk of robots (`resolver_pairs.rs`).
    pairs: Vec<Vec<(usize, usize)>>,
    /// Whether rule 1's pair search runs on the calling rayon pool ([`Resolver::set_parallel`]).
    parallel: bool,
    /// Whether the last run rebuilt the neighbour lists.
    rebuilt_lists: bool,
}

impl Resolver {
    /// A resolver for `n` robots.
    pub fn new(params: CollisionParams, n: usize) -> Self {
        let memory = vec![Memory::default(); n];
        Self {
            params,
            parent: (0..n).collect(),
            size: vec![1; n],
            next: (0..n).collect(),
            grown: Vec::with_capacity(n),
            held: vec![false; n],
            members: Vec::with_capacity(n),
            lists: Vec::with_capacity(n),
            roots: vec![0; n],
            next_slot: vec![0; n],
            near: Vec::with_capacity(64),
            neighbour_lists: NeighbourLists::new(),
            follow: Vec::with_capacity(n),
            conflicts: ConflictGraph::default(),
            moving: vec![false; n],
            bounds: [LayerBounds::default(); 2],
            memory,
            decisions: vec![Decision::default(); n],
            deadlocked_lists: 0,
            largest_list: 0,
            pairs: Vec::new(),
            parallel: false,
            rebuilt_lists: false,
        }
    }

    /// The resolver for a run every `control_steps` steps (`sim.control_period_s`): the same
    /// decisions, with its neighbour lists' skin for that period (0.5 m per step of the period,
    /// at most 1.5 m: robots move farther between two runs).
    pub fn for_control_steps(mut self, control_steps: u64) -> Self {
        self.neighbour_lists = NeighbourLists::with_skin(skin_for_control_steps(control_steps));
        self.neighbour_lists.set_parallel(self.parallel);
        self
    }

    /// Lets (`true`) or forbids (`false`, the default) rule 1's search for the pairs about to
    /// collide and the rebuild of the neighbour lists to run on the threads of the calling
    /// rayon pool: the same decisions either way.
    pub fn set_parallel(&mut self, parallel: bool) {
        self.parallel = parallel;
        self.neighbour_lists.set_parallel(parallel);
    }

    /// Whether the last [`Resolver::resolve`] rebuilt the neighbour lists.
    pub fn rebuilt_lists(&self) -> bool {
        self.rebuilt_lists
    }

    /// Lists found deadlocked (and rotated) by the last [`Resolver::resolve`].
    pub fn deadlocked_lists(&self) -> u64 {
        self.deadlocked_lists
    }

    /// Members of the largest list of the last [`Resolver::resolve`] (0 without lists).
    pub fn largest_list(&self) -> usize {
        self.largest_list
    }

    /// Decisions of the last [`Resolver::resolve`], indexed by robot id.
    pub fn decisions(&self) -> &[Decision] {
        &self.decisions
    }

    /// Whether robot `i` (not held, deflected or blocked by rule 5) stands at the rim of a
    /// goal `goal` taken by a robot standing still, within `tolerance_m` (its goal tolerance,
    /// metres) of the rim point nearest the goal (`world/goal_taken.rs`). Call
    /// after [`Resolver::resolve`] with the same `inputs` (it uses that step's neighbour lists).
    pub fn goal_taken(
        &self,
        inputs: &[ResolverInput],
        i: usize,
        goal: Vec2,
        tolerance_m: f32,
    ) -> bool {
        let margin = self.params.safety_margin_m.get() as f32;
        let near = self.neighbour_lists.of(i);
        super::goal_taken::goal_taken(inputs, i, near, margin, goal, tolerance_m)
    }

    fn sensed(a: &ResolverInput, b: &ResolverInput) -> bool {
        let range = a.sensing.max(b.sensing);
        (b.pos - a.pos).length_squared() <= range * range
    }

    fn clearance(&self, a: &ResolverInput, b: &ResolverInput) -> f32 {
        a.radius + b.radius + self.params.safety_margin_m.get() as f32
    }

    /// The radius around robot `a` beyond which no robot of its layer can take part in one of
    /// the rules with it this step, metres ([`resolver_reach::reach`]).
    fn reach(&self, a: &ResolverInput) -> f32 {
        let margin_m = self.params.safety_margin_m.get() as f32;
        let lookahead_s = self.params.lookahead_s.get() as f32;
        resolver_reach::reach(&self.bounds, margin_m, lookahead_s, a)
    }

    /// The layers' largest sensing range, body radius and intended speed among `inputs`.
    fn measure_bounds(&mut self, inputs: &[ResolverInput]) {
        self.bounds = LayerBounds::measure(inputs);
    }

    /// The largest [`Resolver::reach`] of each layer's robots this step (ground, aerial),
    /// metres: the radius the neighbour lists must cover.
    fn layer_reach(&self, inputs: &[ResolverInput]) -> [f32; 2] {
        let mut query = [0.0f32; 2];
        for a in inputs {
            let q = &mut query[layer_slot(a.layer)];
            *q = q.max(self.reach(a));
        }
        query
    }

    /// Sorts the members of every list (component of two or more) into `self.lists` as
    /// (root, id), lists by root and members by ascending id: a counting sort by root (the
    /// ids come in ascending order), `O(n)`.
    fn collect_lists(&mut self, n: usize) {
        self.lists.clear();
        self.next_slot[..n].iter_mut().for_each(|c| *c = 0);
        let mut members = 0;
        for i in 0..n {
            let root = find(&mut self.parent, i);
            self.roots[i] = root;
            if self.size[root] >= 2 {
                self.next_slot[root] += 1;
                members += 1;
            }
        }
        // Each root's first slot: the members of all smaller roots come before it.
        let mut at = 0;
        for slot in &mut self.next_slot[..n] {
            let count = *slot;
            *slot = at;
            at += count;
        }
        self.lists.resize(members, (0, 0));
        for i in 0..n {
            let root = self.roots[i];
            if self.size[root] >= 2 {
                self.lists[self.next_slot[root]] = (root, i);
                self.next_slot[root] += 1;
            }
        }
    }

    /// The end of the list starting at `self.lists[start]`.
    fn list_end(&self, start: usize) -> usize {
        let root = self.lists[start].0;
        self.lists[start..]
            .iter()
            .position(|&(r, _)| r != root)
            .map_or(self.lists.len(), |k| start + k)
    }

    /// Loads the list `self.lists[start..end]` into `self.members` sorted by (key, id), and
    /// returns its rotation (the largest of its members'). The head is
    /// `members[rotation mod len]`.
    fn load_list(&mut self, inputs: &[ResolverInput], start: usize, end: usize) -> u32 {
        self.members.clear();
        self.members
            .extend(self.lists[start..end].iter().map(|&(_, i)| i));
        self.order_members(inputs)
    }

    /// Sorts `self.members` by (key, id) and returns their rotation (the largest of theirs).
    fn order_members(&mut self, inputs: &[ResolverInput]) -> u32 {
        self.members
            .sort_unstable_by(|&a, &b| inputs[a].key.total_cmp(&inputs[b].key).then(a.cmp(&b)));
        self.members
            .iter()
            .map(|&m| self.memory[m].rotation)
            .max()
            .unwrap_or(0)
    }

    /// Marks every list member held except its head (no side effects on memory).
    fn assign_heads(&mut self, inputs: &[ResolverInput]) {
        self.held.iter_mut().for_each(|h| *h = false);
        self.collect_lists(inputs.len());
        let mut start = 0;
        while start < self.lists.len() {
            let end = self.list_end(start);
            let rotation = self.load_list(inputs, start, end);
            self.hold_members(rotation);
            start = end;
        }
    }

    /// Builds the collision lists, detects deadlocks and decides who is held (rules 1-4 of the
    /// module docs). `inputs` is indexed by robot id; `near` answers neighbour queries over
    /// the robots at `inputs[..].pos` (the world's [`super::neighbours::NeighbourIndex`], or
    /// [`super::neighbours::AllRobots`] for the all-pairs scan: same result); `dt` is the time
    /// since the last call, seconds (the world's control period: the step without
    /// `sim.control_period_s`). `O(n k)` for `k` robots within a robot's interaction
    /// distance, plus the follower rounds (rule 3).
    pub fn resolve(
        &mut self,
        inputs: &[ResolverInput],
        near: &(impl NeighbourQuery + Sync),
        dt: f64,
    ) {
        self.measure_bounds(inputs);
        let query = self.layer_reach(inputs);
        self.rebuilt_lists = self.neighbour_lists.refresh(inputs, query, near);
        self.track_progress(inputs, dt);
        self.link_pairs(inputs);
        if self.params.hold_rule == HoldRule::ListHead {
            self.join_followers(inputs);
        }
        self.decide(inputs);
        self.forget_unlisted(inputs);
    }

    /// Rule 4's "moved": last step's list members that made no progress stall for `dt` more;
    /// the others restart their stall timer from their current remaining length.
    fn track_progress(&mut self, inputs: &[ResolverInput], dt: f64) {
        for (mem, input) in self.memory.iter_mut().zip(inputs) {
            if mem.in_list && input.remaining >= mem.best - DEADLOCK_PROGRESS_TOLERANCE_M {
                mem.stall_s += dt;
            } else {
                mem.best = input.remaining;
                mem.stall_s = 0.0;
            }
        }
    }

    /// Rule 1: unites the pairs about to collide (fresh union-find): each robot with its
    /// neighbours of higher id. The components (and their roots, the smallest ids) do not
    /// depend on the order of the unions, so this equals the scan of all pairs.
    fn link_pairs(&mut self, inputs: &[ResolverInput]) {
        let n = inputs.len();
        let keep_pairs = self.params.hold_rule == HoldRule::Yield;
        self.conflicts.clear();
        for i in 0..n {
            self.parent[i] = i;
            self.size[i] = 1;
            self.next[i] = i;
        }
        let mut pairs = std::mem::take(&mut self.pairs);
        let horizon = self.params.lookahead_s.get() as f32;
        let this = &*self;
        pairs_by_chunk(n, self.parallel, &mut pairs, |i, push| {
            let a = &inputs[i];
            if !a.active {
                return;
            }
            for &j in this.neighbour_lists.above(i) {
                let b = &inputs[j];
                if b.active
                    && a.layer == b.layer
                    && Self::sensed(a, b)
                    && about_to_collide(
                        b.pos - a.pos,
                        b.intent - a.intent,
                        this.clearance(a, b),
                        horizon,
                    )
                {
                    push(j);
                }
            }
        });
        for &(i, j) in pairs.iter().flatten() {
            union(&mut self.parent, &mut self.size, &mut self.next, i, j);
            if keep_pairs {
                self.conflicts.push(i, j);
            }
        }
        self.pairs = pairs;
        if keep_pairs {
            self.conflicts.build(n);
        }
    }

    /// Rules 2-3: heads, then followers join held robots, until nobody joins. Which robot
    /// would hit which robot standing still does not change within a step, so those pairs are
    /// found once ([`Resolver::find_followers`]) and each round only checks who is held. (Within
    /// a round the held robots are fixed and the unions' outcome does not depend on their
    /// order: this equals the rounds of all-pairs scans.) After a round only the lists that
    /// grew get new heads (the others keep their members, rotation and head), so a round costs
    /// the follower pairs plus the grown lists, not the team.
    fn join_followers(&mut self, inputs: &[ResolverInput]) {
        let n = inputs.len();
        self.assign_heads(inputs);
        if !self.held.contains(&true) {
            return;
        }
        self.find_followers(inputs);
        for _ in 0..n {
            self.grown.clear();
            for &(i, j) in &self.follow {
                if self.held[i] || !self.held[j] {
                    continue;
                }
                if union(&mut self.parent, &mut self.size, &mut self.next, i, j) {
                    self.grown.push(i);
                }
            }
            if self.grown.is_empty() {
                break;
            }
            self.reassign_grown_heads(inputs);
        }
    }

    /// [`Resolver::assign_heads`] for the lists of the robots in `self.grown` only.
    fn reassign_grown_heads(&mut self, inputs: &[ResolverInput]) {
        // Each grown list once, by its root.
        for k in 0..self.grown.len() {
            self.grown[k] = find(&mut self.parent, self.grown[k]);
        }
        self.grown.sort_unstable();
        self.grown.dedup();
        for k in 0..self.grown.len() {
            let root = self.grown[k];
            self.members.clear();
            let mut m = root;
            loop {
                self.members.push(m);
                m = self.next[m];
                if m == root {
                    break;
                }
            }
            let rotation = self.order_members(inputs);
            self.hold_members(rotation);
        }
    }

    /// Rule 3's test without "held": the pairs `(i, j)` where active robot `i`, moving with its
    /// intent, would hit robot `j` of its layer within sensing range if `j` stood still, into
    /// `self.follow`.
    fn find_followers(&mut self, inputs: &[ResolverInput]) {
        let horizon = self.params.lookahead_s.get() as f32;
        self.follow.clear();
        for (i, a) in inputs.iter().enumerate() {
            if !a.active || a.intent == Vec2::ZERO {
                continue;
            }
            for &j in self.neighbour_lists.of(i) {
                let b = &inputs[j];
                if j != i
                    && a.layer == b.layer
                    && Self::sensed(a, b)
                    && about_to_collide(b.pos - a.pos, -a.intent, self.clearance(a, b), horizon)
                {
                    self.follow.push((i, j));
                }
            }
        }
    }

    /// Rule 4: rotates deadlocked lists, then fixes each list's head, the members' memory and
    /// the decisions.
    fn decide(&mut self, inputs: &[ResolverInput]) {
        let after = self.params.deadlock_after_s.get();
        self.held.iter_mut().for_each(|h| *h = false);
        for d in &mut self.decisions {
            *d = Decision::default();
        }
        self.deadlocked_lists = 0;
        self.largest_list = 0;
        self.collect_lists(inputs.len());
        let mut start = 0;
        while start < self.lists.len() {
            let end = self.list_end(start);
            let mut rotation = self.load_list(inputs, start, end);
            start = end;
            let deadlocked = self
                .members
                .iter()
                .all(|&m| self.memory[m].in_list && self.memory[m].stall_s >= after);
            if deadlocked {
                rotation = rotation.wrapping_add(1);
                self.deadlocked_lists += 1;
            }
            self.largest_list = self.largest_list.max(self.members.len());
            self.hold_members(rotation);
            for &m in &self.members {
                let held = self.held[m];
                let mem = &mut self.memory[m];
                mem.rotation = rotation;
                if deadlocked {
                    mem.stall_s = 0.0;
                    mem.best = inputs[m].remaining;
                }
                let d = &mut self.decisions[m];
                d.in_list = true;
                d.held = held;
                d.joined = !mem.in_list;
                d.deadlock_detected = deadlocked;
            }
        }
    }

    /// Sets `self.held` for the list in `self.members` (sorted by priority) with rotation
    /// `rotation`, by the hold rule: under [`HoldRule::ListHead`] all but the head
    /// `members[rotation mod len]`; under [`HoldRule::Yield`] the members taken from the head
    /// on (wrapping around) are held when a member before them that moves is about to collide
    /// with them. `O(list + its conflict pairs)`.
    fn hold_members(&mut self, rotation: u32) {
        let len = self.members.len();
        let first = rotation as usize % len;
        match self.params.hold_rule {
            HoldRule::ListHead => {
                let head = self.members[first];
                for &m in &self.members {
                    self.held[m] = m != head;
                }
            }
            HoldRule::Yield => {
                for k in 0..len {
                    let m = self.members[(first + k) % len];
                    let blocked = self.conflicts.neighbours(m).any(|j| self.moving[j]);
                    self.held[m] = blocked;
                    self.moving[m] = !blocked;
                }
                for &m in &self.members {
                    self.moving[m] = false;
                }
            }
        }
    }

    /// Robots in no list forget their rotation and stall (a deadlock they were part of is
    /// resolved); every robot remembers whether it is in a list now.
    fn forget_unlisted(&mut self, inputs: &[ResolverInput]) {
        for (i, input) in inputs.iter().enumerate() {
            let mem = &mut self.memory[i];
            let d = &mut self.decisions[i];
            if !d.in_list {
                d.deadlock_resolved = mem.in_list && mem.rotation > 0;
                mem.rotation = 0;
                mem.stall_s = 0.0;
                mem.best = input.remaining;
            }
            mem.in_list = d.in_list;
        }
    }

    /// Rule 5: the velocity robot `i` (not held) commands, its intent deflected around robots
    /// standing still; `None` when every candidate heading is blocked. `static_inflation` is
    /// the body radius plus [`STEER_STATIC_GAP_M`] (ground robots), or `None` for aerial robots
    /// (no static check). Call after [`Resolver::resolve`] with the same `inputs` (it uses
    /// that step's held robots, bounds and neighbour lists). The robots standing still near
    /// `i` are looked up once, not per candidate heading.
    pub fn steer(
        &mut self,
        inputs: &[ResolverInput],
        i: usize,
        grid: &ClearanceGrid,
        static_inflation: Option<f32>,
    ) -> Option<Vec2> {
        let mut near = std::mem::take(&mut self.near);
        let steered = self.steer_with(inputs, i, grid, static_inflation, 0.0, &mut near);
        self.near = near;
        steered
    }

    /// [`Resolver::steer`] with the caller's scratch list `near` (cleared, then filled with the
    /// robots near `i` it tests headings against: those standing still, and under
    /// `collision.steering: KeepSide` the moving ones too; its capacity is kept between calls;
    /// `Vec::new()` makes one) instead of the resolver's own, so that it borrows the resolver
    /// immutably and robots may steer on
    /// several threads at once; and with a steering side `side`: `0` tries the turns right
    /// side first at each angle, as [`Resolver::steer`] (the same answer, bit for bit); `< 0`
    /// right turns first, `> 0` left turns first, within a bound (the side of the robot's
    /// last deflection, so that it keeps sliding along an obstacle one way; see
    /// `steering::pick_turn`).
    pub fn steer_with(
        &self,
        inputs: &[ResolverInput],
        i: usize,
        grid: &ClearanceGrid,
        static_inflation: Option<f32>,
        side: f32,
        near: &mut Vec<NearRobot>,
    ) -> Option<Vec2> {
        let a = &inputs[i];
        if a.intent == Vec2::ZERO {
            return Some(Vec2::ZERO);
        }
        let horizon = self.params.lookahead_s.get() as f32;
        let held = &self.held;
        let still = |b: &ResolverInput, j: usize| held[j] || !b.active || b.intent == Vec2::ZERO;
        // Against a robot standing still (velocity 0); under `collision.steering: KeepSide` a
        // deflected heading also against a moving robot's intent (the pair test, rule 1, saw
        // only the intents, and a kept side may turn further than the smallest clear turn).
        let moving_too = self.params.steering == Steering::KeepSide;
        near.clear();
        near.extend(self.neighbour_lists.of(i).iter().filter_map(|&j| {
            let b = &inputs[j];
            if j == i || b.layer != a.layer {
                return None;
            }
            let b_still = still(b, j);
            ((moving_too || b_still) && Self::sensed(a, b))
                .then(|| NearRobot::new(b.pos - a.pos, b_still, b.intent, self.clearance(a, b)))
        }));
        let obstacles = &*near;
        // The robot that blocked the last heading tried on the same side is tested first.
        let last_blocker = [const { Cell::new(None) }; 2];
        let clear_of_robots = |w: Vec2, deflected: bool| {
            let hint = &last_blocker[usize::from(a.intent.perp_dot(w) > 0.0)];
            all_clear_hinted(obstacles.len(), hint, |k| {
                obstacles[k].clear_of(w, deflected, horizon)
            })
        };
        let clear_of_statics = |w: Vec2| {
            let Some(infl) = static_inflation else {
                return true;
            };
            // Looked up only when a turn is tried (most robots keep their intent), once per
            // turn that is clear of robots.
            let here = grid.clearance_at(a.pos);
            let speed = a.intent.length();
            let len = (speed * horizon).min(STEER_STATIC_LOOKAHEAD_M);
            let dir = w / speed;
            let step = grid.cell_m() * 0.5;
            let n = (len / step).ceil() as u32;
            (1..=n).all(|k| {
                let c = grid.clearance_at(a.pos + dir * (k as f32 * step).min(len));
                c >= infl || c >= here
            })
        };
        if clear_of_robots(a.intent, false) {
            return Some(a.intent);
        }
        let turned = |(s, c): (f32, f32)| {
            Vec2::new(
                a.intent.x * c - a.intent.y * s,
                a.intent.x * s + a.intent.y * c,
            )
        };
        pick_turn(side, |t| {
            let w = turned(t);
            clear_of_robots(w, true) && clear_of_statics(w)
        })
        .map(turned)
    }
}

#[cfg(test)]
mod tests {
    use parry2d::math::Pose;
    use parry2d::shape::Cuboid;

    use super::*;
    use crate::scenario::{Arena, Locomotion, NonNegative, Positive};
    use crate::world::bodies::{StaticObstacle, StaticShape};
    use crate::world::neighbours::{AllRobots, NeighbourIndex};
    use proptest::strategy::{Strategy, ValueTree};

    /// The neighbour index (3 m cells over the 10 m x 10 m test field) of `inputs`.
    fn index(inputs: &[ResolverInput]) -> NeighbourIndex {
        let mut ix = NeighbourIndex::with_cells(10.0, 10.0, 3.0, 3.0);
        ix.rebuild(inputs.iter().map(|a| (a.layer, a.pos)), false);
        ix
    }

    /// One resolver step over `inputs` with their neighbour index.
    fn resolve(r: &mut Resolver, inputs: &[ResolverInput], dt: f64) {
        r.resolve(inputs, &index(inputs), dt);
    }

    /// Steers robot `i` after a [`resolve`] of the same inputs.
    fn steer(
        r: &mut Resolver,
        inputs: &[ResolverInput],
        i: usize,
        g: &ClearanceGrid,
        infl: Option<f32>,
    ) -> Option<Vec2> {
        r.steer(inputs, i, g, infl)
    }

    /// Look-ahead 1 s, margin 0.2 m, deadlock after 2 s.
    fn params() -> CollisionParams {
        CollisionParams {
            enabled: true,
            lookahead_s: Positive::new(1.0).unwrap(),
            safety_margin_m: NonNegative::new(0.2).unwrap(),
            deadlock_after_s: Positive::new(2.0).unwrap(),
            hold_rule: HoldRule::ListHead,
            ..CollisionParams::default()
        }
    }

    /// An active ground robot of radius 0.4 m and sensing 5 m with 10 m of path left.
    fn robot(x: f32, y: f32, vx: f32, vy: f32, key: f64) -> ResolverInput {
        ResolverInput {
            pos: Vec2::new(x, y),
            intent: Vec2::new(vx, vy),
            radius: 0.4,
            sensing: 5.0,
            layer: Locomotion::Ground,
            active: true,
            key,
            remaining: 10.0,
        }
    }

    /// A standing (idle) robot.
    fn idle(x: f32, y: f32) -> ResolverInput {
        ResolverInput {
            active: false,
            ..robot(x, y, 0.0, 0.0, 0.0)
        }
    }

    /// A 10 m x 10 m grid of 0.25 m cells (clearance capped at 2 m) around `statics`.
    fn grid(statics: &[StaticObstacle]) -> ClearanceGrid {
        let arena = Arena {
            width_m: Positive::new(10.0).unwrap(),
            height_m: Positive::new(10.0).unwrap(),
            wall_thickness_m: Positive::new(0.5).unwrap(),
        };
        ClearanceGrid::build(&arena, statics, 0.25, 2.0)
    }

    /// Head-on pair: robots 0 and 1 drive at each other along the x axis, 1.5 m apart.
    fn head_on(key0: f64, key1: f64) -> Vec<ResolverInput> {
        vec![
            robot(0.0, 0.0, 1.0, 0.0, key0),
            robot(1.5, 0.0, -1.0, 0.0, key1),
        ]
    }

    fn held(r: &Resolver) -> Vec<bool> {
        r.decisions().iter().map(|d| d.held).collect()
    }

    #[test]
    fn head_on_pair_forms_one_list_with_the_lower_key_first() {
        let mut r = Resolver::new(params(), 2);
        resolve(&mut r, &head_on(2.0, 1.0), 0.02);
        assert!(r.decisions().iter().all(|d| d.in_list && d.joined));
        assert_eq!(r.largest_list(), 2);
        // Robot 1 has the lower key: it moves, robot 0 is held.
        assert_eq!(held(&r), [true, false]);
        let mut r = Resolver::new(params(), 2);
        resolve(&mut r, &head_on(1.0, 2.0), 0.02);
        assert_eq!(held(&r), [false, true]);
        // Equal keys: the lower id goes first.
        let mut r = Resolver::new(params(), 2);
        resolve(&mut r, &head_on(0.0, 0.0), 0.02);
        assert_eq!(held(&r), [false, true]);
        assert_eq!(r.deadlocked_lists(), 0);
    }

    /// A chain: robot 0 (first in priority) and robot 1 drive at each other; robot 2 crosses
    /// robot 1's way from the side but stays clear of robot 0.
    fn chain() -> Vec<ResolverInput> {
        vec![
            robot(0.0, 0.0, 0.0, 1.0, 0.0),
            robot(0.0, 2.5, 0.0, -1.0, 1.0),
            robot(-2.0, 2.5, 2.0, 0.0, 2.0),
        ]
    }

    fn yield_params() -> CollisionParams {
        CollisionParams {
            hold_rule: HoldRule::Yield,
            ..params()
        }
    }

    #[test]
    fn yield_holds_only_members_in_conflict_with_a_moving_member_before_them() {
        let inputs = chain();
        let clear = 0.4 + 0.4 + 0.2;
        let conflict = |i: usize, j: usize| {
            let (a, b) = (&inputs[i], &inputs[j]);
            about_to_collide(b.pos - a.pos, b.intent - a.intent, clear, 1.0)
        };
        assert!(conflict(0, 1) && conflict(1, 2) && !conflict(0, 2));
        // The paper's rule: one list of three, only its head (robot 0) moves.
        let mut r = Resolver::new(params(), 3);
        resolve(&mut r, &inputs, 0.02);
        assert_eq!(r.largest_list(), 3);
        assert_eq!(held(&r), [false, true, true]);
        // Yield: robot 1 gives way to robot 0; robot 2's only conflict is robot 1, which
        // stands, so robot 2 moves.
        let mut r = Resolver::new(yield_params(), 3);
        resolve(&mut r, &inputs, 0.02);
        assert_eq!(r.largest_list(), 3);
        assert_eq!(held(&r), [false, true, false]);
        assert!(r.decisions().iter().all(|d| d.in_list));
    }

    #[test]
    fn yield_decides_a_pair_as_the_paper_does_and_rotates_a_deadlock_alike() {
        for keys in [(2.0, 1.0), (1.0, 2.0), (0.0, 0.0)] {
            let mut paper = Resolver::new(params(), 2);
            let mut crowd = Resolver::new(yield_params(), 2);
            let inputs = head_on(keys.0, keys.1);
            // 3 s of no progress: both detect the deadlock at 2 s and rotate the same way.
            for _ in 0..150 {
                resolve(&mut paper, &inputs, 0.02);
                resolve(&mut crowd, &inputs, 0.02);
                assert_eq!(paper.decisions(), crowd.decisions());
            }
            assert_eq!(paper.decisions().iter().filter(|d| d.held).count(), 1);
        }
    }

    #[test]
    fn robots_that_part_or_fly_form_no_list() {
        let mut r = Resolver::new(params(), 2);
        // Receding: robot 1 drives away faster than robot 0 follows.
        resolve(
            &mut r,
            &[
                robot(0.0, 0.0, 1.0, 0.0, 0.0),
                robot(1.5, 0.0, 2.0, 0.0, 0.0),
            ],
            0.02,
        );
        assert!(r.decisions().iter().all(|d| !d.in_list && !d.held));
        // Head-on, but on different layers.
        let mut inputs = head_on(0.0, 1.0);
        inputs[1].layer = Locomotion::Aerial;
        resolve(&mut r, &inputs, 0.02);
        assert!(r.decisions().iter().all(|d| !d.in_list));
        assert_eq!(r.largest_list(), 0);
    }

    #[test]
    fn a_follower_driving_into_a_held_robot_joins_its_list() {
        // 0 and 1 head-on (0 goes first, 1 held); 2 follows 1 at its speed, so rule 1 alone
        // never links 2, but it would drive into 1 standing still.
        let inputs = [
            robot(0.0, 0.0, 1.0, 0.0, 0.0),
            robot(1.5, 0.0, -1.0, 0.0, 1.0),
            robot(3.0, 0.0, -1.0, 0.0, 2.0),
        ];
        let mut r = Resolver::new(params(), 3);
        resolve(&mut r, &inputs, 0.02);
        assert!(r.decisions().iter().all(|d| d.in_list));
        assert_eq!(r.largest_list(), 3);
        assert_eq!(held(&r), [false, true, true]);
    }

    #[test]
    fn a_deadlocked_list_rotates_after_deadlock_after_s() {
        // dt 0.25 s (exact in binary): the stall timer reaches 2 s at the 9th step.
        let inputs = head_on(2.0, 1.0);
        let mut r = Resolver::new(params(), 2);
        for step in 1..=8 {
            resolve(&mut r, &inputs, 0.25);
            assert_eq!(held(&r), [true, false], "step {step}");
            assert_eq!(r.deadlocked_lists(), 0, "step {step}");
        }
        resolve(&mut r, &inputs, 0.25);
        assert_eq!(r.deadlocked_lists(), 1);
        assert!(r.decisions().iter().all(|d| d.deadlock_detected));
        // Algorithm 5's swap: the next robot in priority order moves.
        assert_eq!(held(&r), [false, true]);
        // The stall timers restarted: the next rotation comes 8 steps later.
        for step in 10..=16 {
            resolve(&mut r, &inputs, 0.25);
            assert_eq!(held(&r), [false, true], "step {step}");
            assert_eq!(r.deadlocked_lists(), 0, "step {step}");
        }
        resolve(&mut r, &inputs, 0.25);
        assert_eq!(r.deadlocked_lists(), 1);
        assert_eq!(held(&r), [true, false]);
        // Leaving the rotated list resolves the deadlock for both.
        let mut parted = inputs.clone();
        parted[1].intent = Vec2::new(2.0, 0.0);
        resolve(&mut r, &parted, 0.25);
        assert!(
            r.decisions()
                .iter()
                .all(|d| !d.in_list && d.deadlock_resolved)
        );
    }

    #[test]
    fn progress_along_the_path_is_no_deadlock() {
        let mut inputs = head_on(2.0, 1.0);
        let mut r = Resolver::new(params(), 2);
        for step in 0..40 {
            // The head gains 0.1 m per step (more than the 0.05 m tolerance).
            inputs[1].remaining = 10.0 - 0.1 * step as f32;
            resolve(&mut r, &inputs, 0.25);
            assert_eq!(r.deadlocked_lists(), 0, "step {step}");
            assert_eq!(held(&r), [true, false], "step {step}");
        }
    }

    #[test]
    fn a_robot_standing_still_is_steered_around_right_side_first() {
        // Robot 1 stands 1.2 m ahead; clearance 0.4 + 0.4 + 0.2 = 1 m needs a deflection of
        // asin(1 / 1.2) = 56.4 degrees: the first clear candidate is 60 degrees to the right.
        let inputs = [robot(5.0, 5.0, 1.0, 0.0, 0.0), idle(6.2, 5.0)];
        let mut r = Resolver::new(params(), 2);
        resolve(&mut r, &inputs, 0.02);
        assert!(r.decisions().iter().all(|d| !d.in_list));
        let g = grid(&[]);
        let w = steer(&mut r, &inputs, 0, &g, None).expect("a clear heading");
        let right = Vec2::new(0.5, -(3f32.sqrt()) / 2.0);
        assert!((w - right).length() < 1e-5, "{w:?}");
        // Nothing in the way: the intent is kept.
        let free = [robot(5.0, 5.0, 1.0, 0.0, 0.0), idle(5.0, 8.0)];
        resolve(&mut r, &free, 0.02);
        assert_eq!(steer(&mut r, &free, 0, &g, None), Some(Vec2::new(1.0, 0.0)));
    }

    #[test]
    fn steering_keeps_ground_robots_off_debris_and_stops_when_boxed_in() {
        // Debris just below the robot (top edge at y = 4.45): the right-hand deflection would
        // drive towards it, so the robot turns left instead.
        let block = StaticObstacle {
            shape: StaticShape::Cuboid(Cuboid::new(Vec2::new(3.0, 0.4))),
            pose: Pose::translation(5.0, 4.05),
            is_wall: false,
        };
        let g = grid(&[block]);
        let inputs = [robot(5.0, 4.95, 1.0, 0.0, 0.0), idle(6.2, 4.95)];
        let mut r = Resolver::new(params(), 2);
        resolve(&mut r, &inputs, 0.02);
        let w =
            steer(&mut r, &inputs, 0, &g, Some(0.4 + STEER_STATIC_GAP_M)).expect("a clear heading");
        let left = Vec2::new(0.5, 3f32.sqrt() / 2.0);
        assert!((w - left).length() < 1e-5, "{w:?}");
        // Standing robots ahead, left and right: every heading up to 120 degrees collides.
        let boxed = [
            robot(5.0, 5.0, 1.0, 0.0, 0.0),
            idle(6.0, 5.0),
            idle(5.0, 6.0),
            idle(5.0, 4.0),
        ];
        let mut r = Resolver::new(params(), 4);
        resolve(&mut r, &boxed, 0.02);
        assert_eq!(steer(&mut r, &boxed, 0, &grid(&[]), None), None);
    }

    /// A random robot in and around a 30 m x 30 m field: radius 0.2-0.5 m, sensing 1-6 m,
    /// speed up to 3 m/s, a third aerial, four in five active, keys with ties.
    fn random_robot() -> impl Strategy<Value = ResolverInput> {
        (
            (-3.0f32..33.0, -3.0f32..33.0),
            (-3.0f32..3.0, -3.0f32..3.0),
            (0.2f32..0.5, 1.0f32..6.0),
            (0u8..3, 0u8..5, 0u8..4),
        )
            .prop_map(
                |((x, y), (vx, vy), (radius, sensing), (layer, active, key))| ResolverInput {
                    pos: Vec2::new(x, y),
                    intent: if active == 0 {
                        Vec2::ZERO
                    } else {
                        Vec2::new(vx, vy)
                    },
                    radius,
                    sensing,
                    layer: if layer == 0 {
                        Locomotion::Aerial
                    } else {
                        Locomotion::Ground
                    },
                    active: active != 0,
                    key: f64::from(key),
                    remaining: 10.0,
                },
            )
    }

    /// Rules 2-3 as first written: every list's head recomputed after every follower round
    /// (the reference for the incremental rounds of [`Resolver::join_followers`]).
    fn join_by_full_rounds(r: &mut Resolver, inputs: &[ResolverInput]) {
        r.assign_heads(inputs);
        if !r.held.contains(&true) {
            return;
        }
        r.find_followers(inputs);
        for _ in 0..inputs.len() {
            let mut changed = false;
            for k in 0..r.follow.len() {
                let (i, j) = r.follow[k];
                if !r.held[i] && r.held[j] {
                    changed |= union(&mut r.parent, &mut r.size, &mut r.next, i, j);
                }
            }
            if !changed {
                break;
            }
            r.assign_heads(inputs);
        }
    }

    /// [`Resolver::resolve`] with the incremental or the reference follower rounds.
    fn resolve_with(
        r: &mut Resolver,
        inputs: &[ResolverInput],
        near: &(impl NeighbourQuery + Sync),
        full: bool,
    ) {
        r.measure_bounds(inputs);
        let query = r.layer_reach(inputs);
        r.neighbour_lists.refresh(inputs, query, near);
        r.track_progress(inputs, 0.25);
        r.link_pairs(inputs);
        if full {
            join_by_full_rounds(r, inputs);
        } else {
            r.join_followers(inputs);
        }
        r.decide(inputs);
        r.forget_unlisted(inputs);
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(64))]

        /// Reassigning heads only in the lists that grew decides as recomputing every list
        /// after every follower round, on random dense crowds over several steps.
        #[test]
        fn incremental_follower_rounds_equal_full_rounds(
            crowd in proptest::collection::vec(random_robot(), 2..300),
        ) {
            let n = crowd.len();
            let mut inputs = crowd;
            let (mut fast, mut full) = (Resolver::new(params(), n), Resolver::new(params(), n));
            for _ in 0..8 {
                let mut ix = NeighbourIndex::with_cells(30.0, 30.0, 3.0, 4.0);
                ix.rebuild(inputs.iter().map(|a| (a.layer, a.pos)), false);
                resolve_with(&mut fast, &inputs, &ix, false);
                resolve_with(&mut full, &inputs, &ix, true);
                proptest::prop_assert_eq!(fast.decisions(), full.decisions());
                proptest::prop_assert_eq!(&fast.lists, &full.lists);
                for (i, a) in inputs.iter_mut().enumerate() {
                    if !fast.decisions()[i].held {
                        a.pos += a.intent * 0.1;
                    }
                }
            }
        }

        /// The counting sort of the lists equals sorting every (root, id) of a component of two
        /// or more, on random unions.
        #[test]
        fn lists_are_sorted_by_root_then_id(
            n in 1usize..60,
            pairs in proptest::collection::vec((0usize..60, 0usize..60), 0..80),
        ) {
            let mut r = Resolver::new(params(), n);
            for &(a, b) in &pairs {
                union(&mut r.parent, &mut r.size, &mut r.next, a % n, b % n);
            }
            let mut expected: Vec<(usize, usize)> = (0..n)
                .map(|i| (find(&mut r.parent, i), i))
                .filter(|&(root, _)| r.size[root] >= 2)
                .collect();
            expected.sort_unstable();
            r.collect_lists(n);
            proptest::prop_assert_eq!(&r.lists, &expected);
        }

        /// On random crowds the resolver with the neighbour index decides exactly as with the
        /// all-pairs scan ([`AllRobots`]): the same lists, heads, deadlocks and steered
        /// velocities, step after step (robots drift by their commands between steps), under
        /// both hold rules, with the skin of one step per control period and the 1.5 m skin of
        /// longer periods.
        #[test]
        fn the_index_decides_as_the_all_pairs_scan(
            crowd in proptest::collection::vec(random_robot(), 2..150),
            crowd_rule in proptest::bool::ANY,
            drift_s in proptest::prop_oneof![proptest::strategy::Just(0.25f32), proptest::strategy::Just(0.02)],
        ) {
            let n = crowd.len();
            let mut inputs = crowd;
            let rule = if crowd_rule { yield_params() } else { params() };
            let mut with_index = Resolver::new(rule, n);
            let mut wide_skin = Resolver::new(rule, n).for_control_steps(5);
            let mut all_pairs = Resolver::new(rule, n);
            let g = ClearanceGrid::build(
                &Arena {
                    width_m: Positive::new(30.0).unwrap(),
                    height_m: Positive::new(30.0).unwrap(),
                    wall_thickness_m: Positive::new(0.5).unwrap(),
                },
                &[],
                0.5,
                2.0,
            );
            for step in 0..12 {
                let mut ix = NeighbourIndex::with_cells(30.0, 30.0, 3.0, 4.0);
                ix.rebuild(inputs.iter().map(|a| (a.layer, a.pos)), false);
                with_index.resolve(&inputs, &ix, 0.25);
                wide_skin.resolve(&inputs, &ix, 0.25);
                all_pairs.resolve(&inputs, &AllRobots(n), 0.25);
                proptest::prop_assert_eq!(with_index.decisions(), all_pairs.decisions());
                proptest::prop_assert_eq!(wide_skin.decisions(), all_pairs.decisions());
                proptest::prop_assert_eq!(with_index.largest_list(), all_pairs.largest_list());
                proptest::prop_assert_eq!(
                    with_index.deadlocked_lists(),
                    all_pairs.deadlocked_lists()
                );
                let mut commands = vec![Vec2::ZERO; n];
                for i in 0..n {
                    if with_index.decisions()[i].held {
                        continue;
                    }
                    let infl = (inputs[i].layer == Locomotion::Ground).then_some(0.45);
                    let a = with_index.steer(&inputs, i, &g, infl);
                    let b = all_pairs.steer(&inputs, i, &g, infl);
                    let c = wide_skin.steer(&inputs, i, &g, infl);
                    proptest::prop_assert_eq!(a, b, "step {} robot {}", step, i);
                    proptest::prop_assert_eq!(c, b, "step {} robot {} (1.5 m skin)", step, i);
                    commands[i] = a.unwrap_or(Vec2::ZERO);
                }
                // Drifts of up to about 1 m (the neighbour lists rebuilt every step) or 8 cm
                // (kept over several steps).
                for (a, v) in inputs.iter_mut().zip(&commands) {
                    a.pos += *v * drift_s;
                }
            }
        }
    }

    /// The resolver never reads `remaining` of an inactive robot (the world passes 0 for them,
    /// `Nav::resolver_input`): with NaN there instead of a length it decides the same lists,
    /// holds and deadlocks, step after step, on 64 random crowds (a fixed seed) in which one
    /// robot stops or starts every step (list members among them) and the active robots'
    /// progress stalls often enough that lists deadlock and rotate.
    #[test]
    fn inactive_robots_remaining_is_never_read() {
        let crowds = (
            proptest::collection::vec(random_robot(), 40..120),
            proptest::collection::vec((0usize..120, 0.0f32..0.5), 16),
        );
        let mut runner = proptest::test_runner::TestRunner::deterministic();
        let mut deadlocks = 0u64;
        for _ in 0..64 {
            let (mut inputs, flips) = ValueTree::current(&crowds.new_tree(&mut runner).unwrap());
            let n = inputs.len();
            let (mut real, mut nan) = (Resolver::new(params(), n), Resolver::new(params(), n));
            for (step, &(flip, progress_m)) in flips.iter().enumerate() {
                let f = &mut inputs[flip % n];
                f.active = !f.active;
                // Progress every sixth step only: lists standing four steps (2 s) deadlock.
                if step % 6 == 5 {
                    for a in inputs.iter_mut() {
                        a.remaining = (a.remaining - progress_m).max(0.0);
                    }
                }
                let masked: Vec<ResolverInput> = inputs
                    .iter()
                    .map(|a| ResolverInput {
                        remaining: if a.active { a.remaining } else { f32::NAN },
                        ..*a
                    })
                    .collect();
                let mut ix = NeighbourIndex::with_cells(30.0, 30.0, 3.0, 4.0);
                ix.rebuild(inputs.iter().map(|a| (a.layer, a.pos)), false);
                real.resolve(&inputs, &ix, 0.5);
                nan.resolve(&masked, &ix, 0.5);
                assert_eq!(real.decisions(), nan.decisions(), "step {step}");
                assert_eq!(real.lists, nan.lists, "step {step}");
                assert_eq!(
                    real.deadlocked_lists(),
                    nan.deadlocked_lists(),
                    "step {step}"
                );
                deadlocks += real.deadlocked_lists();
                for (i, a) in inputs.iter_mut().enumerate() {
                    if !real.decisions()[i].held {
                        a.pos += a.intent * 0.05;
                    }
                }
            }
        }
        assert!(deadlocks > 0, "no list deadlocked: the crowds test nothing");
    }
}
