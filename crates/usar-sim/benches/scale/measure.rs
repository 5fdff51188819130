//! The scaling bench's measurement: the logic and the fair bare-Rapier baseline in
//! alternating blocks, the baseline replaying the velocities the logic commanded.
//!
//! Each block runs [`BLOCK_STEPS`] steps of the full simulation (`Simulation::step`), copying
//! after each step the velocity the world commanded for every body
//! (`World::commanded_velocities`, `n` x 8 bytes per step) into a buffer of one block; then
//! the same number of steps of bare Rapier (a `PhysicsScene` of the same scenario: same
//! bodies, colliders, integration parameters and static obstacles), each driven by that step's
//! commands with the world's write rule (`drive_bodies`). So both step the same motion, and
//! both see the same load of a shared machine. After each block (untimed) the bare bodies'
//! positions are compared with the world's: equal bit for bit while the replay is exact.

use std::time::Instant;

use parry2d::math::Vector as Vec2;
use usar_sim::mission::Simulation;
use usar_sim::scenario::Scenario;
use usar_sim::world::bodies::{PhysicsScene, to_point};
use usar_sim::world::drive_bodies;

/// Steps per block: the logic and the bare replay alternate this many steps at a time; the
/// recorded commands of one block (`n` x 50 x 8 bytes, 4 MB for 10,000 robots) are all that is
/// kept.
pub const BLOCK_STEPS: u64 = 50;

/// What one measurement covered and cost.
pub struct Measured {
    /// Steps run before the measured window, untimed (0: the window starts at the trial's
    /// first step).
    pub warmup: u64,
    /// Steps asked for (`--steps`).
    pub planned: u64,
    /// Steps measured, the same for the logic and the replay (after the warm-up).
    pub steps: u64,
    /// Blocks run.
    pub blocks: u64,
    /// CPU seconds of this thread in the logic's steps (with the copy of the commands).
    pub logic_cpu_s: f64,
    /// Wall-clock seconds of the logic's steps.
    pub logic_wall_s: f64,
    /// CPU seconds of this thread in the replay's steps (with the velocity writes).
    pub bare_cpu_s: f64,
    /// Why and where the measurement stopped before `planned` (the wall-clock budget).
    pub cut: Option<String>,
    /// The first block end (a step count) at which a bare body stood elsewhere than the
    /// world's, if any: the replay was then no longer the same motion.
    pub diverged_at: Option<u64>,
    /// Physics step, seconds.
    pub dt_s: f64,
}

impl Measured {
    /// Logic steps per CPU second.
    pub fn logic_rate(&self) -> f64 {
        self.steps as f64 / self.logic_cpu_s
    }

    /// Bare replay steps per CPU second.
    pub fn bare_rate(&self) -> f64 {
        self.steps as f64 / self.bare_cpu_s
    }

    /// The step cost of the logic over the bare replay's.
    pub fn ratio(&self) -> f64 {
        self.logic_cpu_s / self.bare_cpu_s
    }

    /// What the measurement covered, e.g. `steps 1-1500 (0.00-30.00 s simulated), measured
    /// in full`, or where it was cut.
    pub fn coverage(&self) -> String {
        let window = window(self.warmup, self.steps, self.dt_s);
        match &self.cut {
            None => format!("{window}, measured in full ({} blocks)", self.blocks),
            Some(why) => format!(
                "{window}: CUT after {} of {} steps ({why})",
                self.steps, self.planned
            ),
        }
    }
}

/// A window of `steps` steps after `warmup` steps of `dt_s` seconds, e.g. `steps 251-350
/// (5.00-7.00 s simulated)`.
pub fn window(warmup: u64, steps: u64, dt_s: f64) -> String {
    format!(
        "steps {}-{} ({:.2}-{:.2} s simulated)",
        warmup + 1,
        warmup + steps,
        warmup as f64 * dt_s,
        (warmup + steps) as f64 * dt_s
    )
}

