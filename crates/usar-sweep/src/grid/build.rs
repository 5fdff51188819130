//! Building a parameter grid from `--vary` arguments: parse them, count the cells, make and
//! validate every cell, and refuse a grid whose values overlap or repeat a scenario.

use std::collections::HashMap;

use serde_json::Value;
use usar_sim::scenario::ScenarioSpec;

use crate::data::grid_cells::{Grid, GridCell};
use crate::data::limits::MAX_SWEEP_TRIALS;
use crate::fingerprint::scenario_hash;
use crate::grid::error::GridError;
use crate::grid::names;
use crate::settings::Setting;
use crate::vary::{Override, Vary, apply_overrides, brief, rule_error, spec_json};

/// What the functions of this module return.
type Result<T> = std::result::Result<T, GridError>;

/// The refusal of the `--vary` argument `arg` (already shortened) for `problem`.
fn refused(arg: String, problem: impl std::fmt::Display) -> GridError {
    GridError::Vary {
        arg,
        problem: problem.to_string(),
    }
}

/// Parses the `--vary` arguments `args` (at least one).
fn parse_varies(args: &[String]) -> Result<Vec<Vary>> {
    if args.is_empty() {
        return Err(GridError::NoVary);
    }
    args.iter()
        .map(|a| Vary::parse(a).map_err(|e| refused(brief(a), e)))
        .collect()
}

/// The product of the value counts of `varies`, saturating at `usize::MAX`.
fn cells_of(varies: &[Vary]) -> usize {
    varies
        .iter()
        .fold(1usize, |n, v| n.saturating_mul(v.values.len()))
}

/// The value counts of `varies` as a product, `10 x 10 x 3 values`.
fn shape_text(varies: &[Vary]) -> String {
    let counts: Vec<String> = varies.iter().map(|v| v.values.len().to_string()).collect();
    format!("{} values", counts.join(" x "))
}

/// A saturated count as "more than 18446744073709551614", else the count.
fn count_text(n: usize) -> String {
    if n == usize::MAX {
        format!("more than {}", usize::MAX - 1)
    } else {
        n.to_string()
    }
}

/// Parses the `--vary` arguments `args` and builds every cell from `base`.
///
/// # Errors
/// One line naming the `--vary` argument and what is wrong: a malformed argument, a field
/// given twice (or two overlapping fields, such as `zones[*].r` and `zones[2].r`), a path
/// that names nothing (`--vary mission.hp_rate=1: no field "hp_rate" in mission (fields:
/// duration_s, ...)`), a value of the wrong type, two values giving the same scenario, or
/// a cell that breaks a rule (`--vary mission.duration_s=-5: mission.duration_s: expected
/// a finite number > 0, found -5`; a rule broken only by a combination names every value
/// of the cell), or more cells than [`MAX_SWEEP_TRIALS`] (checked before any cell is made).
pub fn build_grid(base: &ScenarioSpec, args: &[String]) -> Result<Grid> {
    let varies = parse_varies(args)?;
    check_distinct(&varies)?;
    let n_cells = cells_of(&varies);
    if n_cells > MAX_SWEEP_TRIALS {
        return Err(GridError::TooManyCells {
            shape: shape_text(&varies),
            cells: count_text(n_cells),
            limit: MAX_SWEEP_TRIALS,
        });
    }
    let base_json = spec_json(base).map_err(|problem| GridError::Base { problem })?;
    for (v, arg) in varies.iter().zip(args) {
        check_values(base, &base_json, v, arg)?;
    }
    let labels = names::field_labels(&varies.iter().map(|v| &v.path).collect::<Vec<_>>());
    let mut cells = Vec::with_capacity(n_cells);
    for index in 0..n_cells {
        let overrides = cell_overrides(&varies, index);
        let origin = format!("cell {index}");
        let spec =
            apply_overrides(base, &overrides).map_err(|(i, e)| refused(overrides[i].brief(), e))?;
        let scenario = spec.validate(&origin).map_err(|e| GridError::CellRule {
            line: rule_error(&Setting::Vary.to_string(), &overrides, &e),
        })?;
        let values: Vec<&str> = overrides.iter().map(|o| o.value.text.as_str()).collect();
        cells.push(GridCell {
            index,
            dir: names::cell_dir(index, n_cells, &labels, &values),
            overrides,
            spec,
            scenario,
        });
    }
    check_same_scenarios(&varies, args, &cells)?;
    Ok(Grid { varies, cells })
}

