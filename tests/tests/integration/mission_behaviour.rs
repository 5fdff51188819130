//! Behaviour of the mission rules (paper, section VI.B), each on a variant of paper-v1.ron (the model before the authors' clock).

use integration_tests::{fixed, method, paper_v1, paper_v1_with};
use usar_sim::mission::{Phase, Simulation, hp_factor};
use usar_sim::scenario::{
    CircleSpec, DebrisSpec, Locomotion, RadiationZoneSpec, RestStationsSpec, Role, Scenario,
    ScenarioSpec,
};

/// Highest speed robot `id` reaches during the first `seconds` of the trial, m/s.
fn top_speed(sim: &mut Simulation, id: usize, seconds: f64) -> f64 {
    let mut top: f64 = 0.0;
    while sim.time_s() < seconds {
        sim.step().unwrap();
        top = top.max(sim.world().robot(id).velocity.norm());
    }
    top
}

#[test]
fn a_group_without_an_observer_is_30_percent_slower() {
    let s = paper_v1_with(|s| {
        let observer = s
            .kinds
            .iter()
            .position(|k| k.role == Role::Observer)
            .unwrap();
        // The easy group gets no observer.
        s.kinds[observer].quota.0.insert("easy".into(), 0);
        s.kinds[observer].quota.0.insert("hard".into(), 2);
        s.mission.initial_hp = fixed(100.0);
        s.mission.initial_energy = fixed(100.0);
    });
    let mut sim = Simulation::for_trial(&s, method("dis", &s), 0);
    sim.step().unwrap();
    let round = &sim.rounds()[0];
    assert!(
        round.groups[s.task_id("easy").unwrap()]
            .iter()
            .all(|&id| s.kind_of(id).role != Role::Observer)
    );
    let easy_carrier = *round.groups[s.task_id("easy").unwrap()]
        .iter()
        .find(|&&id| s.kind_of(id).role == Role::Carrier)
        .unwrap();
    let hard_carrier = *round.groups[s.task_id("hard").unwrap()]
        .iter()
        .find(|&&id| s.kind_of(id).role == Role::Carrier)
        .unwrap();
    assert!((sim.world().robot(easy_carrier).speed_factor - 0.7).abs() < 1e-12);
    assert!((sim.world().robot(hard_carrier).speed_factor - 1.0).abs() < 1e-12);
    let mut other = Simulation::for_trial(&s, method("dis", &s), 0);
    let v_easy = top_speed(&mut sim, easy_carrier, 8.0);
    let v_hard = top_speed(&mut other, hard_carrier, 8.0);
    let v_max = s.kind_of(easy_carrier).max_speed_m_per_s;
    assert!(
        (v_easy - 0.7 * v_max).abs() < 0.02 * v_max,
        "easy carrier top speed {v_easy}"
    );
    assert!(
        (v_hard - v_max).abs() < 0.02 * v_max,
        "hard carrier top speed {v_hard}"
    );
}

#[test]
fn lower_hp_means_lower_speed() {
    let run = |hp: f64| {
        let s = paper_v1_with(|s| {
            s.mission.initial_hp = fixed(hp);
            s.mission.initial_energy = fixed(100.0);
        });
        let mut sim = Simulation::for_trial(&s, method("dis", &s), 0);
        (top_speed(&mut sim, 0, 8.0), s.kind_of(0).max_speed_m_per_s)
    };
    let (full, v_max) = run(100.0);
    let (low, _) = run(60.0);
    assert!((full - v_max).abs() < 0.02 * v_max, "{full}");
    assert!(
        (low - hp_factor(paper_v1().mission(), 60.0) * v_max).abs() < 0.02 * v_max,
        "{low}"
    );
    assert!(low < full);
}

/// Every robot starts just above the 30 % energy threshold, so all leave for the rest station
/// within seconds; a radiation zone of dose factor 2 covers the rest station.
fn low_energy_scenario() -> Scenario {
    paper_v1_with(|s| {
        s.mission.initial_energy = fixed(30.5);
        s.mission.initial_hp = fixed(90.0);
        let station = &s.rest_station.circles()[0];
        s.radiation_zones.push(RadiationZoneSpec {
            center_m: station.center_m,
            radius_m: (station.radius_m.get() + 1.5).try_into().unwrap(),
            dose_rate_factor: 2.0.try_into().unwrap(),
        });
    })
}

