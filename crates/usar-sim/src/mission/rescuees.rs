//! The rescuees of one task: where they lie, who knows of them, who claimed, carries or
//! delivered each (paper, sections IV and VI.B).

use serde::{Deserialize, Serialize};

use crate::scenario::{PointM, Rect};

/// What has become of one rescuee.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum RescueeStatus {
    /// Lying in the search area, free to be claimed.
    Waiting,
    /// Claimed by robot `.0`, which is driving to it.
    Claimed(usize),
    /// Picked up and carried by robot `.0`.
    Carried(usize),
    /// Delivered to the task's drop-off: counts for the task.
    Delivered,
    /// Dropped by a robot that left its task to recharge; lost for the trial.
    Abandoned,
    /// No robot could get close enough to pick it up (it lies inside inflated debris).
    Unreachable,
    /// A claim on it expired (its robot could not get there in time, e.g. other robots stood
    /// in the way); it waits again from the next round on.
    Skipped,
}

/// The rescuees of one task, indexed as in [`crate::scenario::Task::rescuees`].
#[derive(Debug, Clone)]
pub struct RescueeField {
    positions: Vec<PointM>,
    status: Vec<RescueeStatus>,
    known: Vec<bool>,
    pickups: Vec<u32>,
    unknown_waiting: usize,
    area: Rect,
}

impl RescueeField {
    /// All rescuees of a task, waiting and unknown to everyone.
    pub fn new(positions: Vec<PointM>, area: Rect) -> Self {
        let n = positions.len();
        Self {
            positions,
            status: vec![RescueeStatus::Waiting; n],
            known: vec![false; n],
            pickups: vec![0; n],
            unknown_waiting: n,
            area,
        }
    }

    /// Number of rescuees.
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Whether the task has no rescuees.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// Position of rescuee `i`, world frame, metres.
    pub fn position(&self, i: usize) -> PointM {
        self.positions[i]
    }

    /// Status of rescuee `i`.
    pub fn status(&self, i: usize) -> RescueeStatus {
        self.status[i]
    }

    /// How many times rescuee `i` was picked up (at most once in a correct run, unless it was
    /// put back by a leaving robot: see [`RescueeField::put_back`]).
    pub fn pickups(&self, i: usize) -> u32 {
        self.pickups[i]
    }

    /// Forgets what the previous group knew (a new round's group starts with no shared map),
    /// and puts skipped rescuees back to waiting.
    pub fn forget(&mut self) {
        self.known.iter_mut().for_each(|k| *k = false);
        for s in &mut self.status {
            if *s == RescueeStatus::Skipped {
                *s = RescueeStatus::Waiting;
            }
        }
        self.unknown_waiting = self
            .status
            .iter()
            .filter(|s| **s == RescueeStatus::Waiting)
            .count();
    }

    /// Marks as known every waiting rescuee within `range_m` of `center` (paper: detecting
    /// rescuees within the observing range). Cheap when everything is known or `center` is far
    /// from the search area.
    pub fn detect(&mut self, center: &PointM, range_m: f64) {
        if self.unknown_waiting == 0 {
            return;
        }
        let a = &self.area;
        let dx = (a.min.x - center.x).max(center.x - a.max.x).max(0.0);
        let dy = (a.min.y - center.y).max(center.y - a.max.y).max(0.0);
        if dx * dx + dy * dy > range_m * range_m {
            return;
        }
        let r2 = range_m * range_m;
        for i in 0..self.positions.len() {
            if !self.known[i]
                && self.status[i] == RescueeStatus::Waiting
                && (self.positions[i] - center).norm_squared() <= r2
            {
                self.known[i] = true;
                self.unknown_waiting -= 1;
            }
        }
    }

    /// The known, waiting rescuee nearest to `from` (ties: lowest index) for which `free`
    /// holds, if any (the caller excludes rescuees under other robots' bodies). `free` is only
    /// asked about rescuees nearer than the best so far (the answer is the same).
    pub fn nearest_known_waiting(
        &self,
        from: &PointM,
        free: impl Fn(&PointM) -> bool,
    ) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        for i in 0..self.positions.len() {
            if self.known[i] && self.status[i] == RescueeStatus::Waiting {
                let d = (self.positions[i] - from).norm_squared();
                if best.is_none_or(|(bd, _)| d < bd) && free(&self.positions[i]) {
                    best = Some((d, i));
                }
            }
        }
        best.map(|(_, i)| i)
    }

    /// Robot `robot` claims waiting rescuee `i`.
    pub fn claim(&mut self, i: usize, robot: usize) {
        debug_assert_eq!(self.status[i], RescueeStatus::Waiting);
        self.status[i] = RescueeStatus::Claimed(robot);
    }

    /// Releases a claim: the rescuee waits again (and stays known).
    pub fn release(&mut self, i: usize) {
        if matches!(self.status[i], RescueeStatus::Claimed(_)) {
            self.status[i] = RescueeStatus::Waiting;
        }
    }

    /// Robot `robot` picks up rescuee `i`.
    pub fn pick_up(&mut self, i: usize, robot: usize) {
        self.status[i] = RescueeStatus::Carried(robot);
        self.pickups[i] += 1;
    }

    /// Puts carried rescuee `i` back where it was found: it waits again, unknown to everyone
    /// (`mission.load_on_leave: ReturnToArea`). It may be picked up again, so
    /// [`RescueeField::pickups`] can exceed 1 for it.
    pub fn put_back(&mut self, i: usize) {
        self.status[i] = RescueeStatus::Waiting;
        self.known[i] = false;
        self.unknown_waiting += 1;
    }

    /// Sets the final status of a carried or claimed rescuee (`Delivered`, `Abandoned` or
    /// `Unreachable`).
    pub fn settle(&mut self, i: usize, status: RescueeStatus) {
        self.status[i] = status;
    }
}
