//! Validation: [`ScenarioSpec`] -> [`Scenario`], once ("parse, don't validate").
//!
//! The leaf parameter blocks are already checked (their numbers are validated types); this
//! step checks what spans fields and expands the compact forms ([`super::generate`]). In order
//! (the first failure is reported, with its field path): name; tasks (names, search areas,
//! goals, drop-offs inside the arena); kinds (names, counts, quotas by task name); listed
//! debris (inside the arena); rest station; goals, drop-off centres and the rest station clear
//! of debris; start positions (count, inside the arena with the body); generated debris; start
//! positions against debris (ground robots) and against each other (same locomotion);
//! rescuees; radiation zones; cross-field parameter rules; the limits of derived quantities;
//! the blind-search sweeps' sizes.
//!
//! This file only runs the steps in that order; each step lives in the file of its spec
//! section (`check_names`, `check_tasks`, `check_kinds`, `check_debris`,
//! `check_rest_stations`, `check_clear_places`, `check_starts`, `check_radiation`,
//! `check_params`, and [`super::limits`]).

use super::check_clear_places::{check_reachable, protected_places};
use super::check_debris::listed_debris;
use super::check_kinds::validate_kinds;
use super::check_names::check_name;
use super::check_params::check_params;
use super::check_radiation::radiation_zones;
use super::check_rest_stations::rest_stations;
use super::check_starts::{check_starts, expand_starts};
use super::check_tasks::{expand_tasks, task_geometry};
use super::context::{Ctx, R};
use super::error::ScenarioError;
use super::generate::{ProtectedPlaces, generate_debris_field};
use super::limits::{check_derived, check_lists, check_sweeps};
use super::model::Locomotion;
use super::shape::DebrisShape;
use super::spec::ScenarioSpec;
use super::validated::Scenario;

impl ScenarioSpec {
    /// Checks every rule and builds the validated [`Scenario`] (grid layouts, start rows and
    /// debris fields expanded). `origin` names the source in errors (e.g. the file path).
    ///
    /// Errors from this method carry the field path but no line/column (the spec has no
    /// source text); [`super::from_str`] and [`super::load`] add positions.
    ///
    /// # Errors
    /// [`ScenarioError::Invalid`] for the first rule broken; see `docs/scenario-format.md`.
    pub fn validate(&self, origin: &str) -> Result<Scenario, ScenarioError> {
        validate(self, &Ctx { origin, map: None })
    }
}

/// See the module docs.
pub(crate) fn validate(spec: &ScenarioSpec, ctx: &Ctx<'_>) -> R<Scenario> {
    check_name(ctx, "name".into(), "name", &spec.name)?;
    let arena = spec.arena;
    check_lists(ctx, &spec.kinds, spec.tasks.len())?;
    let geometry = task_geometry(ctx, &spec.tasks, &arena)?;
    let kinds = validate_kinds(ctx, &spec.kinds, &spec.tasks)?;
    // Reach: how close to debris a point may be for a ground robot to get to it.
    let reach = kinds
        .iter()
        .filter(|k| k.locomotion == Locomotion::Ground)
        .map(|k| k.body_radius_m)
        .reduce(f64::min)
        .unwrap_or(0.0);
    let mut debris = listed_debris(ctx, &spec.debris, &arena)?;
    let rest_stations = rest_stations(ctx, &spec.rest_station, &arena)?;
    check_reachable(ctx, &rest_stations, &spec.tasks, &geometry, &debris, reach)?;
    let starts = expand_starts(ctx, spec, &kinds, &arena)?;
    let protected = protected_places(&starts, &kinds, &rest_stations, &spec.tasks, &geometry);
    let protected = ProtectedPlaces::new(&protected);
    for (j, field) in spec.debris_fields.iter().enumerate() {
        let existing: Vec<DebrisShape> = debris.iter().map(|(d, _)| *d).collect();
        let generated =
            generate_debris_field(ctx, j, field, &arena, spec.sim.seed, &existing, &protected)?;
        debris.extend(
            generated
                .into_iter()
                .enumerate()
                .map(|(n, d)| (d, format!("debris_fields[{j}] shape {n}"))),
        );
    }
    check_starts(ctx, &starts, &kinds, &debris)?;
    let tasks = expand_tasks(ctx, &spec.tasks, geometry, &debris, reach)?;
    let radiation_zones = radiation_zones(ctx, spec, &arena)?;
    check_params(ctx, spec)?;
    check_derived(
        ctx,
        &arena,
        &spec.navigation,
        &spec.collision,
        &spec.needs_weights,
        &kinds,
        &spec.sim,
    )?;
    let scenario = Scenario {
        name: spec.name.clone(),
        description: spec.description.clone(),
        arena,
        kinds,
        robots: starts.iter().map(|(_, r)| *r).collect(),
        rest_stations: rest_stations.into_iter().map(|(_, c)| c).collect(),
        tasks,
        debris: debris.iter().map(|(d, _)| *d.debris()).collect(),
        radiation_zones,
        needs_weights: spec.needs_weights,
        mission: spec.mission.clone(),
        navigation: spec.navigation,
        collision: spec.collision,
        sim: spec.sim,
        spec: spec.clone(),
    };
    check_sweeps(ctx, &scenario)?;
    Ok(scenario)
}