#[test]
fn a_robot_below_30_percent_energy_recharges_and_comes_back() {
    let s = low_energy_scenario();
    let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
        .with_duration_s(200.0)
        .unwrap();
    let id = 0;
    let mut phases: Vec<Phase> = Vec::new();
    let mut recharge_steps = 0u32;
    while !sim.is_finished() {
        sim.step().unwrap();
        let r = &sim.robots()[id];
        if let Phase::Recharging { .. } = r.phase {
            recharge_steps += 1;
        }
        let name = std::mem::discriminant(&r.phase);
        if phases
            .last()
            .is_none_or(|p| std::mem::discriminant(p) != name)
        {
            phases.push(r.phase);
        }
        if r.phase == Phase::AtStart && sim.result().robots[id].recharges == 1 {
            break;
        }
    }
    let kinds: Vec<&str> = phases
        .iter()
        .map(|p| match p {
            Phase::ToRest => "rest",
            Phase::Recharging { .. } => "recharge",
            Phase::RestToStart => "back",
            Phase::AtStart => "start",
            _ => "task",
        })
        .collect();
    let tail: Vec<&str> = kinds.iter().copied().skip_while(|k| *k != "rest").collect();
    assert_eq!(
        &tail[..4],
        &["rest", "recharge", "back", "start"],
        "phases {kinds:?}"
    );
    let r = &sim.robots()[id];
    assert_eq!(sim.result().robots[id].recharges, 1);
    assert!(
        r.energy_pct > 95.0,
        "energy after recharging {}",
        r.energy_pct
    );
    let recharge_s = f64::from(recharge_steps) * s.sim().dt_s.get();
    assert!(
        (recharge_s - s.mission().recharge_s.get()).abs() <= 2.0 * s.sim().dt_s.get(),
        "{recharge_s}"
    );
}

/// paper.ron with every robot just above the 30 % energy threshold (all leave to recharge
/// within seconds) and a second rest station at (24, 4), left of the start rows, mirroring the
/// paper's (56, 4) about their middle.
fn two_station_scenario() -> Scenario {
    paper_v1_with(two_stations)
}

/// The spec edit of [`two_station_scenario`].
fn two_stations(s: &mut ScenarioSpec) {
    s.mission.initial_energy = fixed(30.5);
    s.mission.initial_hp = fixed(90.0);
    let paper_station = s.rest_station.circles()[0].clone();
    s.rest_station = RestStationsSpec::Many(vec![
        paper_station,
        CircleSpec {
            center_m: [24.0, 4.0],
            radius_m: 2.0.try_into().unwrap(),
        },
    ]);
}

/// For each robot's first trip to rest in 120 s: the robot, the station it heads for (by its
/// goal), and the station nearest to it in a straight line when it left. Also checks that
/// every recharging robot stands in a station's disc.
fn first_trips_to_rest(s: &Scenario) -> Vec<(usize, usize, usize)> {
    let mut sim = Simulation::for_trial(s, method("rne", s), 0)
        .with_duration_s(120.0)
        .unwrap();
    let mut trips: Vec<Option<(usize, usize, usize)>> = vec![None; s.robots().len()];
    while !sim.is_finished() {
        sim.step().unwrap();
        for (id, trip) in trips.iter_mut().enumerate() {
            let phase = sim.robots()[id].phase;
            let robot = sim.world().robot(id);
            if phase == Phase::ToRest && trip.is_none() {
                let goal = robot.goal.expect("a robot on its way to rest has a goal");
                let to = s
                    .rest_stations()
                    .iter()
                    .position(|c| (goal - c.center).norm() < 1e-6)
                    .unwrap_or_else(|| panic!("robot {id} heads for {goal:?}, not a station"));
                *trip = Some((id, to, s.nearest_rest_station(&robot.position)));
            }
            if let Phase::Recharging { .. } = phase {
                assert!(
                    s.in_rest_station(&robot.position),
                    "robot {id} recharges at {:?}",
                    robot.position
                );
            }
        }
    }
    trips.into_iter().flatten().collect()
}

/// In the open, a robot leaving to recharge heads for the nearer station: both are used, and
/// each robot goes to the one nearest to it.
#[test]
fn with_several_rest_stations_a_robot_goes_to_the_nearest() {
    let trips = first_trips_to_rest(&two_station_scenario());
    assert!(trips.len() >= 6, "{trips:?}");
    assert!(
        trips.iter().all(|(_, to, nearest)| to == nearest),
        "{trips:?}"
    );
    assert!(trips.iter().any(|t| t.1 == 0) && trips.iter().any(|t| t.1 == 1));
}

/// Nearest by path, not in a straight line: with a wall between the start rows and the left
/// station, whose way round is long, every ground robot goes to the right one, also those
/// nearer to the left one in a straight line; aerial robots fly over the wall and still take
/// the nearer one.
#[test]
fn a_rest_station_behind_a_wall_is_farther_by_path() {
    let s = paper_v1_with(|s| {
        two_stations(s);
        s.debris.push(DebrisSpec::Rect {
            center_m: [28.0, 15.0],
            size_m: [1.0, 30.0],
            rotation_deg: 0.0,
        });
    });
    let trips = first_trips_to_rest(&s);
    let (ground, aerial): (Vec<&(usize, usize, usize)>, Vec<_>) = trips
        .iter()
        .partition(|t| s.kind_of(t.0).locomotion == Locomotion::Ground);
    assert!(ground.iter().all(|t| t.1 == 0), "{trips:?}");
    assert!(
        ground.iter().any(|t| t.2 == 1),
        "no ground robot nearer the left station: {trips:?}"
    );
    assert!(aerial.iter().all(|t| t.1 == t.2), "{trips:?}");
}

