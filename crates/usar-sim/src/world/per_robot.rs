//! The per-robot outputs of a step's parallel phases (`parallel.rs`), kept between steps, and
//! when those phases run in parallel (team size threshold, rayon pool).
//!
//! Not in the paper.

use parry2d::math::Vector as Vec2;

use super::follow::Followed;
use super::steering::NearRobot;

/// Smallest team whose per-robot phases run on several threads (robots, 512). Smaller teams
/// stay serial: a phase costs tens of nanoseconds per robot, so below a few hundred robots
/// rayon's fork-join (a few microseconds per phase) costs more than it saves. The paper's 12
/// robots and the 100-robot teams are always serial.
pub const PARALLEL_MIN_ROBOTS: usize = 512;

/// Robots per parallel task (256): each task steers its robots with one scratch list.
pub(crate) const CHUNK_ROBOTS: usize = 256;

/// Runs `step` (one step of a world or a trial, whose per-robot phases run in parallel when
/// `parallel`) where those phases start cheaply: at once on a thread of a rayon pool, or when
/// `parallel` is false; otherwise, on a thread outside every pool, handed over once to a
/// thread of the global pool while the calling thread waits. Outside a pool, each parallel
/// phase would otherwise be handed over on its own (a step has several, each putting the
/// calling thread to sleep and waking it); stepped this way, a trial from outside every pool
/// runs as fast as one on a thread of the pool (`cargo bench -p usar-sim --bench
/// stepping_thread`). The same bits either way: where a phase runs never changes what it
/// computes.
pub(crate) fn on_a_pool_thread<R: Send>(parallel: bool, step: impl FnOnce() -> R + Send) -> R {
    if parallel && rayon::current_thread_index().is_none() {
        rayon::scope(|_| step())
    } else {
        step()
    }
}

/// The per-robot outputs of the parallel phases, kept between steps (allocated once for the
/// team, grown only with it), and whether they may run in parallel.
#[derive(Debug)]
pub(super) struct PerRobot {
    /// `World::set_parallel`: `false` keeps every phase serial.
    pub(super) enabled: bool,
    /// Each robot's steered velocity of this control step (rule 5), `None` when blocked;
    /// unused for held robots.
    pub(super) steered: Vec<Option<Vec2>>,
    /// One scratch list of nearby robots per task of [`CHUNK_ROBOTS`] robots.
    pub(super) scratch: Vec<Vec<NearRobot>>,
    /// Each robot's path following of this control step when it needed no planner, `None`
    /// when it does (filled only when path following runs in parallel).
    pub(super) followed: Vec<Option<Followed>>,
}

impl PerRobot {
    /// The buffers of `n` robots, parallel enabled.
    pub(super) fn new(n: usize) -> Self {
        Self {
            enabled: true,
            steered: vec![None; n],
            scratch: (0..n.div_ceil(CHUNK_ROBOTS).max(1))
                .map(|_| Vec::new())
                .collect(),
            followed: vec![None; n],
        }
    }

    /// Whether a phase over `n` robots runs in parallel: enabled, at least
    /// [`PARALLEL_MIN_ROBOTS`] robots, and the calling thread's rayon pool (the global pool
    /// outside any) has more than one thread.
    pub(super) fn parallel_for(&self, n: usize) -> bool {
        self.enabled && n >= PARALLEL_MIN_ROBOTS && rayon::current_num_threads() > 1
    }
}
