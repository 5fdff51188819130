//! The rescuees of one task: where they lie, who knows of them, who claimed, carries or
//! delivered each (paper, sections IV and VI.B).

use serde::{Deserialize, Serialize};

use parry2d::math::Vector as Vec2;

use crate::scenario::{PointM, Rect};
use crate::world::neighbours::NeighbourGrid;

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
///
/// # Panics
/// Every method that takes a rescuee index `i` panics if `i >= self.len()`, as slice
/// indexing does (the mission only passes indices it got from this field).
#[derive(Debug, Clone)]
pub struct RescueeField {
    positions: Vec<PointM>,
    status: Vec<RescueeStatus>,
    known: Vec<bool>,
    pickups: Vec<u32>,
    unknown_waiting: usize,
    area: Rect,
    /// The rescuees that are known and waiting (any order): what
    /// [`RescueeField::nearest_known_waiting`] scans, so a claim costs the known waiting
    /// rescuees, not the task's whole list.
    known_waiting: Vec<u32>,
    /// Position of rescuee `i` in `known_waiting`, or [`NOT_LISTED`].
    slot: Vec<u32>,
    /// The rescuees bucketed by position relative to the search area's `min` corner (`f32`
    /// metres, the world's neighbour grid): what [`RescueeField::detect`] scans.
    grid: NeighbourGrid,
    /// Rescuees detected in one call (scratch of [`RescueeField::detect`]).
    hits: Vec<u32>,
}

/// `slot` of a rescuee that is not in the known-waiting list.
const NOT_LISTED: u32 = u32::MAX;

/// Rescuees per cell of [`RescueeField`]'s grid, about (the cell side is
/// `sqrt(area * RESCUEES_PER_CELL / n)`); default 4.
const RESCUEES_PER_CELL: f64 = 4.0;

/// `p` relative to `origin`, in `f32` metres (a point of [`RescueeField`]'s grid).
fn from_origin(p: &PointM, origin: &PointM) -> Vec2 {
    Vec2::new((p.x - origin.x) as f32, (p.y - origin.y) as f32)
}

/// The neighbour grid of `positions` over `area`: cells sized for about
/// [`RESCUEES_PER_CELL`] rescuees, positions relative to `area.min` (outside the area they
/// fall into the border cells; a degenerate area or no rescuees gives one cell).
fn rescuee_grid(positions: &[PointM], area: &Rect) -> NeighbourGrid {
    let (w, h) = (area.max.x - area.min.x, area.max.y - area.min.y);
    let cell_m = (w * h * RESCUEES_PER_CELL / positions.len().max(1) as f64).sqrt();
    let mut grid = NeighbourGrid::new(w as f32, h as f32, cell_m as f32);
    grid.rebuild(
        positions
            .iter()
            .enumerate()
            .map(|(i, p)| (i, from_origin(p, &area.min))),
    );
    grid
}

impl RescueeField {
    /// All rescuees of a task, waiting and unknown to everyone.
    pub fn new(positions: Vec<PointM>, area: Rect) -> Self {
        let n = positions.len();
        Self {
            grid: rescuee_grid(&positions, &area),
            hits: Vec::new(),
            positions,
            status: vec![RescueeStatus::Waiting; n],
            known: vec![false; n],
            pickups: vec![0; n],
            unknown_waiting: n,
            area,
            known_waiting: Vec::new(),
            slot: vec![NOT_LISTED; n],
        }
    }

    /// Sets rescuee `i`'s status and `known` flag: the one place both change, so the
    /// unknown-waiting count and the known-waiting list always agree with them (any sequence
    /// of calls keeps them exact, including ones the mission never makes, such as claiming an
    /// unknown rescuee).
    fn set(&mut self, i: usize, status: RescueeStatus, known: bool) {
        let unknown_waiting = |s: RescueeStatus, k: bool| !k && s == RescueeStatus::Waiting;
        let before = unknown_waiting(self.status[i], self.known[i]);
        self.status[i] = status;
        self.known[i] = known;
        match (before, unknown_waiting(status, known)) {
            (true, false) => self.unknown_waiting -= 1,
            (false, true) => self.unknown_waiting += 1,
            _ => {}
        }
        self.sync(i);
    }

