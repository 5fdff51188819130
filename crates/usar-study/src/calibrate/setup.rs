//! What a calibration needs ([`CalibrationSetup`], with the defaults of `usar calibrate`) and
//! the checks made before anything runs ([`CalibrationSetup::check`]).

use std::time::Duration;

use usar_sim::scenario::{Scenario, ScenarioError, ScenarioSpec};

use super::free::{FreeError, FreeField, check_distinct};
use super::optimizer::Optimizer;
use super::trial_plan::TrialPlan;
use usar_report::targets::file::{Targets, TargetsError};
use usar_sweep::data::hooks::CalibrationHooks;
use usar_sweep::data::limits::{MAX_SWEEP_TRIALS, max_threads};
use usar_sweep::data::setting_error::SettingError;
use usar_sweep::method_factory::{canonical_method, trust_model};

/// Trials per method and evaluation by default (10, as a sweep).
pub const DEFAULT_TRIALS: u32 = 10;
/// Significant digits of the free values by default (4).
pub const DEFAULT_DIGITS: u32 = 4;
/// Evaluations at most by default (60).
pub const DEFAULT_MAX_EVALS: usize = 60;
/// Trials per method of the check on unseen trials by default (30).
pub const DEFAULT_CHECK_TRIALS: u32 = 30;
/// Base seed of the check on unseen trials by default (7, the seed `docs/calibration.md`
/// checks `paper.ron` with), or 8 when the calibration itself uses 7
/// ([`default_check_seed`]).
pub const DEFAULT_CHECK_SEED: u64 = 7;

/// The check's default base seed for a calibration with `base_seed`: [`DEFAULT_CHECK_SEED`],
/// or the next one when the calibration uses it (the check must see other trials).
pub fn default_check_seed(base_seed: u64) -> u64 {
    if base_seed == DEFAULT_CHECK_SEED {
        DEFAULT_CHECK_SEED + 1
    } else {
        DEFAULT_CHECK_SEED
    }
}

/// Everything a calibration needs. [`CalibrationSetup::new`] gives the defaults of `usar
/// calibrate`; set the fields that differ. See [`super::calibrate`] for an example.
#[derive(Debug, Clone)]
pub struct CalibrationSetup {
    /// The scenario whose free fields are fitted (unvalidated spec, as parsed).
    pub base: ScenarioSpec,
    /// Where it came from (a file path, for messages and the outputs).
    pub origin: String,
    /// What the statistics must satisfy.
    pub targets: Targets,
    /// The fields fitted and their ranges (at least one, each once).
    pub free: Vec<FreeField>,
    /// The trials of each evaluation, the same at every point (common random numbers):
    /// default the four built-in methods, [`DEFAULT_TRIALS`] trials per method from the
    /// scenario's `sim.seed`, each as long as the scenario's `mission.duration_s`.
    pub trial_plan: TrialPlan,
    /// Significant digits the free values are rounded to before they are evaluated (1 to 17;
    /// default [`DEFAULT_DIGITS`]).
    pub digits: u32,
    /// Most evaluations in the search's sequence, reused ones included (>= 1; default
    /// [`DEFAULT_MAX_EVALS`]). Not part of the calibration's identity: a resume may raise it.
    pub max_evals: usize,
    /// Wall-clock budget of this run: no new evaluation starts once it is spent (`None`, or
    /// a budget so long that its end cannot be represented, such as `Duration::MAX`: no
    /// limit). Not part of the calibration's identity.
    pub max_time: Option<Duration>,
    /// Worker threads for the trials (>= 1; capped at [`max_threads`] and the trials of an
    /// evaluation).
    pub threads: usize,
    /// Base seed of the check of the best values on unseen trials (default
    /// [`default_check_seed`] of the scenario's seed).
    pub check_seed: u64,
    /// Trials per method of that check (0 skips it; default [`DEFAULT_CHECK_TRIALS`]).
    pub check_trials: u32,
    /// Discard a trace of another calibration (and its outputs) in the output folder instead
    /// of refusing to start.
    pub overwrite: bool,
    /// The search (default [`Optimizer::NelderMead`]; `--optimizer`). Part of the
    /// calibration's identity.
    pub optimizer: Optimizer,
    /// Start the search at the middle of each free range ([`super::FreeField::midpoint`])
    /// instead of the scenario's own values (default `false`): a fit that does not depend on
    /// the values the file holds (`--start-mid`). Part of the calibration's identity.
    pub start_mid: bool,
    /// Start the search at these values of the free fields (in `--free` order, each inside
    /// its range; default `None`: the scenario's own values, or the middles with
    /// [`CalibrationSetup::start_mid`]). A multiverse with a shared design starts each
    /// universe where the design's emulator predicts the least loss
    /// (`crate::multiverse::emulator`). Part of the calibration's identity.
    pub start: Option<Vec<f64>>,
    /// How the calibration was asked for, quoted in `calibrated.ron` and `calibration.md`
    /// (`usar calibrate` puts its command line; default a description of the call).
    pub command: String,
    /// The time stamp of the outputs (default `None`: the system clock, UTC, to the second).
    pub date: Option<String>,
    /// Extension points: a step observer per trial, a stop flag (default none). Not part of
    /// the calibration's identity.
    pub hooks: CalibrationHooks,
}

