//! One evaluation of a calibration: the base scenario with the free values applied
//! ([`usar_sweep::vary::apply_overrides`], then validated), every method x trials `0..n` run in
//! parallel (trial `k` of every method and every evaluation from `trial_seed(base_seed, k)`:
//! common random numbers), each target's statistic over the results pooled over methods, and
//! the loss.
//!
//! Results are kept in (method order, trial) order, so nothing depends on the thread count. A
//! trial that fails or panics (isolated as in a sweep, `usar_sweep::executor`), or free values
//! that make the scenario break a rule, make the evaluation's loss +inf and its message says
//! why; the calibration goes on.

use std::time::Instant;

use serde::{Deserialize, Serialize};
use usar_sim::mission::{TrialResult, trial_seed};
use usar_sim::scenario::{Scenario, ScenarioSpec, trial_steps};

use super::error::CalibrationError;
use super::free::FreeField;
use super::loss::loss;
use super::setup::{CalibrationSetup, Checked};
use usar_report::targets::file::Target;
use usar_report::targets::float_text;
use usar_sweep::data::hooks::SweepHooks;
use usar_sweep::executor::{CellPlan, Job, Runner, run_trial};
use usar_sweep::method_factory::trust_model;
use usar_sweep::settings::Setting;
use usar_sweep::vary::{Override, apply_overrides, rule_error, spec_from_json, spec_json};

/// One evaluated point of a calibration (a line of `trace.jsonl` and a row of `trace.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Evaluation {
    /// Position in the search's sequence of distinct points, from 0.
    pub index: usize,
    /// The free values, rounded, in free-field order: exactly what ran.
    pub values: Vec<f64>,
    /// Each target's statistic, in target order (NaN when undefined or not run).
    #[serde(with = "float_text::vec")]
    pub statistics: Vec<f64>,
    /// The loss ([`super::loss()`]): 0 when every statistic is in its band, +inf when a trial
    /// failed, the scenario broke a rule, or a statistic is NaN or infinite.
    #[serde(with = "float_text")]
    pub loss: f64,
    /// Why the loss is +inf: failed trials, a broken rule, or a fitted target's statistic
    /// that is NaN or infinite (naming the target and what its statistic needs).
    pub message: Option<String>,
    /// Trials that ran to their end.
    pub trials_ok: usize,
    /// Wall-clock time of the evaluation, seconds (informative only).
    pub wall_s: f64,
    /// The loss of the same values on the calibration's unseen trials (`check_trials` per
    /// method from `check_seed`): run only for a point in band (loss 0) when the calibration
    /// checks unseen trials; NaN otherwise (and absent from the trace). A point is accepted
    /// only when it is 0 too ([`Evaluation::search_loss`]).
    #[serde(
        default = "float_text::nan",
        with = "float_text",
        skip_serializing_if = "float_text::is_nan"
    )]
    pub unseen_loss: f64,
}

impl Evaluation {
    /// The loss the search sees and the best point is chosen by: [`Evaluation::loss`], or
    /// for a point in band whose check on unseen trials failed, that check's loss (so the
    /// search goes on, and prefers points in band on both sets of trials).
    pub fn search_loss(&self) -> f64 {
        if self.unseen_loss > 0.0 {
            self.unseen_loss
        } else {
            self.loss
        }
    }
}

/// The trials of one scenario: the successful results in (method order, trial) order and a
/// message per failed trial.
#[derive(Debug, Clone, Default)]
pub struct TrialSet {
    /// Successful results, by method order then trial.
    pub results: Vec<TrialResult>,
    /// `METHOD trial K (seed S): message` per failed trial, in the same order.
    pub failures: Vec<String>,
}

/// Runs the evaluations of one calibration on one thread pool.
pub struct Evaluator<'a> {
    setup: &'a CalibrationSetup,
    methods: Vec<String>,
    pool: rayon::ThreadPool,
}