/// CPU time of this process so far, all its threads, seconds
/// (`clock_gettime(CLOCK_PROCESS_CPUTIME_ID)`).
pub fn process_cpu_s() -> f64 {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ProcessCPUTime);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// CPU time of this thread so far, seconds (`clock_gettime(CLOCK_THREAD_CPUTIME_ID)`, exact
/// to the nanosecond: `/proc/thread-self/schedstat` moves only at scheduler ticks), so other
/// load on a shared machine does not count.
pub fn cpu_s() -> f64 {
    let t = rustix::time::clock_gettime(rustix::time::ClockId::ThreadCPUTime);
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// Whether every bare body stands where the world's robot does, bit for bit.
fn same_positions(scene: &PhysicsScene, sim: &Simulation) -> bool {
    let robots = sim.world().robots();
    scene
        .robot_bodies
        .iter()
        .zip(robots)
        .all(|(&b, r)| to_point(scene.physics.bodies[b].translation()) == r.position)
}

/// Trial 0 of `s` under `method`, long enough (1e5 simulated seconds) for any measurement.
/// Errors (one line): the simulation does not build (an unknown method).
pub fn trial(s: &Scenario, method: &str) -> Result<Simulation, String> {
    Simulation::builder(s)
        .method_named(method)
        .trial(0)
        .duration_s(1e5)
        .build()
        .map_err(|e| e.to_string())
}

/// The costs of one block: the logic's thread CPU and wall seconds, the replay's thread CPU
/// seconds.
struct BlockCost {
    logic_cpu_s: f64,
    logic_wall_s: f64,
    bare_cpu_s: f64,
}

/// Runs `len` steps of `sim` (the first of them step `first`), recording its commands, then
/// replays them on `scene` (see the module docs). Errors (one line): a step fails.
fn run_block(
    sim: &mut Simulation,
    scene: &mut PhysicsScene,
    commands: &mut Vec<Vec2>,
    len: u64,
    first: u64,
) -> Result<BlockCost, String> {
    let n = sim.world().robots().len().max(1);
    commands.clear();
    let (c0, w0) = (cpu_s(), Instant::now());
    for k in 0..len {
        sim.step().map_err(|e| format!("step {}: {e}", first + k))?;
        commands.extend(sim.world().commanded_velocities());
    }
    let c1 = cpu_s();
    let logic_wall_s = w0.elapsed().as_secs_f64();
    for step in commands.chunks_exact(n) {
        drive_bodies(scene, step);
        scene.step();
    }
    let c2 = cpu_s();
    Ok(BlockCost {
        logic_cpu_s: c1 - c0,
        logic_wall_s,
        bare_cpu_s: c2 - c1,
    })
}

/// Measures `steps` steps of trial 0 of `s` under `method` after `warmup` untimed ones
/// (logic and replay alike), logic and bare replay in alternating blocks (see the module
/// docs); with `budget_s`, stops at the first block end after that much wall-clock time (of
/// the measured window) and says so in [`Measured::cut`]. Errors (one line): the simulation
/// does not build (an unknown method) or a step fails.
pub fn measure(
    s: &Scenario,
    method: &str,
    warmup: u64,
    steps: u64,
    budget_s: Option<f64>,
) -> Result<Measured, String> {
    let mut sim = trial(s, method)?;
    let mut scene = PhysicsScene::new(s);
    let n = s.robots().len().max(1);
    let mut commands: Vec<Vec2> = Vec::with_capacity(n * BLOCK_STEPS as usize);
    let mut m = Measured {
        warmup,
        planned: steps,
        steps: 0,
        blocks: 0,
        logic_cpu_s: 0.0,
        logic_wall_s: 0.0,
        bare_cpu_s: 0.0,
        cut: None,
        diverged_at: None,
        dt_s: s.sim().dt_s.get(),
    };
    let mut done = 0;
    while done < warmup {
        let len = BLOCK_STEPS.min(warmup - done);
        run_block(&mut sim, &mut scene, &mut commands, len, done + 1)?;
        done += len;
        if m.diverged_at.is_none() && !same_positions(&scene, &sim) {
            m.diverged_at = Some(done);
        }
    }
    let t0 = Instant::now();
    while m.steps < steps {
        if let Some(b) = budget_s.filter(|&b| t0.elapsed().as_secs_f64() > b) {
            m.cut = Some(format!("wall-clock budget --budget-s {b} spent"));
            break;
        }
        let len = BLOCK_STEPS.min(steps - m.steps);
        let cost = run_block(&mut sim, &mut scene, &mut commands, len, done + 1)?;
        m.logic_cpu_s += cost.logic_cpu_s;
        m.logic_wall_s += cost.logic_wall_s;
        m.bare_cpu_s += cost.bare_cpu_s;
        m.steps += len;
        m.blocks += 1;
        done += len;
        if m.diverged_at.is_none() && !same_positions(&scene, &sim) {
            m.diverged_at = Some(done);
        }
    }
    Ok(m)
}

/// Peak resident set size of this process since the last [`reset_peak_rss`], MiB (`VmHWM`
/// of `/proc/self/status`; 0 where unavailable).
pub fn peak_rss_mib() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|kb| kb.parse::<f64>().ok())
        })
        .map_or(0.0, |kb| kb / 1024.0)
}

/// Resets the peak resident set size to the current one (writes `5` to
/// `/proc/self/clear_refs`, Linux 4.0 and later); returns whether it could.
pub fn reset_peak_rss() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}