/// How many cells the `--vary` arguments `args` make (the product of their value
/// counts; `usize::MAX` when that overflows), without building any: a caller checks a
/// sweep's size with it before [`build_grid`] validates every cell.
///
/// # Errors
/// As [`build_grid`] for a malformed argument or none at all.
pub fn cell_count(args: &[String]) -> Result<usize> {
    parse_varies(args).map(|v| cells_of(&v))
}

/// The overrides of cell `index`: the first `--vary` varies slowest.
fn cell_overrides(varies: &[Vary], index: usize) -> Vec<Override> {
    let mut rest = index;
    let mut picks = vec![0; varies.len()];
    for (i, v) in varies.iter().enumerate().rev() {
        picks[i] = rest % v.values.len();
        rest /= v.values.len();
    }
    varies.iter().zip(picks).map(|(v, k)| v.at(k)).collect()
}

/// No field may be varied twice, directly or through a wildcard or an enclosing field.
fn check_distinct(varies: &[Vary]) -> Result<()> {
    for (i, a) in varies.iter().enumerate() {
        for b in &varies[..i] {
            if a.path == b.path {
                return Err(GridError::Twice {
                    path: a.path.to_string(),
                });
            }
            if a.path.overlaps(&b.path) {
                return Err(GridError::Overlap {
                    first: b.path.to_string(),
                    second: a.path.to_string(),
                });
            }
        }
    }
    Ok(())
}

/// The path names something and each value has the right type on the base spec (values
/// that give the same scenario are found on the built cells: [`check_same_scenarios`]).
fn check_values(base: &ScenarioSpec, base_json: &Value, v: &Vary, arg: &str) -> Result<()> {
    v.path
        .set(&mut base_json.clone(), &mut |old| Ok(old.clone()))
        .map_err(|e| refused(brief(arg), e))?;
    for k in 0..v.values.len() {
        let o = v.at(k);
        apply_overrides(base, std::slice::from_ref(&o)).map_err(|(_, e)| refused(o.brief(), e))?;
    }
    Ok(())
}

/// Refuses two values of one `--vary` that give the same validated scenario in every cell,
/// whatever the other `--vary` values are: `60` and `60.0`, or two spellings of one scenario
/// (`Row(...)` and the `List([...])` it expands to), are one value. Two values that coincide
/// only with some value of another `--vary` (a debris field's `seed: None` and `Some(s)`
/// where `sim.seed` is `s`) are kept: the grid needs both.
///
/// Linear in the cells: each cell's [`scenario_hash`] once, then per `--vary` a map from a
/// value's cells' hashes to the value; equal hashes are confirmed on the scenarios.
fn check_same_scenarios(varies: &[Vary], args: &[String], cells: &[GridCell]) -> Result<()> {
    let hashes: Vec<String> = cells
        .iter()
        .map(|c| scenario_hash(&c.scenario))
        .collect::<std::result::Result<_, _>>()
        .map_err(|e| GridError::Base {
            problem: e.to_string(),
        })?;
    let mut stride = cells.len();
    for (v, arg) in varies.iter().zip(args) {
        let m = v.values.len();
        stride /= m;
        // Cell `hi * m * stride + pick * stride + lo` holds value `pick` of this --vary.
        let cells_of = |pick: usize| {
            (0..cells.len() / (m * stride))
                .flat_map(move |hi| (0..stride).map(move |lo| (hi * m + pick) * stride + lo))
        };
        let mut first: HashMap<Vec<&str>, usize> = HashMap::with_capacity(m);
        for k in 0..m {
            let key: Vec<&str> = cells_of(k).map(|c| hashes[c].as_str()).collect();
            match first.get(&key) {
                Some(&j)
                    if cells_of(j)
                        .zip(cells_of(k))
                        .all(|(a, b)| cells[a].scenario == cells[b].scenario) =>
                {
                    return Err(same_scenario(arg, v, j, k));
                }
                Some(_) => {}
                None => {
                    first.insert(key, k);
                }
            }
        }
    }
    Ok(())
}