    /// Puts rescuee `i` into the known-waiting list or takes it out, as its `known` flag and
    /// status now say (called by [`RescueeField::set`]; [`RescueeField::forget`] empties the
    /// list itself).
    fn sync(&mut self, i: usize) {
        let listed = self.slot[i] != NOT_LISTED;
        let should = self.known[i] && self.status[i] == RescueeStatus::Waiting;
        if should && !listed {
            self.slot[i] = self.known_waiting.len() as u32;
            self.known_waiting.push(i as u32);
        } else if !should && listed {
            let k = self.slot[i] as usize;
            self.known_waiting.swap_remove(k);
            if let Some(&moved) = self.known_waiting.get(k) {
                self.slot[moved as usize] = k as u32;
            }
            self.slot[i] = NOT_LISTED;
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
        for &i in &self.known_waiting {
            self.slot[i as usize] = NOT_LISTED;
        }
        self.known_waiting.clear();
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
    /// rescuees within the observing range), in index order. Cheap when everything is known or
    /// `center` is far from the search area; else `O(rescuees near center)` through a
    /// neighbour grid of the rescuees.
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
        let mut hits = std::mem::take(&mut self.hits);
        hits.clear();
        // Candidates within the range plus the grid's slack, which covers the rounding to
        // `f32`; the exact test is the `f64` one.
        let c = from_origin(center, &self.area.min);
        self.grid.for_each_candidate(c, range_m as f32, |i, _| {
            if !self.known[i]
                && self.status[i] == RescueeStatus::Waiting
                && (self.positions[i] - center).norm_squared() <= r2
            {
                hits.push(i as u32);
            }
        });
        hits.sort_unstable();
        for &i in &hits {
            self.set(i as usize, RescueeStatus::Waiting, true);
        }
        self.hits = hits;
    }

    /// The known, waiting rescuee nearest to `from` (ties: lowest index) for which `free`
    /// holds, if any (the caller excludes rescuees under other robots' bodies). `free` is only
    /// asked about rescuees that beat the best so far in (squared distance, index) order, so
    /// it must not depend on the order it is asked in. `O(k)` for `k` known waiting rescuees.
    pub fn nearest_known_waiting(
        &self,
        from: &PointM,
        free: impl Fn(&PointM) -> bool,
    ) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        for &i in &self.known_waiting {
            let i = i as usize;
            let d = (self.positions[i] - from).norm_squared();
            let beats = best.is_none_or(|(bd, bi)| d < bd || (d == bd && i < bi));
            if beats && free(&self.positions[i]) {
                best = Some((d, i));
            }
        }
        best.map(|(_, i)| i)
    }

    /// Robot `robot` claims waiting rescuee `i`. `robot` is stored as given (not checked
    /// against the team).
    ///
    /// # Panics
    /// If `i >= self.len()`; in debug builds also if rescuee `i` is not waiting (claiming a
    /// rescuee another robot holds is a logic error of the caller; a release build records
    /// the new claim).
    pub fn claim(&mut self, i: usize, robot: usize) {
        debug_assert_eq!(self.status[i], RescueeStatus::Waiting);
        self.set(i, RescueeStatus::Claimed(robot), self.known[i]);
    }

    /// Releases a claim: the rescuee waits again (and stays known).
    pub fn release(&mut self, i: usize) {
        if matches!(self.status[i], RescueeStatus::Claimed(_)) {
            self.set(i, RescueeStatus::Waiting, self.known[i]);
        }
    }

    /// Robot `robot` picks up rescuee `i`.
    pub fn pick_up(&mut self, i: usize, robot: usize) {
        self.set(i, RescueeStatus::Carried(robot), self.known[i]);
        self.pickups[i] += 1;
    }

    /// Puts carried rescuee `i` back where it was found: it waits again, unknown to everyone
    /// (`mission.load_on_leave: ReturnToArea`). It may be picked up again, so
    /// [`RescueeField::pickups`] can exceed 1 for it.
    pub fn put_back(&mut self, i: usize) {
        self.set(i, RescueeStatus::Waiting, false);
    }

    /// Sets the final status of a carried or claimed rescuee (`Delivered`, `Abandoned` or
    /// `Unreachable`).
    pub fn settle(&mut self, i: usize, status: RescueeStatus) {
        self.set(i, status, self.known[i]);
    }
}

#[cfg(test)]
mod tests {
    use nalgebra::Point2;
    use proptest::prelude::*;

    use super::*;

    /// The scan of every rescuee in index order that the known-waiting list replaces.
    fn nearest_by_scan(
        f: &RescueeField,
        from: &PointM,
        free: impl Fn(&PointM) -> bool,
    ) -> Option<usize> {
        let mut best: Option<(f64, usize)> = None;
        for i in 0..f.len() {
            if f.known[i] && f.status[i] == RescueeStatus::Waiting {
                let d = (f.positions[i] - from).norm_squared();
                if best.is_none_or(|(bd, _)| d < bd) && free(&f.positions[i]) {
                    best = Some((d, i));
                }
            }
        }
        best.map(|(_, i)| i)
    }

    /// One mutation of a field: (operation, rescuee or robot, x, y).
    fn op() -> impl Strategy<Value = (u8, usize, f64, f64)> {
        (0u8..8, 0usize..12, 0.0f64..10.0, 0.0f64..10.0)
    }

