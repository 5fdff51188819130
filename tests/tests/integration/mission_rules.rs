//! The mission rules the paper leaves open (`mission.*` options, `docs/mission-model.md`): each
//! setting's behaviour, on variants of paper-v1.ron (the model before the authors' clock).

use integration_tests::{fixed, method, paper_v1, paper_v1_with};
use usar_sim::mission::{
    Phase, RescueeStatus, Simulation, hp_factor, sweep_spacing_m, sweep_waypoints,
};
use usar_sim::scenario::{
    LoadOnLeave, RadiationFalloff, RadiationOverlap, RadiationZoneSpec, Refresh, RestAt, Role,
    RoundStart, Scenario,
};

#[test]
fn energy_is_charged_per_moving_step_plus_per_metre() {
    let s = paper_v1_with(|s| {
        s.mission.energy_pct_per_moving_step = 0.001.try_into().unwrap();
        s.mission.energy_pct_per_m = 0.2.try_into().unwrap();
    });
    let mut sim = Simulation::for_trial(&s, method("dis", &s), 0)
        .with_duration_s(60.0)
        .unwrap();
    let mut charged = 0;
    while !sim.is_finished() {
        let before: Vec<f64> = sim.robots().iter().map(|r| r.energy_pct).collect();
        sim.step().unwrap();
        for r in sim.robots() {
            let w = sim.world().robot(r.id);
            let lost = before[r.id] - r.energy_pct;
            let expected = if w.moved_this_step {
                (0.001 + 0.2 * w.step_distance_m).min(before[r.id])
            } else {
                0.0
            };
            assert!(
                (lost - expected).abs() < 1e-9,
                "robot {}: lost {lost}, expected {expected}",
                r.id
            );
            charged += usize::from(w.moved_this_step);
        }
    }
    assert!(charged > 10_000, "only {charged} moving robot-steps");
}

/// Every robot starts just above the energy threshold, so all leave for the rest station at
/// once; two overlapping radiation zones cover the rest station.
fn resting_in_two_zones(overlap: RadiationOverlap, falloff: RadiationFalloff) -> Scenario {
    paper_v1_with(|s| {
        s.mission.initial_energy = fixed(30.05);
        s.mission.initial_hp = fixed(90.0);
        s.mission.radiation_overlap = overlap;
        s.mission.radiation_falloff = falloff;
        // Low enough that nobody reaches 0 % HP (the loss is then clamped) within the test.
        s.mission.hp_pct_per_step_in_radiation = 0.001.try_into().unwrap();
        let station = &s.rest_station.circles()[0];
        let [x, y] = station.center_m;
        // 2 m wider than the station, as far as the arena's floor allows (a zone lies inside
        // the arena): every robot resting there is inside both zones.
        let radius_m = (station.radius_m.get() + 2.0).min(y);
        for (dx, factor) in [(0.0, 2.0), (1.0, 1.0)] {
            s.radiation_zones.push(RadiationZoneSpec {
                center_m: [x + dx, y],
                radius_m: radius_m.try_into().unwrap(),
                dose_rate_factor: factor.try_into().unwrap(),
            });
        }
    })
}

#[test]
fn overlapping_zones_sum_or_take_the_strongest_and_linear_dose_falls_off() {
    use RadiationFalloff::{Linear, Uniform};
    use RadiationOverlap::{Max, Sum};
    for (overlap, falloff) in [(Sum, Uniform), (Max, Uniform), (Sum, Linear), (Max, Linear)] {
        let s = resting_in_two_zones(overlap, falloff);
        let zones = &s.radiation_zones()[s.radiation_zones().len() - 2..];
        let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
            .with_duration_s(90.0)
            .unwrap();
        let mut checked = 0;
        while !sim.is_finished() {
            let before: Vec<(f64, Phase)> =
                sim.robots().iter().map(|r| (r.hp_pct, r.phase)).collect();
            sim.step().unwrap();
            for r in sim.robots() {
                let (hp0, phase0) = before[r.id];
                if !(matches!(phase0, Phase::Recharging { .. })
                    && matches!(r.phase, Phase::Recharging { .. }))
                {
                    continue;
                }
                // The dose by hand: each zone's factor, uniform or falling off linearly.
                let p = sim.world().robot(r.id).position;
                let doses = zones.iter().map(|z| {
                    let d = (p - z.area.center).norm();
                    match falloff {
                        Uniform => z.dose_rate_factor,
                        Linear => z.dose_rate_factor * (1.0 - d / z.area.radius_m),
                    }
                });
                let dose = match overlap {
                    Sum => doses.sum::<f64>(),
                    Max => doses.fold(0.0, f64::max),
                };
                let lost = hp0 - r.hp_pct;
                let expected = s.mission().hp_pct_per_step_in_radiation.get() * dose;
                assert!(
                    (lost - expected).abs() < 1e-9,
                    "{overlap:?}/{falloff:?}: lost {lost}, expected {expected}"
                );
                checked += 1;
            }
        }
        assert!(checked > 500, "{overlap:?}/{falloff:?}: {checked} checks");
    }
}