impl CalibrationSetup {
    /// The defaults of `usar calibrate` for fitting `free` in `base` (read from `origin`) to
    /// `targets`: the four built-in methods, [`DEFAULT_TRIALS`] trials, the scenario's
    /// `sim.seed`, each trial as long as its `mission.duration_s`, [`DEFAULT_DIGITS`] digits,
    /// [`DEFAULT_MAX_EVALS`] evaluations, no time limit, all cores, a check on
    /// [`DEFAULT_CHECK_TRIALS`] unseen trials per method, no overwrite, the system clock.
    pub fn new(
        base: ScenarioSpec,
        origin: impl Into<String>,
        targets: Targets,
        free: Vec<FreeField>,
    ) -> Self {
        let origin = origin.into();
        let seed = base.sim.seed;
        Self {
            command: format!("usar_study::calibrate::calibrate of {origin}"),
            origin,
            targets,
            free,
            trial_plan: TrialPlan::builtin(DEFAULT_TRIALS, seed),
            digits: DEFAULT_DIGITS,
            max_evals: DEFAULT_MAX_EVALS,
            max_time: None,
            threads: std::thread::available_parallelism().map_or(1, usize::from),
            check_seed: default_check_seed(seed),
            check_trials: DEFAULT_CHECK_TRIALS,
            overwrite: false,
            start_mid: false,
            start: None,
            optimizer: Optimizer::NelderMead,
            date: None,
            hooks: CalibrationHooks::default(),
            base,
        }
    }