#[test]
fn a_robot_standing_in_radiation_loses_hp_at_the_stated_rate() {
    let s = low_energy_scenario();
    let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
        .with_duration_s(120.0)
        .unwrap();
    let mut checked = 0;
    while !sim.is_finished() {
        let before: Vec<(f64, Phase)> = sim.robots().iter().map(|r| (r.hp_pct, r.phase)).collect();
        sim.step().unwrap();
        for r in sim.robots() {
            let (hp0, phase0) = before[r.id];
            let standing = matches!(phase0, Phase::Recharging { .. })
                && matches!(r.phase, Phase::Recharging { .. });
            if standing {
                let factor = sim.world().radiation_factor(r.id);
                assert!(factor >= 2.0, "robot {} recharges outside the zone", r.id);
                let lost = hp0 - r.hp_pct;
                let expected = s.mission().hp_pct_per_step_in_radiation.get() * factor;
                assert!(
                    (lost - expected).abs() < 1e-12,
                    "lost {lost}, expected {expected}"
                );
                assert!(!sim.world().robot(r.id).moved_this_step);
                checked += 1;
            }
        }
    }
    assert!(
        checked > 1000,
        "only {checked} robot-steps standing in radiation"
    );
}

#[test]
fn regrouping_happens_every_round_with_the_current_state() {
    // ENG sends, per kind, the robots with the most energy *now* to the hard task.
    let s = paper_v1();
    let mut sim = Simulation::for_trial(&s, method("eng", &s), 3);
    let mut groupings = Vec::new();
    while !sim.is_finished() {
        let energy: Vec<f64> = sim.robots().iter().map(|r| r.energy_pct).collect();
        let rounds = sim.rounds().len();
        sim.step().unwrap();
        if sim.rounds().len() > rounds {
            let round = sim.rounds().last().unwrap().clone();
            for kind in 0..s.kinds().len() {
                let of_kind = |ids: &Vec<usize>| -> Vec<f64> {
                    ids.iter()
                        .filter(|&&id| s.robots()[id].kind == kind)
                        .map(|&id| energy[id])
                        .collect()
                };
                let hard = of_kind(&round.groups[s.task_id("hard").unwrap()]);
                let easy = of_kind(&round.groups[s.task_id("easy").unwrap()]);
                let weakest_hard = hard.iter().copied().fold(f64::INFINITY, f64::min);
                let strongest_easy = easy.iter().copied().fold(f64::NEG_INFINITY, f64::max);
                assert!(
                    hard.is_empty() || easy.is_empty() || weakest_hard >= strongest_easy,
                    "round {rounds}, kind {kind}: hard {hard:?} easy {easy:?}"
                );
            }
            groupings.push(round.groups);
        }
    }
    assert!(groupings.len() >= 3, "only {} rounds", groupings.len());
    assert!(
        groupings.iter().any(|g| g != &groupings[0]),
        "the groups never changed: regrouping ignored the robots' current state"
    );
}

#[test]
fn a_trial_run_twice_gives_identical_results() {
    let s = paper_v1();
    for name in ["rne", "dis"] {
        let a = Simulation::for_trial(&s, method(name, &s), 1)
            .run_to_end()
            .unwrap();
        let b = Simulation::for_trial(&s, method(name, &s), 1)
            .run_to_end()
            .unwrap();
        assert_eq!(a, b);
        assert_eq!(
            serde_json::to_string(&a).unwrap(),
            serde_json::to_string(&b).unwrap()
        );
    }
}

#[test]
fn ground_robots_never_enter_debris_during_a_trial() {
    // Aerial robots crossing debris is covered by usar-sim's world_debris test.
    let s = paper_v1();
    let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
        .with_duration_s(300.0)
        .unwrap();
    while !sim.is_finished() {
        sim.step().unwrap();
        for w in sim.world().robots() {
            if w.locomotion == Locomotion::Ground {
                let d = sim.world().static_distance_at(&w.position);
                assert!(
                    d > 0.0,
                    "ground robot {} inside debris at {:?}",
                    w.id,
                    w.position
                );
            }
        }
    }
}

#[test]
fn the_needs_vector_follows_the_robot_state() {
    use usar_sim::mission::entry;
    let s = paper_v1();
    let mut sim = Simulation::for_trial(&s, method("rne", &s), 0);
    let id = 0; // a carrier
    let kind = s.kind_of(id);
    let before = sim.needs(id);
    while sim.robots()[id].load.is_empty() && !sim.is_finished() {
        sim.step().unwrap();
    }
    let r = &sim.robots()[id];
    let now = sim.needs(id);
    let v = now.as_slice();
    assert!((v[entry::ENG] - kind.energy_needs_full * r.energy_pct / 100.0).abs() < 1e-12);
    assert!((v[entry::HP] - kind.hp_needs_full * r.hp_pct / 100.0).abs() < 1e-12);
    assert!(
        (v[entry::V] - kind.max_speed_m_per_s * hp_factor(s.mission(), r.hp_pct)).abs() < 1e-12
    );
    assert_eq!(v[entry::CAP], f64::from(r.capacity_free));
    assert!(
        v[entry::CAP] < before.as_slice()[entry::CAP],
        "picking up used capacity"
    );
    assert!(
        v[entry::ENG] < before.as_slice()[entry::ENG],
        "driving used energy"
    );
}
