//! What a multiverse needs ([`MultiverseSetup`], with the defaults of `usar multiverse`) and
//! the checks made before anything runs ([`MultiverseSetup::check`]).

use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use usar_sim::scenario::{Scenario, ScenarioSpec};

use super::axes::Axes;
pub use super::error::MultiverseError;
use super::record::UniverseRecord;
use super::universe::{Sample, Universe, check_shards, factorial_size, select, shard_of};
use super::validate::check_axes;
use crate::calibrate::setup::{DEFAULT_DIGITS, default_check_seed, too_few_trials};
use crate::calibrate::{
    CalibrationSetup, EvaluationHook, FreeField, Optimizer, Targets, TrialPlan,
};
use usar_report::claims::Claims;
use usar_sweep::data::hooks::{CalibrationHooks, TrialObserverFactory, is_set};
use usar_sweep::data::setting_error::SettingError;
use usar_sweep::shard::Shard;
use usar_sweep::sweep::{SweepHooks, check_sweep_size};

/// Comparison trials per method and universe by default (10, as a sweep).
pub const DEFAULT_TRIALS: u32 = 10;
/// Trials per method of each calibration evaluation by default (5).
pub const DEFAULT_CALIBRATION_TRIALS: u32 = 5;
/// Evaluations of each universe's calibration at most by default (30).
pub const DEFAULT_MAX_EVALS: usize = 30;
/// Design evaluations shared by the universes' calibrations by default (0: none; each
/// universe's search starts from the scenario's own values).
pub const DEFAULT_DESIGN: usize = 0;
/// The most design evaluations a multiverse takes (100,000).
pub const MAX_DESIGN: usize = 100_000;
/// The fewest design evaluations of a design (10: the emulator's 5-fold cross-validation
/// holds out two points a fold).
pub const MIN_DESIGN: usize = 10;
/// Seed of `--sample`'s draw by default (0).
pub const DEFAULT_SAMPLE_SEED: u64 = 0;

/// Called once per universe this run finishes, with its record and how many this run has
/// finished so far (1, 2, ...).
pub type UniverseHook = Arc<dyn Fn(&UniverseRecord, usize) + Send + Sync>;

/// Extension points (default: none). `usar multiverse`'s hidden `--stop-after N` (its tests'
/// stand-in for a kill) is built on the first two.
#[derive(Clone, Default)]
pub struct MultiverseHooks {
    /// Called after each new calibration evaluation is in its trace.
    pub calibration: Option<EvaluationHook>,
    /// A step observer per comparison trial and a call per journaled comparison trial.
    pub sweep: SweepHooks,
    /// Called after each universe's record is written.
    pub universe_done: Option<UniverseHook>,
    /// A step observer per calibration trial (the comparison's are `sweep.trial_observer`).
    pub calibration_trials: Option<TrialObserverFactory>,
    /// Set to `true` to stop (e.g. on Ctrl-C in the Python package): the calibration
    /// evaluation running is dropped (see [`CalibrationHooks::stop`]), the comparison trials
    /// running end and are kept in its journal, nothing new starts, the universe running
    /// writes no record and no comparison files, and [`super::run_multiverse`] returns
    /// [`usar_sweep::data::hooks::Stopped`] without writing the top files; running it again
    /// continues. Default `None`.
    pub stop: Option<Arc<AtomicBool>>,
}

impl MultiverseHooks {
    /// Whether [`MultiverseHooks::stop`] is set.
    pub fn stopped(&self) -> bool {
        is_set(self.stop.as_ref())
    }
}

impl fmt::Debug for MultiverseHooks {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("MultiverseHooks")
            .field("calibration", &self.calibration.is_some())
            .field("sweep", &self.sweep)
            .field("universe_done", &self.universe_done.is_some())
            .field("calibration_trials", &self.calibration_trials.is_some())
            .field("stop", &self.stop)
            .finish()
    }
}

