//! Building one trial for a command (`usar run`, `usar render`, `usar replay`): the builder's
//! errors named by their flag, and the warning for a `--duration` that is not a whole number
//! of steps.

use anyhow::Result;
use usar_sim::mission::{MissionError, Simulation, TrialBuilder, trial_steps};
use usar_sim::scenario::number_text;

/// Builds the trial, with the flag a builder error is about as its context: `--method` for an
/// unknown or failing grouping method, `--duration` for a bad trial length.
///
/// # Errors
/// The builder's [`MissionError`], with that context.
pub fn build_trial(builder: TrialBuilder<'_>) -> Result<Simulation> {
    builder.build().map_err(|e| {
        let flag = match e {
            MissionError::Method(_) | MissionError::Grouping { .. } => "--method",
            MissionError::Duration(_) => "--duration",
            MissionError::World(_) => "the trial",
        };
        anyhow::Error::new(e).context(flag)
    })
}

/// Warns on stderr when the trial does not run the `requested` length exactly: a length that
/// is not a whole number of steps is rounded up to one (shorter than one step: one step).
pub fn warn_if_rounded(requested: Option<f64>, sim: &Simulation) {
    if let Some(d) = requested
        && let Some(w) = rounding_warning(d, sim.scenario().sim().dt_s.get())
    {
        experiments::console::warn(w);
    }
}

/// The warning for a `--duration` of `requested_s` seconds at step `dt_s` when the trial runs
/// another length (its steps times `dt_s`, see `usar_sim::mission::trial_steps`), naming the
/// length actually run; `None` when it runs `requested_s` (within 1e-9 relative) or when the
/// length is refused anyway (the caller reports that error).
pub fn rounding_warning(requested_s: f64, dt_s: f64) -> Option<String> {
    let steps = trial_steps(requested_s, dt_s).ok()?;
    let actual_s = experiments::sweep::simulated_length_s(requested_s, dt_s);
    if actual_s == requested_s {
        return None;
    }
    let why = if requested_s < dt_s {
        "is shorter than one step"
    } else {
        "is not a whole number of steps"
    };
    Some(format!(
        "warning: --duration {} s {why} of {} s (sim.dt_s): the trial runs {} s ({steps} \
         step{})",
        number_text(requested_s),
        number_text(dt_s),
        number_text(actual_s),
        if steps == 1 { "" } else { "s" }
    ))
}
