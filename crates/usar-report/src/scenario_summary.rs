//! [`ScenarioSummary`]: what a valid scenario holds, as data: the arena and timing, the kinds
//! with their quotas, the tasks with their distances from the team's starts, every robot's
//! start, the hazards, the scenario hash and the mission's parameters. `usar check` prints it
//! as text and the Python package's `Scenario.check()` returns it as a dict; both render this
//! one summary, so the two never disagree.
//!
//! Positions and distances are metres in the world frame, times seconds. Distances are
//! straight lines from a robot's start to a task's goal.

use serde::Serialize;
use usar_sim::scenario::{Debris, Locomotion, PointM, Scenario};
use usar_sim::world::ControlClock;
use usar_sweep::fingerprint::scenario_hash;
use usar_sweep::sweep::simulated_length_s;

/// What a valid scenario holds (see the [module documentation](self)).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ScenarioSummary {
    /// The scenario's name.
    pub name: String,
    /// Its description.
    pub description: String,
    /// The arena's width, height and wall thickness, m.
    pub arena: ArenaSummary,
    /// The physics step, s.
    pub dt_s: f64,
    /// `mission.duration_s` as written, s.
    pub duration_s: f64,
    /// What a trial simulates: the duration rounded up to whole steps, s.
    pub simulated_s: f64,
    /// Steps per trial.
    pub steps: u64,
    /// `sim.seed`.
    pub seed: u64,
    /// `sim.control_period_s` (`None`: the robots decide every step).
    pub control_period_s: Option<f64>,
    /// The control period in whole steps (1 without one).
    pub control_period_steps: u64,
    /// `sim.physics` as the scenario file writes it (`EveryStep`, `NearContacts`,
    /// `NearBodies`).
    pub physics: String,
    /// The kinds, in the scenario's order.
    pub kinds: Vec<KindSummary>,
    /// The tasks, in the scenario's order.
    pub tasks: Vec<TaskSummary>,
    /// Every robot, by id.
    pub robots: Vec<RobotSummary>,
    /// Per kind with robots, the extent of their starts and their distances to each goal.
    pub starts_by_kind: Vec<KindStarts>,
    /// The rest stations: centre (x, y) and radius, m.
    pub rest_stations: Vec<((f64, f64), f64)>,
    /// Rectangular debris pieces.
    pub debris_rects: usize,
    /// Disc-shaped debris pieces.
    pub debris_circles: usize,
    /// The radiation zones: centre (x, y), radius (m) and dose-rate factor.
    pub radiation_zones: Vec<((f64, f64), f64, f64)>,
    /// The needs weights (hp, v, sen, eng, res, cap, obs).
    pub needs_weights: [f64; 7],
    /// Entries of a needs vector (`usar_sim::scenario::NEEDS_LEN`).
    pub needs_len: usize,
    /// The scenario hash ([`scenario_hash`]).
    pub hash: String,
    /// The mission's parameters as the scenario file writes them (every field, defaults too).
    pub mission: serde_json::Value,
}

/// The arena's size, m.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ArenaSummary {
    /// Width (x), m.
    pub width_m: f64,
    /// Height (y), m.
    pub height_m: f64,
    /// Wall thickness, m.
    pub wall_thickness_m: f64,
}

/// One kind of robot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KindSummary {
    /// Its name.
    pub name: String,
    /// Its role (`Carrier`, `Supplier`, `Observer`).
    pub role: String,
    /// `ground` or `aerial`.
    pub locomotion: &'static str,
    /// Robots of the kind.
    pub count: usize,
    /// Its quota of each task: (task name, robots), in task order.
    pub quota: Vec<(String, usize)>,
    /// Top speed, m/s.
    pub max_speed_m_per_s: f64,
    /// Sensing range, m.
    pub sensing_range_m: f64,
    /// Observing range, m.
    pub observing_range_m: f64,
    /// Body radius, m.
    pub body_radius_m: f64,
    /// Rescuees carried at once.
    pub carrying_capacity: u32,
    /// Rescuing resources.
    pub rescuing_resources: u32,
}

/// One task.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TaskSummary {
    /// Its name.
    pub name: String,
    /// Its difficulty.
    pub difficulty: u32,
    /// Its place from the hardest, 0 for the hardest (as a grouping request counts tasks).
    pub rank: usize,
    /// Its rescuees.
    pub rescuees: usize,
    /// Its search area's corners (x, y), min then max, m.
    pub search_area_m: ((f64, f64), (f64, f64)),
    /// Its goal (x, y), m.
    pub goal_m: (f64, f64),
    /// Its drop-off's centre (x, y) and radius, m.
    pub drop_off: ((f64, f64), f64),
    /// Each kind's quota of it: (kind name, robots), in kind order.
    pub quota: Vec<(String, usize)>,
    /// The robots' distances from their starts to its goal: least, greatest and mean, m
    /// (infinite and 0 without robots).
    pub start_to_goal_m: (f64, f64, f64),
}

