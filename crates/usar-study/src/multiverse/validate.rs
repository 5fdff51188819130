//! The checks of an axes file against the base scenario and the free fields, made before
//! anything runs ([`check_axes`]): every alternative applied to the base spec alone must name
//! fields that exist, take values of their type and give a scenario that keeps every rule;
//! two alternatives of one axis must not give the same scenario and target flags; every target
//! an alternative flags must be in the targets file; no axis may set a field that
//! is `--free` (a calibrated field cannot be a choice too); and no axis may be named like a
//! free field (both are columns of `multiverse.csv`).
//!
//! Alternatives of different axes are not tried together here (the factorial can be large):
//! a universe whose combination breaks a rule is recorded as invalid when it runs.

use usar_sim::scenario::{ScenarioError, ScenarioSpec};

use super::axes::{Alternative, Axes, AxesError};
use crate::calibrate::FreeField;
use usar_report::targets::file::Targets;
use usar_sweep::settings::Setting;
use usar_sweep::vary::{Override, apply_overrides, spec_json, touching};

/// Checks `axes` against the base spec `base` (read from `origin`), the free fields and the
/// targets.
///
/// # Errors
/// The first problem, one line at the override or alternative it is about: a field that
/// does not exist or a value it cannot take (`set[j]`, with the `--vary` message), a rule the
/// alternative's scenario breaks, a target name the targets file does not have, an
/// alternative leaving every target out of the loss, two alternatives of an axis that give the
/// same scenario and target flags, a
/// field that is also `--free`, or an axis named like a free field.
pub fn check_axes(
    axes: &Axes,
    base: &ScenarioSpec,
    origin: &str,
    free: &[FreeField],
    targets: &Targets,
) -> Result<(), AxesError> {
    for (i, axis) in axes.axes.iter().enumerate() {
        if let Some(f) = free.iter().find(|f| f.field == axis.name.trim()) {
            return Err(axes.error(
                &format!("axes[{i}].name"),
                format!(
                    "axis {:?} is named like {} {f}; both are columns of multiverse.csv: \
                     name the axis otherwise",
                    axis.name,
                    Setting::Free
                ),
            ));
        }
        let mut specs: Vec<(serde_json::Value, Vec<bool>)> = Vec::new();
        for k in 0..axis.alternatives.len() {
            check_free(axes, i, k, free)?;
            let spec = apply_alternative(axes, i, k, base, origin)?;
            let json = spec_json(&spec).map_err(|m| alt_error(axes, i, k, "name", m))?;
            let flags = target_flags(axes, i, k, targets)?;
            let json = (json, flags);
            if let Some(m) = specs.iter().position(|s| *s == json) {
                return Err(alt_error(
                    axes,
                    i,
                    k,
                    "name",
                    format!(
                        "gives the same scenario and target flags as alternative {:?} \
                         (alternatives[{m}]): alternatives of an axis must differ",
                        axis.alternatives[m].name
                    ),
                ));
            }
            specs.push(json);
        }
    }
    check_some_target_fitted(axes, targets)
}

/// Each target's `report_only` flag in a universe of `targets` that takes alternative `k`
/// of axis `i` (and the file's flags elsewhere); refuses a name no target has, or an
/// alternative that leaves every target out of the loss.
fn target_flags(
    axes: &Axes,
    i: usize,
    k: usize,
    targets: &Targets,
) -> Result<Vec<bool>, AxesError> {
    let alt = &axes.axes[i].alternatives[k];
    let known = |n: &String| targets.targets().iter().any(|t| &t.name == n);
    let field = if alt.require.iter().all(known) {
        "report_only"
    } else {
        "require"
    };
    let mut t = targets.clone();
    t.set_flags(&alt.require, &alt.report_only)
        .map_err(|e| alt_error(axes, i, k, field, e.0.message))?;
    Ok(t.targets().iter().map(|t| t.report_only).collect())
}

