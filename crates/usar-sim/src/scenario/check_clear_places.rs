//! The places debris must keep clear of: rest stations, goals and drop-offs that ground robots
//! must reach, and the start discs that generated debris must not cover.
//!
//! [`check_reachable`] checks the listed debris against the places ground robots drive to;
//! [`protected_places`] lists what the generated debris fields keep away from.

use super::check_debris::NamedDebris;
use super::check_tasks::TaskGeometry;
use super::context::{Ctx, R, fmt_pt};
use super::generate::{Protected, Start};
use super::model::{Circle, PointM, RobotKind, RobotStart, number_text, number_text_3dp};
use super::spec::TaskSpec;

/// Every rest station's centre, every goal and every drop-off centre at least `reach` (the
/// smallest ground body radius) from the listed debris, so ground robots can get there.
pub(crate) fn check_reachable(
    ctx: &Ctx<'_>,
    rest_stations: &[(String, Circle)],
    tasks: &[TaskSpec],
    geometry: &[TaskGeometry],
    debris: &NamedDebris,
    reach: f64,
) -> R<()> {
    let mut places: Vec<(String, PointM, String)> = rest_stations
        .iter()
        .map(|(field, c)| {
            (
                format!("{field}.center_m"),
                c.center,
                "rest station centre".to_owned(),
            )
        })
        .collect();
    for (i, (t, g)) in tasks.iter().zip(geometry).enumerate() {
        places.push((
            format!("tasks[{i}].goal_m"),
            g.goal,
            format!("task {:?}: goal", t.name),
        ));
        places.push((
            format!("tasks[{i}].drop_off.center_m"),
            g.drop_off.center,
            format!("task {:?}: drop-off centre", t.name),
        ));
    }
    for (field, p, what) in places {
        for (d, name) in debris {
            let dist = d.distance_to_point(&p);
            if dist < reach || dist == 0.0 {
                return Err(ctx.err(
                    field,
                    format!(
                        "{what} {} is {} m from {name}; it must be at least {} m (the \
                         smallest ground body radius) away so ground robots can reach it",
                        fmt_pt(&p),
                        number_text_3dp(dist),
                        number_text(reach)
                    ),
                ));
            }
        }
    }
    Ok(())
}

/// The places generated debris keeps away from: every start disc, every rest station, every
/// drop-off and every goal point.
pub(crate) fn protected_places(
    starts: &[(Start, RobotStart)],
    kinds: &[RobotKind],
    rest_stations: &[(String, Circle)],
    tasks: &[TaskSpec],
    geometry: &[TaskGeometry],
) -> Vec<Protected> {
    let mut out: Vec<Protected> = starts
        .iter()
        .map(|(s, r)| Protected {
            center: r.start_in_world,
            radius_m: kinds[r.kind].body_radius_m,
            what: format!("the start of {}", s.label),
        })
        .collect();
    out.extend(rest_stations.iter().map(|(field, c)| Protected {
        center: c.center,
        radius_m: c.radius_m,
        what: if rest_stations.len() == 1 {
            "the rest station".to_owned()
        } else {
            format!("the rest station {field}")
        },
    }));
    for (t, g) in tasks.iter().zip(geometry) {
        out.push(Protected {
            center: g.drop_off.center,
            radius_m: g.drop_off.radius_m,
            what: format!("the drop-off of task {:?}", t.name),
        });
        out.push(Protected {
            center: g.goal,
            radius_m: 0.0,
            what: format!("the goal of task {:?}", t.name),
        });
    }
    out
}
