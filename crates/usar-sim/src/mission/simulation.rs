//! [`Simulation`]: one trial of the persistent USAR mission (paper, sections IV-VI) on top of
//! the physical [`World`]; [`TrialBuilder`], its one checked entry point; [`StepObserver`], the
//! hook that sees every step.

use rne_core::grouping::{GroupingMethod, method_from_name};
use rne_core::{NeedsVector, TrustModel, Weights};

use super::account::account;
use super::decide::decide;
use super::error::MissionError;
use super::events::MissionEvent;
use super::initial::{draw_initial_levels, trial_seed};
use super::metrics::{RoundRecord, TrialResult};
use super::needs::needs_vector;
use super::recorder::TrialInfo;
use super::rescuees::RescueeField;
use super::robot::MissionRobot;
use super::round_clock::{close_round, round_complete, start_round};
use super::state::MissionState;
use super::step_costs::charge_step_costs;
use crate::scenario::Scenario;
use crate::world::{ControlClock, World, on_a_pool_thread};

/// Sees every step of a trial (after the step), e.g. to draw a progress bar, sample robot
/// paths or record a replay. Any `FnMut(&Simulation)` is one.
pub trait StepObserver {
    /// Called after each step with the simulation as it is then.
    fn on_step(&mut self, sim: &Simulation);

    /// Called once by [`Simulation::run_observed`] before the first step, with the trial at
    /// its start (time 0 for a fresh trial); does nothing by default (a closure's is a no-op).
    fn on_start(&mut self, sim: &Simulation) {
        let _ = sim;
    }
}

impl<F: FnMut(&Simulation)> StepObserver for F {
    fn on_step(&mut self, sim: &Simulation) {
        self(sim)
    }
}

/// One trial: the world, the team's mission state, the rounds and the metrics.
///
/// ```no_run
/// use usar_sim::{mission::Simulation, scenario};
///
/// let s = scenario::load("scenarios/paper.ron")?;
/// let mut sim = Simulation::builder(&s).method_named("rne").trial(0).build()?;
/// let result = sim.run_to_end()?;
/// for (task, n) in result.tasks.iter().zip(&result.rescued) {
///     println!("{task}: {n} rescued");
/// }
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
pub struct Simulation {
    scenario: Scenario,
    method: Box<dyn GroupingMethod>,
    world: World,
    /// When the robots' software runs, from `scenario.sim`, computed once: passed to the
    /// world and to every step.
    clock: ControlClock,
    state: MissionState,
    steps_done: u64,
    total_steps: u64,
    trial: u32,
    seed: u64,
}

/// The RNE trust model of `scenario`: its needs weights, the default smoothing and natural
/// log (see `rne_core::TrustModel`).
///
/// # Errors
/// [`MissionError::Method`] if rne-core rejects the weights (they are > 0 and finite in a
/// valid scenario, so it does not).
pub fn trust_model(scenario: &Scenario) -> Result<TrustModel, MissionError> {
    let weights = Weights::new(scenario.needs_weights.to_array().to_vec())
        .map_err(|e| MissionError::Method(format!("needs_weights: {e}")))?;
    Ok(TrustModel::with_weights(weights))
}

/// Trial steps for `duration_s` at step `dt_s` ([`crate::scenario::trial_steps`]).
///
/// # Errors
/// [`MissionError::Duration`] unless `duration_s` is finite and `> 0` and the steps number at
/// most [`crate::scenario::MAX_TRIAL_STEPS`].
pub fn trial_steps(duration_s: f64, dt_s: f64) -> Result<u64, MissionError> {
    crate::scenario::trial_steps(duration_s, dt_s).map_err(MissionError::Duration)
}