/// The error for values `j` and `k` of `--vary` `arg` that give the same scenario.
fn same_scenario(arg: &str, v: &Vary, j: usize, k: usize) -> GridError {
    GridError::SameScenario {
        arg: brief(arg),
        first: brief(&v.values[j].text),
        second: brief(&v.values[k].text),
    }
}

#[cfg(test)]
mod tests {
    use usar_sim::scenario::parse_spec;

    use super::*;

    const PAPER: &str = include_str!("../../../../scenarios/paper.ron");

    fn build(args: &[&str]) -> Result<Grid> {
        let base = parse_spec(PAPER, "paper.ron").unwrap();
        build_grid(
            &base,
            &args.iter().map(|s| s.to_string()).collect::<Vec<_>>(),
        )
    }

    fn err(args: &[&str]) -> String {
        format!("{:#}", build(args).unwrap_err())
    }

    #[test]
    fn cells_are_the_product_first_field_slowest() {
        let g = build(&[
            "mission.hp_pct_per_step_in_radiation=0.0003,0.003",
            "kinds[0].max_speed_m_per_s=1,1.5,2",
        ])
        .unwrap();
        assert_eq!(
            g.fields(),
            [
                "mission.hp_pct_per_step_in_radiation",
                "kinds[0].max_speed_m_per_s"
            ]
        );
        let values: Vec<Vec<String>> = g.cells.iter().map(GridCell::values).collect();
        assert_eq!(
            values,
            [
                ["0.0003", "1"],
                ["0.0003", "1.5"],
                ["0.0003", "2"],
                ["0.003", "1"],
                ["0.003", "1.5"],
                ["0.003", "2"]
            ]
        );
        let c = &g.cells[4];
        assert_eq!(c.index, 4);
        assert_eq!(c.scenario.mission().hp_pct_per_step_in_radiation, 0.003);
        assert_eq!(c.scenario.kinds()[0].max_speed_m_per_s, 1.5);
        assert_eq!(
            c.dir,
            "c04_hp_pct_per_step_in_radiation=0.003_max_speed_m_per_s=1.5"
        );
    }

    #[test]
    fn a_grid_over_the_trial_limit_is_refused_before_any_cell_is_made() {
        let ten = "=0,1,2,3,4,5,6,7,8,9";
        let fields = [
            "mission.pickup_s",
            "mission.recharge_s",
            "mission.low_hp_pct",
            "mission.low_energy_pct",
            "mission.energy_pct_per_m",
            "collision.safety_margin_m",
            "navigation.clearance_m",
        ];
        let args: Vec<String> = fields.iter().map(|f| format!("{f}{ten}")).collect();
        let refs: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_eq!(cell_count(&args).unwrap(), 10_000_000);
        assert_eq!(
            err(&refs),
            "the grid's 10 x 10 x 10 x 10 x 10 x 10 x 10 values make 10000000 cells, more \
             than the limit of 1000000 trials per sweep"
        );
        // The count saturates instead of overflowing.
        let many = vec![format!("mission.pickup_s{ten}"); 30];
        assert_eq!(cell_count(&many).unwrap(), usize::MAX);
        assert!(cell_count(&[]).is_err());
    }

    #[test]
    fn rule_errors_name_the_vary_argument() {
        assert_eq!(
            err(&["mission.duration_s=60,-5"]),
            "--vary mission.duration_s=-5: mission.duration_s: expected a finite number > 0, \
             found -5"
        );
        // A wildcard names its field; the rule's field is the element's.
        let e = err(&["radiation_zones[*].radius_m=2,100"]);
        assert!(
            e.starts_with("--vary radiation_zones[*].radius_m=100: radiation_zones[0]"),
            "{e}"
        );
        // The rule's field belongs to one varied field: that one is named.
        assert_eq!(
            err(&["kinds[0].count=6,4", "kinds[0].quota.easy=3,1"]),
            "--vary kinds[0].quota.easy=1: kinds[0].quota: hard 3 + easy 1 = 4 but count is 6"
        );
        // The rule is about no varied field: every value of the cell is named.
        let e = err(&[
            "debris[0].center_m=(30.0, 18.0),(58.0, 44.0)",
            "mission.recharge_s=10",
        ]);
        assert!(
            e.starts_with(
                "--vary debris[0].center_m=(58.0, 44.0) --vary mission.recharge_s=10: \
                 tasks[1].goal_m: task \"easy\": goal (58, 44) is 0.000 m from debris[0]"
            ),
            "{e}"
        );
    }

