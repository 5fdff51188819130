//! One trial on several threads: a large team's per-robot phases (path following up to the
//! planner, the contact gate of `sim.physics: NearBodies`, the read-back after the physics
//! step, the rebuild of the resolver's neighbour lists, its search for pairs about to collide
//! and its steering) run on the rayon pool the trial runs in, and the trial's numbers are
//! bit-identical for any number of threads, and when stepped from a thread outside every pool
//! (`docs/scaling.md`, "One trial on all cores"); and two trials side by side on one pool, as
//! a sweep runs them, finish.

use integration_tests::{load, method, scenario_path};
use usar_sim::mission::{Simulation, TrialResult};
use usar_sim::scenario::PhysicsStepping;
use usar_sim::scenario::Positive;
use usar_sim::world::{PARALLEL_MIN_ROBOTS, WorldStats};

/// Simulated seconds: grouping, the round start (every robot plans) and 100 control steps of
/// the team leaving its start grids, with collision lists, holds, steering, detours and
/// re-plans (with [`STALL_REPLAN_S`]).
const SHORT_S: f64 = 10.0;

/// `navigation.stall_replan_s` of the test's scenario, seconds (the file's is 3): short, so
/// that robots take detours and re-plan within [`SHORT_S`] (with the file's, none does before
/// about 15 s), and the serial part of parallel path following is run too.
const STALL_REPLAN_S: f64 = 0.5;

/// What a trial leaves: every robot's position, velocity and distance travelled as bits,
/// the mission's HP and energy as bits, its re-plans, and the trial's result.
struct Outcome {
    robots: Vec<[u64; 5]>,
    levels: Vec<[u64; 2]>,
    replans: Vec<u64>,
    /// The world's totals: steps, Rapier's steps (the gate), deadlocks, the largest list, the
    /// neighbour lists' rebuilds.
    stats: WorldStats,
    result: TrialResult,
}

/// `swarm-1000.ron` with [`STALL_REPLAN_S`], DIS, trial 0, [`SHORT_S`] seconds, in a rayon
/// pool of `threads` threads (per-robot phases parallel when `parallel`).
fn run(threads: usize, parallel: bool) -> Outcome {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a thread pool");
    pool.install(|| {
        assert_eq!(rayon::current_num_threads(), threads);
        trial(parallel)
    })
}

/// The trial of [`run`] on the calling thread, in whatever rayon pool it belongs to (the
/// global pool when it belongs to none).
fn trial(parallel: bool) -> Outcome {
    let stall = Positive::new(STALL_REPLAN_S).expect("positive");
    let s = load(&scenario_path("swarm-1000.ron"))
        .edit(|s| s.navigation.stall_replan_s = Some(stall))
        .expect("a valid edit");
    assert!(s.robots().len() >= PARALLEL_MIN_ROBOTS);
    assert_eq!(
        s.sim().physics,
        PhysicsStepping::NearBodies,
        "the gate runs per robot"
    );
    let mut sim = Simulation::builder(&s)
        .method(method("dis", &s))
        .duration_s(SHORT_S)
        .build()
        .expect("builds");
    sim.set_parallel(parallel);
    let result = sim.run_to_end().expect("runs");
    let robots = sim
        .world()
        .robots()
        .iter()
        .map(|r| {
            [
                r.position.x.to_bits(),
                r.position.y.to_bits(),
                r.velocity.x.to_bits(),
                r.velocity.y.to_bits(),
                r.distance_travelled_m.to_bits(),
            ]
        })
        .collect();
    let levels = sim
        .robots()
        .iter()
        .map(|r| [r.hp_pct.to_bits(), r.energy_pct.to_bits()])
        .collect();
    let replans = sim
        .world()
        .robots()
        .iter()
        .map(|r| r.counters.replans)
        .collect();
    Outcome {
        robots,
        levels,
        replans,
        stats: *sim.world().stats(),
        result,
    }
}