    proptest! {
        /// Detection through the grid marks exactly the rescuees a scan of all would: many
        /// rescuees (small cells) in a search area away from the origin (rescuees lie in their
        /// task's area), queries inside and outside it, ranges from 0 to past the area, some
        /// exactly at a rescuee's distance.
        #[test]
        fn detect_marks_exactly_the_rescuees_in_range(
            points in prop::collection::vec((0.0f64..=1.0, 0.0f64..=1.0), 0..300),
            queries in prop::collection::vec((-10.0f64..40.0, -10.0f64..30.0, 0.0f64..40.0, any::<bool>()), 1..20),
            size in (0.5f64..30.0, 0.5f64..20.0),
            origin in (0.0f64..100.0, 0.0f64..100.0),
        ) {
            let shift = |x: f64, y: f64| Point2::new(x + origin.0, y + origin.1);
            let area = Rect { min: shift(0.0, 0.0), max: shift(size.0, size.1) };
            let positions: Vec<PointM> =
                points.iter().map(|&(u, v)| shift(u * size.0, v * size.1)).collect();
            let mut f = RescueeField::new(positions.clone(), area);
            for (k, &(x, y, r, exact)) in queries.iter().enumerate() {
                let c = shift(x, y);
                // Half the queries reach exactly to some rescuee.
                let r = match positions.get(k % positions.len().max(1)) {
                    Some(p) if exact => (p - c).norm(),
                    _ => r,
                };
                let before = f.known.clone();
                f.detect(&c, r);
                for (j, p) in positions.iter().enumerate() {
                    let in_range = (p - c).norm_squared() <= r * r;
                    prop_assert_eq!(f.known[j], before[j] || in_range, "rescuee {} r {}", j, r);
                }
            }
        }

        #[test]
        fn the_known_waiting_list_answers_as_the_full_scan(
            // Integer positions so that equal distances (ties by index) are common.
            cells in prop::collection::vec((0u8..5, 0u8..5), 1..12),
            ops in prop::collection::vec(op(), 0..60),
        ) {
            let positions: Vec<PointM> =
                cells.iter().map(|&(x, y)| Point2::new(f64::from(x) * 2.0, f64::from(y) * 2.0)).collect();
            let area = Rect { min: Point2::new(0.0, 0.0), max: Point2::new(10.0, 10.0) };
            let n = positions.len();
            let mut f = RescueeField::new(positions, area);
            for (kind, k, x, y) in ops {
                let i = k % n;
                let p = Point2::new(x, y);
                match kind {
                    0 | 1 => {
                        // Every waiting rescuee within range becomes known, and nothing else.
                        let before = f.known.clone();
                        f.detect(&p, 3.0);
                        for (j, &was) in before.iter().enumerate() {
                            let seen = f.status[j] == RescueeStatus::Waiting
                                && (f.positions[j] - p).norm_squared() <= 9.0;
                            prop_assert_eq!(f.known[j], was || seen, "rescuee {}", j);
                        }
                    }
                    2 if f.status(i) == RescueeStatus::Waiting => f.claim(i, k),
                    3 => f.release(i),
                    4 if matches!(f.status(i), RescueeStatus::Claimed(_)) => f.pick_up(i, k),
                    5 if matches!(f.status(i), RescueeStatus::Carried(_)) => f.put_back(i),
                    6 => f.settle(i, [RescueeStatus::Skipped, RescueeStatus::Unreachable][k % 2]),
                    7 => f.forget(),
                    _ => {}
                }
                // `free` excludes one spot, so the lazy test matters.
                let blocked = Point2::new(2.0 * (k % 5) as f64, 2.0 * (k % 3) as f64);
                let free = |q: &PointM| *q != blocked;
                prop_assert_eq!(f.nearest_known_waiting(&p, free), nearest_by_scan(&f, &p, free));
                let unknown = (0..n).filter(|&j| !f.known[j] && f.status[j] == RescueeStatus::Waiting).count();
                prop_assert_eq!(f.unknown_waiting, unknown);
            }
        }
    }

    /// Regression (CI, 2026-11-21): a claim that outlives [`RescueeField::forget`] (a new
    /// round) and is then released made its rescuee wait unknown without counting it, and
    /// detecting it then underflowed the count.
    #[test]
    fn a_claim_released_after_forget_is_counted_and_detected_once() {
        let area = Rect {
            min: Point2::new(0.0, 0.0),
            max: Point2::new(10.0, 10.0),
        };
        let mut f = RescueeField::new(vec![Point2::new(1.0, 1.0)], area);
        f.detect(&Point2::new(1.0, 1.0), 1.0);
        f.claim(0, 3);
        f.forget();
        f.release(0);
        assert_eq!(f.unknown_waiting, 1);
        f.detect(&Point2::new(1.0, 1.0), 1.0);
        assert_eq!(f.unknown_waiting, 0);
        assert_eq!(
            f.nearest_known_waiting(&Point2::new(0.0, 0.0), |_| true),
            Some(0)
        );
    }
}
