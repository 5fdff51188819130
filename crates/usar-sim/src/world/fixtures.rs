//! Scenarios built in code for tests and benchmarks of the world (no RON needed).
//!
//! All use the paper's mission defaults (section VI.B) and the default navigation/collision
//! parameters (cell 0.25 m, clearance 0.1 m, waypoint tolerance 0.3 m, look-ahead 1 s, margin
//! 0.2 m, deadlock after 2 s) at `dt = 1/50 s`.

use nalgebra::Vector2;

use crate::scenario::{
    Arena, Circle, ClampedNormal, CollisionParams, Debris, Locomotion, MissionParams,
    NavigationParams, PointM, Rect, RobotKind, RobotStart, Role, Scenario, SimParams, Task,
    TaskLevel,
};

/// Body radius of the fixtures' ground robots, metres (as in `scenarios/*.ron`).
pub const GROUND_RADIUS_M: f64 = 0.4;
fn kind(name: &str, role: Role, locomotion: Locomotion, count: usize, radius: f64) -> RobotKind {
    let aerial = locomotion == Locomotion::Aerial;
    RobotKind {
        name: name.to_owned(),
        role,
        locomotion,
        count,
        quota: [count - count / 2, count / 2],
        body_radius_m: radius,
        max_speed_m_per_s: if aerial { 1.0 } else { 1.5 },
        sensing_range_m: if aerial { 12.0 } else { 2.0 },
        observing_range_m: if aerial { 50.0 } else { 0.05 },
        carrying_capacity: if role == Role::Carrier { 6 } else { 1 },
        rescuing_resources: if role == Role::Supplier { 10 } else { 1 },
        hp_needs_full: if aerial { 1.0 } else { 2.0 },
        energy_needs_full: if aerial { 1.0 } else { 1.5 },
    }
}

fn task(level: TaskLevel, goal: PointM) -> Task {
    let min = PointM::new(goal.x - 0.5, goal.y - 0.5);
    let max = PointM::new(goal.x + 0.5, goal.y + 0.5);
    Task {
        level,
        search_area: Rect { min, max },
        goal,
        drop_off: Circle {
            center: goal,
            radius_m: 0.5,
        },
        rescuees: vec![goal],
    }
}

fn scenario(
    name: &str,
    arena: Arena,
    kinds: Vec<RobotKind>,
    robots: Vec<RobotStart>,
    goals: [PointM; 2],
    debris: Vec<Debris>,
) -> Scenario {
    let level = |mean_pct, std_dev_pct| ClampedNormal {
        mean_pct,
        std_dev_pct,
        min_pct: 0.0,
        max_pct: 100.0,
    };
    Scenario {
        name: name.to_owned(),
        description: format!("world fixture `{name}`"),
        arena,
        kinds,
        robots,
        rest_station: Circle {
            center: PointM::new(arena.width_m / 2.0, arena.height_m / 2.0),
            radius_m: 0.5,
        },
        tasks: [
            task(TaskLevel::Easy, goals[0]),
            task(TaskLevel::Hard, goals[1]),
        ],
        debris,
        radiation_zones: Vec::new(),
        needs_weights: [1.0; crate::scenario::NEEDS_LEN],
        mission: MissionParams {
            duration_s: 600.0,
            energy_pct_per_moving_step: 0.0045,
            hp_pct_per_step_in_radiation: 0.0003,
            low_energy_pct: 30.0,
            low_hp_pct: 30.0,
            recharge_s: 30.0,
            no_observer_speed_factor: 0.7,
            initial_energy: level(80.0, 20.0),
            initial_hp: level(90.0, 10.0),
        },
        navigation: NavigationParams {
            grid_cell_m: 0.25,
            clearance_m: 0.1,
            waypoint_tolerance_m: 0.3,
        },
        collision: CollisionParams {
            enabled: true,
            lookahead_s: 1.0,
            safety_margin_m: 0.2,
            deadlock_after_s: 2.0,
        },
        sim: SimParams {
            dt_s: 0.02,
            seed: 1,
        },
    }
}

/// The debris block of [`debris_crossing`]: a 4 m x 4 m square centred at (10, 5).
pub fn debris_block() -> Debris {
    Debris::Rect {
        center: PointM::new(10.0, 5.0),
        half_extents_m: Vector2::new(2.0, 2.0),
        rotation_rad: 0.0,
    }
}

/// A 20 m x 10 m arena with one debris block ([`debris_block`]) in the middle, one ground robot
/// (id 0) at (3, 5.5) and one aerial robot (id 1) at (3, 4.5); the straight lines to (17, 5.5)
/// and (17, 4.5) cross the block.
pub fn debris_crossing() -> Scenario {
    let kinds = vec![
        kind(
            "carrier",
            Role::Carrier,
            Locomotion::Ground,
            1,
            GROUND_RADIUS_M,
        ),
        kind("observer", Role::Observer, Locomotion::Aerial, 1, 0.3),
    ];
    let robots = vec![
        RobotStart {
            kind: 0,
            start_in_world: PointM::new(3.0, 5.5),
        },
        RobotStart {
            kind: 1,
            start_in_world: PointM::new(3.0, 4.5),
        },
    ];
    let arena = Arena {
        width_m: 20.0,
        height_m: 10.0,
        wall_thickness_m: 0.5,
    };
    let goals = [PointM::new(17.0, 5.5), PointM::new(17.0, 4.5)];
    scenario(
        "debris-crossing",
        arena,
        kinds,
        robots,
        goals,
        vec![debris_block()],
    )
}
