//! Neighbour lists kept over several steps (Verlet lists) for the resolver's pair rules and the
//! contact gate's pair test.
//!
//! Every robot's list holds the robots of its layer within a *build radius* `B` of it at the
//! positions of the last rebuild (the *epoch*), and possibly some others. The lists stay valid
//! while, for each layer,
//!
//! `(q + 2 d) (1 + 1e-4) + 1e-4 <= B`
//!
//! where `q` bounds every robot's query radius this step (the resolver's reach) and `d` is the
//! largest distance any robot has moved since the epoch: two robots within `q` of each other
//! now were within `q + 2 d` at the epoch (triangle inequality; the factor and the term cover
//! `f32` rounding), so each is on the other's list. When the test fails for any layer (or the
//! team's size or a robot's layer changed, or a position is not finite) every list is rebuilt
//! from the caller's [`NeighbourQuery`] with `B = Q + s`, `s` the skin ([`skin_for_control_steps`]:
//! [`NEIGHBOUR_LIST_SKIN_M`] per step of the control period, at most three), `Q` the largest
//! `q` of the layer seen so far. The lists hold every robot within the step's query radius (not
//! necessarily every robot a fresh query returns: those also include a thin band beyond the
//! radius), in another order. The query radius (the resolver's reach) bounds every pair that
//! can pass the resolver's exact tests, the rules apply those tests to every candidate and do
//! not depend on the order, so they decide exactly as with a fresh query per robot and step
//! (tested against [`super::neighbours::AllRobots`]).
//!
//! `Q` only grows: a step with a much larger reach (a speed or sensing spike) makes every later
//! list longer (slower, still exact).
//!
//! Cost: a check per resolver run, `O(n)`; a rebuild, one query per robot. Robots of
//! `swarm-1000.ron` drive at up to 2.5 m/s, 25 cm per 0.1 s control period, and its lists have
//! the 1.5 m skin; with the software at every step (0.5 m skin, 5 cm per step) a 300 s trial
//! (15,000 steps, method DIS) rebuilt them between 2,000 and 3,000 times (counted with a
//! temporary print in the rebuild), about every five to seven steps.
//!
//! A rebuild of a large team runs robot by robot on the calling rayon pool
//! ([`NeighbourLists::set_parallel`]): each chunk of [`CHUNK_ROBOTS`] robots fills its own
//! buffer with its robots' lists, and the buffers are united in robot order, so the lists are
//! the same bytes as a serial rebuild on any number of threads (not in the paper).
//!
//! Reference: L. Verlet, "Computer 'experiments' on classical fluids. I. Thermodynamical
//! properties of Lennard-Jones molecules", Phys. Rev. 159, 98 (1967).

use parry2d::math::Vector as Vec2;
use rayon::prelude::*;

use super::nav_state::Nav;
use super::neighbours::NeighbourQuery;
use super::per_robot::CHUNK_ROBOTS;
use super::resolver_input::{ResolverInput, layer_slot};
use crate::scenario::Locomotion;

/// A robot as the lists see it: where it is and on which layer. The resolver lists its
/// [`ResolverInput`]s, the contact gate (`contact_gate.rs`) the robots' [`Nav`] states.
pub(super) trait Listed {
    /// The robot's centre, metres.
    fn centre(&self) -> Vec2;
    /// The robot's collision layer.
    fn layer(&self) -> Locomotion;
}

impl Listed for ResolverInput {
    fn centre(&self) -> Vec2 {
        self.pos
    }
    fn layer(&self) -> Locomotion {
        self.layer
    }
}

impl Listed for Nav {
    fn centre(&self) -> Vec2 {
        self.pos
    }
    fn layer(&self) -> Locomotion {
        self.layer
    }
}

/// Skin added to a layer's largest query radius when the lists are rebuilt, with the resolver
/// run every step, metres: a larger skin means longer lists and fewer rebuilds (a robot may
/// move `skin / 2` before the lists must be rebuilt). See [`skin_for_control_steps`].
pub const NEIGHBOUR_LIST_SKIN_M: f32 = 0.5;

