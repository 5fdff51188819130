//! Shared helpers of the cross-crate integration tests in `tests/tests/`.

use rne_core::grouping::{GroupingMethod, method_from_name};
use rne_core::{TrustModel, Weights};
use usar_sim::mission::Simulation;
use usar_sim::scenario::{self, ClampedNormal, Scenario, ScenarioSpec};

/// Path of a file in the workspace's `scenarios/` folder.
pub fn scenario_path(file: &str) -> String {
    format!("{}/../scenarios/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// Path of a file in the test data folder `tests/data/` (scenarios only the tests use).
pub fn data_path(file: &str) -> String {
    format!("{}/data/{file}", env!("CARGO_MANIFEST_DIR"))
}

/// A scenario file at `path`, loaded and validated.
///
/// # Panics
/// If the file does not load (that is a test failure).
pub fn load(path: &str) -> Scenario {
    scenario::load(path).unwrap_or_else(|e| panic!("{path}: {e}"))
}

/// `scenarios/paper.ron`, loaded and validated.
///
/// # Panics
/// If the file does not load (that is a test failure).
pub fn paper() -> Scenario {
    scenario::load(scenario_path("paper.ron")).expect("scenarios/paper.ron loads")
}

/// `scenarios/paper.ron` with its spec changed by `edit`, validated again
/// ([`Scenario::edit`]).
///
/// # Panics
/// If the edited scenario breaks a rule (that is a test failure).
pub fn paper_with(edit: impl FnOnce(&mut ScenarioSpec)) -> Scenario {
    paper()
        .edit(edit)
        .unwrap_or_else(|e| panic!("edited paper.ron: {e}"))
}

/// `scenarios/paper-v1.ron`, loaded and validated: the paper mission before the authors' clock
/// (per-paper-step costs, rounds when all are back, rests out of the round), pinned. The rule
/// tests change one rule of it at a time.
///
/// # Panics
/// If the file does not load (that is a test failure).
pub fn paper_v1() -> Scenario {
    scenario::load(scenario_path("paper-v1.ron")).expect("scenarios/paper-v1.ron loads")
}

/// `scenarios/paper-v1.ron` with its spec changed by `edit`, validated again
/// ([`Scenario::edit`]).
///
/// # Panics
/// If the edited scenario breaks a rule (that is a test failure).
pub fn paper_v1_with(edit: impl FnOnce(&mut ScenarioSpec)) -> Scenario {
    paper_v1()
        .edit(edit)
        .unwrap_or_else(|e| panic!("edited paper-v1.ron: {e}"))
}

/// A built-in grouping method by name (`rne`, `dis`, `eng`, `hp_dis`), RNE using the
/// scenario's needs weights.
///
/// # Panics
/// On an unknown name.
pub fn method(name: &str, s: &Scenario) -> Box<dyn GroupingMethod> {
    let model = TrustModel::with_weights(
        Weights::new(s.needs_weights().to_array().to_vec()).expect("weights"),
    );
    method_from_name(name, &model).expect("built-in method")
}

/// A "distribution" that always draws `level_pct` (no spread), for fixed starting levels.
///
/// # Panics
/// If `level_pct` is not in `[0, 100]`.
pub fn fixed(level_pct: f64) -> ClampedNormal {
    ClampedNormal::fixed(level_pct).expect("a level in [0, 100]")
}

/// `(method, trial, hard rescuees, easy rescuees)` of whole trials 0 and 1 of `s` for each
/// built-in grouping method, in the order rne, dis, eng, hp_dis: the golden numbers the
/// tests pin.
///
/// # Panics
/// If a trial fails (built-in methods do not).
pub fn golden_counts(s: &Scenario) -> Vec<(&'static str, u32, u32, u32)> {
    let mut out = Vec::new();
    for name in ["rne", "dis", "eng", "hp_dis"] {
        for trial in 0..2 {
            let r = Simulation::for_trial(s, method(name, s), trial)
                .run_to_end()
                .expect("built-in methods do not fail");
            let task = |n: &str| r.task_id(n).map_or(0, |t| r.rescued[t]);
            out.push((name, trial, task("hard"), task("easy")));
        }
    }
    out
}

/// `(method, trial, rescuees per task in the scenario's task order)` of whole trials `trials`
/// of `s` for each built-in grouping method, in the order rne, dis, eng, hp_dis.
///
/// # Panics
/// If a trial fails (built-in methods do not).
pub fn per_task_counts(
    s: &Scenario,
    trials: std::ops::Range<u32>,
) -> Vec<(&'static str, u32, Vec<u32>)> {
    let mut out = Vec::new();
    for name in ["rne", "dis", "eng", "hp_dis"] {
        for trial in trials.clone() {
            let r = Simulation::for_trial(s, method(name, s), trial)
                .run_to_end()
                .expect("built-in methods do not fail");
            assert_eq!(r.tasks, s.task_names());
            assert_eq!(r.rescued.iter().sum::<u32>(), r.rescued_total());
            out.push((name, trial, r.rescued));
        }
    }
    out
}

/// The longest stretch without progress of one trial, found by [`NoProgressMonitor`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct LongestStall {
    /// Length of the stretch, seconds.
    pub duration_s: f64,
    /// The robot's id.
    pub robot: usize,
    /// Simulated time at which the stretch ended (or the trial did), seconds.
    pub end_s: f64,
    /// Where the robot stood then, metres.
    pub at: (f64, f64),
}

#[derive(Debug, Clone, Copy, Default)]
struct Track {
    goal: Option<(f64, f64)>,
    best_m: f64,
    since_s: f64,
    replans: u64,
}

/// Measures the bound on congestion stalls that `docs/world-model.md` states: for each ground
/// robot with a goal it has not reached and outside every collision list, the time without
/// progress, i.e. without its remaining path length (to its current waypoint, then along the
/// rest of its path) falling [`NoProgressMonitor::PROGRESS_M`] below its best value. The clock
/// restarts when the robot gets a new goal, reaches it, or is in a collision list (the
/// resolver's deadlock rotation bounds those stretches); a re-plan keeps the clock but takes
/// the new path's remaining length as the best value. Use it as a
/// [`usar_sim::mission::StepObserver`].
#[derive(Debug, Clone, Default)]
pub struct NoProgressMonitor {
    tracks: Vec<Track>,
    /// The longest stretch so far.
    pub longest: LongestStall,
}

impl NoProgressMonitor {
    /// Progress that restarts the clock, metres.
    pub const PROGRESS_M: f64 = 0.05;

    /// Updates every ground robot's clock after a step of `sim`.
    pub fn observe(&mut self, sim: &Simulation) {
        let world = sim.world();
        let now = world.time_s();
        self.tracks.resize(world.robots().len(), Track::default());
        for (id, r) in world.robots().iter().enumerate() {
            if r.locomotion != usar_sim::scenario::Locomotion::Ground {
                continue;
            }
            let mut prev = r.position;
            let remaining: f64 = world
                .waypoints(id)
                .map(|w| {
                    let d = (w - prev).norm();
                    prev = w;
                    d
                })
                .sum();
            let goal = r.goal.map(|g| (g.x, g.y));
            let t = &mut self.tracks[id];
            let watched = r.is_active() && !r.in_collision_list;
            if !watched || goal != t.goal {
                *t = Track {
                    goal,
                    best_m: remaining,
                    since_s: now,
                    replans: r.counters.replans,
                };
                continue;
            }
            if r.counters.replans != t.replans {
                t.replans = r.counters.replans;
                t.best_m = remaining;
            }
            if remaining < t.best_m - Self::PROGRESS_M {
                t.best_m = remaining;
                t.since_s = now;
            }
            if now - t.since_s > self.longest.duration_s {
                self.longest = LongestStall {
                    duration_s: now - t.since_s,
                    robot: id,
                    end_s: now,
                    at: (r.position.x, r.position.y),
                };
            }
        }
    }
}

/// Runs whole trial `trial` of `s` with the built-in method `name` and returns its longest
/// stall without progress ([`NoProgressMonitor`]) and its round lengths, seconds.
///
/// # Panics
/// If the trial fails (built-in methods do not).
pub fn longest_stall(s: &Scenario, name: &str, trial: u32) -> (LongestStall, Vec<f64>) {
    let mut monitor = NoProgressMonitor::default();
    let result = Simulation::for_trial(s, method(name, s), trial)
        .run_observed(&mut |sim: &Simulation| monitor.observe(sim))
        .expect("built-in methods do not fail");
    let rounds = result.rounds.iter().map(|r| r.end_s - r.start_s).collect();
    (monitor.longest, rounds)
}

/// The code blocks of `docs/library.md`, compiled and run as doctests
/// (`cargo test -p integration-tests --doc`), so the page shows the API as it is.
#[cfg(doctest)]
#[doc = include_str!("../../docs/library.md")]
pub struct LibraryDoc;

/// The code blocks of the crates' own READMEs (what crates.io shows), run as doctests.
#[cfg(doctest)]
#[doc = include_str!("../../crates/rne-core/README.md")]
pub struct RneCoreReadme;

/// See [`RneCoreReadme`].
#[cfg(doctest)]
#[doc = include_str!("../../crates/usar-sim/README.md")]
pub struct UsarSimReadme;