/// Refuses axes of which some combination of alternatives leaves every target out of the
/// loss. Each target belongs to one axis, so the worst combination takes, on each axis, the
/// alternative that fits the fewest of the targets the axis flags.
fn check_some_target_fitted(axes: &Axes, targets: &Targets) -> Result<(), AxesError> {
    let names: Vec<&str> = targets.targets().iter().map(|t| t.name.as_str()).collect();
    let base: Vec<bool> = targets.targets().iter().map(|t| !t.report_only).collect();
    let mut touched = vec![false; names.len()];
    let mut fitted_at_worst = 0;
    let mut worst: Vec<String> = Vec::new();
    for axis in &axes.axes {
        let flags =
            |a: &Alternative, name: &str| a.require.iter().chain(&a.report_only).any(|n| n == name);
        let own: Vec<usize> = (0..names.len())
            .filter(|&t| axis.alternatives.iter().any(|a| flags(a, names[t])))
            .collect();
        if own.is_empty() {
            continue;
        }
        let fitted = |a: &Alternative| {
            own.iter()
                .filter(|&&t| {
                    let name = names[t];
                    !a.report_only.iter().any(|n| n == name)
                        && (base[t] || a.require.iter().any(|n| n == name))
                })
                .count()
        };
        let Some((alt, least)) = axis
            .alternatives
            .iter()
            .map(|a| (a, fitted(a)))
            .min_by_key(|&(_, n)| n)
        else {
            continue;
        };
        for &t in &own {
            touched[t] = true;
        }
        fitted_at_worst += least;
        worst.push(format!("{:?} of axis {:?}", alt.name, axis.name));
    }
    fitted_at_worst += (0..names.len()).filter(|&t| !touched[t] && base[t]).count();
    if fitted_at_worst == 0 {
        return Err(axes.error(
            "axes",
            format!(
                "the universes taking {} fit no target (every one report-only): give those \
                 alternatives fewer report_only targets",
                worst.join(" and ")
            ),
        ));
    }
    Ok(())
}

/// An error about `field` of alternative `k` of axis `i` (`name`, `set[2]`), naming both.
fn alt_error(axes: &Axes, i: usize, k: usize, field: &str, message: String) -> AxesError {
    let axis = &axes.axes[i];
    axes.error(
        &format!("axes[{i}].alternatives[{k}].{field}"),
        format!(
            "axis {:?}, alternative {:?}: {message}",
            axis.name, axis.alternatives[k].name
        ),
    )
}

/// Refuses an override of alternative `k` of axis `i` that sets a free field.
fn check_free(axes: &Axes, i: usize, k: usize, free: &[FreeField]) -> Result<(), AxesError> {
    for (j, o) in axes.overrides(i, k).iter().enumerate() {
        if let Some(f) = free.iter().find(|f| f.path().overlaps(&o.path)) {
            return Err(alt_error(
                axes,
                i,
                k,
                &format!("set[{j}]"),
                format!(
                    "{} is also {} {f}: a calibrated field cannot be a choice too (drop \
                     it from the axis or from {})",
                    o.path,
                    Setting::Free,
                    Setting::Free
                ),
            ));
        }
    }
    Ok(())
}

/// The base spec with alternative `k` of axis `i` applied, checked against every rule.
fn apply_alternative(
    axes: &Axes,
    i: usize,
    k: usize,
    base: &ScenarioSpec,
    origin: &str,
) -> Result<ScenarioSpec, AxesError> {
    let overrides = axes.overrides(i, k);
    let spec = apply_overrides(base, &overrides)
        .map_err(|(j, m)| alt_error(axes, i, k, &format!("set[{j}]"), m))?;
    if let Err(e) = spec.validate(origin) {
        return Err(rule_error(axes, i, k, &overrides, &e));
    }
    Ok(spec)
}

/// A broken rule, placed at the one override whose field it is about, or else at the
/// alternative's name.
fn rule_error(
    axes: &Axes,
    i: usize,
    k: usize,
    overrides: &[Override],
    e: &ScenarioError,
) -> AxesError {
    let (field, message) = match e {
        ScenarioError::Invalid { field, message, .. } => (field.as_str(), message.as_str()),
        other => return alt_error(axes, i, k, "name", other.to_string()),
    };
    let culprits = touching(overrides, field);
    let at = match culprits.as_slice() {
        [one] => overrides
            .iter()
            .position(|o| o == *one)
            .map_or("name".to_string(), |j| format!("set[{j}]")),
        _ => "name".to_string(),
    };
    alt_error(axes, i, k, &at, format!("{field}: {message}"))
}