    #[test]
    fn values_that_give_one_scenario_only_with_some_other_value_are_kept() {
        // paper.ron's debris_fields[0] has seed Some(2021) and sim.seed is 2021: seed None
        // (sim.seed + 0) is the same field there, another with sim.seed 7.
        assert_eq!(
            err(&["debris_fields[0].seed=None,Some(2021)"]),
            "--vary debris_fields[0].seed=None,Some(2021): values None and Some(2021) give the \
             same scenario"
        );
        let g = build(&["debris_fields[0].seed=None,Some(2021)", "sim.seed=2021,7"]).unwrap();
        let values: Vec<Vec<String>> = g.cells.iter().map(GridCell::values).collect();
        assert_eq!(
            values,
            [
                ["None", "2021"],
                ["None", "7"],
                ["Some(2021)", "2021"],
                ["Some(2021)", "7"]
            ]
        );
        assert!(g.cells[0].scenario == g.cells[2].scenario);
        assert!(g.cells[1].scenario != g.cells[3].scenario);
        // Whichever --vary comes first.
        assert!(build(&["sim.seed=2021,7", "debris_fields[0].seed=None,Some(2021)"]).is_ok());
        // Equal in every cell: refused, with another --vary beside it.
        assert_eq!(
            err(&["sim.seed=2021,7", "mission.duration_s=60,60.0"]),
            "--vary mission.duration_s=60,60.0: values 60 and 60.0 give the same scenario"
        );
    }

    #[test]
    fn bad_arguments_are_refused() {
        let e = err(&["mission.hp_rate=1"]);
        assert!(
            e.starts_with(
                "--vary mission.hp_rate=1: no field \"hp_rate\" in mission (fields: duration_s, \
                 energy_pct_per_moving_step,"
            ),
            "{e}"
        );
        assert_eq!(
            err(&["radiation_zones[7].radius_m=1"]),
            "--vary radiation_zones[7].radius_m=1: no element [7] in radiation_zones: it has 7 \
             (indices 0 to 6)"
        );
        assert_eq!(
            err(&["mission.duration_s=60,abc"]),
            "--vary mission.duration_s=abc: mission.duration_s: expected a number, found abc"
        );
        assert_eq!(
            err(&["mission.duration_s=1", "mission.duration_s=2"]),
            "--vary mission.duration_s is given twice: vary each field once"
        );
        assert_eq!(
            err(&[
                "radiation_zones[*].radius_m=1",
                "radiation_zones[2].radius_m=2"
            ]),
            "--vary radiation_zones[*].radius_m overlaps --vary radiation_zones[2].radius_m: \
             they set some of the same values"
        );
        assert_eq!(
            err(&["mission.duration_s=60,60.0"]),
            "--vary mission.duration_s=60,60.0: values 60 and 60.0 give the same scenario"
        );
        // Two spellings of the same starts: the Row and the List it expands to.
        assert_eq!(
            err(&[
                "kinds[0].starts=Row(first_m: (32.5, 3.0), step_m: (3.0, 0.0)),List([(32.5, 3.0), (35.5, 3.0), (38.5, 3.0), (41.5, 3.0), (44.5, 3.0), (47.5, 3.0)])"
            ]),
            "--vary kinds[0].starts=Row(first_m: (32.5, 3.0), step_m: (3.0, 0.0)... (146 \
             characters): values Row(first_m: (32.5, 3.0), step_m: (3.0, 0.0)) and List([(32.5, \
             3.0), (35.5, 3.0), (38.5, 3.0), (41.5, 3.0), (4... (84 characters) give the same \
             scenario"
        );
        assert_eq!(
            err(&["mission.duration_s"]),
            "--vary mission.duration_s: expected FIELD=VALUE"
        );
    }
}