#[cfg(test)]
mod tests {
    use crate::scenario::{from_str, load};
    use nalgebra::Point2;

    fn scenario_file(name: &str) -> std::path::PathBuf {
        std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("../../scenarios")
            .join(name)
    }

    #[test]
    fn paper_debris_keeps_gaps_ground_robots_fit_through() {
        let s = load(scenario_file("paper.ron")).expect("paper.ron loads");
        // 8 + 3 listed, 8 + 5 generated.
        assert_eq!(s.debris.len(), 24);
        for (i, a) in s.debris.iter().enumerate() {
            for b in &s.debris[i + 1..] {
                let d = a.shape().distance(&b.shape());
                assert!(d >= 2.0, "gap {d} between {a:?} and {b:?}");
            }
        }
    }

    #[test]
    fn rows_expand_in_order_and_kinds_order_robots() {
        let src = std::fs::read_to_string(scenario_file("paper.ron")).expect("paper.ron");
        let s = from_str(&src, "paper.ron").expect("loads");
        assert_eq!(s.robots.len(), 12);
        let kinds: Vec<usize> = s.robots.iter().map(|r| r.kind).collect();
        assert_eq!(kinds, [0, 0, 0, 0, 0, 0, 1, 1, 1, 1, 2, 2]);
        assert_eq!(s.robots[0].start_in_world, Point2::new(32.5, 3.0));
        assert_eq!(s.robots[5].start_in_world, Point2::new(47.5, 3.0));
    }

    #[test]
    fn zero_row_step_is_rejected() {
        let src = std::fs::read_to_string(scenario_file("corridor.ron")).expect("corridor.ron");
        let src = src.replacen("step_m: (-1.0, 0.0)", "step_m: (0.0, 0.0)", 1);
        let err = from_str(&src, "c.ron").expect_err("zero step");
        assert_eq!(err.field(), Some("kinds[0].starts.step_m"));
        assert!(err.line_col().is_some());
    }

    /// paper.ron with its carriers' row replaced by `grid`.
    fn paper_with_carrier_starts(grid: &str) -> String {
        let src = std::fs::read_to_string(scenario_file("paper.ron")).expect("paper.ron");
        let row = "Row(first_m: (32.5, 3.0), step_m: (3.0, 0.0))";
        assert!(src.contains(row));
        src.replacen(row, grid, 1)
    }

    #[test]
    fn grids_fill_row_by_row() {
        let src = paper_with_carrier_starts(
            "Grid(first_m: (32.5, 3.0), columns: 4, spacing_m: (3.0, -1.5))",
        );
        let s = from_str(&src, "p.ron").expect("loads");
        let starts: Vec<(f64, f64)> = s.robots[..6]
            .iter()
            .map(|r| (r.start_in_world.x, r.start_in_world.y))
            .collect();
        let want = [
            (32.5, 3.0),
            (35.5, 3.0),
            (38.5, 3.0),
            (41.5, 3.0),
            (32.5, 1.5),
            (35.5, 1.5),
        ];
        for (got, want) in starts.iter().zip(want) {
            assert!((got.0 - want.0).abs() < 1e-12 && (got.1 - want.1).abs() < 1e-12);
        }
    }

    #[test]
    fn degenerate_grids_are_rejected_with_their_field() {
        for (grid, field) in [
            (
                "Grid(first_m: (32.5, 3.0), columns: 0, spacing_m: (3.0, 1.5))",
                "kinds[0].starts.columns",
            ),
            (
                "Grid(first_m: (32.5, 3.0), columns: 3, spacing_m: (0.0, 1.5))",
                "kinds[0].starts.spacing_m",
            ),
            (
                "Grid(first_m: (32.5, 3.0), columns: 3, spacing_m: (3.0, 0.0))",
                "kinds[0].starts.spacing_m",
            ),
        ] {
            let err = from_str(&paper_with_carrier_starts(grid), "p.ron").expect_err(grid);
            assert_eq!(err.field(), Some(field), "{grid}: {err}");
            assert!(err.line_col().is_some(), "{grid}: {err}");
        }
        // One row needs no y spacing, one column no x spacing.
        for ok in [
            "Grid(first_m: (32.5, 3.0), columns: 6, spacing_m: (3.0, 0.0))",
            "Grid(first_m: (20.0, 3.0), columns: 1, spacing_m: (0.0, 0.9))",
        ] {
            from_str(&paper_with_carrier_starts(ok), "p.ron").expect(ok);
        }
    }
}