#[cfg(test)]
mod tests {
    use usar_sim::scenario::parse_spec;

    use super::*;

    const CORRIDOR: &str = include_str!("../../../../scenarios/corridor.ron");

    fn base() -> ScenarioSpec {
        parse_spec(CORRIDOR, "corridor.ron").unwrap()
    }

    fn axes(alternatives: &str) -> Axes {
        let src = format!(
            "Axes(axes: [\n  (name: \"round start\", alternatives: [(name: \"available\", set: \
             [\"mission.round_start=Available\"]), (name: \"all back\", set: \
             [\"mission.round_start=AllBack\"])]),\n  (name: \"b\", alternatives: [\n{alternatives}\n  ]),\n])"
        );
        Axes::parse(&src, "a.ron").unwrap()
    }

    /// Two targets, the second report-only.
    fn targets() -> Targets {
        Targets::parse(
            "Targets(targets: [(name: \"rounds\", statistic: Mean(\"rounds\"), value: 6.0, \
             band: PlusMinus(1.0)), (name: \"energy\", statistic: Mean(\"rescued_total\"), \
             value: 4000.0, band: PlusMinus(500.0), report_only: true)])",
            "t.ron",
        )
        .unwrap()
    }

    fn check(alternatives: &str, free: &[&str]) -> Result<(), String> {
        let free: Vec<FreeField> = free.iter().map(|f| FreeField::parse(f).unwrap()).collect();
        check_axes(
            &axes(alternatives),
            &base(),
            "corridor.ron",
            &free,
            &targets(),
        )
        .map_err(|e| e.to_string())
    }

    #[test]
    fn good_alternatives_pass() {
        let alts = "(name: \"slow\", set: [\"kinds[*].max_speed_m_per_s=1.0\"]), (name: \"base\")";
        check(alts, &["mission.pickup_s=0.5..2"]).unwrap();
    }

    #[test]
    fn an_unknown_field_or_a_bad_value_names_the_override() {
        let e = check("(name: \"x\", set: [\"mission.pickup_sec=1\"])", &[]).unwrap_err();
        assert!(
            e.starts_with(
                "a.ron:4:19: axes[1].alternatives[0].set[0]: axis \"b\", alternative \"x\": no \
                 field \"pickup_sec\" in mission"
            ),
            "{e}"
        );
        let e = check("(name: \"x\", set: [\"kinds[0].count=2.5\"])", &[]).unwrap_err();
        assert!(
            e.contains(
                "set[0]: axis \"b\", alternative \"x\": kinds[0].count: expected a whole number"
            ),
            "{e}"
        );
    }

    #[test]
    fn a_broken_rule_names_the_override_whose_field_it_is() {
        let e = check(
            "(name: \"x\", set: [\"mission.pickup_s=1\", \"kinds[0].quota.easy=1\"])",
            &[],
        )
        .unwrap_err();
        assert!(
            e.contains(
                "axes[1].alternatives[0].set[1]: axis \"b\", alternative \"x\": kinds[0].quota: "
            ),
            "{e}"
        );
    }

