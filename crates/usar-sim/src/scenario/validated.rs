//! The validated scenario: the only scenario type the simulator takes, sealed.
//!
//! A [`Scenario`] is made only by validation: from a file by [`crate::scenario::load`] or
//! [`crate::scenario::from_str`], from a spec by [`ScenarioSpec::validate`], in code by
//! [`ScenarioSpec::builder`], or from another scenario by [`Scenario::edit`] ("parse, don't
//! validate"). Its fields are private to the crate and read through accessors, so nothing in
//! the public API can change a validated scenario, and every scenario a trial gets has passed
//! every rule. To change one, edit its spec ([`Scenario::to_spec`], [`Scenario::edit`]); that
//! validates again.
//!
//! Frame and units: the world frame has its origin at the arena's bottom-left inner corner, x to
//! the right, y up; lengths in metres (`_m`), times in seconds (`_s`), speeds in metres per second
//! (`_m_per_s`), energy and health in percent of the robot's full level (`_pct`).

use serde::Serialize;

use super::model::{
    Circle, Debris, MAX_TRIAL_STEPS, PointM, RadiationZone, RobotKind, RobotStart, Task,
    trial_steps,
};
use super::params::{
    Arena, CollisionParams, MissionParams, NavigationParams, NeedsWeights, SimParams,
};
use super::spec::{ReportSpec, ScenarioSpec};

/// A fully validated USAR scenario (paper, sections IV-VI).
///
/// Read-only: every part has an accessor ([`Scenario::kinds`], [`Scenario::tasks`],
/// [`Scenario::mission`], ...); to change a value, [`Scenario::edit`] its spec, which
/// validates again.
///
/// Equality and serialisation (the scenario hash of the `experiments` crate) are those of the
/// validated, expanded parts a trial sees, not of the spec they came from: a `Row` of starts
/// and the `List` of its points give equal scenarios, and so do specs that differ only in
/// their `report` section. `scenario.to_spec().validate(..)` equals `scenario`.
#[derive(Debug, Clone, Serialize)]
pub struct Scenario {
    pub(crate) name: String,
    pub(crate) description: String,
    pub(crate) arena: Arena,
    pub(crate) kinds: Vec<RobotKind>,
    pub(crate) robots: Vec<RobotStart>,
    pub(crate) rest_stations: Vec<Circle>,
    pub(crate) tasks: Vec<Task>,
    pub(crate) debris: Vec<Debris>,
    pub(crate) radiation_zones: Vec<RadiationZone>,
    pub(crate) needs_weights: NeedsWeights,
    pub(crate) mission: MissionParams,
    pub(crate) navigation: NavigationParams,
    pub(crate) collision: CollisionParams,
    pub(crate) sim: SimParams,
    /// The spec this scenario was validated from, as it was given (compact forms such as
    /// start rows and debris fields not expanded).
    #[serde(skip)]
    pub(crate) spec: ScenarioSpec,
}

impl PartialEq for Scenario {
    /// Equal validated parts; the spec is left out (see [`Scenario`]).
    fn eq(&self, other: &Self) -> bool {
        let Self {
            name,
            description,
            arena,
            kinds,
            robots,
            rest_stations,
            tasks,
            debris,
            radiation_zones,
            needs_weights,
            mission,
            navigation,
            collision,
            sim,
            spec: _,
        } = self;
        *name == other.name
            && *description == other.description
            && *arena == other.arena
            && *kinds == other.kinds
            && *robots == other.robots
            && *rest_stations == other.rest_stations
            && *tasks == other.tasks
            && *debris == other.debris
            && *radiation_zones == other.radiation_zones
            && *needs_weights == other.needs_weights
            && *mission == other.mission
            && *navigation == other.navigation
            && *collision == other.collision
            && *sim == other.sim
    }
}

impl Scenario {
    /// Short name, non-empty, used for output folders (e.g. `paper`).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Free text shown by `usar check`; may be empty.
    pub fn description(&self) -> &str {
        &self.description
    }

    /// The walled field `[0, width] x [0, height]`, metres.
    pub fn arena(&self) -> &Arena {
        &self.arena
    }

    /// Robot kinds, at least one, in the merge order of the hierarchical grouping (paper:
    /// carrier, supplier, observer). A robot's [`RobotStart::kind`] indexes this list.
    pub fn kinds(&self) -> &[RobotKind] {
        &self.kinds
    }

    /// Every robot of the team, ordered by kind (in [`Scenario::kinds`] order) and then as
    /// listed in the file (start rows and grids expanded). A robot's id is its index here.
    pub fn robots(&self) -> &[RobotStart] {
        &self.robots
    }