impl Simulation {
    /// The checked way to set up a trial of `scenario`: choose the method, the trial (or seed)
    /// and the length, then [`TrialBuilder::build`].
    pub fn builder(scenario: &Scenario) -> TrialBuilder<'_> {
        TrialBuilder {
            scenario,
            method: None,
            trial: 0,
            seed: None,
            base_seed: None,
            duration_s: None,
        }
    }

    /// A trial whose starting team is drawn from `seed` (see [`draw_initial_levels`]), grouped
    /// by `method`, of the scenario's `mission.duration_s`. The trial index recorded in the
    /// result is 0.
    pub fn new(scenario: &Scenario, method: Box<dyn GroupingMethod>, seed: u64) -> Self {
        let levels = draw_initial_levels(scenario, seed);
        let clock = ControlClock::of(&scenario.sim);
        Self {
            world: World::new(scenario, &clock),
            clock,
            state: MissionState::new(scenario, &levels),
            scenario: scenario.clone(),
            method,
            steps_done: 0,
            total_steps: scenario.steps_per_trial(),
            trial: 0,
            seed,
        }
    }

    /// Trial `trial` (0-based) of a sweep over `scenario`: seed
    /// `trial_seed(scenario.sim.seed, trial)`, so every method sees the same starting team.
    pub fn for_trial(scenario: &Scenario, method: Box<dyn GroupingMethod>, trial: u32) -> Self {
        let mut sim = Self::new(scenario, method, trial_seed(scenario.sim.seed, trial));
        sim.trial = trial;
        sim
    }

    /// Replaces the trial length, seconds (see [`trial_steps`] for how it becomes steps);
    /// default `mission.duration_s`.
    ///
    /// # Errors
    /// As [`trial_steps`].
    pub fn with_duration_s(mut self, duration_s: f64) -> Result<Self, MissionError> {
        self.total_steps = trial_steps(duration_s, self.scenario.sim.dt_s.get())?;
        Ok(self)
    }

    /// The physical world (positions, velocities, resolver counters).
    pub fn world(&self) -> &World {
        &self.world
    }

    /// The trial's control clock ([`ControlClock::of`] the scenario's `sim`): the next step
    /// is a control step when `clock().is_control_step(world().steps())`.
    pub fn clock(&self) -> &ControlClock {
        &self.clock
    }

    /// Lets (`true`, the default) or forbids (`false`) the world's per-robot phases to run on
    /// the threads of the calling rayon pool for a team of at least
    /// [`PARALLEL_MIN_ROBOTS`](crate::world::PARALLEL_MIN_ROBOTS) robots
    /// ([`World::set_parallel`]). Results are bit-identical either way.
    pub fn set_parallel(&mut self, enabled: bool) {
        self.world.set_parallel(enabled);
    }

    /// The team's mission state, indexed by robot id.
    pub fn robots(&self) -> &[MissionRobot] {
        &self.state.robots
    }

    /// The mission state (robots, rescuees, sweeps, rounds, search clocks).
    pub fn state(&self) -> &MissionState {
        &self.state
    }

    /// Robot `id`'s needs vector now (Eqs. 19-21; see [`needs_vector`]): its current HP and
    /// energy, and the rescuing resources and free carrying capacity it holds at this step
    /// (under `mission.resource_stock: TeamPerRound` its own resources, which pick-ups leave
    /// alone: they draw on the team's stock). Grouping methods see the same vector with
    /// capacity refilled and, unless `resource_stock` is `AtRest`, resources refilled, as at
    /// the start of a round ([`crate::mission::snapshot`]).
    ///
    /// # Panics
    /// If `id` is not a robot id.
    pub fn needs(&self, id: usize) -> NeedsVector {
        let r = &self.state.robots[id];
        needs_vector(
            self.scenario.kind_of(id),
            &self.scenario.mission,
            r.hp_pct,
            r.energy_pct,
            r.resources,
            r.capacity_free,
        )
    }

    /// The rescuees of task `t` (a task id).
    ///
    /// # Panics
    /// If `t` is not a task id.
    pub fn rescuees(&self, t: usize) -> &RescueeField {
        &self.state.fields[t]
    }

    /// What happened in the mission during the last step, in order (empty before the first
    /// step): rounds, pick-ups, deliveries, leaves for and returns from the rest station.
    /// Deadlocks are counted per robot in [`crate::world::RobotState::counters`].
    pub fn events(&self) -> &[MissionEvent] {
        &self.state.events
    }

    /// The rounds so far (the last may be open).
    pub fn rounds(&self) -> &[RoundRecord] {
        self.state.recorder.rounds()
    }

    /// The scenario being run.
    pub fn scenario(&self) -> &Scenario {
        &self.scenario
    }

    /// The grouping method's name.
    pub fn method_name(&self) -> &str {
        self.method.name()
    }

    /// Simulated time, seconds.
    pub fn time_s(&self) -> f64 {
        self.world.time_s()
    }

    /// The trial's length: its steps times `sim.dt_s`, seconds.
    pub fn duration_s(&self) -> f64 {
        self.total_steps as f64 * self.scenario.sim.dt_s.get()
    }

    /// Steps taken and steps in the whole trial.
    pub fn progress(&self) -> (u64, u64) {
        (self.steps_done, self.total_steps)
    }

    /// Whether the time limit has been reached.
    pub fn is_finished(&self) -> bool {
        self.steps_done >= self.total_steps
    }

    /// Advances the trial by one step of `sim.dt_s`: on a control step (every step without
    /// `sim.control_period_s`) regroups if a round is due and lets every robot decide; steps
    /// the world; accounts energy and HP; and after the step before a control step, and
    /// after the last, reviews detections, pick-ups, deliveries and arrivals. Does nothing
    /// once the trial is finished. A team whose per-robot phases run in parallel
    /// ([`World::per_robot_parallel`]), stepped from a thread outside every rayon pool, takes
    /// the whole step on a thread of the global pool (the calling thread waits): the same bits,
    /// without handing each parallel phase over on its own.
    ///
    /// # Errors
    /// [`MissionError::Grouping`] if the grouping method fails; [`MissionError::World`] if the
    /// world refuses a command (a bug).
    pub fn step(&mut self) -> Result<(), MissionError> {
        if self.is_finished() {
            return Ok(());
        }
        let parallel = self.world.per_robot_parallel();
        on_a_pool_thread(parallel, || self.step_here())
    }

    /// [`Simulation::step`] on the calling thread (a thread of the pool its parallel phases
    /// run on, [`on_a_pool_thread`]).
    fn step_here(&mut self) -> Result<(), MissionError> {
        let (sc, world, st) = (&self.scenario, &mut self.world, &mut self.state);
        let clock = &self.clock;
        st.events.clear();
        if clock.is_control_step(world.steps()) {
            if !st.round_open {
                start_round(sc, world, st, self.method.as_ref())?;
            }
            decide(sc, world, st)?;
        }
        // The robots read back beside Rapier's step are charged there, the others by `account`.
        let (robots, costs) = (&mut st.robots, &mut st.step_costs);
        let totals = st.recorder.robot_costs_mut();
        world.step_beside(clock, |read| {
            charge_step_costs(sc, &read, robots, totals, costs);
        });
        self.steps_done += 1;
        let last = self.steps_done >= self.total_steps;
        // The review runs after the step before a control step (and after the last step), so
        // the decisions of that control step see what it found.
        let review = clock.is_control_step(world.steps()) || last;
        account(sc, world, st, review)?;
        if review && st.round_open && round_complete(sc, st, world.time_s()) {
            close_round(world, st, true);
        }
        if last && st.round_open {
            close_round(world, st, false);
        }
        Ok(())
    }

    /// Runs the trial to its time limit and returns its metrics.
    ///
    /// # Errors
    /// As [`Simulation::step`].
    pub fn run_to_end(&mut self) -> Result<TrialResult, MissionError> {
        self.run_observed(&mut |_: &Simulation| {})
    }

    /// Runs the trial to its time limit, calling `observer` once before the first step
    /// ([`StepObserver::on_start`]) and after every step, and returns its metrics.
    ///
    /// # Errors
    /// As [`Simulation::step`].
    pub fn run_observed(
        &mut self,
        observer: &mut dyn StepObserver,
    ) -> Result<TrialResult, MissionError> {
        observer.on_start(self);
        while !self.is_finished() {
            self.step()?;
            observer.on_step(self);
        }
        Ok(self.result())
    }

    /// The metrics so far (complete once [`Simulation::is_finished`]).
    pub fn result(&self) -> TrialResult {
        self.state.recorder.result(
            &self.scenario,
            &self.state.robots,
            &self.world,
            TrialInfo {
                method: self.method.display_name(),
                trial: self.trial,
                seed: self.seed,
                duration_s: self.duration_s(),
            },
        )
    }
}

