//! The sweep configuration a shard's plan rebuilds (`usar merge`): the plan's scenario, grid
//! and options as a [`SweepConfig`] ([`SweepPlan::config`]).

use std::path::Path;

use anyhow::Result;
use usar_sim::scenario::{self, path_text};

use crate::data::config::SweepConfig;
use crate::data::grid_cells::Grid;
use crate::data::sweep_plan::SweepPlan;
use crate::method_factory::MethodFactory;
use crate::sweep::check_grid_size;

impl SweepPlan {
    /// The sweep's configuration: the scenario from [`SweepPlan::scenario_text`], the grid
    /// of [`SweepPlan::vary`], the built-in methods, output folder `out_dir`, one thread, no
    /// progress bar, no resume or overwrite, no hooks, no shard.
    ///
    /// # Errors
    /// A scenario or `--vary` that does not load (the messages of `usar sweep`), or a sweep
    /// above [`crate::sweep::MAX_SWEEP_TRIALS`] trials (refused before the grid is built).
    pub fn config(&self, out_dir: &Path) -> Result<SweepConfig> {
        let origin = path_text(&self.scenario_path);
        let scenario = scenario::from_str(&self.scenario_text, &origin)?;
        let grid = if self.vary.is_empty() {
            None
        } else {
            check_grid_size(&self.vary, self.methods.len(), self.trials)?;
            let spec = scenario::parse_spec(&self.scenario_text, &origin)?;
            Some(Grid::build(&spec, &self.vary)?)
        };
        Ok(SweepConfig {
            grid,
            methods: self.methods.clone(),
            method_factory: MethodFactory::builtin(),
            trials: self.trials,
            base_seed: self.seed.unwrap_or(scenario.sim().seed),
            duration_s: self.duration_s,
            threads: 1,
            out_dir: out_dir.to_path_buf(),
            progress: false,
            ..SweepConfig::new(scenario, &self.scenario_path)
        })
    }
}
