//! What a sweep's executor runs: each cell's plan (scenario, trust model, trial length) and
//! each job (its method and seed), the same for a sweep on disk ([`crate::sweep::run_sweep`])
//! and in memory ([`crate::sweep::run_in_memory`]).

use usar_sim::mission::trial_seed;
use usar_sim::scenario::trial_steps;

use crate::data::config::SweepConfig;
use crate::data::config_error::ConfigError;
use crate::data::jobs::JobId;
use crate::error::SweepError;
use crate::executor::{CellPlan, Job};
use crate::journal::SweepHeader;
use crate::method_factory::trust_model;

/// The plan of each cell of `cfg`, in cell order; `header` is [`crate::sweep::header_of`]
/// `cfg`.
///
/// # Errors
/// A trial length (`--duration`) that is not a whole positive number of steps, or a cell whose
/// trust model cannot be built.
pub(crate) fn cell_plans<'a>(
    cfg: &'a SweepConfig,
    header: &SweepHeader,
) -> Result<Vec<CellPlan<'a>>, SweepError> {
    cfg.cell_scenarios()
        .into_iter()
        .zip(&header.grid.cells)
        .enumerate()
        .map(|(i, (scenario, h))| {
            let steps = trial_steps(h.duration_s, scenario.sim().dt_s.get())
                .map_err(|reason| ConfigError::TrialLength { reason })?;
            Ok(CellPlan {
                label: match &cfg.grid {
                    Some(g) => format!(" in cell {}", g.cells[i].dir),
                    None => String::new(),
                },
                scenario,
                model: trust_model(scenario)?,
                duration_s: h.duration_s,
                step_us: (scenario.sim().dt_s.get() * 1e6).round().max(1.0) as u64,
                steps_per_trial: steps,
            })
        })
        .collect()
}

/// The job `id` of `cfg`: its method (as given, and canonical from `header`), its trial and
/// the trial's seed `trial_seed(base_seed, trial)`, common to every method and cell.
pub(crate) fn job_of(cfg: &SweepConfig, header: &SweepHeader, id: JobId) -> Job {
    Job {
        cell: id.cell,
        method_arg: cfg.methods[id.method].clone(),
        method: header.methods[id.method].clone(),
        trial: id.trial,
        seed: trial_seed(cfg.base_seed, id.trial),
    }
}