/// Sets up one trial ([`Simulation::builder`]): the grouping method (built-in by name, with
/// the scenario's needs weights, or given), the starting team (trial `k` of a base seed, or an
/// explicit seed) and the trial's length, checked once by [`TrialBuilder::build`].
pub struct TrialBuilder<'a> {
    scenario: &'a Scenario,
    method: Option<Result<Box<dyn GroupingMethod>, String>>,
    trial: u32,
    seed: Option<u64>,
    base_seed: Option<u64>,
    duration_s: Option<f64>,
}

impl TrialBuilder<'_> {
    /// Groups with `method`.
    pub fn method(mut self, method: Box<dyn GroupingMethod>) -> Self {
        self.method = Some(Ok(method));
        self
    }

    /// Groups with the built-in method called `name` (`rne`, `dis`, `eng`, `hp_dis`; see
    /// `rne_core::grouping::method_from_name`), RNE with the scenario's needs weights.
    pub fn method_named(mut self, name: &str) -> Self {
        self.method = Some(
            trust_model(self.scenario)
                .map_err(|e| e.to_string())
                .and_then(|m| method_from_name(name, &m).map_err(|e| e.to_string())),
        );
        self
    }

    /// Trial `trial` (0-based): the starting team of seed `trial_seed(base, trial)`, `base`
    /// being [`TrialBuilder::base_seed`] or the scenario's `sim.seed`; default 0.
    pub fn trial(mut self, trial: u32) -> Self {
        self.trial = trial;
        self
    }

    /// The base seed trials are drawn from; default the scenario's `sim.seed`.
    pub fn base_seed(mut self, base_seed: u64) -> Self {
        self.base_seed = Some(base_seed);
        self
    }

    /// The starting team of exactly this seed (replaces the trial's seed; the trial index is
    /// still recorded).
    pub fn seed(mut self, seed: u64) -> Self {
        self.seed = Some(seed);
        self
    }

    /// The trial's length, seconds; default the scenario's `mission.duration_s`.
    pub fn duration_s(mut self, duration_s: f64) -> Self {
        self.duration_s = Some(duration_s);
        self
    }

    /// The simulation, ready to step.
    ///
    /// # Errors
    /// [`MissionError::Method`] without a method or for an unknown method name;
    /// [`MissionError::Duration`] for a bad length (see [`trial_steps`]).
    pub fn build(self) -> Result<Simulation, MissionError> {
        let method = match self.method {
            Some(Ok(m)) => m,
            Some(Err(e)) => return Err(MissionError::Method(e)),
            None => return Err(MissionError::Method("no grouping method given".into())),
        };
        let duration_s = self
            .duration_s
            .unwrap_or(self.scenario.mission.duration_s.get());
        let total_steps = trial_steps(duration_s, self.scenario.sim.dt_s.get())?;
        let base = self.base_seed.unwrap_or(self.scenario.sim.seed);
        let seed = self.seed.unwrap_or(trial_seed(base, self.trial));
        let mut sim = Simulation::new(self.scenario, method, seed);
        sim.trial = self.trial;
        sim.total_steps = total_steps;
        Ok(sim)
    }
}