    /// Checks the setup before anything runs: the options, the base scenario (validated),
    /// the targets against its tasks, the free fields against its spec, the methods.
    ///
    /// # Errors
    /// One line: an option out of range (naming its `usar calibrate` flag; `trials` below 2
    /// when a target is a spread or a correlation, [`too_few_trials`]), a base scenario
    /// that breaks a rule, a target metric naming a task the scenario lacks (naming the
    /// target), a free field that names nothing, is not a real number, or is given twice, an
    /// unknown or repeated method.
    pub fn check(&self) -> Result<Checked, SetupError> {
        let bad = |m: String| Err(SetupError::Invalid(m));
        let refuse = |field, problem: String| Err(SettingError::new(field, problem).into());
        let plan = &self.trial_plan;
        if plan.trials == 0 {
            return refuse("trials", " must be at least 1".into());
        }
        if let Some(problem) = too_few_trials(&self.targets, plan.trials) {
            return refuse("trials", problem);
        }
        if !(1..=17).contains(&self.digits) {
            return refuse("digits", format!(" must be 1 to 17, found {}", self.digits));
        }
        if self.max_evals == 0 {
            return refuse("max_evals", " must be at least 1".into());
        }
        if self.threads == 0 {
            return refuse("threads", " must be at least 1".into());
        }
        if let Some(d) = plan.duration_s
            && !(d.is_finite() && d > 0.0)
        {
            return refuse(
                "duration_s",
                format!(" must be a finite number > 0, found {d}"),
            );
        }
        if self.free.is_empty() {
            return refuse("free", ": give at least one FIELD=LO..HI".into());
        }
        let total = plan.methods.len().saturating_mul(plan.trials as usize);
        if total > MAX_SWEEP_TRIALS {
            return bad(format!(
                "{} method(s) x {} trials make {total} trials per evaluation, more than the \
                 limit of {MAX_SWEEP_TRIALS}",
                plan.methods.len(),
                plan.trials
            ));
        }
        if let Some(start) = &self.start {
            self.check_start(start)?;
        }
        let scenario = self.base.validate(&self.origin)?;
        self.targets.check_tasks(&scenario.task_names())?;
        check_distinct(&self.free)?;
        let base_values = self
            .free
            .iter()
            .map(|f| f.base_value(&self.base))
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Checked {
            methods: self.canonical_methods(&scenario)?,
            threads: self.threads.min(max_threads()),
            scenario,
            base_values,
        })
    }

    /// Checks a given start point: one value per free field, each inside its range, and not
    /// together with [`CalibrationSetup::start_mid`].
    fn check_start(&self, start: &[f64]) -> Result<(), SetupError> {
        let bad = |m: String| Err(SetupError::Invalid(m));
        if self.start_mid {
            return Err(SettingError::new(
                "start_mid",
                " and a given start point exclude each other",
            )
            .into());
        }
        if start.len() != self.free.len() {
            return bad(format!(
                "the start point has {} values for {} free fields",
                start.len(),
                self.free.len()
            ));
        }
        for (f, &x) in self.free.iter().zip(start) {
            if !(f.lo..=f.hi).contains(&x) {
                return bad(format!(
                    "the start point's {x} for {} lies outside its range",
                    f.label()
                ));
            }
        }
        Ok(())
    }

    /// The methods' display names (as written; see [`canonical_method`]).
    fn canonical_methods(&self, scenario: &Scenario) -> Result<Vec<String>, SetupError> {
        let plan = &self.trial_plan;
        if plan.methods.is_empty() {
            return Err(SettingError::new("methods", " needs at least one method").into());
        }
        let model = trust_model(scenario).map_err(|e| SetupError::Invalid(format!("{e:#}")))?;
        let mut names: Vec<String> = Vec::new();
        for m in &plan.methods {
            let name = canonical_method(m, &plan.method_factory, &model, plan.base_seed)
                .map_err(|e| SettingError::new("methods", format!(": {e:#}")))?;
            if names.contains(&name) {
                return Err(
                    SettingError::new("methods", format!(": {name} is given twice")).into(),
                );
            }
            names.push(name);
        }
        Ok(names)
    }
}

/// Why `trials` per method are too few for `targets` (the rest of the line after the
/// setting's name: ` must be at least 2: target "sd" (PooledSd(rescued_total)): it needs at
/// least 2 trials per method defining rescued_total`), or `None`: a spread or a correlation
/// within a method's trials is NaN from one trial, whether the target is fitted or reported.
pub fn too_few_trials(targets: &Targets, trials: u32) -> Option<String> {
    let t = targets
        .targets()
        .iter()
        .find(|t| t.statistic.min_trials_per_method() > trials)?;
    Some(format!(
        " must be at least {}: target {:?} ({}): {}",
        t.statistic.min_trials_per_method(),
        t.name,
        t.statistic,
        t.statistic.needs()
    ))
}

/// A setup checked by [`CalibrationSetup::check`].
#[derive(Debug, Clone)]
pub struct Checked {
    /// The base scenario, validated.
    pub scenario: Scenario,
    /// The methods' display names (as written; see [`canonical_method`]), in order.
    pub methods: Vec<String>,
    /// The value of each free field in the base scenario, when it has one (see
    /// [`FreeField::base_value`]).
    pub base_values: Vec<Option<f64>>,
    /// Worker threads, capped at [`max_threads`].
    pub threads: usize,
}

/// Why a calibration cannot start: one line.
#[derive(Debug, thiserror::Error)]
pub enum SetupError {
    /// The base scenario breaks a rule.
    #[error(transparent)]
    Scenario(#[from] ScenarioError),
    /// A target does not fit the scenario.
    #[error(transparent)]
    Targets(#[from] TargetsError),
    /// A free field does not fit the scenario, or is given twice.
    #[error(transparent)]
    Free(#[from] FreeError),
    /// An option out of range, or a method that is unknown or repeated, named by its field.
    #[error(transparent)]
    Setting(#[from] SettingError),
    /// A start point that does not fit the free fields, or a trust model that cannot be built.
    #[error("{0}")]
    Invalid(String),
}