/// Everything a multiverse needs. [`MultiverseSetup::new`] gives the defaults of `usar
/// multiverse`; set the fields that differ. See [`super::run_multiverse`] for an example.
#[derive(Debug, Clone)]
pub struct MultiverseSetup {
    /// The base scenario every universe starts from (unvalidated spec, as parsed).
    pub base: ScenarioSpec,
    /// Where it came from (a path as given: messages, reports and the commands they suggest).
    pub origin: String,
    /// The axes; a universe takes one alternative of each.
    pub axes: Axes,
    /// What each universe's calibration must reach (admissible: every band, loss 0).
    pub targets: Targets,
    /// The claims each admissible universe's comparison checks (`--claims FILE`, or the base
    /// scenario's `report: (claims: ...)`); default `None`: no claims, the multiverse says
    /// only which universes are admissible.
    pub claims: Option<Claims>,
    /// `--near-loss LOSS`: also report the shares among the universes whose calibration
    /// reached a loss of at most LOSS (> 0, finite), a sensitivity variant of admissibility
    /// (loss 0); default `None`. Changes no universe.
    pub near_loss: Option<f64>,
    /// The fields each universe's calibration fits, with their ranges (at least one, each
    /// once, none set by an axis).
    pub free: Vec<FreeField>,
    /// The comparison's trials in every universe, the same in each (common random numbers):
    /// default the four built-in methods, [`DEFAULT_TRIALS`] trials per method from the base
    /// scenario's `sim.seed`, each as long as the universe's `mission.duration_s`. Each
    /// universe's calibration runs the same methods and length.
    pub comparison: TrialPlan,
    /// Trials per method of each calibration evaluation (>= 1; default
    /// [`DEFAULT_CALIBRATION_TRIALS`]).
    pub calibration_trials: u32,
    /// Base seed of the calibrations' trials (default: the comparison's, so the comparison's
    /// first trials are the calibration's).
    pub calibration_seed: u64,
    /// Most evaluations of each calibration (>= 1; default [`DEFAULT_MAX_EVALS`]).
    pub max_evals: usize,
    /// `--design N`: evaluations of a design shared by every universe (0 to
    /// [`MAX_DESIGN`]; default [`DEFAULT_DESIGN`], none). With a design, N
    /// points spread over the universes and the free ranges are evaluated first
    /// ([`super::design`]), an emulator of every target's statistic is fitted to them
    /// ([`super::emulator`]), and each universe's calibration starts where the emulator
    /// predicts its least loss.
    pub design: usize,
    /// The search of each calibration (`--optimizer`; default Nelder-Mead).
    pub optimizer: Optimizer,
    /// Trials per method of each calibration's check on unseen trials (`--check-trials`;
    /// default 0: no check). With a check, a point in band counts only when the unseen
    /// trials are in band too ([`crate::calibrate::Evaluation::search_loss`]), so an
    /// admissible universe is confirmed on trials its calibration did not see.
    pub check_trials: u32,
    /// Base seed of that check (`--check-seed`; `None`, the default:
    /// [`crate::calibrate::setup::default_check_seed`] of the calibration seed, so never the
    /// calibration's own trials).
    pub check_seed: Option<u64>,
    /// Significant digits of the calibrated values (1 to 17; default
    /// [`DEFAULT_DIGITS`]).
    pub digits: u32,
    /// `--sample N --sample-seed S`: run `N` universes drawn from the factorial (`None`: all
    /// of them).
    pub sample: Option<Sample>,
    /// Worker threads for each calibration's and comparison's trials (>= 1). Never changes
    /// a result.
    pub threads: usize,
    /// Run one shard's universes only (`--shard I/N`; `None`: all).
    pub shard: Option<Shard>,
    /// Discard a multiverse of other parameters in the output folder (and its universes)
    /// instead of refusing to start.
    pub overwrite: bool,
    /// The folder the run's relative paths are relative to (for the commands messages
    /// suggest; default the current folder).
    pub working_dir: Option<PathBuf>,
    /// The time stamp of each calibration's outputs (default `None`: the system clock).
    pub date: Option<String>,
    /// Extension points (default none).
    pub hooks: MultiverseHooks,
}

impl MultiverseSetup {
    /// The base seed of the check on unseen trials: [`MultiverseSetup::check_seed`], or by
    /// default [`default_check_seed`] of the calibration seed.
    pub fn check_seed(&self) -> u64 {
        self.check_seed
            .unwrap_or_else(|| default_check_seed(self.calibration_seed))
    }

    /// The defaults of `usar multiverse` for `axes` over `base` (read from `origin`),
    /// calibrating `free` to `targets`: the four built-in methods, [`DEFAULT_TRIALS`]
    /// comparison trials, the scenario's `sim.seed` for both seeds, each universe's
    /// `mission.duration_s`, [`DEFAULT_CALIBRATION_TRIALS`] trials per evaluation and at most
    /// [`DEFAULT_MAX_EVALS`] evaluations, every universe, all cores, no shard, no overwrite,
    /// the current folder, the system clock, no hooks.
    pub fn new(
        base: ScenarioSpec,
        origin: impl Into<String>,
        axes: Axes,
        targets: Targets,
        free: Vec<FreeField>,
    ) -> Self {
        let seed = base.sim.seed;
        Self {
            origin: origin.into(),
            axes,
            targets,
            claims: None,
            near_loss: None,
            free,
            comparison: TrialPlan::builtin(DEFAULT_TRIALS, seed),
            calibration_trials: DEFAULT_CALIBRATION_TRIALS,
            calibration_seed: seed,
            max_evals: DEFAULT_MAX_EVALS,
            design: DEFAULT_DESIGN,
            optimizer: Optimizer::NelderMead,
            check_trials: 0,
            check_seed: None,
            digits: DEFAULT_DIGITS,
            sample: None,
            threads: std::thread::available_parallelism().map_or(1, usize::from),
            shard: None,
            overwrite: false,
            working_dir: std::env::current_dir().ok(),
            date: None,
            hooks: MultiverseHooks::default(),
            base,
        }
    }

