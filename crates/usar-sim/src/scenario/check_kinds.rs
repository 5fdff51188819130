//! Validating the robot kinds: unique non-blank names, at least one robot each, quotas that
//! name known tasks and add up to the count, and each kind's numbers within the limits.

use super::check_names::check_name;
use super::context::{Ctx, R};
use super::limits::check_kind;
use super::model::RobotKind;
use super::spec::{KindSpec, TaskSpec};
use super::suggest::did_you_mean;

/// Kinds: names unique and non-empty, at least one robot each, quotas naming known tasks and
/// adding up to the count (a task a kind's quota does not name gets none of it).
pub(crate) fn validate_kinds(
    ctx: &Ctx<'_>,
    specs: &[KindSpec],
    tasks: &[TaskSpec],
) -> R<Vec<RobotKind>> {
    if specs.is_empty() {
        return Err(ctx.err("kinds", "expected at least one robot kind"));
    }
    let mut kinds: Vec<RobotKind> = Vec::with_capacity(specs.len());
    for (k, s) in specs.iter().enumerate() {
        let f = |name: &str| format!("kinds[{k}].{name}");
        check_name(ctx, f("name"), "kind name", &s.name)?;
        if let Some(j) = kinds.iter().position(|o| o.name == s.name) {
            return Err(ctx.err(
                f("name"),
                format!("duplicate kind name {:?} (also kinds[{j}])", s.name),
            ));
        }
        if s.count == 0 {
            return Err(ctx.err(f("count"), "expected at least 1 robot, found 0"));
        }
        let quota = quotas_by_task(ctx, &f("quota"), s, tasks)?;
        let kind = RobotKind {
            name: s.name.clone(),
            role: s.role,
            locomotion: s.locomotion,
            count: s.count,
            quota,
            body_radius_m: s.body_radius_m.get(),
            max_speed_m_per_s: s.max_speed_m_per_s.get(),
            sensing_range_m: s.sensing_range_m.get(),
            observing_range_m: s.observing_range_m.get(),
            carrying_capacity: s.carrying_capacity,
            rescuing_resources: s.rescuing_resources,
            hp_needs_full: s.hp_needs_full.get(),
            energy_needs_full: s.energy_needs_full.get(),
        };
        check_kind(ctx, k, &kind)?;
        kinds.push(kind);
    }
    Ok(kinds)
}

/// A kind's quota per task id, from its quota by task name.
fn quotas_by_task(ctx: &Ctx<'_>, path: &str, s: &KindSpec, tasks: &[TaskSpec]) -> R<Vec<usize>> {
    let names = || {
        tasks
            .iter()
            .map(|t| format!("{:?}", t.name))
            .collect::<Vec<_>>()
            .join(", ")
    };
    if let Some(unknown) = s
        .quota
        .0
        .keys()
        .find(|n| !tasks.iter().any(|t| &t.name == *n))
    {
        return Err(ctx.err(
            path,
            format!(
                "no task is called {unknown:?} (tasks: {}){}",
                names(),
                did_you_mean(unknown, tasks.iter().map(|t| t.name.as_str()))
            ),
        ));
    }
    let quota: Vec<usize> = tasks
        .iter()
        .map(|t| s.quota.0.get(&t.name).copied().unwrap_or(0))
        .collect();
    let total = quota.iter().try_fold(0usize, |a, q| a.checked_add(*q));
    if total != Some(s.count) {
        let terms: Vec<String> = tasks
            .iter()
            .zip(&quota)
            .map(|(t, q)| format!("{} {q}", t.name))
            .collect();
        return Err(ctx.err(
            path,
            format!(
                "{} = {} but count is {}",
                terms.join(" + "),
                total.map_or_else(|| "overflow".to_owned(), |t| t.to_string()),
                s.count
            ),
        ));
    }
    Ok(quota)
}
