//! [`TrialPlan`]: which trials a study runs at each point it evaluates (the grouping methods,
//! how each trial's method is built, how many trials per method, from which base seed, how
//! long), shared by a calibration's evaluations and a multiverse's comparisons.

use usar_sweep::method_factory::MethodFactory;

/// The trials a study runs at each point: every method in [`TrialPlan::methods`] runs
/// [`TrialPlan::trials`] trials, trial `k` of every method from `trial_seed(base_seed, k)`
/// (common random numbers), each [`TrialPlan::duration_s`] long.
///
/// A calibration runs its plan at every evaluation ([`super::CalibrationSetup::trial_plan`]);
/// a multiverse compares the methods of each universe with its plan and calibrates each
/// universe with the same methods and length but its own trials and seed
/// (`crate::multiverse::MultiverseSetup::comparison`). The checks are the study's own
/// ([`super::CalibrationSetup::check`]), since each names its own fields.
#[derive(Debug, Clone)]
pub struct TrialPlan {
    /// Method names as [`TrialPlan::method_factory`] takes them (built-ins `rne`, `dis`,
    /// `eng`, `hp_dis`, any case); at least one, each once.
    pub methods: Vec<String>,
    /// Builds each trial's grouping method from its name (default: the built-ins).
    pub method_factory: MethodFactory,
    /// Trials per method at each point (>= 1).
    pub trials: u32,
    /// Base seed: trial `k` of every method starts from `trial_seed(base_seed, k)`.
    pub base_seed: u64,
    /// Simulated length of each trial, seconds (> 0, finite); `None`: the scenario's own
    /// `mission.duration_s` (at each point, should that field be varied).
    pub duration_s: Option<f64>,
}

impl TrialPlan {
    /// The four built-in methods (`rne_core::grouping::METHOD_NAMES`), `trials` trials per
    /// method from `base_seed`, each trial as long as its scenario's `mission.duration_s`.
    pub fn builtin(trials: u32, base_seed: u64) -> Self {
        Self {
            methods: rne_core::grouping::METHOD_NAMES
                .iter()
                .map(|m| m.to_string())
                .collect(),
            method_factory: MethodFactory::builtin(),
            trials,
            base_seed,
            duration_s: None,
        }
    }

    /// The same methods and length, `trials` trials per method from `base_seed`.
    pub fn with_trials(&self, trials: u32, base_seed: u64) -> Self {
        Self {
            trials,
            base_seed,
            ..self.clone()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_runs_the_four_methods_at_the_scenarios_length_and_with_trials_keeps_them() {
        let plan = TrialPlan::builtin(3, 11);
        assert_eq!(plan.methods, ["rne", "dis", "eng", "hp_dis"]);
        assert_eq!(
            (plan.trials, plan.base_seed, plan.duration_s),
            (3, 11, None)
        );
        let longer = TrialPlan {
            duration_s: Some(60.0),
            ..plan
        };
        let other = longer.with_trials(5, 2);
        assert_eq!(other.methods, longer.methods);
        assert_eq!((other.trials, other.base_seed), (5, 2));
        assert_eq!(other.duration_s, Some(60.0));
    }
}