/// One robot.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RobotSummary {
    /// Its id.
    pub id: usize,
    /// Its kind's name.
    pub kind: String,
    /// Its kind's index.
    pub kind_index: usize,
    /// Its start (x, y), m.
    pub start_m: (f64, f64),
    /// Its distance to each task's goal: (task name, m), in task order.
    pub distance_to_goal_m: Vec<(String, f64)>,
}

/// The starts of one kind's robots.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KindStarts {
    /// The kind's name.
    pub kind: String,
    /// Its robots.
    pub count: usize,
    /// The least and greatest start x, m.
    pub x_range_m: (f64, f64),
    /// The least and greatest start y, m.
    pub y_range_m: (f64, f64),
    /// Per task, the least and greatest distance from a start to its goal, m.
    pub to_goal_m: Vec<(f64, f64)>,
}

impl ScenarioSummary {
    /// The summary of `s`.
    ///
    /// # Errors
    /// A scenario serde_json cannot write (not expected), as serde_json's error.
    pub fn of(s: &Scenario) -> Result<Self, serde_json::Error> {
        let (dt_s, duration_s) = (s.sim().dt_s.get(), s.mission().duration_s.get());
        let rects = s
            .debris()
            .iter()
            .filter(|d| matches!(d, Debris::Rect { .. }))
            .count();
        Ok(Self {
            name: s.name().to_owned(),
            description: s.description().to_owned(),
            arena: ArenaSummary {
                width_m: s.arena().width(),
                height_m: s.arena().height(),
                wall_thickness_m: s.arena().wall_thickness_m.get(),
            },
            dt_s,
            duration_s,
            simulated_s: simulated_length_s(duration_s, dt_s),
            steps: s.steps_per_trial(),
            seed: s.sim().seed,
            control_period_s: s.sim().control_period_s.map(|p| p.get()),
            control_period_steps: ControlClock::of(s.sim()).period_steps(),
            physics: format!("{:?}", s.sim().physics),
            kinds: kinds(s),
            tasks: tasks(s),
            robots: robots(s),
            starts_by_kind: starts_by_kind(s),
            rest_stations: s
                .rest_stations()
                .iter()
                .map(|c| (xy(c.center), c.radius_m))
                .collect(),
            debris_rects: rects,
            debris_circles: s.debris().len() - rects,
            radiation_zones: s
                .radiation_zones()
                .iter()
                .map(|z| (xy(z.area.center), z.area.radius_m, z.dose_rate_factor))
                .collect(),
            needs_weights: s.needs_weights().to_array(),
            needs_len: usar_sim::scenario::NEEDS_LEN,
            hash: scenario_hash(s)?,
            mission: serde_json::to_value(&s.spec().mission)?,
        })
    }
}

fn xy(p: PointM) -> (f64, f64) {
    (p.x, p.y)
}

/// The straight-line distance between `a` and `b`, m.
fn distance(a: PointM, b: PointM) -> f64 {
    (a - b).norm()
}

/// The least and greatest of `values` (infinite and minus infinite when there are none).
fn range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
        (lo.min(x), hi.max(x))
    })
}

fn kinds(s: &Scenario) -> Vec<KindSummary> {
    s.kinds()
        .iter()
        .map(|k| KindSummary {
            name: k.name.clone(),
            role: format!("{:?}", k.role),
            locomotion: match k.locomotion {
                Locomotion::Ground => "ground",
                Locomotion::Aerial => "aerial",
            },
            count: k.count,
            quota: s
                .tasks()
                .iter()
                .zip(&k.quota)
                .map(|(t, &q)| (t.name.clone(), q))
                .collect(),
            max_speed_m_per_s: k.max_speed_m_per_s,
            sensing_range_m: k.sensing_range_m,
            observing_range_m: k.observing_range_m,
            body_radius_m: k.body_radius_m,
            carrying_capacity: k.carrying_capacity,
            rescuing_resources: k.rescuing_resources,
        })
        .collect()
}

