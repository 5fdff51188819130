//! The metrics of a trial: every numeric column of `trials.csv` ([`METRICS`]), with a label
//! for tables and figures and how to read it from a [`TrialRow`].

use usar_sim::mission::{TrialResult, TrialRow};

/// A metric of [`TrialRow`]: its CSV column name, a short label and how to read it
/// (`None` when undefined for the trial, e.g. a cost per rescuee when nobody was rescued).
#[derive(Clone, Copy)]
pub struct Metric {
    /// Column name in `trials.csv` (and `metric` value in `summary.csv`).
    pub name: &'static str,
    /// Label for tables and figures.
    pub label: &'static str,
    /// Reads the metric from a row.
    pub get: fn(&TrialRow) -> Option<f64>,
}

impl std::fmt::Debug for Metric {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name)
    }
}

macro_rules! metric {
    ($field:ident, $label:expr, some) => {
        Metric {
            name: stringify!($field),
            label: $label,
            get: |r| Some(f64::from(r.$field)),
        }
    };
    ($field:ident, $label:expr, float) => {
        Metric {
            name: stringify!($field),
            label: $label,
            get: |r| Some(r.$field),
        }
    };
    ($field:ident, $label:expr, opt) => {
        Metric {
            name: stringify!($field),
            label: $label,
            get: |r| r.$field,
        }
    };
}

/// Every numeric metric of a trial row, in `trials.csv` column order.
pub const METRICS: [Metric; 17] = [
    metric!(rescued_total, "rescuees, total", some),
    metric!(rescued_hard, "rescuees, hard", some),
    metric!(rescued_easy, "rescuees, easy", some),
    metric!(energy_hard_pct, "energy cost hard (%)", float),
    metric!(energy_easy_pct, "energy cost easy (%)", float),
    metric!(energy_total_pct, "energy cost total (%)", float),
    metric!(hp_hard_pct, "HP cost hard (%)", float),
    metric!(hp_easy_pct, "HP cost easy (%)", float),
    metric!(hp_total_pct, "HP cost total (%)", float),
    metric!(rounds, "rounds", some),
    metric!(
        energy_per_hard_rescuee_pct,
        "energy / hard rescuee (%)",
        opt
    ),
    metric!(
        energy_per_easy_rescuee_pct,
        "energy / easy rescuee (%)",
        opt
    ),
    metric!(energy_per_rescuee_pct, "energy / rescuee (%)", opt),
    metric!(hp_per_hard_rescuee_pct, "HP / hard rescuee (%)", opt),
    metric!(hp_per_easy_rescuee_pct, "HP / easy rescuee (%)", opt),
    metric!(hp_per_rescuee_pct, "HP / rescuee (%)", opt),
    metric!(mean_round_s, "mean round time (s)", opt),
];

/// The metric called `name`, if there is one.
pub fn find_metric(name: &str) -> Option<Metric> {
    METRICS.iter().find(|m| m.name == name).copied()
}

/// The metric called `name`.
///
/// # Panics
/// If no metric has that name (a programming error).
pub fn metric(name: &str) -> Metric {
    *METRICS
        .iter()
        .find(|m| m.name == name)
        .unwrap_or_else(|| panic!("unknown metric {name}"))
}

/// The defined values of `metric` over `rows` of one method, in row order.
pub fn values(rows: &[TrialRow], metric: Metric) -> Vec<f64> {
    rows.iter().filter_map(|r| (metric.get)(r)).collect()
}

/// The rows of `method` among `results`.
pub fn rows_of(results: &[TrialResult], method: &str) -> Vec<TrialRow> {
    results
        .iter()
        .filter(|r| r.method == method)
        .map(TrialResult::row)
        .collect()
}
