//! Validating the tasks: their names, their search areas, goals and drop-offs inside the
//! arena, and their rescuees laid out (at most [`MAX_RESCUEES`] over all tasks).
//!
//! Two steps, as the validation order needs: [`task_geometry`] runs before the kinds (whose
//! quotas name tasks), [`expand_tasks`] after all debris is known (rescuees keep clear of it).

use super::check_debris::NamedDebris;
use super::check_names::{RESERVED_TASK_NAME, check_name, per_rescuee_clash};
use super::context::{Ctx, R};
use super::error::ScenarioError;
use super::generate::expand_rescuees;
use super::limits::MAX_RESCUEES;
use super::model::{Circle, PointM, Rect, Task};
use super::params::Arena;
use super::spec::TaskSpec;

/// A task's checked geometry, before its rescuees are laid out.
pub(crate) struct TaskGeometry {
    /// The area searched for the task's rescuees, inside the arena.
    pub(crate) search_area: Rect,
    /// The goal point, inside the arena.
    pub(crate) goal: PointM,
    /// The drop-off circle, wholly inside the arena.
    pub(crate) drop_off: Circle,
}

/// Task names (non-empty, unique, at least one task) and each task's search area, goal and
/// drop-off inside the arena.
pub(crate) fn task_geometry(
    ctx: &Ctx<'_>,
    tasks: &[TaskSpec],
    arena: &Arena,
) -> R<Vec<TaskGeometry>> {
    if tasks.is_empty() {
        return Err(ctx.err("tasks", "expected at least one task"));
    }
    let mut out = Vec::with_capacity(tasks.len());
    for (i, t) in tasks.iter().enumerate() {
        let base = format!("tasks[{i}]");
        check_name(ctx, format!("{base}.name"), "task name", &t.name)?;
        if t.name == RESERVED_TASK_NAME {
            return Err(ctx.err(
                format!("{base}.name"),
                format!(
                    "the task name {RESERVED_TASK_NAME:?} is reserved: the tables' columns of \
                     all tasks together use it (rescued_total, energy_total_pct)"
                ),
            ));
        }
        if let Some(j) = tasks[..i].iter().position(|o| o.name == t.name) {
            return Err(ctx.err(
                format!("{base}.name"),
                format!("duplicate task name {:?} (also tasks[{j}])", t.name),
            ));
        }
        if let Some(whose) = per_rescuee_clash(&t.name, tasks) {
            return Err(ctx.err(
                format!("{base}.name"),
                format!(
                    "the task name {:?} would give the column energy_{}_pct, the energy per \
                     rescuee of {whose}",
                    t.name, t.name
                ),
            ));
        }
        let named = |e: ScenarioError| match e {
            ScenarioError::Invalid {
                location,
                field,
                message,
            } => ScenarioError::Invalid {
                location,
                field,
                message: format!("task {:?}: {message}", t.name),
            },
            other => other,
        };
        out.push(TaskGeometry {
            search_area: ctx
                .rect_in_arena(&format!("{base}.search_area"), &t.search_area, arena)
                .map_err(named)?,
            goal: ctx
                .point_in_arena(&format!("{base}.goal_m"), &t.goal_m, arena)
                .map_err(named)?,
            drop_off: ctx
                .circle_in_arena(&format!("{base}.drop_off"), &t.drop_off, arena)
                .map_err(named)?,
        });
    }
    Ok(out)
}

/// The tasks with their rescuees laid out.
pub(crate) fn expand_tasks(
    ctx: &Ctx<'_>,
    specs: &[TaskSpec],
    geometry: Vec<TaskGeometry>,
    debris: &NamedDebris,
    reach: f64,
) -> R<Vec<Task>> {
    let mut total = 0usize;
    specs
        .iter()
        .zip(geometry)
        .enumerate()
        .map(|(i, (t, g))| {
            let path = format!("tasks[{i}].rescuees");
            let rescuees = expand_rescuees(ctx, &path, &t.rescuees, &g.search_area, debris, reach)?;
            total += rescuees.len();
            if total > MAX_RESCUEES {
                return Err(ctx.err(
                    path,
                    format!(
                        "{} rescuees bring the tasks to {total}, more than the limit of \
                         {MAX_RESCUEES}",
                        rescuees.len()
                    ),
                ));
            }
            Ok(Task {
                name: t.name.clone(),
                difficulty: t.difficulty,
                search_area: g.search_area,
                goal: g.goal,
                drop_off: g.drop_off,
                rescuees,
            })
        })
        .collect()
}