/// Robots grouped in each round of a whole trial of `s` with DIS.
fn group_sizes(s: &Scenario) -> Vec<usize> {
    let r = Simulation::for_trial(s, method("dis", s), 0)
        .run_to_end()
        .unwrap();
    r.rounds
        .iter()
        .map(|x| x.groups.iter().map(Vec::len).sum())
        .collect()
}

#[test]
fn all_back_rounds_group_the_whole_team_and_available_rounds_do_not() {
    let s = paper_v1_with(|s| {
        s.mission.round_start = RoundStart::AllBack;
    });
    let all_back = group_sizes(&s);
    assert!(all_back.len() >= 4, "{all_back:?}");
    assert!(
        all_back.iter().all(|&n| n == s.robots().len()),
        "{all_back:?}"
    );
    let s = paper_v1_with(|s| s.mission.round_start = RoundStart::Available);
    let available = group_sizes(&s);
    assert!(
        available.iter().any(|&n| n < s.robots().len()),
        "robots recharge during the trial, so some round must go without them: {available:?}"
    );
}

/// A robot that left its group for the rest station while carrying rescuees.
struct LeaveWithLoad {
    id: usize,
    load: Vec<usize>,
    task: usize,
    at_s: f64,
}

/// Runs 200 s of paper.ron with every robot low on energy (so several leave mid-round, some
/// carrying rescuees) under `rule`; calls `check` after every step with the leaves of that step
/// and returns the finished simulation and all leaves.
fn leave_with_load(
    rule: LoadOnLeave,
    mut check: impl FnMut(&Simulation, &[LeaveWithLoad]),
) -> (Simulation, Vec<LeaveWithLoad>) {
    let s = paper_v1_with(|s| {
        s.mission.initial_energy = fixed(36.0);
        s.mission.initial_hp = fixed(100.0);
        s.mission.load_on_leave = rule;
        s.mission.search_time_budget_s = None;
    });
    let mut sim = Simulation::for_trial(&s, method("dis", &s), 0)
        .with_duration_s(200.0)
        .unwrap();
    let mut leaves = Vec::new();
    while !sim.is_finished() {
        let before: Vec<_> = sim
            .robots()
            .iter()
            .map(|r| (r.load.clone(), r.task, r.is_resting()))
            .collect();
        sim.step().unwrap();
        let seen = leaves.len();
        for r in sim.robots() {
            let (load, task, resting) = &before[r.id];
            if !resting && r.is_resting() && !load.is_empty() {
                leaves.push(LeaveWithLoad {
                    id: r.id,
                    load: load.clone(),
                    task: task.expect("a robot with a load is in a group"),
                    at_s: sim.time_s(),
                });
            }
        }
        check(&sim, &leaves[seen..]);
    }
    assert!(
        !leaves.is_empty(),
        "{rule:?}: no robot left carrying rescuees"
    );
    (sim, leaves)
}

#[test]
fn a_leaving_robot_abandons_its_load() {
    leave_with_load(LoadOnLeave::Abandon, |sim, leaves| {
        for l in leaves {
            for &i in &l.load {
                assert_eq!(sim.rescuees(l.task).status(i), RescueeStatus::Abandoned);
            }
            assert!(sim.robots()[l.id].load.is_empty());
        }
    });
}

#[test]
fn a_leaving_robot_puts_its_load_back() {
    leave_with_load(LoadOnLeave::ReturnToArea, |sim, leaves| {
        for l in leaves {
            for &i in &l.load {
                assert_eq!(sim.rescuees(l.task).status(i), RescueeStatus::Waiting);
            }
        }
    });
}

