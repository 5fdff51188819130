//! The planner's store of shared distance fields ([`DistanceField`]), one per shared goal cell
//! and clearance class, held within a memory budget.
//!
//! A field holds 5 bytes per grid cell (80 MiB at the 2^24-cell limit) for as long as it is
//! kept, and a scenario may share up to 64 task goals, 64 drop-offs and 256 rest stations
//! among several clearance classes: kept for the planner's life, 16 goals on a 1,000 m x
//! 1,000 m arena at 0.25 m took 2.5 GB, and 64 aborted on a failed allocation. So the store
//! keeps the fields it used most recently and drops the least recently used one while the
//! fields together hold more than the budget ([`SHARED_FIELDS_BUDGET_BYTES`] by default).
//! The order is that of the uses, a list, never a hash map's, so eviction is deterministic;
//! and a field is a pure function of (grid, goal cell, inflation) whose descents do not depend
//! on earlier queries ([`super::distance_field`]), so a field dropped and made again gives the
//! same paths: the budget changes how often a field is computed, never a path.
//!
//! A field made after dropping one to make room is made in the dropped one's memory
//! ([`DistanceField::renew`]): on a grid of millions of cells, fresh pages for every field
//! made again cost the kernel more than writing the dropped field's cells afresh (a third of
//! the CPU of `swarm-100000.ron`'s run went to it, `docs/measurements.md`).
//!
//! A field larger than the whole budget (only under a budget below the default, e.g. 32 MiB
//! on a grid of more than 6.8 M cells; the default holds six fields of the largest grid) is
//! still made and used for the plan that asked for it, then dropped: the next plan to that
//! goal makes it again. While one plan runs, the fields hold at most the larger of the
//! budget and the one field in use, plus what that field's open set grows by during the plan;
//! between plans, at most the budget.

use std::collections::VecDeque;

use rayon::prelude::*;

use super::clearance_grid::ClearanceGrid;
use super::distance_field::DistanceField;

/// Most heap memory a [`PathPlanner`] keeps in shared distance fields between plans, bytes:
/// 512 MiB, six fields of a grid at the 2^24-cell limit (80 MiB each, 5 bytes a cell), about
/// 6,700 of an 80 m x 60 m arena at 0.25 m. Past it the least recently used fields are
/// dropped and made again when next needed, with the same paths
/// (`docs/world-model.md`, "Shared goals, shared fields").
///
/// [`PathPlanner`]: super::path_planner::PathPlanner
pub const SHARED_FIELDS_BUDGET_BYTES: usize = 512 << 20;

/// Shared distance fields within a memory budget, least recently used dropped first (see the
/// module docs).
#[derive(Debug, Clone)]
pub(super) struct SharedFields {
    /// (heap bytes at the field's last use, the field), least recently used first.
    fields: VecDeque<(usize, DistanceField)>,
    /// The sum of the kept fields' heap bytes.
    held: usize,
    /// Most heap bytes kept between uses.
    budget: usize,
    /// Fields made so far in the memory of a field dropped to make room for them.
    renewed: u64,
}

impl Default for SharedFields {
    fn default() -> Self {
        Self::new(SHARED_FIELDS_BUDGET_BYTES)
    }
}

impl SharedFields {
    /// An empty store that keeps at most `budget_bytes` of fields between uses (any value; 0
    /// keeps none: every use makes its field afresh).
    pub(super) fn new(budget_bytes: usize) -> Self {
        Self {
            fields: VecDeque::new(),
            held: 0,
            budget: budget_bytes,
            renewed: 0,
        }
    }

    /// The budget, bytes.
    pub(super) fn budget_bytes(&self) -> usize {
        self.budget
    }

    /// Heap bytes the kept fields hold (as counted at their last use).
    pub(super) fn held_bytes(&self) -> usize {
        self.held
    }

    /// Fields made so far in the memory of a field dropped to make room for them
    /// ([`DistanceField::renew`]) rather than in memory of their own.
    pub(super) fn renewed(&self) -> u64 {
        self.renewed
    }

    /// The kept fields, least recently used first.
    pub(super) fn iter(&self) -> impl ExactSizeIterator<Item = &DistanceField> {
        self.fields.iter().map(|(_, f)| f)
    }

    /// Runs `use_field` on the field towards cell `goal` of `grid` for `inflation` metres (the
    /// kept one, or a new one made after dropping the least recently used fields the new one
    /// does not fit beside), then drops the least recently used fields until the budget holds
    /// (the one just used too, last, if it alone exceeds the budget). Returns `use_field`'s
    /// answer.
    pub(super) fn with_field<R>(
        &mut self,
        grid: &ClearanceGrid,
        goal: u32,
        inflation: f32,
        use_field: impl FnOnce(&mut DistanceField) -> R,
    ) -> R {
        let mut field = match (self.fields.iter()).position(|(_, f)| f.is_for(goal, inflation)) {
            Some(k) => self.take_kept(k),
            None => {
                // Room for the new field first; the last field dropped for it lends its
                // memory.
                let new_bytes = DistanceField::new_heap_bytes(grid);
                let dropped = self.drop_until(self.budget.saturating_sub(new_bytes));
                self.renewed += u64::from(dropped.is_some());
                made_in(dropped, grid, goal, inflation)
            }
        };
        let answer = use_field(&mut field);
        let bytes = field.heap_bytes();
        self.held += bytes;
        self.fields.push_back((bytes, field));
        // A field dropped here is freed: the budget holds between plans.
        let _freed = self.drop_until(self.budget);
        answer
    }