/// The skin for a resolver run every `control_steps` steps (`sim.control_period_s`), metres:
/// [`NEIGHBOUR_LIST_SKIN_M`] times `min(control_steps, 3)`, since robots move that many times
/// farther between two runs. The lists are exact at any skin (module docs), so the skin only
/// trades rebuilds against list length. Measured (scaling bench, 1,000 robots, 6,000 steps
/// at a period of 5 steps, resolver and intents): 0.59 s with 0.5 m, 0.55 s with 1.0 m, 0.54
/// to 0.55 s with 1.5 m, 0.55 s with 2 m and 3 m; at one step per period 0.25 m and 1 m were no
/// faster than 0.5 m.
pub fn skin_for_control_steps(control_steps: u64) -> f32 {
    NEIGHBOUR_LIST_SKIN_M * control_steps.clamp(1, 3) as f32
}

/// Relative and absolute slack (dimensionless, metres) of the validity test, for `f32`
/// rounding of the displacements and the triangle inequality.
const VALIDITY_SLACK: f32 = 1e-4;

/// A robot's list in the flat ids: its start, the start of its ids above its own, its end.
type Span = (usize, usize, usize);

/// Per-robot neighbour lists over several steps (see the module docs).
#[derive(Debug, Clone)]
pub struct NeighbourLists {
    /// Skin of a rebuild, metres (see [`skin_for_control_steps`]).
    skin_m: f32,
    /// Positions (metres) and layers of the robots at the last rebuild.
    epoch_pos: Vec<Vec2>,
    epoch_layer: Vec<Locomotion>,
    /// Build radius of each layer (ground, aerial), metres; negative before the first build.
    build_m: [f32; 2],
    /// The largest query radius seen per layer, metres.
    high_m: [f32; 2],
    /// `ids[spans[i].0..spans[i].2]` is robot `i`'s list, its ids above `i` from
    /// `spans[i].1` on.
    spans: Vec<Span>,
    ids: Vec<usize>,
    /// Whether a rebuild runs on the calling rayon pool ([`NeighbourLists::set_parallel`]).
    parallel: bool,
    /// A parallel rebuild's buffers, one per chunk of [`CHUNK_ROBOTS`] robots: the chunk's
    /// ids and spans (relative to its ids), kept between rebuilds.
    chunks: Vec<(Vec<usize>, Vec<Span>)>,
}

impl Default for NeighbourLists {
    /// [`NeighbourLists::new`].
    fn default() -> Self {
        Self::new()
    }
}

impl NeighbourLists {
    /// Lists for no robot with the skin [`NEIGHBOUR_LIST_SKIN_M`]; the first
    /// [`NeighbourLists::refresh`] builds them.
    pub fn new() -> Self {
        Self::with_skin(NEIGHBOUR_LIST_SKIN_M)
    }

    /// Lists for no robot with a skin of `skin_m` metres (finite, > 0).
    pub fn with_skin(skin_m: f32) -> Self {
        Self {
            skin_m,
            epoch_pos: Vec::new(),
            epoch_layer: Vec::new(),
            build_m: [-1.0; 2],
            high_m: [0.0; 2],
            spans: Vec::new(),
            ids: Vec::new(),
            parallel: false,
            chunks: Vec::new(),
        }
    }

    /// Lets (`true`) or forbids (`false`, the default) a rebuild to run robot by robot on the
    /// threads of the calling rayon pool: the same lists either way (module docs).
    pub fn set_parallel(&mut self, parallel: bool) {
        self.parallel = parallel;
    }

    /// Makes the lists valid for the robots `inputs` (indexed by id) at their
    /// [`Listed::centre`]s (metres) on their [`Listed::layer`]s, whose query radii this step
    /// are at most `query_m` (metres, ground and aerial; a NaN radius makes every refresh
    /// rebuild): rebuilds them from `near` (which must index the robots at those centres)
    /// unless they still are.
    /// Returns whether it rebuilt.
    pub fn refresh(
        &mut self,
        inputs: &[impl Listed + Sync],
        query_m: [f32; 2],
        near: &(impl NeighbourQuery + Sync),
    ) -> bool {
        if !self.stale(inputs, query_m) {
            return false;
        }
        self.rebuild(inputs, near);
        true
    }