#[test]
fn a_leaving_robot_delivers_its_load_first() {
    let (sim, leaves) = leave_with_load(LoadOnLeave::DeliverFirst, |sim, leaves| {
        for l in leaves {
            // It drives to its task's drop-off with its load, away from its group's work.
            let r = &sim.robots()[l.id];
            assert_eq!(
                (r.phase, r.leaving, &r.load),
                (Phase::ToDropOff, true, &l.load)
            );
            assert_eq!(r.task, Some(l.task));
        }
    });
    // Everyone who left early enough has delivered and been to the rest station.
    let early: Vec<_> = leaves.iter().filter(|l| l.at_s < 120.0).collect();
    assert!(!early.is_empty());
    for l in early {
        let field = sim.rescuees(l.task);
        assert!(
            l.load
                .iter()
                .all(|&i| field.status(i) == RescueeStatus::Delivered)
        );
        assert!(sim.result().robots[l.id].recharges >= 1);
    }
}

#[test]
fn a_group_leaves_when_its_search_time_budget_is_spent() {
    let s = paper_v1();
    let budget = s
        .mission()
        .search_time_budget_s
        .expect("paper.ron has a budget")
        .get();
    let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
        .with_duration_s(300.0)
        .unwrap();
    let k = s.tasks().len();
    let mut first_in: Vec<Option<f64>> = vec![None; k];
    let mut ended = vec![false; k];
    let mut rounds = 0;
    let mut cut_short = 0;
    while !sim.is_finished() {
        sim.step().unwrap();
        if sim.rounds().len() != rounds {
            rounds = sim.rounds().len();
            first_in = vec![None; k];
            ended = vec![false; k];
        }
        let now = sim.time_s();
        for level in 0..s.tasks().len() {
            let area = s.tasks()[level].search_area;
            let s = &s;
            let sim = &sim;
            let members = move || {
                sim.robots().iter().filter(move |r| {
                    r.task == Some(level) && s.kind_of(r.id).role != Role::Observer
                })
            };
            if first_in[level].is_none()
                && members().any(|r| area.contains(&sim.world().robot(r.id).position))
            {
                first_in[level] = Some(now);
            }
            let Some(t0) = first_in[level] else {
                continue;
            };
            let searching = members().any(|r| r.is_on_task());
            if now > t0 + budget + 2.0 * s.sim().dt_s.get() {
                assert!(
                    !searching,
                    "task {level} group still searching at {now} s (in at {t0} s)"
                );
            }
            // The budget, not capacity or resources, ended this trip: the group turned for
            // its drop-off just as the budget ran out, with room left.
            let turned = members().any(|r| r.phase == Phase::ToDropOff);
            if !ended[level] && turned {
                ended[level] = true;
                let free: u32 = members().map(|r| r.capacity_free).sum();
                if now >= t0 + budget && now <= t0 + budget + 2.0 * s.sim().dt_s.get() && free > 0 {
                    cut_short += 1;
                }
            }
        }
    }
    assert!(cut_short > 0, "the budget never ended a trip");
}

#[test]
fn low_only_refresh_restores_only_the_level_below_its_threshold() {
    for (refresh, hp_after) in [(Refresh::LowOnly, 60.0), (Refresh::Both, 100.0)] {
        let s = paper_v1_with(|s| {
            s.mission.initial_energy = fixed(30.05);
            s.mission.initial_hp = fixed(60.0);
            s.mission.refresh = refresh;
        });
        let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
            .with_duration_s(120.0)
            .unwrap();
        let id = 0;
        while sim.result().robots[id].recharges == 0 && !sim.is_finished() {
            sim.step().unwrap();
        }
        let r = &sim.robots()[id];
        assert_eq!(sim.result().robots[id].recharges, 1, "{refresh:?}");
        assert_eq!(r.energy_pct, 100.0, "{refresh:?}");
        // No radiation between the start and the rest station: HP is untouched or full.
        assert_eq!(r.hp_pct, hp_after, "{refresh:?}");
    }
}