    /// Runs `use_field(k, field)` on the field towards each `keys[k]` (goal cell of `grid`,
    /// inflation metres; the keys distinct), and returns the answers by `k`: side by side on
    /// the calling rayon pool when `parallel` and the fields fit the budget together (the
    /// kept ones and a new one, [`DistanceField::new_heap_bytes`], for each key not kept;
    /// while they run, plus what their open sets grow by), else one after the other as
    /// [`SharedFields::with_field`] does. Either way the fields are then kept as if used in
    /// the order of `keys`, within the budget.
    pub(super) fn with_fields<R: Send>(
        &mut self,
        grid: &ClearanceGrid,
        keys: &[(u32, f32)],
        parallel: bool,
        use_field: impl Fn(usize, &mut DistanceField) -> R + Sync,
    ) -> Vec<R> {
        let kept = |&(goal, inflation): &(u32, f32)| {
            self.fields.iter().any(|(_, f)| f.is_for(goal, inflation))
        };
        let new_bytes =
            keys.iter().filter(|k| !kept(k)).count() * DistanceField::new_heap_bytes(grid);
        if !parallel || self.held.saturating_add(new_bytes) > self.budget {
            let each = keys.iter().enumerate();
            return each
                .map(|(k, &(goal, inflation))| {
                    self.with_field(grid, goal, inflation, |f| use_field(k, f))
                })
                .collect();
        }
        let mut taken: Vec<DistanceField> = (keys.iter())
            .map(|&(goal, inflation)| self.take(grid, goal, inflation))
            .collect();
        let answers = (taken.par_iter_mut().enumerate())
            .map(|(k, f)| use_field(k, f))
            .collect();
        for field in taken {
            let bytes = field.heap_bytes();
            self.held += bytes;
            self.fields.push_back((bytes, field));
        }
        // A field dropped here is freed: the budget holds between plans.
        let _freed = self.drop_until(self.budget);
        answers
    }

    /// The field towards cell `goal` for `inflation` metres, taken out of the store (the kept
    /// one, or a new one).
    fn take(&mut self, grid: &ClearanceGrid, goal: u32, inflation: f32) -> DistanceField {
        match (self.fields.iter()).position(|(_, f)| f.is_for(goal, inflation)) {
            Some(k) => self.take_kept(k),
            None => DistanceField::new(grid, goal, inflation),
        }
    }

    /// The kept field at position `k` of the store (least recently used first), taken out.
    fn take_kept(&mut self, k: usize) -> DistanceField {
        let (bytes, field) = self.fields.remove(k).expect("k is a kept field's position");
        self.held -= bytes;
        field
    }

    /// Drops the least recently used fields until they hold at most `limit` bytes; returns
    /// the last one dropped, if any.
    fn drop_until(&mut self, limit: usize) -> Option<DistanceField> {
        let mut last = None;
        while self.held > limit {
            let Some((bytes, field)) = self.fields.pop_front() else {
                break;
            };
            self.held -= bytes;
            last = Some(field);
        }
        last
    }
}

/// The field towards cell `goal` of `grid` for `inflation` metres, nothing expanded: made in
/// the memory of `dropped` ([`DistanceField::renew`]) when given, else new.
fn made_in(
    dropped: Option<DistanceField>,
    grid: &ClearanceGrid,
    goal: u32,
    inflation: f32,
) -> DistanceField {
    match dropped {
        Some(mut field) => {
            field.renew(grid, goal, inflation);
            field
        }
        None => DistanceField::new(grid, goal, inflation),
    }
}

#[cfg(test)]
mod tests {
    use parry2d::math::Vector as Vec2;

    use super::*;
    use crate::scenario::{Arena, Positive};

    const INFL: f32 = 0.3;

    fn grid() -> ClearanceGrid {
        let arena = Arena {
            width_m: Positive::new(6.0).unwrap(),
            height_m: Positive::new(6.0).unwrap(),
            wall_thickness_m: Positive::new(0.5).unwrap(),
        };
        ClearanceGrid::build(&arena, &[], 0.25, 2.0)
    }

    /// Under a budget of one field, each new goal drops the last one's field and is made in
    /// its memory; the costs are a new field's, and the budget holds between uses.
    #[test]
    fn a_new_field_is_made_in_the_memory_of_the_field_dropped_for_it() {
        let g = grid();
        let goals = [
            Vec2::new(1.0, 1.0),
            Vec2::new(5.0, 5.0),
            Vec2::new(1.0, 5.0),
        ];
        let mut store = SharedFields::new(DistanceField::new_heap_bytes(&g) + 4096);
        let from = g.cell_index(Vec2::new(3.0, 3.0));
        let mut memory = Vec::new();
        for goal in goals.map(|p| g.cell_index(p)) {
            let cost = store.with_field(&g, goal, INFL, |f| f.cost_from(&g, from));
            let fresh = DistanceField::new(&g, goal, INFL).cost_from(&g, from);
            assert_eq!(cost, fresh);
            assert_eq!(store.iter().len(), 1, "one field kept");
            let kept = store.iter().next().expect("the field just used");
            assert!(kept.is_for(goal, INFL));
            memory.push(kept.cost_memory());
            assert!(store.held_bytes() <= store.budget_bytes());
        }
        assert!(memory.windows(2).all(|m| m[0] == m[1]), "{memory:?}");
        assert_eq!(store.renewed(), 2, "the second and third goals");
    }
}
