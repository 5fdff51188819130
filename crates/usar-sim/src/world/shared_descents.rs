//! Plans to shared goals for many robots at once, side by side: at a round's start a large
//! team is sent to its tasks' goal points, one shared distance field per goal and clearance
//! class ([`super::shared_fields`]).
//!
//! [`prepare_descents`] expands each field once to every start it is asked from (Dijkstra's
//! search is serial within a field; the fields are expanded side by side when they fit the
//! fields' memory budget together, else one at a time, [`SharedFields::with_fields`]), then
//! runs the descents and their smoothing from those starts in parallel: a descent from a
//! settled cell only reads the field ([`DistanceField::descend_settled`]), and its path does
//! not depend on how far the field was expanded (module docs of [`super::distance_field`]).
//! The plans are exactly those the planner would make one by one
//! ([`super::path_planner::PathPlanner::plan`]), so preparing them changes no path, only
//! when they are computed.

use std::collections::HashMap;

use rayon::prelude::*;

use super::clearance_grid::ClearanceGrid;
use super::distance_field::DistanceField;
use super::error::NavError;
use super::path_smoothing::smooth_galloping;
use super::plan_cache::{PlanKey, Planned};
use super::plan_query::{Endpoints, PlanQuery};
use super::shared_fields::SharedFields;

/// Fewest descents a rayon task takes: a descent and its smoothing cost microseconds.
const MIN_DESCENTS_PER_TASK: usize = 32;

/// The plan of a descent from cell `start` to cell `goal` for `inflation` metres whose raw
/// cells (start to goal) are `raw`, `found` when the descent found them: `raw` smoothed by
/// line of sight ([`smooth_galloping`]), `[start, goal]` when it holds fewer than two cells,
/// and [`NavError::NoPath`] when not `found`.
pub(super) fn smoothed(
    grid: &ClearanceGrid,
    raw: &[u32],
    (start, goal): (u32, u32),
    inflation: f32,
    found: bool,
) -> Planned {
    if !found {
        return Err(NavError::NoPath);
    }
    if raw.len() < 2 {
        return Ok(vec![start, goal]);
    }
    Ok(smooth_galloping(grid, raw, inflation))
}

/// Plans each of `queries` (shared goals: every query's goal is one of the planner's shared
/// goals) whose key (inflation, start cell, goal cell, shared) is neither `known` nor already
/// in `into`, by descent of its field from `fields` (kept or made, as
/// [`SharedFields::with_fields`] does), and puts the plans into `into` by key. The fields and
/// the descents of each run in parallel on the calling rayon pool when `parallel` (the fields
/// within the budget), one by one otherwise.
/// A query whose ends do not snap ([`Endpoints::snap`] fails) is left out: planning it fails
/// before any descent.
pub(super) fn prepare_descents(
    fields: &mut SharedFields,
    grid: &ClearanceGrid,
    arena: (f32, f32),
    queries: &[PlanQuery],
    known: impl Fn(&PlanKey) -> bool,
    parallel: bool,
    into: &mut HashMap<PlanKey, Planned>,
) {
    let asked = starts_by_field(grid, arena, queries, |k| known(k) || into.contains_key(k));
    let keys: Vec<(u32, f32)> = (asked.iter())
        .map(|&((goal, bits), _)| (goal, f32::from_bits(bits)))
        .collect();
    let plans = fields.with_fields(grid, &keys, parallel, |k, field| {
        let ((goal, bits), starts) = &asked[k];
        let found: Vec<bool> = (starts.iter())
            .map(|&s| field.cost_from(grid, s).is_some())
            .collect();
        let inflation = f32::from_bits(*bits);
        descend_all(field, grid, (*goal, inflation), starts, &found, parallel)
    });
    for (((goal, bits), starts), plans) in asked.into_iter().zip(plans) {
        for (start, plan) in starts.into_iter().zip(plans) {
            into.insert((bits, start, goal, true), plan);
        }
    }
}

/// The distinct start cells of `queries` per field (goal cell, inflation bits), fields and
/// starts in the order of their first query, leaving out the keys `skip` says and the
/// queries whose ends do not snap.
fn starts_by_field(
    grid: &ClearanceGrid,
    arena: (f32, f32),
    queries: &[PlanQuery],
    skip: impl Fn(&PlanKey) -> bool,
) -> Vec<((u32, u32), Vec<u32>)> {
    let mut fields: Vec<((u32, u32), Vec<u32>)> = Vec::new();
    let mut field_of: HashMap<(u32, u32), usize> = HashMap::new();
    let mut seen: std::collections::HashSet<PlanKey> = std::collections::HashSet::new();
    for q in queries {
        let Ok(ends) = Endpoints::snap(grid, arena, *q) else {
            continue;
        };
        let bits = q.inflation_m.to_bits();
        let key = (bits, ends.start, ends.goal, true);
        if skip(&key) || !seen.insert(key) {
            continue;
        }
        let k = *field_of.entry((ends.goal, bits)).or_insert_with(|| {
            fields.push(((ends.goal, bits), Vec::new()));
            fields.len() - 1
        });
        fields[k].1.push(ends.start);
    }
    fields
}

/// The plans from each of `starts` down `field` towards `goal` for `inflation` metres
/// (`(goal, inflation)`), `found[i]` when the field reached `starts[i]`; side by side when
/// `parallel`.
fn descend_all(
    field: &DistanceField,
    grid: &ClearanceGrid,
    (goal, inflation): (u32, f32),
    starts: &[u32],
    found: &[bool],
    parallel: bool,
) -> Vec<Planned> {
    let one = |raw: &mut Vec<u32>, (&start, &reached): (&u32, &bool)| {
        let found = reached && field.descend_settled(grid, start, raw);
        smoothed(grid, raw, (start, goal), inflation, found)
    };
    if parallel {
        starts
            .par_iter()
            .zip(found)
            .with_min_len(MIN_DESCENTS_PER_TASK)
            .map_init(Vec::new, one)
            .collect()
    } else {
        let mut raw = Vec::new();
        starts.iter().zip(found).map(|s| one(&mut raw, s)).collect()
    }
}
