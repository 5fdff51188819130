//! Shared navigation: paths a ground robot takes from a shared distance field (to a task's
//! goal point, a drop-off or the rest station) keep the body clear of every wall and debris
//! block, from random starts in the shipped scenarios, and a goal check answers as the plan.

use std::sync::LazyLock;

use proptest::prelude::*;
use usar_sim::scenario::{Locomotion, PointM, Scenario};
use usar_sim::world::{ControlClock, World};

fn scenario(file: &str) -> Scenario {
    let path = format!("{}/../../scenarios/{file}", env!("CARGO_MANIFEST_DIR"));
    let s = usar_sim::scenario::load(&path).unwrap_or_else(|e| panic!("{path}: {e}"));
    // The shipped files pin A*-only navigation (their published numbers); test the fields.
    s.edit(|spec| spec.navigation.shared_goal_fields = true)
        .unwrap_or_else(|e| panic!("{path}: {e}"))
}

static PAPER: LazyLock<Scenario> = LazyLock::new(|| scenario("paper.ron"));
static THREE_TASKS: LazyLock<Scenario> = LazyLock::new(|| scenario("three-tasks.ron"));

/// The shared goals of `s`: each task's goal point and drop-off centre, the rest station.
fn shared_goals(s: &Scenario) -> Vec<PointM> {
    s.tasks()
        .iter()
        .flat_map(|t| [t.goal, t.drop_off.center])
        .chain(s.rest_stations().iter().map(|c| c.center))
        .collect()
}

/// Teleports each ground robot of `s` (one per kind) to `(fx * W, fy * H)` if that point's
/// grid cell is free for its planning inflation, sends it to every shared goal and checks every
/// leg of the path, sampled each centimetre, against the exact distance to the statics.
fn check_paths_from(s: &Scenario, fx: f64, fy: f64) -> Result<(), TestCaseError> {
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(s, &clock);
    let start = PointM::new(fx * s.arena().width_m.get(), fy * s.arena().height_m.get());
    let cell = s.navigation().grid_cell_m.get();
    for kind in 0..s.kinds().len() {
        let Some(id) = s.robots().iter().position(|r| r.kind == kind) else {
            continue;
        };
        if s.kinds()[kind].locomotion != Locomotion::Ground {
            continue;
        }
        let radius = w.robot(id).radius_m;
        // A start whose cell is free: the planner does not snap it.
        let inflation = radius + s.navigation().clearance_m.get() + cell;
        if w.static_distance_at(&start) < inflation {
            continue;
        }
        for goal in shared_goals(s) {
            w.teleport(id, start).unwrap();
            // The goal check (from the grid's regions) answers as the plan does.
            let reachable = w.is_goal_reachable(id, goal);
            let planned = w.set_goal(id, Some(goal));
            prop_assert_eq!(reachable, planned.is_ok(), "{:?} from {:?}", goal, start);
            if planned.is_err() {
                continue;
            }
            let path: Vec<PointM> = std::iter::once(start).chain(w.waypoints(id)).collect();
            for leg in path.windows(2) {
                let n = ((leg[1] - leg[0]).norm() / 0.01).ceil().max(1.0) as u32;
                for k in 0..=n {
                    let p = leg[0] + (leg[1] - leg[0]) * (f64::from(k) / f64::from(n));
                    let d = w.static_distance_at(&p);
                    prop_assert!(
                        d >= radius,
                        "{}: kind {kind} from {start:?} to {goal:?}: {p:?} is {d} m from a \
                         static obstacle (body radius {radius} m); path {path:?}",
                        s.name()
                    );
                }
            }
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn shared_paths_clear_the_debris_of_paper(fx in 0.01f64..0.99, fy in 0.01f64..0.99) {
        check_paths_from(&PAPER, fx, fy)?;
    }

    #[test]
    fn shared_paths_clear_the_debris_of_three_tasks(fx in 0.01f64..0.99, fy in 0.01f64..0.99) {
        check_paths_from(&THREE_TASKS, fx, fy)?;
    }
}

/// `World::set_goals` gives every robot the result, goal and path that `World::set_goal`
/// gives it one robot after the other, on a team large enough to plan its shared goals side
/// by side (swarm-1000.ron's 1,000 robots on a two-thread pool): every shared goal, an own
/// goal in the open, and a goal outside the arena.
#[test]
fn set_goals_plans_as_set_goal_one_by_one() {
    let s = scenario("swarm-1000.ron");
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    pool.install(|| {
        let clock = ControlClock::of(s.sim());
        let (mut one, mut all) = (World::new(&s, &clock), World::new(&s, &clock));
        assert!(all.per_robot_parallel());
        let mut targets = shared_goals(&s);
        targets.push(PointM::new(120.5, 119.5));
        targets.push(PointM::new(-3.0, 10.0));
        let goals: Vec<(usize, PointM)> = (0..s.robots().len())
            .map(|id| (id, targets[id % targets.len()]))
            .collect();
        let by_one: Vec<String> = (goals.iter())
            .map(|&(id, g)| format!("{:?}", one.set_goal(id, Some(g))))
            .collect();
        let by_all: Vec<String> = (all.set_goals(&goals).iter())
            .map(|r| format!("{r:?}"))
            .collect();
        assert_eq!(by_one, by_all);
        assert!(by_all.iter().any(|r| r != "Ok(())"), "a goal fails");
        for id in 0..s.robots().len() {
            assert_eq!(one.robot(id).goal, all.robot(id).goal, "robot {id}");
            let path = |w: &World| w.waypoints(id).collect::<Vec<_>>();
            assert_eq!(path(&one), path(&all), "robot {id}");
        }
    });
}
