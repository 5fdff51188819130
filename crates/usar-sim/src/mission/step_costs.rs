//! The energy and HP costs of one step for every robot (paper, section VI.B; the rules:
//! `docs/mission-model.md`), robot by robot on the calling rayon pool for a large team: each
//! robot charges its own levels and its own cost totals and writes its cost to its own slot, and
//! the tasks' sums are then added in robot order, so any number of threads gives the bits of
//! one loop over the team in id order.

use rayon::prelude::*;

use super::robot::MissionRobot;
use crate::scenario::{CostsCount, Scenario};
#[cfg(doc)]
use crate::world::World;
use crate::world::{CHUNK_ROBOTS, ReadBackSoFar, RobotState};

/// What one robot's step cost it, and the task it counts for: energy spent and HP lost this
/// step (percent points, `>= 0`: zero when it did not move or stood outside radiation, and a
/// task's sum, a non-negative `f64`, is unchanged by adding `+0.0`). A robot that neither moved
/// nor stood in radiation gets [`StepCost::default`]: no task, no cost.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct StepCost {
    /// The task the costs count for, if any (`mission.costs_count`).
    pub(crate) counted: Option<usize>,
    /// Energy spent, percent points.
    pub(crate) spent_pct: f64,
    /// HP lost, percent points.
    pub(crate) lost_pct: f64,
}

/// One robot's cost totals so far (the recorder's, copied into its metrics at the end):
/// energy spent and HP lost, percent points, and time in radiation, seconds.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct RobotCosts {
    /// Energy spent so far, percent points.
    pub(crate) energy_spent_pct: f64,
    /// HP lost so far, percent points.
    pub(crate) hp_lost_pct: f64,
    /// Time spent in radiation so far, seconds.
    pub(crate) time_in_radiation_s: f64,
}

/// The per-step rates of `scenario.mission` on its cost clock (percent points per step of
/// `dt_s` seconds), read once per step.
#[derive(Debug, Clone, Copy)]
struct Rates {
    energy_per_moving_step: f64,
    energy_per_m: f64,
    hp_per_step: f64,
    every_cost: bool,
}

/// Charges the step just taken to every robot `read` covers (by id; `robots`, `totals` and
/// `costs` are resized or of the team's length): energy per moving step and per metre moved,
/// HP per step in radiation times the dose factor (each at most what is left), written to
/// `robots[id]`'s levels and `totals[id]`, and each robot's [`StepCost`] to `costs[id]` for
/// the tasks' sums, which the caller adds in id order once every robot is charged. Each
/// robot's charge reads only its own slots, so the robots a step hands over beside Rapier's
/// step ([`World::step_beside`]) and the rest ([`World::read_back_rest`]) get the bits of one
/// pass. On the calling rayon pool when `read` may run in parallel
/// ([`ReadBackSoFar::parallel`]), but for the near robots of `sim.physics: NearBodies`
/// ([`ReadBackSoFar::near_ids`]: one scan of their flags, then a loop over them alone).
pub(crate) fn charge_step_costs(
    scenario: &Scenario,
    read: &ReadBackSoFar,
    robots: &mut [MissionRobot],
    totals: &mut [RobotCosts],
    costs: &mut Vec<StepCost>,
) {
    let m = &scenario.mission;
    let dt = scenario.sim.dt_s.get();
    let rates = Rates {
        energy_per_moving_step: m.per_step_on_cost_clock(m.energy_pct_per_moving_step, dt),
        energy_per_m: m.energy_pct_per_m.get(),
        hp_per_step: m.per_step_on_cost_clock(m.hp_pct_per_step_in_radiation, dt),
        every_cost: m.costs_count == CostsCount::Every,
    };
    costs.resize(robots.len(), StepCost::default());
    if read.covers_none() {
        return;
    }
    let (states, factors) = (read.robots(), read.radiation_factors());
    if let Some(ids) = read.near_ids() {
        // A few robots of a large team: one scan of the flags, then a loop over them alone.
        for id in ids {
            let (r, total) = (&mut robots[id], &mut totals[id]);
            costs[id] = charge(&rates, dt, &states[id], factors[id], r, total);
        }
        return;
    }
    let each = |(id, (((r, total), cost), (w, &rad))): (usize, Slot<'_>)| {
        if read.covers(id) {
            *cost = charge(&rates, dt, w, rad, r, total);
        }
    };
    if read.parallel() {
        robots
            .par_iter_mut()
            .zip(totals.par_iter_mut())
            .zip(costs.par_iter_mut())
            .zip(states.par_iter().zip(factors))
            .enumerate()
            .with_min_len(CHUNK_ROBOTS)
            .with_max_len(CHUNK_ROBOTS)
            .for_each(each);
    } else {
        // The same charge robot by robot, without the closure's zipped slots (a small team
        // pays this loop at every step).
        for (id, r) in robots.iter_mut().enumerate() {
            if read.covers(id) {
                costs[id] = charge(&rates, dt, &states[id], factors[id], r, &mut totals[id]);
            }
        }
    }
}

/// One robot's slots in [`charge_step_costs`]: its mission state, cost totals and step cost (written),
/// its world state and dose factor (read).
type Slot<'a> = (
    ((&'a mut MissionRobot, &'a mut RobotCosts), &'a mut StepCost),
    (&'a RobotState, &'a f64),
);

/// One robot's step cost (see [`charge_step_costs`]), `rad` its dose factor.
fn charge(
    rates: &Rates,
    dt_s: f64,
    w: &RobotState,
    rad: f64,
    r: &mut MissionRobot,
    total: &mut RobotCosts,
) -> StepCost {
    // A robot that stood outside radiation costs nothing: its zero cost counts for no task,
    // which leaves every task's sum the same bits (adding `+0.0` to a non-negative sum), and
    // its mission record is not read (in a jam thousands stand, and the record's first read
    // is the charge's cache miss).
    let irradiated = rad > 0.0; // false for a NaN factor too, as below
    if !w.moved_this_step && !irradiated {
        return StepCost::default();
    }
    // The task the costs count for: the robot's group's, or under `Every` its latest's.
    let counted = if rates.every_cost {
        r.task.or(r.last_task)
    } else {
        r.task
    };
    let mut cost = StepCost {
        counted,
        ..StepCost::default()
    };
    if w.moved_this_step {
        let c = rates.energy_per_moving_step + rates.energy_per_m * w.step_distance_m;
        cost.spent_pct = c.min(r.energy_pct);
        r.energy_pct -= cost.spent_pct;
        total.energy_spent_pct += cost.spent_pct;
    }
    if irradiated {
        cost.lost_pct = (rates.hp_per_step * rad).min(r.hp_pct);
        r.hp_pct -= cost.lost_pct;
        total.hp_lost_pct += cost.lost_pct;
        total.time_in_radiation_s += dt_s;
    }
    cost
}