    /// Whether the lists must be rebuilt for the robots `inputs` (by id) whose query radii
    /// this step are at most `query_m` (metres, ground and aerial): the first half of
    /// [`NeighbourLists::refresh`], for a caller that must make its [`NeighbourQuery`] current
    /// before [`NeighbourLists::rebuild`]. Records `query_m` in the layers' largest radii.
    pub(super) fn stale(&mut self, inputs: &[impl Listed + Sync], query_m: [f32; 2]) -> bool {
        for (high, q) in self.high_m.iter_mut().zip(query_m) {
            *high = high.max(q);
        }
        !self.valid(inputs, query_m)
    }

    /// Whether every layer passes the validity test of the module docs. The largest
    /// displacement is found chunk by chunk on the calling rayon pool when the lists may run
    /// in parallel (a maximum is the same in any order).
    fn valid(&self, inputs: &[impl Listed + Sync], query_m: [f32; 2]) -> bool {
        if inputs.len() != self.epoch_pos.len() {
            return false;
        }
        let moved = |(robots, epoch): (&[_], (&[Vec2], &[Locomotion]))| {
            largest_moves(robots, epoch.0, epoch.1)
        };
        let chunks = (
            self.epoch_pos.chunks(CHUNK_ROBOTS),
            self.epoch_layer.chunks(CHUNK_ROBOTS),
        );
        let moved2 = if self.parallel && inputs.len() > CHUNK_ROBOTS {
            inputs
                .par_chunks(CHUNK_ROBOTS)
                .zip(
                    self.epoch_pos
                        .par_chunks(CHUNK_ROBOTS)
                        .zip(self.epoch_layer.par_chunks(CHUNK_ROBOTS)),
                )
                .with_max_len(1)
                .map(moved)
                .reduce(|| Some([0.0; 2]), merge_moves)
        } else {
            inputs
                .chunks(CHUNK_ROBOTS)
                .zip(chunks.0.zip(chunks.1))
                .map(moved)
                .fold(Some([0.0; 2]), merge_moves)
        };
        let Some(moved2) = moved2 else {
            return false;
        };
        (0..2).all(|l| {
            let need =
                (query_m[l] + 2.0 * moved2[l].sqrt()) * (1.0 + VALIDITY_SLACK) + VALIDITY_SLACK;
            need <= self.build_m[l]
        })
    }

    /// Rebuilds every list with the build radius `high + skin` of its layer from `near` (which
    /// must index the robots at `inputs[..]`'s centres): serially into the lists, or with
    /// [`NeighbourLists::set_parallel`] chunk by chunk on the calling rayon pool and then
    /// united in robot order (the same bytes).
    pub(super) fn rebuild(
        &mut self,
        inputs: &[impl Listed + Sync],
        near: &(impl NeighbourQuery + Sync),
    ) {
        for l in 0..2 {
            self.build_m[l] = self.high_m[l].max(0.0) + self.skin_m;
        }
        let build_m = self.build_m;
        let n = inputs.len();
        self.ids.clear();
        self.spans.clear();
        let chunks = n.div_ceil(CHUNK_ROBOTS);
        if self.parallel && chunks > 1 {
            if self.chunks.len() < chunks {
                self.chunks.resize_with(chunks, Default::default);
            }
            self.chunks[..chunks]
                .par_iter_mut()
                .enumerate()
                .with_max_len(1)
                .for_each(|(c, (ids, spans))| {
                    ids.clear();
                    spans.clear();
                    let robots = c * CHUNK_ROBOTS..((c + 1) * CHUNK_ROBOTS).min(n);
                    build_lists(inputs, robots, build_m, near, ids, spans);
                });
            for (ids, spans) in &self.chunks[..chunks] {
                let off = self.ids.len();
                self.ids.extend_from_slice(ids);
                self.spans
                    .extend(spans.iter().map(|&(a, m, b)| (a + off, m + off, b + off)));
            }
        } else {
            build_lists(inputs, 0..n, build_m, near, &mut self.ids, &mut self.spans);
        }
        self.epoch_pos.clear();
        self.epoch_layer.clear();
        self.epoch_pos.extend(inputs.iter().map(|a| a.centre()));
        self.epoch_layer.extend(inputs.iter().map(|a| a.layer()));
    }

