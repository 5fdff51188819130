//! The sweep's header: its parameters and grid as the journal records them.

use crate::data::config::SweepConfig;
use crate::data::grid_cells::Grid;
use crate::data::software::software_build;
use crate::error::SweepError;
use crate::fingerprint::scenario_hash;
use crate::journal::{CellHeader, GridHeader, JOURNAL_FORMAT, SweepHeader};
use crate::method_factory::{canonical_method, trust_model};
use crate::sweep::checks::check_trial_count;

/// The sweep's header: its parameters and grid as recorded in the journal.
///
/// # Errors
/// An unknown method, a scenario that cannot be serialised, or more than
/// [`MAX_SWEEP_TRIALS`](crate::sweep::MAX_SWEEP_TRIALS) trials in all.
pub fn header_of(cfg: &SweepConfig) -> Result<SweepHeader, SweepError> {
    check_trial_count(cfg)?;
    let model = trust_model(&cfg.scenario)?;
    let values: Vec<Vec<String>> = match &cfg.grid {
        Some(g) => g.cells.iter().map(|c| c.values()).collect(),
        None => vec![Vec::new()],
    };
    let cells = cfg
        .cell_scenarios()
        .into_iter()
        .zip(values)
        .map(|(s, values)| {
            Ok(CellHeader {
                values,
                scenario_hash: scenario_hash(s).map_err(SweepError::Serialise)?,
                duration_s: cfg.duration_of(s),
                tasks: s.task_names(),
                hardest_first: s.hardest_first(),
            })
        })
        .collect::<Result<_, SweepError>>()?;
    Ok(SweepHeader {
        format: JOURNAL_FORMAT,
        version: env!("CARGO_PKG_VERSION").to_string(),
        build: software_build().to_owned(),
        scenario: cfg.scenario.name().to_owned(),
        methods: cfg
            .methods
            .iter()
            .map(|m| canonical_method(m, &cfg.method_factory, &model, cfg.base_seed))
            .collect::<Result<_, _>>()?,
        trials: cfg.trials,
        base_seed: cfg.base_seed,
        grid: GridHeader {
            fields: cfg.grid.as_ref().map(Grid::fields).unwrap_or_default(),
            cells,
        },
    })
}
