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
/// Width (y extent) of the [`corridor`] arena, metres.
pub const CORRIDOR_WIDTH_M: f64 = 3.4;
/// Length (x extent) of the [`corridor`] arena, metres.
pub const CORRIDOR_LENGTH_M: f64 = 24.0;

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

/// A straight walled corridor, [`CORRIDOR_LENGTH_M`] x [`CORRIDOR_WIDTH_M`], with
/// `per_side` (1..=4) ground robots (radius 0.4 m, 1.5 m/s) in a row on the centre line at each
/// end, facing each other: ids `0..per_side` start at the west end (id 0 in front, at
/// x = 6.5 m, then 5.5, ...), ids `per_side..2 per_side` at the east end (front at 17.5 m).
///
/// The width lets one robot pass another that stands still on the centre line (offset
/// `2 r + margin = 1.0 m`, plus `r + clearance + cell / 2` to the wall: `3.25 m`), but not two
/// robots driving head-on on the centre line. Use [`corridor_goals`] for the swap goals.
///
/// # Panics
/// If `per_side` is not in `1..=4`.
pub fn corridor(per_side: usize) -> Scenario {
    assert!((1..=4).contains(&per_side), "per_side must be 1..=4");
    let y = CORRIDOR_WIDTH_M / 2.0;
    let kinds = vec![
        kind(
            "eastbound",
            Role::Carrier,
            Locomotion::Ground,
            per_side,
            GROUND_RADIUS_M,
        ),
        kind(
            "westbound",
            Role::Carrier,
            Locomotion::Ground,
            per_side,
            GROUND_RADIUS_M,
        ),
    ];
    let mut robots = Vec::new();
    for k in 0..per_side {
        robots.push(RobotStart {
            kind: 0,
            start_in_world: PointM::new(6.5 - k as f64, y),
        });
    }
    for k in 0..per_side {
        robots.push(RobotStart {
            kind: 1,
            start_in_world: PointM::new(17.5 + k as f64, y),
        });
    }
    let arena = Arena {
        width_m: CORRIDOR_LENGTH_M,
        height_m: CORRIDOR_WIDTH_M,
        wall_thickness_m: 0.5,
    };
    let goals = [PointM::new(22.6, y), PointM::new(1.4, y)];
    scenario("corridor-wide", arena, kinds, robots, goals, Vec::new())
}

/// Swap goals of [`corridor`]: each robot drives to the far end, the front robot of a row to
/// the deepest slot (east-bound robot `k` to x = 22.5 - 1.5 k, west-bound robot `k` to
/// x = 1.5 + 1.5 k), so arrivals never block later ones (slots 1.5 m apart leave room for the
/// 1.0 m clearance `2 r + margin` plus the 0.3 m arrival tolerance).
pub fn corridor_goals(s: &Scenario) -> Vec<PointM> {
    let per_side = s.robots.len() / 2;
    let y = s.arena.height_m / 2.0;
    (0..s.robots.len())
        .map(|id| {
            if id < per_side {
                PointM::new(22.5 - 1.5 * id as f64, y)
            } else {
                PointM::new(1.5 + 1.5 * (id - per_side) as f64, y)
            }
        })
        .collect()
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