    /// Robot `i`'s list (ids, any order; possibly `i` itself): every robot of its layer within
    /// this step's query radius of it, and possibly others (callers test each). Call after
    /// [`NeighbourLists::refresh`]; panics if `i` is not below the team size of that refresh.
    pub fn of(&self, i: usize) -> &[usize] {
        let (a, _, b) = self.spans[i];
        &self.ids[a..b]
    }

    /// The ids above `i` in robot `i`'s list (any order): each pair of robots within the
    /// query radius of the lower id once.
    pub fn above(&self, i: usize) -> &[usize] {
        let (_, a, b) = self.spans[i];
        &self.ids[a..b]
    }
}

/// The largest squared displacement per layer of `robots` from their `epoch_pos`, or `None`
/// if one is not finite (a NaN or infinite position) or changed its layer.
fn largest_moves(
    robots: &[impl Listed],
    epoch_pos: &[Vec2],
    epoch_layer: &[Locomotion],
) -> Option<[f32; 2]> {
    let mut moved2 = [0.0f32; 2];
    for (a, (&p0, &layer0)) in robots.iter().zip(epoch_pos.iter().zip(epoch_layer)) {
        let d2 = (a.centre() - p0).length_squared();
        if !d2.is_finite() || a.layer() != layer0 {
            return None;
        }
        let m = &mut moved2[layer_slot(a.layer())];
        *m = m.max(d2);
    }
    Some(moved2)
}

/// Two chunks' [`largest_moves`] together.
fn merge_moves(a: Option<[f32; 2]>, b: Option<[f32; 2]>) -> Option<[f32; 2]> {
    Some([a?[0].max(b?[0]), a?[1].max(b?[1])])
}

/// Appends the lists of `robots` (ids into `inputs`, ascending) to `ids` and their spans
/// (into `ids`) to `spans`: each robot's candidates from `near` within the build radius
/// `build_m` of its layer, its ids up to its own first, then those above it.
fn build_lists(
    inputs: &[impl Listed],
    robots: std::ops::Range<usize>,
    build_m: [f32; 2],
    near: &impl NeighbourQuery,
    ids: &mut Vec<usize>,
    spans: &mut Vec<Span>,
) {
    for i in robots {
        let (layer, centre) = (inputs[i].layer(), inputs[i].centre());
        let start = ids.len();
        near.candidates(layer, centre, build_m[layer_slot(layer)], ids);
        // Ids up to `i` first, then those above it.
        let list = &mut ids[start..];
        let mut mid = 0;
        for k in 0..list.len() {
            if list[k] <= i {
                list.swap(mid, k);
                mid += 1;
            }
        }
        spans.push((start, start + mid, ids.len()));
    }
}

#[cfg(test)]
mod tests {
    use proptest::prelude::*;

    use super::*;
    use crate::world::neighbours::NeighbourIndex;

    fn robot(x: f32, y: f32, layer: Locomotion) -> ResolverInput {
        ResolverInput {
            pos: Vec2::new(x, y),
            intent: Vec2::ZERO,
            radius: 0.4,
            sensing: 3.0,
            layer,
            active: true,
            key: 0.0,
            remaining: 0.0,
        }
    }

    fn index(inputs: &[ResolverInput]) -> NeighbourIndex {
        let mut ix = NeighbourIndex::with_cells(30.0, 30.0, 3.0, 4.0);
        ix.rebuild(inputs.iter().map(|a| (a.layer, a.pos)), false);
        ix
    }

    fn layer(ground: bool) -> Locomotion {
        if ground {
            Locomotion::Ground
        } else {
            Locomotion::Aerial
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(128))]