#[test]
fn a_robot_recharges_at_a_rest_station_or_at_its_own_start() {
    for rest_at in [RestAt::RestStation, RestAt::OwnStart] {
        // 1 % above the energy threshold: robot 0 falls below it on its way to its task, a few
        // metres from its start.
        let s = paper_v1_with(|s| {
            s.mission.initial_energy = fixed(31.0);
            s.mission.rest_at = rest_at;
        });
        let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
            .with_duration_s(300.0)
            .unwrap();
        let id = 0;
        let mut left_start = false;
        while !matches!(sim.robots()[id].phase, Phase::Recharging { .. }) && !sim.is_finished() {
            sim.step().unwrap();
            left_start |= sim.world().robot(id).distance_travelled_m > 1.0;
        }
        assert!(left_start, "{rest_at:?}: robot {id} never set off");
        let pos = sim.world().robot(id).position;
        let start = s.robots()[id].start_in_world;
        let tolerance_m = s.navigation().waypoint_tolerance_m.get() + 0.05;
        match rest_at {
            RestAt::RestStation => {
                assert!(
                    s.in_rest_station(&pos),
                    "{rest_at:?}: recharging at {pos:?}"
                );
                assert!((pos - start).norm() > 1.0, "{rest_at:?}: at its start");
            }
            RestAt::OwnStart => {
                let d = (pos - start).norm();
                assert!(
                    d <= tolerance_m,
                    "{rest_at:?}: recharging {d} m from its start"
                );
            }
        }
        while sim.result().robots[id].recharges == 0 && !sim.is_finished() {
            sim.step().unwrap();
        }
        assert_eq!(sim.result().robots[id].recharges, 1, "{rest_at:?}");
        assert_eq!(sim.robots()[id].energy_pct, 100.0, "{rest_at:?}");
    }
}

/// Fraction of a scenario's rescuees that a ground robot following its task's blind sweep
/// (`sweep_waypoints` at `sweep_spacing_m`) passes within its detection radius of
/// (body radius + observing range at full HP).
fn swept_fraction(s: &Scenario) -> f64 {
    let kind = &s.kinds()[0];
    let reach = kind.body_radius_m + kind.observing_range_m;
    let (mut seen, mut all) = (0, 0);
    for task in s.tasks() {
        let w = sweep_waypoints(
            &task.search_area,
            sweep_spacing_m(s),
            s.mission().sweep_pattern,
        );
        for p in &task.rescuees {
            let d = w
                .windows(2)
                .map(|seg| {
                    let (a, b) = (seg[0], seg[1]);
                    let ab = b - a;
                    let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
                    (a + ab * t - p).norm()
                })
                .fold(f64::INFINITY, f64::min);
            seen += usize::from(d <= reach + 1e-9);
            all += 1;
        }
    }
    seen as f64 / all as f64
}

#[test]
fn a_blind_sweep_passes_every_rescuee_within_detection_range() {
    // Regression: rows 2 m apart put a ground robot (detection radius 0.45 m) midway between
    // the rows of a 1 m rescuee grid, so a group without an observer could only find rescuees
    // by chance. The default spacing is the detection width.
    let s = paper_v1();
    assert_eq!(s.mission().sweep_spacing_m, None);
    assert!((sweep_spacing_m(&s) - 0.9).abs() < 1e-12);
    assert_eq!(swept_fraction(&s), 1.0);
    let v0 = usar_sim::scenario::load(integration_tests::scenario_path("paper-v0.ron")).unwrap();
    assert_eq!(v0.mission().sweep_spacing_m.map(|x| x.get()), Some(2.0));
    let f = swept_fraction(&v0);
    assert!(f < 0.2, "2 m rows pass {f} of the rescuees");
}

/// Regression: a row of the blind sweep ended at the centre of its last column and the robot
/// turned within `navigation.waypoint_tolerance_m` of it, cutting the corner, so rescuees
/// along the left and right edges of the area were missed (2 of the 8 in
/// `tests/data/blind-edges.ron` found in 600 s, none of the four corners); and the pattern's
/// last waypoint was assigned but never driven to. Now the rows reach the edges and the robot
/// turns only at them: one sweep finds all 8.
#[test]
fn a_blind_sweep_finds_the_rescuees_at_the_corners_and_edges() {
    let s = integration_tests::load(&integration_tests::data_path("blind-edges.ron"));
    assert!(!s.kinds().iter().any(|k| k.role == Role::Observer));
    let reach = s.kinds()[0].body_radius_m + s.kinds()[0].observing_range_m;
    let area = &s.tasks()[0].search_area;
    for p in &s.tasks()[0].rescuees {
        let to_edge = (p.x - area.min.x)
            .min(area.max.x - p.x)
            .min(p.y - area.min.y)
            .min(area.max.y - p.y);
        assert!(to_edge < 0.25 * reach, "{p:?} is not at an edge");
    }
    let r = Simulation::for_trial(&s, method("dis", &s), 0)
        .run_to_end()
        .unwrap();
    assert_eq!(
        r.rounds[0].rescued,
        vec![8],
        "first round: {:?}",
        r.rounds[0]
    );
    assert_eq!(r.rescued, vec![8]);
}