impl<'a> Evaluator<'a> {
    /// An evaluator for `setup` as `checked` ([`CalibrationSetup::check`]).
    ///
    /// # Errors
    /// The thread pool cannot be started.
    pub fn new(setup: &'a CalibrationSetup, checked: &Checked) -> Result<Self, CalibrationError> {
        let per_evaluation = checked.methods.len() * setup.trial_plan.trials as usize;
        let threads = checked.threads.min(per_evaluation).max(1);
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(CalibrationError::ThreadPool)?;
        Ok(Self {
            setup,
            methods: checked.methods.clone(),
            pool,
        })
    }

    /// The overrides that set the free fields that are not factors to `values` (a factor
    /// field is applied by [`Evaluator::scenario_at`]).
    pub fn overrides(&self, values: &[f64]) -> Vec<Override> {
        self.setup
            .free
            .iter()
            .zip(values)
            .filter(|(f, _)| !f.factor)
            .map(|(f, &x)| f.override_for(x))
            .collect()
    }

    /// Every free value as a rule error names it: `FIELD=x`, a factor as `FIELD=x (factor)`.
    fn named(&self, values: &[f64]) -> Vec<Override> {
        self.setup
            .free
            .iter()
            .zip(values)
            .map(|(f, &x)| {
                let mut o = f.override_for(x);
                if f.factor {
                    o.value.text = format!("{} (factor)", o.value.text);
                }
                o
            })
            .collect()
    }

    /// The base spec with the free fields set to `values` (a `:factor` field's value(s)
    /// scaled by its value, after the others are set), and its validated scenario.
    ///
    /// # Errors
    /// A value the field cannot take, or a scenario that breaks a rule: one line naming the
    /// `--free` values (`--free mission.pickup_s=-1: mission.pickup_s: expected ...`).
    pub fn scenario_at(&self, values: &[f64]) -> Result<(ScenarioSpec, Scenario), String> {
        let overrides = self.overrides(values);
        let mut spec = apply_overrides(&self.setup.base, &overrides)
            .map_err(|(i, e)| format!("{} {}: {e}", Setting::Free, overrides[i].brief()))?;
        let factors: Vec<(&FreeField, f64)> = self
            .setup
            .free
            .iter()
            .zip(values.iter().copied())
            .filter(|(f, _)| f.factor)
            .collect();
        if !factors.is_empty() {
            let mut json = spec_json(&spec)?;
            for (f, x) in &factors {
                f.scale_in(&mut json, *x)
                    .map_err(|e| format!("{} {}: {e}", Setting::Free, f.assignment(*x)))?;
            }
            spec = spec_from_json(json).map_err(|e| format!("{} factors: {e}", Setting::Free))?;
        }
        let scenario = spec
            .validate(&self.setup.origin)
            .map_err(|e| rule_error(&Setting::Free.to_string(), &self.named(values), &e))?;
        Ok((spec, scenario))
    }

    /// Evaluates the free `values` (already rounded): index 0, the caller numbers it.
    pub fn evaluate(&self, values: &[f64]) -> Evaluation {
        let t0 = Instant::now();
        let n = self.setup.targets.targets().len();
        let mut e = Evaluation {
            index: 0,
            values: values.to_vec(),
            statistics: vec![f64::NAN; n],
            loss: f64::INFINITY,
            message: None,
            trials_ok: 0,
            wall_s: 0.0,
            unseen_loss: f64::NAN,
        };
        match self.scenario_at(values) {
            Err(m) => e.message = Some(m),
            Ok((_, scenario)) => {
                let set = self.run(
                    &scenario,
                    self.setup.trial_plan.base_seed,
                    self.setup.trial_plan.trials,
                );
                e.statistics = self.setup.targets.values(&set.results);
                e.trials_ok = set.results.len();
                e.loss = loss(self.setup.targets.targets(), &e.statistics);
                e.message = undefined_statistics(self.setup.targets.targets(), &e.statistics);
                if e.loss == 0.0 && set.failures.is_empty() && self.setup.check_trials > 0 {
                    let check = self.run(&scenario, self.setup.check_seed, self.setup.check_trials);
                    let stats = self.setup.targets.values(&check.results);
                    e.unseen_loss = if check.failures.is_empty() {
                        loss(self.setup.targets.targets(), &stats)
                    } else {
                        f64::INFINITY
                    };
                }
                if !set.failures.is_empty() {
                    e.loss = f64::INFINITY;
                    e.message = Some(format!(
                        "{} of {} trials failed: {}",
                        set.failures.len(),
                        set.failures.len() + set.results.len(),
                        set.failures.join("; ")
                    ));
                }
            }
        }
        e.wall_s = t0.elapsed().as_secs_f64();
        e
    }

