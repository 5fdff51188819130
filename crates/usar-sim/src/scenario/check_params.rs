//! The parameter rules that span fields: the initial levels' clamp ranges, the trial's length
//! against its step, and the control period as a whole number of steps.

use super::context::{Ctx, R};
use super::model::number_text;
use super::params::ClampedNormal;
use super::spec::ScenarioSpec;

/// The parameter rules that span fields: the clamp ranges of the initial levels, and a step no
/// longer than the trial.
pub(crate) fn check_params(ctx: &Ctx<'_>, spec: &ScenarioSpec) -> R<()> {
    let m = &spec.mission;
    for (path, d) in [
        ("mission.initial_energy", &m.initial_energy),
        ("mission.initial_hp", &m.initial_hp),
    ] {
        check_clamp(ctx, path, d)?;
    }
    let dt_s = spec.sim.dt_s.get();
    if let Err(e) = super::model::trial_steps(m.duration_s.get(), dt_s) {
        // Blame the length where the file writes it, else the step (the default length of
        // 600 s is too many steps only of a step the file sets).
        let written = |f: &str| ctx.map.is_some_and(|map| map.contains(f));
        let field = if !written("mission.duration_s") && written("sim.dt_s") {
            "sim.dt_s"
        } else {
            "mission.duration_s"
        };
        return Err(ctx.err(field, e));
    }
    if dt_s > m.duration_s.get() {
        return Err(ctx.err(
            "sim.dt_s",
            format!(
                "step {} s is longer than the trial (mission.duration_s = {} s)",
                number_text(dt_s),
                number_text(m.duration_s.get())
            ),
        ));
    }
    check_control_period(ctx, spec)
}

/// `sim.control_period_s`: a whole number of steps (relative tolerance 1e-9), from one step
/// to the whole trial.
fn check_control_period(ctx: &Ctx<'_>, spec: &ScenarioSpec) -> R<()> {
    let Some(period) = spec.sim.control_period_s else {
        return Ok(());
    };
    let (period_s, dt_s) = (period.get(), spec.sim.dt_s.get());
    let duration_s = spec.mission.duration_s.get();
    let steps = (period_s / dt_s).round();
    let problem = if period_s < dt_s * (1.0 - 1e-9) {
        Some(format!(
            "shorter than one step (sim.dt_s = {} s)",
            number_text(dt_s)
        ))
    } else if period_s > duration_s {
        Some(format!(
            "longer than the trial (mission.duration_s = {} s)",
            number_text(duration_s)
        ))
    } else if (steps * dt_s - period_s).abs() > 1e-9 * period_s {
        Some(format!(
            "not a whole number of steps of {} s (sim.dt_s): {} steps",
            number_text(dt_s),
            number_text(period_s / dt_s)
        ))
    } else {
        None
    };
    match problem {
        Some(why) => Err(ctx.err(
            "sim.control_period_s",
            format!("control period {} s is {why}", number_text(period_s)),
        )),
        None => Ok(()),
    }
}

/// A clamped normal draw at `path` whose `max_pct` is at least its `min_pct`.
fn check_clamp(ctx: &Ctx<'_>, path: &str, d: &ClampedNormal) -> R<()> {
    if d.max_pct < d.min_pct {
        return Err(ctx.err(
            format!("{path}.max_pct"),
            format!(
                "expected a number in [{}, 100] (at least min_pct), found {}",
                number_text(d.min_pct.get()),
                number_text(d.max_pct.get())
            ),
        ));
    }
    Ok(())
}