    #[test]
    fn a_free_field_cannot_be_a_choice_and_names_cannot_clash() {
        let e = check(
            "(name: \"x\", set: [\"mission.pickup_s=1\"])",
            &["mission.pickup_s=0.5..2"],
        )
        .unwrap_err();
        assert!(
            e.contains(
                "set[0]: axis \"b\", alternative \"x\": mission.pickup_s is also --free \
                 mission.pickup_s=0.5..2: a calibrated field cannot be a choice too"
            ),
            "{e}"
        );
        let src = "Axes(axes: [(name: \"mission.pickup_s\", alternatives: [(name: \"x\")])])";
        let a = Axes::parse(src, "a.ron").unwrap();
        let free = [FreeField::parse("mission.pickup_s=0.5..2").unwrap()];
        let e = check_axes(&a, &base(), "corridor.ron", &free, &targets())
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("axes[0].name: axis \"mission.pickup_s\" is named like --free"),
            "{e}"
        );
    }

    #[test]
    fn alternatives_that_give_the_same_scenario_are_refused() {
        // pickup_s is 1.0 by default in corridor.ron.
        let base_pickup = base().mission.pickup_s;
        let alts = format!(
            "(name: \"base\"), (name: \"same\", set: [\"mission.pickup_s={base_pickup}\"])"
        );
        let e = check(&alts, &[]).unwrap_err();
        assert!(
            e.contains(
                "axes[1].alternatives[1].name: axis \"b\", alternative \"same\": gives the same \
                 scenario and target flags as alternative \"base\" (alternatives[0])"
            ),
            "{e}"
        );
    }

    /// Two alternatives that differ only in their target flags are two readings; a name the
    /// targets file lacks, or an alternative with nothing left to fit, is refused at the name.
    #[test]
    fn target_flags_make_alternatives_and_name_targets_that_exist() {
        let alts = "(name: \"unknown unit\"), (name: \"% points\", require: [\"energy\"])";
        check(alts, &[]).unwrap();
        let a = axes(alts);
        let flags = |choice: usize| -> Vec<bool> {
            let t = a.universe_targets(&[0, choice], &targets()).unwrap();
            t.targets().iter().map(|t| t.report_only).collect()
        };
        assert_eq!(flags(0), [false, true]);
        assert_eq!(flags(1), [false, false]);
        let e = check("(name: \"x\", require: [\"energy per trial\"])", &[]).unwrap_err();
        assert!(
            e.contains(
                "axes[1].alternatives[0].require: axis \"b\", alternative \"x\": --require \
                 \"energy per trial\": no target has that name (targets: \"rounds\", \"energy\")"
            ),
            "{e}"
        );
        let e = check("(name: \"x\", report_only: [\"rounds\"])", &[]).unwrap_err();
        assert!(e.contains("every target is report-only"), "{e}");
        let e = check("(name: \"x\"), (name: \"y\", report_only: [])", &[]).unwrap_err();
        assert!(e.contains("gives the same scenario"), "{e}");
    }

    /// Two axes that each leave one of the two fitted targets out pass alternative by
    /// alternative, but their combination fits nothing: refused before anything runs. And a
    /// universe's flags do not depend on the order of the axes.
    #[test]
    fn a_combination_of_alternatives_that_fits_nothing_is_refused() {
        let two = Targets::parse(
            "Targets(targets: [(name: \"rounds\", statistic: Mean(\"rounds\"), value: 6.0, \
             band: PlusMinus(1.0)), (name: \"total\", statistic: Mean(\"rescued_total\"), \
             value: 100.0, band: PlusMinus(10.0))])",
            "t.ron",
        )
        .unwrap();
        let src = "Axes(axes: [(name: \"a\", alternatives: [(name: \"a0\"), (name: \"a1\", \
                   report_only: [\"rounds\"])]), (name: \"b\", alternatives: [(name: \"b0\"), \
                   (name: \"b1\", report_only: [\"total\"])])])";
        let a = Axes::parse(src, "a.ron").unwrap();
        let e = check_axes(&a, &base(), "corridor.ron", &[], &two)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains(
                "the universes taking \"a1\" of axis \"a\" and \"b1\" of axis \"b\" fit no target"
            ),
            "{e}"
        );
        let energy = targets();
        let src = "Axes(axes: [(name: \"a\", alternatives: [(name: \"a0\"), (name: \"a1\", \
                   report_only: [\"rounds\"])]), (name: \"b\", alternatives: [(name: \"b0\"), \
                   (name: \"b1\", require: [\"energy\"])])])";
        let a = Axes::parse(src, "a.ron").unwrap();
        // a1 alone leaves nothing to fit; with b1 (after it in axis order) it does.
        let t = a.universe_targets(&[1, 1], &energy).unwrap();
        let flags: Vec<bool> = t.targets().iter().map(|t| t.report_only).collect();
        assert_eq!(flags, [true, false]);
        assert!(a.universe_targets(&[1, 0], &energy).is_err());
    }
}