    /// Runs every method x trials `0..trials` of `scenario` from `base_seed`, in parallel.
    pub fn run(&self, scenario: &Scenario, base_seed: u64, trials: u32) -> TrialSet {
        let duration_s = self
            .setup
            .trial_plan
            .duration_s
            .unwrap_or(scenario.mission().duration_s.get());
        let plan = match (
            trust_model(scenario),
            trial_steps(duration_s, scenario.sim().dt_s.get()),
        ) {
            (Ok(model), Ok(steps)) => CellPlan {
                label: String::new(),
                scenario,
                model,
                duration_s,
                step_us: (scenario.sim().dt_s.get() * 1e6).round().max(1.0) as u64,
                steps_per_trial: steps,
            },
            (Err(e), _) => return everything_failed(format!("{e:#}")),
            (_, Err(e)) => return everything_failed(format!("{}: {e}", Setting::DurationS)),
        };
        let jobs: Vec<Job> = self
            .setup
            .trial_plan
            .methods
            .iter()
            .zip(&self.methods)
            .flat_map(|(arg, name)| {
                (0..trials).map(move |k| Job {
                    cell: 0,
                    method_arg: arg.clone(),
                    method: name.clone(),
                    trial: k,
                    seed: trial_seed(base_seed, k),
                })
            })
            .collect();
        let hooks = SweepHooks {
            trial_observer: self.setup.hooks.trial_observer.clone(),
            ..SweepHooks::default()
        };
        let runner = Runner {
            factory: &self.setup.trial_plan.method_factory,
            hooks: &hooks,
            progress: false,
            threads: self.pool.current_num_threads(),
            inside_trials: false,
        };
        let outcomes: Vec<Result<TrialResult, String>> = self.pool.install(|| {
            use rayon::prelude::*;
            jobs.par_iter()
                .map(|job| {
                    // Stopped: the trials not started are skipped (their evaluation is not
                    // kept, see the searcher).
                    if self.setup.hooks.stopped() {
                        return Err("stopped before it ran".to_string());
                    }
                    run_trial(&plan, &runner, job, &|_| {})
                })
                .collect()
        });
        let mut set = TrialSet::default();
        for (job, outcome) in jobs.iter().zip(outcomes) {
            match outcome {
                Ok(r) => set.results.push(r),
                Err(m) => set.failures.push(format!(
                    "{} trial {} (seed {}): {m}",
                    job.method, job.trial, job.seed
                )),
            }
        }
        set
    }
}

/// Why the loss of `statistics` is +inf although every trial ran: each fitted target whose
/// statistic is NaN or infinite, with what the statistic needs (`target "sd":
/// PooledSd(rescued_total) is NaN: it needs at least 2 trials per method defining
/// rescued_total`), joined by `; `; `None` when every fitted statistic is finite.
fn undefined_statistics(targets: &[Target], statistics: &[f64]) -> Option<String> {
    let lines: Vec<String> = targets
        .iter()
        .zip(statistics)
        .filter(|(t, x)| !t.report_only && !x.is_finite())
        .map(|(t, &x)| {
            format!(
                "target {:?}: {} is {}: {}",
                t.name,
                t.statistic,
                float_text::short(x),
                t.statistic.needs()
            )
        })
        .collect();
    (!lines.is_empty()).then(|| lines.join("; "))
}

/// A trial set where nothing could run, for `why`.
fn everything_failed(why: String) -> TrialSet {
    TrialSet {
        results: Vec::new(),
        failures: vec![why],
    }
}