        /// After every refresh, each robot's list holds every robot of its layer within the
        /// step's query radius (and none of the other layer), `above` is the part of the list
        /// above the robot's id, over steps of small drifts (lists kept), jumps (teleports)
        /// and growing query radii.
        #[test]
        fn lists_cover_every_query_of_the_step(
            start in prop::collection::vec((-2.0f32..32.0, -2.0f32..32.0, any::<bool>()), 1..80),
            steps in prop::collection::vec(
                (prop::collection::vec((-0.06f32..0.06, -0.06f32..0.06), 80),
                 prop::option::weighted(0.2, (0usize..80, -2.0f32..32.0, -2.0f32..32.0)),
                 0.0f32..4.0, 0.0f32..6.0),
                1..30),
        ) {
            let mut inputs: Vec<_> =
                start.iter().map(|&(x, y, g)| robot(x, y, layer(g))).collect();
            let n = inputs.len();
            let mut lists = NeighbourLists::new();
            for (drift, jump, q_ground, q_aerial) in &steps {
                for (a, d) in inputs.iter_mut().zip(drift) {
                    a.pos += Vec2::new(d.0, d.1);
                }
                if let Some((k, x, y)) = *jump {
                    inputs[k % n].pos = Vec2::new(x, y);
                }
                let query = [*q_ground, *q_aerial];
                lists.refresh(&inputs, query, &index(&inputs));
                for (i, a) in inputs.iter().enumerate() {
                    let of = lists.of(i);
                    let q = query[layer_slot(a.layer)];
                    for (j, b) in inputs.iter().enumerate() {
                        let near = (b.pos - a.pos).length_squared() <= q * q;
                        if b.layer != a.layer {
                            prop_assert!(!of.contains(&j), "{} lists {} of the other layer", i, j);
                        } else if near {
                            prop_assert!(of.contains(&j), "{} misses {}", i, j);
                        }
                    }
                    let mut above: Vec<usize> = of.iter().copied().filter(|&j| j > i).collect();
                    let mut got = lists.above(i).to_vec();
                    above.sort_unstable();
                    got.sort_unstable();
                    prop_assert_eq!(above, got);
                }
            }
        }
    }

    /// A rebuild chunk by chunk on two threads gives the same lists, in the same order, as a
    /// serial one, over several chunks of both layers.
    #[test]
    fn a_parallel_rebuild_gives_the_same_lists() {
        let n = 3 * CHUNK_ROBOTS + 7;
        let inputs: Vec<_> = (0..n)
            .map(|i| {
                let (x, y) = ((i * 37 % 290) as f32 * 0.1, (i * 53 % 290) as f32 * 0.1);
                robot(x, y, layer(i % 3 != 0))
            })
            .collect();
        let query = [3.0, 4.0];
        let mut serial = NeighbourLists::new();
        assert!(serial.refresh(&inputs, query, &index(&inputs)));
        let mut parallel = NeighbourLists::new();
        parallel.set_parallel(true);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        assert!(pool.install(|| parallel.refresh(&inputs, query, &index(&inputs))));
        assert_eq!(serial.spans, parallel.spans);
        assert_eq!(serial.ids, parallel.ids);
        assert!(serial.ids.len() > 4 * n, "{} ids", serial.ids.len());
    }

    #[test]
    fn lists_are_kept_until_a_robot_moves_half_the_skin() {
        let mut inputs = vec![
            robot(5.0, 5.0, Locomotion::Ground),
            robot(7.0, 5.0, Locomotion::Ground),
            robot(5.0, 6.0, Locomotion::Aerial),
        ];
        let query = [3.0, 4.0];
        let mut lists = NeighbourLists::new();
        assert!(lists.refresh(&inputs, query, &index(&inputs)));
        // Moves that add up to less than half the skin (less the slack): the lists stay.
        let step = NEIGHBOUR_LIST_SKIN_M * 0.45 / 10.0;
        for _ in 0..10 {
            inputs[0].pos.x += step;
            assert!(!lists.refresh(&inputs, query, &index(&inputs)));
        }
        // A robot beyond half the skin from its epoch position: rebuilt.
        inputs[0].pos.x += NEIGHBOUR_LIST_SKIN_M * 0.06;
        assert!(lists.refresh(&inputs, query, &index(&inputs)));
        // A larger query radius than the lists were built for: rebuilt.
        assert!(lists.refresh(
            &inputs,
            [3.0 + NEIGHBOUR_LIST_SKIN_M * 1.2, 4.0],
            &index(&inputs)
        ));
        assert!(!lists.refresh(
            &inputs,
            [3.0 + NEIGHBOUR_LIST_SKIN_M * 1.2, 4.0],
            &index(&inputs)
        ));
        // A non-finite position, or another team size: rebuilt.
        inputs[2].pos.x = f32::NAN;
        assert!(lists.refresh(&inputs, query, &index(&inputs)));
        inputs.pop();
        assert!(lists.refresh(&inputs, query, &index(&inputs)));
        assert!(!lists.refresh(&inputs, query, &index(&inputs)));
    }
}