    /// The calibration of one universe: `spec` (the base with the universe's choices, read
    /// from `origin`), fitted to `targets` (this setup's, with the universe's target flags,
    /// [`Axes::universe_targets`]) with this setup's free fields, methods, budget, search and
    /// check on unseen trials, from the scenario's own values, described by `command`.
    pub fn calibration_setup(
        &self,
        spec: ScenarioSpec,
        targets: Targets,
        origin: String,
        command: String,
    ) -> CalibrationSetup {
        CalibrationSetup {
            trial_plan: self
                .comparison
                .with_trials(self.calibration_trials, self.calibration_seed),
            digits: self.digits,
            max_evals: self.max_evals,
            max_time: None,
            threads: self.threads,
            check_trials: self.check_trials,
            check_seed: self.check_seed(),
            optimizer: self.optimizer,
            overwrite: false,
            command,
            date: self.date.clone(),
            hooks: CalibrationHooks {
                trial_observer: self.hooks.calibration_trials.clone(),
                stop: self.hooks.stop.clone(),
            },
            ..CalibrationSetup::new(spec, origin, targets, self.free.clone())
        }
    }

    /// Checks the setup before anything runs: the options, the base scenario (validated),
    /// the targets and free fields against it, the methods, the claims against both, the axes
    /// against it and the free fields, the universes (count, sample) and the shard.
    ///
    /// # Errors
    /// One line: an option out of range (naming its flag), what
    /// [`CalibrationSetup::check`] refuses for the base scenario, what the axes file's
    /// checks refuse ([`check_axes`]), too many universes or a sample larger than the
    /// factorial, or a shard count above the universes to run.
    pub fn check(&self) -> Result<CheckedMultiverse, MultiverseError> {
        let refuse = |field, problem: String| Err(SettingError::new(field, problem).into());
        if self.comparison.trials == 0 {
            return refuse("trials", " must be at least 1".into());
        }
        if self.calibration_trials == 0 {
            return refuse("calibration_trials", " must be at least 1".into());
        }
        if let Some(problem) = too_few_trials(&self.targets, self.calibration_trials) {
            return refuse("calibration_trials", problem);
        }
        if self.design > 0 && self.design < MIN_DESIGN {
            return refuse(
                "design",
                format!(
                    " {} is too few: a design needs at least {MIN_DESIGN} points (the \
                     emulator's 5-fold cross-validation)",
                    self.design
                ),
            );
        }
        if self.design > MAX_DESIGN {
            return refuse(
                "design",
                format!(
                    " {} is more than the limit of {MAX_DESIGN} design evaluations",
                    self.design
                ),
            );
        }
        if let Some(l) = self.near_loss
            && !(l.is_finite() && l > 0.0)
        {
            return refuse(
                "near_loss",
                format!(" must be a finite loss above 0 (0 is admissibility itself), not {l}"),
            );
        }
        check_sweep_size(1, self.comparison.methods.len(), self.comparison.trials)?;
        let calibration = self.calibration_setup(
            self.base.clone(),
            self.targets.clone(),
            self.origin.clone(),
            String::new(),
        );
        let checked = calibration.check()?;
        check_axes(
            &self.axes,
            &self.base,
            &self.origin,
            &self.free,
            &self.targets,
        )?;
        if let Some(claims) = &self.claims {
            claims.check_tasks(&checked.scenario.task_names())?;
            claims.check_methods(&checked.methods)?;
        }
        let sizes = self.axes.sizes();
        let universes = select(&sizes, self.sample)?;
        if let Some(s) = self.shard {
            check_shards(&format!("--shard {s}"), s.count, universes.len())?;
        }
        Ok(CheckedMultiverse {
            scenario: checked.scenario,
            methods: checked.methods,
            factorial: factorial_size(&sizes)?,
            universes,
        })
    }
}

/// A setup checked by [`MultiverseSetup::check`].
#[derive(Debug, Clone)]
pub struct CheckedMultiverse {
    /// The base scenario, validated.
    pub scenario: Scenario,
    /// The methods' display names (as written; see `canonical_method`), in order.
    pub methods: Vec<String>,
    /// The size of the full factorial.
    pub factorial: u64,
    /// The universes the multiverse runs (all shards), in index order.
    pub universes: Vec<Universe>,
}

impl CheckedMultiverse {
    /// The positions (into [`CheckedMultiverse::universes`]) of the universes `shard` runs
    /// (every one without a shard).
    pub fn own(&self, shard: Option<Shard>) -> Vec<usize> {
        match shard {
            Some(s) => shard_of(self.universes.len(), s),
            None => (0..self.universes.len()).collect(),
        }
    }
}