#[test]
fn hp_slows_a_robot_no_further_than_the_floor() {
    let top = |min_factor: f64| {
        let s = paper_v1_with(|s| {
            s.mission.initial_hp = fixed(5.0);
            s.mission.initial_energy = fixed(100.0);
            s.mission.min_hp_factor = min_factor.try_into().unwrap();
        });
        let mut sim = Simulation::for_trial(&s, method("dis", &s), 0);
        let mut top: f64 = 0.0;
        while sim.time_s() < 8.0 {
            sim.step().unwrap();
            top = top.max(sim.world().robot(0).velocity.norm());
        }
        (top, s.kind_of(0).max_speed_m_per_s)
    };
    let (floored, v_max) = top(0.2);
    let mut floor = paper_v1().mission().clone();
    floor.min_hp_factor = 0.2.try_into().unwrap();
    assert!((hp_factor(&floor, 5.0) - 0.2).abs() < 1e-12);
    assert!(
        (floored - 0.2 * v_max).abs() < 0.02 * v_max,
        "{floored} vs {}",
        0.2 * v_max
    );
    let (linear, _) = top(0.0);
    assert!(
        (linear - 0.05 * v_max).abs() < 0.01 * v_max,
        "{linear} vs {}",
        0.05 * v_max
    );
}

#[test]
fn a_rescue_takes_pickup_s_standing_still() {
    let s = paper_v1();
    let pickup_s = s.mission().pickup_s.get();
    assert!(pickup_s > 0.0);
    let mut sim = Simulation::for_trial(&s, method("dis", &s), 0)
        .with_duration_s(120.0)
        .unwrap();
    let n = s.robots().len();
    let mut since: Vec<Option<f64>> = vec![None; n];
    let mut rescues = 0;
    while !sim.is_finished() {
        let before: Vec<(u32, Option<f64>)> = sim
            .robots()
            .iter()
            .map(|r| (r.capacity_free, r.picking_until_s))
            .collect();
        sim.step().unwrap();
        let now = sim.time_s();
        for r in sim.robots() {
            let (cap0, picking0) = before[r.id];
            if picking0.is_none() && r.picking_until_s.is_some() {
                since[r.id] = Some(now);
            }
            if r.picking_until_s.is_some() {
                // Standing still: no goal (other robots may still nudge its body).
                assert!(
                    sim.world().robot(r.id).goal.is_none(),
                    "robot {} drives",
                    r.id
                );
            }
            if r.capacity_free < cap0 {
                let start = since[r.id].take().expect("a rescue starts before it ends");
                let took = now - start;
                assert!(
                    (took - pickup_s).abs() <= s.sim().dt_s.get() + 1e-9,
                    "robot {}: rescue took {took} s",
                    r.id
                );
                rescues += 1;
            }
        }
    }
    assert!(rescues >= 10, "{rescues} rescues");
}

/// `min_hp_factor: 0` lets a robot at 0 % HP with an empty battery (and, for an observer, no
/// resources or capacity) have an all-zero needs vector; RNE grouping gives such a group the
/// uniform distribution (relative smoothing's convention) and the trial runs. Every RNE trial
/// of this valid scenario used to fail with "all weighted needs equal to zero".
#[test]
fn robots_with_all_zero_needs_are_grouped_by_rne() {
    let s = paper_v1_with(|s| {
        s.mission.min_hp_factor = 0.0.try_into().unwrap();
        s.mission.initial_hp = fixed(0.0);
        s.mission.initial_energy = fixed(0.0);
    });
    let mut sim = Simulation::for_trial(&s, method("rne", &s), 0)
        .with_duration_s(5.0)
        .unwrap();
    // The observers: no rescuing resources, no carrying capacity.
    let zero = sim
        .robots()
        .iter()
        .filter(|r| sim.needs(r.id).as_slice().iter().all(|&n| n == 0.0))
        .count();
    assert_eq!(zero, 2, "the observers' needs vectors are all zero");
    while !sim.is_finished() {
        sim.step().expect("an RNE step with all-zero needs vectors");
    }
    assert_eq!(sim.result().rounds.len(), 1);
}
