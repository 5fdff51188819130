//! The sweep configuration a shard's plan rebuilds (`usar merge`): the plan's scenario, grid
//! and options as a [`SweepConfig`] ([`plan_config`]).

use std::path::Path;

use usar_sim::scenario::{self, path_text};

use crate::data::config::SweepConfig;
use crate::data::sweep_plan::SweepPlan;
use crate::error::SweepError;
use crate::grid::build::build_grid;
use crate::method_factory::MethodFactory;
use crate::sweep::check_grid_size;

/// The sweep's configuration of `plan`: the scenario from [`SweepPlan::scenario_text`], the grid
/// of [`SweepPlan::vary`], the built-in methods, output folder `out_dir`, one thread, no
/// progress bar, no resume or overwrite, no hooks, no shard.
///
/// # Errors
/// A scenario or `--vary` that does not load (the messages of `usar sweep`), or a sweep
/// above [`crate::sweep::MAX_SWEEP_TRIALS`] trials (refused before the grid is built).
pub fn plan_config(plan: &SweepPlan, out_dir: &Path) -> Result<SweepConfig, SweepError> {
    let origin = path_text(&plan.scenario_path);
    let scenario = scenario::from_str(&plan.scenario_text, &origin)?;
    let grid = if plan.vary.is_empty() {
        None
    } else {
        check_grid_size(&plan.vary, plan.methods.len(), plan.trials)?;
        let spec = scenario::parse_spec(&plan.scenario_text, &origin)?;
        Some(build_grid(&spec, &plan.vary)?)
    };
    Ok(SweepConfig {
        grid,
        methods: plan.methods.clone(),
        method_factory: MethodFactory::builtin(),
        trials: plan.trials,
        base_seed: plan.seed.unwrap_or(scenario.sim().seed),
        duration_s: plan.duration_s,
        threads: 1,
        out_dir: out_dir.to_path_buf(),
        progress: false,
        ..SweepConfig::new(scenario, &plan.scenario_path)
    })
}