    /// Where robots recharge energy and refresh HP (paper, section VI.B: "rest position"): at
    /// least one station, in the file's order. The paper has one; a robot leaving to recharge
    /// goes to the one with the shortest path from where it stands.
    pub fn rest_stations(&self) -> &[Circle] {
        &self.rest_stations
    }

    /// The tasks, at least one, in the file's order (a task's index here is its id everywhere:
    /// quotas, groups, results; rescuee grids expanded). [`Scenario::hardest_first`] orders
    /// them by difficulty.
    pub fn tasks(&self) -> &[Task] {
        &self.tasks
    }

    /// Static obstacles: the listed ones, then the generated ones (debris fields expanded).
    pub fn debris(&self) -> &[Debris] {
        &self.debris
    }

    /// Radiation zones (robots inside lose HP); may be empty.
    pub fn radiation_zones(&self) -> &[RadiationZone] {
        &self.radiation_zones
    }

    /// Weights of the 7-entry needs vector (hp, v, sen, eng, res, cap, obs), all > 0 (Eq. 8).
    pub fn needs_weights(&self) -> &NeedsWeights {
        &self.needs_weights
    }

    /// Mission rules: energy and HP costs, thresholds, recharging, initial levels (section
    /// VI.B).
    pub fn mission(&self) -> &MissionParams {
        &self.mission
    }

    /// Path planning of ground robots.
    pub fn navigation(&self) -> &NavigationParams {
        &self.navigation
    }

    /// Priority-based collision avoidance and deadlock solving (section V, Algorithm 5).
    pub fn collision(&self) -> &CollisionParams {
        &self.collision
    }

    /// Time step, control period and seed.
    pub fn sim(&self) -> &SimParams {
        &self.sim
    }

    /// What the reports of a sweep of this scenario compare it with (the file's `report`
    /// section; data only, the simulator does not read it). Default: no targets, no claims.
    pub fn report(&self) -> &ReportSpec {
        &self.spec.report
    }

    /// The spec this scenario was validated from, as it was given (start rows, rescuee grids
    /// and debris fields not expanded). [`ScenarioSpec::validate`] of it gives a scenario
    /// equal to this one.
    pub fn spec(&self) -> &ScenarioSpec {
        &self.spec
    }

    /// A copy of [`Scenario::spec`], to change and validate again (or see
    /// [`Scenario::edit`]): `scenario.to_spec().validate(origin)` equals `scenario`.
    pub fn to_spec(&self) -> ScenarioSpec {
        self.spec.clone()
    }

    /// The kind of robot `id`.
    ///
    /// # Panics
    /// If `id >= self.robots().len()`.
    pub fn kind_of(&self, id: usize) -> &RobotKind {
        &self.kinds[self.robots[id].kind]
    }

    /// The id (index in [`Scenario::tasks`]) of the task called `name`.
    pub fn task_id(&self, name: &str) -> Option<usize> {
        self.tasks.iter().position(|t| t.name == name)
    }

    /// Task ids from the hardest to the easiest: by `difficulty` descending, on equal ranks the
    /// task listed first first. Grouping methods fill tasks in this order.
    pub fn hardest_first(&self) -> Vec<usize> {
        let mut order: Vec<usize> = (0..self.tasks.len()).collect();
        order.sort_by_key(|&t| std::cmp::Reverse(self.tasks[t].difficulty));
        order
    }

    /// The index in [`Scenario::rest_stations`] of the station whose centre is nearest to `p`
    /// (straight-line distance, metres; on equal distances the one listed first). The mission
    /// sends a robot leaving to recharge to the station with the shortest *path*, and uses
    /// this only when no station can be reached (see `docs/scenario-format.md`, "Rest
    /// stations"); with the paper's single station, always 0.
    pub fn nearest_rest_station(&self, p: &PointM) -> usize {
        let mut best = (0, f64::INFINITY);
        for (i, c) in self.rest_stations.iter().enumerate() {
            let d2 = (p - c.center).norm_squared();
            if d2 < best.1 {
                best = (i, d2);
            }
        }
        best.0
    }

    /// Whether `p` lies inside any rest station (boundary included).
    pub fn in_rest_station(&self, p: &PointM) -> bool {
        self.rest_stations.iter().any(|c| c.contains(p))
    }

    /// The task names, in task-id order.
    pub fn task_names(&self) -> Vec<String> {
        self.tasks.iter().map(|t| t.name.clone()).collect()
    }

    /// Number of simulation steps in a trial of `mission.duration_s` ([`trial_steps`]; a
    /// validated scenario's trial is within [`MAX_TRIAL_STEPS`]).
    pub fn steps_per_trial(&self) -> u64 {
        trial_steps(self.mission.duration_s.get(), self.sim.dt_s.get()).unwrap_or(MAX_TRIAL_STEPS)
    }
}