fn tasks(s: &Scenario) -> Vec<TaskSummary> {
    let order = s.hardest_first();
    s.tasks()
        .iter()
        .enumerate()
        .map(|(t, task)| {
            let ds: Vec<f64> = s
                .robots()
                .iter()
                .map(|r| distance(r.start_in_world, task.goal))
                .collect();
            let (lo, hi) = range(ds.iter().copied());
            let mean = ds.iter().sum::<f64>() / ds.len().max(1) as f64;
            let area = &task.search_area;
            TaskSummary {
                name: task.name.clone(),
                difficulty: task.difficulty,
                rank: order.iter().position(|&x| x == t).unwrap_or(0),
                rescuees: task.rescuees.len(),
                search_area_m: (xy(area.min), xy(area.max)),
                goal_m: xy(task.goal),
                drop_off: (xy(task.drop_off.center), task.drop_off.radius_m),
                quota: s
                    .kinds()
                    .iter()
                    .map(|k| (k.name.clone(), k.quota[t]))
                    .collect(),
                start_to_goal_m: (lo, hi, mean),
            }
        })
        .collect()
}

fn robots(s: &Scenario) -> Vec<RobotSummary> {
    s.robots()
        .iter()
        .enumerate()
        .map(|(id, r)| RobotSummary {
            id,
            kind: s.kind_of(id).name.clone(),
            kind_index: r.kind,
            start_m: xy(r.start_in_world),
            distance_to_goal_m: s
                .tasks()
                .iter()
                .map(|t| (t.name.clone(), distance(r.start_in_world, t.goal)))
                .collect(),
        })
        .collect()
}

fn starts_by_kind(s: &Scenario) -> Vec<KindStarts> {
    s.kinds()
        .iter()
        .enumerate()
        .filter_map(|(k, kind)| {
            let starts: Vec<PointM> = s
                .robots()
                .iter()
                .filter(|r| r.kind == k)
                .map(|r| r.start_in_world)
                .collect();
            (!starts.is_empty()).then(|| KindStarts {
                kind: kind.name.clone(),
                count: starts.len(),
                x_range_m: range(starts.iter().map(|p| p.x)),
                y_range_m: range(starts.iter().map(|p| p.y)),
                to_goal_m: s
                    .tasks()
                    .iter()
                    .map(|t| range(starts.iter().map(|&p| distance(p, t.goal))))
                    .collect(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    const PAPER: &str = include_str!("../../../scenarios/paper.ron");

    #[test]
    fn the_summary_agrees_with_itself_and_the_scenario() {
        let s = usar_sim::scenario::from_str(PAPER, "paper.ron").unwrap();
        let sum = ScenarioSummary::of(&s).unwrap();
        assert_eq!(sum.robots.len(), 12);
        assert_eq!(sum.hash, scenario_hash(&s).unwrap());
        assert_eq!(sum.steps, s.steps_per_trial());
        // Ranks count from the hardest task, 0 first, each once.
        let mut ranks: Vec<usize> = sum.tasks.iter().map(|t| t.rank).collect();
        ranks.sort_unstable();
        assert_eq!(ranks, (0..sum.tasks.len()).collect::<Vec<_>>());
        for (t, task) in sum.tasks.iter().enumerate() {
            let ds: Vec<f64> = sum
                .robots
                .iter()
                .map(|r| r.distance_to_goal_m[t].1)
                .collect();
            let (lo, hi, mean) = task.start_to_goal_m;
            assert_eq!(lo, ds.iter().copied().fold(f64::INFINITY, f64::min));
            assert_eq!(hi, ds.iter().copied().fold(f64::NEG_INFINITY, f64::max));
            approx::assert_relative_eq!(mean, ds.iter().sum::<f64>() / 12.0, max_relative = 1e-12);
            let quota: usize = task.quota.iter().map(|(_, q)| q).sum();
            assert!(quota <= sum.robots.len());
        }
        let counted: usize = sum.starts_by_kind.iter().map(|k| k.count).sum();
        assert_eq!(counted, sum.robots.len());
        for k in &sum.starts_by_kind {
            assert!(k.x_range_m.0 <= k.x_range_m.1 && k.y_range_m.0 <= k.y_range_m.1);
            assert_eq!(k.to_goal_m.len(), sum.tasks.len());
        }
        assert_eq!(sum.debris_rects + sum.debris_circles, s.debris().len());
        // Serialisable, with the mission's fields as the file writes them.
        let json = serde_json::to_value(&sum).unwrap();
        assert_eq!(
            json["mission"],
            serde_json::to_value(&s.spec().mission).unwrap()
        );
        assert_eq!(json["tasks"][0]["name"], sum.tasks[0].name.as_str());
    }
}