#[test]
fn a_large_team_gives_the_same_bits_on_any_thread_count_in_or_outside_a_pool() {
    let one = run(1, true);
    // The trial did something worth comparing: robots moved, some were held or steered.
    let moved = one
        .robots
        .iter()
        .filter(|r| f64::from_bits(r[4]) > 0.5)
        .count();
    assert!(moved > 500, "{moved} robots moved more than 0.5 m");
    // Some robots needed the planner while following their paths (detours, re-plans): the
    // part of path following that stays serial ran between the parallel parts.
    let replanned = one.replans.iter().filter(|&&r| r > 0).count();
    assert!(replanned >= 10, "{replanned} robots re-planned");
    // The gate let Rapier step on some steps only, and the resolver found pairs about to
    // collide (lists of more than one robot).
    let stats = one.stats;
    assert!(
        0 < stats.physics_steps && stats.physics_steps < stats.steps,
        "{stats:?}"
    );
    assert!(stats.max_list_len > 1, "{stats:?}");
    // The resolver rebuilt its neighbour lists (robot by robot in parallel) more than once.
    assert!(stats.list_rebuilds > 1, "{stats:?}");
    for (threads, parallel) in [(2, true), (4, true), (4, false), (0, true)] {
        // `0`: stepped from this test's thread, outside every pool: each step is handed over
        // whole to a thread of the global pool (`Simulation::step`).
        let other = if threads == 0 {
            outside_every_pool()
        } else {
            run(threads, parallel)
        };
        for (id, (a, b)) in one.robots.iter().zip(&other.robots).enumerate() {
            assert_eq!(a, b, "robot {id}, {threads} threads, parallel {parallel}");
        }
        assert_eq!(
            one.levels, other.levels,
            "{threads} threads, parallel {parallel}"
        );
        assert_eq!(
            one.stats, other.stats,
            "{threads} threads, parallel {parallel}"
        );
        assert_eq!(
            one.replans, other.replans,
            "{threads} threads, parallel {parallel}"
        );
        assert_eq!(
            format!("{:?}", one.result),
            format!("{:?}", other.result),
            "{threads} threads, parallel {parallel}"
        );
    }
}

/// The trial of [`run`] stepped from a thread outside every rayon pool, per-robot phases
/// parallel on a global pool of at least two threads (two when this test builds it).
fn outside_every_pool() -> Outcome {
    // An error when an earlier user of the global pool built it (one thread per core, or
    // `RAYON_NUM_THREADS`): the assertion below checks that it has more than one.
    let _built_before = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build_global()
        .is_err();
    std::thread::spawn(|| {
        assert_eq!(rayon::current_thread_index(), None, "outside every pool");
        assert!(
            rayon::current_num_threads() > 1,
            "the global pool has one thread (one core?): run with RAYON_NUM_THREADS=2, so that \
             the trial's per-robot phases run in parallel from outside every pool"
        );
        trial(true)
    })
    .join()
    .expect("the trial outside every pool")
}

/// Longest wait for [`two_trials_side_by_side_on_one_pool_finish`], seconds: its two 30 s
/// trials of `paper.ron` take well under a second each, even in a debug build.
const SIDE_BY_SIDE_TIMEOUT_S: u64 = 300;

/// Two trials side by side, one on each thread of a 2-thread rayon pool, as a sweep runs its
/// trials, both finish and agree. Built with Rapier's `parallel` feature they never finish:
/// each Rapier step waits for a task queued on its own busy thread (`docs/scaling.md`,
/// "Rapier's `parallel` feature"); this test then fails after [`SIDE_BY_SIDE_TIMEOUT_S`]
/// instead of hanging the suite.
#[test]
fn two_trials_side_by_side_on_one_pool_finish() {
    let (sender, receiver) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let s = load(&scenario_path("paper.ron"));
        let trial = || {
            Simulation::builder(&s)
                .method(method("dis", &s))
                .duration_s(30.0)
                .build()
                .expect("builds")
                .run_to_end()
                .expect("runs")
        };
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .expect("a thread pool");
        let (a, b) = pool.install(|| rayon::join(trial, trial));
        // The receiver is gone only when the test has already failed on the timeout.
        let _ = sender.send((format!("{a:?}"), format!("{b:?}")));
    });
    let timeout = std::time::Duration::from_secs(SIDE_BY_SIDE_TIMEOUT_S);
    let (a, b) = receiver.recv_timeout(timeout).unwrap_or_else(|e| {
        panic!("two trials on a 2-thread pool did not finish in {SIDE_BY_SIDE_TIMEOUT_S} s: {e}")
    });
    assert_eq!(a, b, "the same trial twice, side by side");
    assert!(a.contains("rescued"), "a trial result: {a}");
}
