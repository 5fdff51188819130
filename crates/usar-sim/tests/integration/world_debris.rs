//! Aerial robots fly straight over debris; ground robots plan around it (paper, section IV:
//! debris is an adversary of ground robots only).

use crate::common;
use usar_sim::scenario::{Debris, PointM};

use usar_sim::world::{ControlClock, World};

/// Simulated time within which both robots must arrive, seconds (straight line: 14 m).
const BOUND_S: f64 = 30.0;

fn inside_block(p: &PointM, grow: f64) -> bool {
    let Debris::Rect {
        center,
        half_extents_m,
        ..
    } = common::debris_crossing().debris()[0]
    else {
        unreachable!()
    };
    (p.x - center.x).abs() <= half_extents_m.x + grow
        && (p.y - center.y).abs() <= half_extents_m.y + grow
}

#[test]
fn aerial_flies_over_debris_ground_goes_around() {
    let s = common::debris_crossing();
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(&s, &clock);
    w.set_goal(0, Some(s.tasks()[0].goal)).unwrap();
    w.set_goal(1, Some(s.tasks()[1].goal)).unwrap();
    // The ground path's waypoints keep the body clear of the block.
    let path: Vec<PointM> = w.waypoints(0).collect();
    assert!(
        path.len() >= 2,
        "a path around the block has corners: {path:?}"
    );
    let r = w.robot(0).radius_m;
    assert!(path.iter().all(|p| !inside_block(p, r)), "{path:?}");
    let mut aerial_over_block = false;
    let mut max_aerial_dev = 0.0f64;
    let steps = (BOUND_S / s.sim().dt_s.get()) as usize;
    for _ in 0..steps {
        w.step(&clock);
        let g = w.robot(0);
        assert!(
            !inside_block(&g.position, r - 0.05),
            "ground robot entered the debris at {:?}",
            g.position
        );
        let a = w.robot(1);
        aerial_over_block |= inside_block(&a.position, 0.0);
        max_aerial_dev = max_aerial_dev.max((a.position.y - 4.5).abs());
        if g.goal_reached && a.goal_reached {
            break;
        }
    }
    assert!(w.robot(0).goal_reached && w.robot(1).goal_reached);
    assert!(
        aerial_over_block,
        "the aerial robot flew through the block's footprint"
    );
    assert!(
        max_aerial_dev < 1e-3,
        "aerial robot flies straight ({max_aerial_dev} m)"
    );
    // Going around is longer than the straight 14 m (minus the 0.3 m arrival tolerance).
    assert!(w.robot(0).distance_travelled_m > 14.5);
    assert!(w.max_penetration_m() <= 0.05);
}

#[test]
fn unreachable_goal_is_reported_not_panicking() {
    let s = common::debris_crossing();
    let clock = ControlClock::of(s.sim());
    let mut w = World::new(&s, &clock);
    let err = w.set_goal(0, Some(PointM::new(50.0, 5.0))).unwrap_err();
    assert!(matches!(
        err,
        usar_sim::world::WorldError::Unreachable { id: 0, .. }
    ));
    assert!(w.robot(0).goal.is_none());
    // A goal in the middle of the block is not reachable for the ground robot...
    assert!(!w.is_goal_reachable(0, PointM::new(10.0, 5.0)));
    // ...but is for the aerial one.
    assert!(w.is_goal_reachable(1, PointM::new(10.0, 5.0)));
}

/// `set_goal_within` holds a robot to its own tolerance: the ground robot drives around the
/// block to its goal and stops within 1 mm of it (the arena's floor), where `set_goal` lets
/// it stop `navigation.waypoint_tolerance_m` (0.3 m) short; a tolerance below the floor, or
/// NaN, is raised to it instead of never being met.
#[test]
fn a_goal_set_within_a_tolerance_is_reached_within_it() {
    let s = common::debris_crossing();
    let tol = s.navigation().waypoint_tolerance_m.get();
    let goal = s.tasks()[0].goal;
    let stop_distance = |tolerance_m: Option<f64>| {
        let clock = ControlClock::of(s.sim());
        let mut w = World::new(&s, &clock);
        match tolerance_m {
            Some(t) => w.set_goal_within(0, goal, t).unwrap(),
            None => w.set_goal(0, Some(goal)).unwrap(),
        }
        for _ in 0..(BOUND_S / s.sim().dt_s.get()) as usize {
            w.step(&clock);
            if w.robot(0).goal_reached {
                break;
            }
        }
        assert!(w.robot(0).goal_reached, "{tolerance_m:?}: not reached");
        // Standing still after arrival.
        let at = w.robot(0).position;
        w.step(&clock);
        assert!((w.robot(0).position - at).norm() < 1e-6);
        (at - goal).norm()
    };
    let loose = stop_distance(None);
    assert!(loose > 0.5 * tol && loose <= tol + 1e-6, "{loose}");
    for t in [0.0, 1e-9, f64::NAN, 1e-3] {
        let d = stop_distance(Some(t));
        assert!(
            d <= 1e-3 + 1e-6,
            "tolerance {t}: stopped {d} m from the goal"
        );
    }
    let d = stop_distance(Some(0.1));
    assert!(d <= 0.1 + 1e-6 && d > 0.01, "tolerance 0.1: {d}");
}
