//! One universe, run into its folder `universes/<id>/`:
//!
//! ```text
//! universes/u007/
//!   scenario.ron    the base scenario with the universe's choices (every field written out)
//!   calibration/    the calibration of the free fields (usar calibrate's files: trace.jsonl,
//!                   calibrated.ron, trace.csv, calibration.md, convergence.svg)
//!   comparison/     the comparison on the calibrated scenario (usar sweep's files: journal,
//!                   trials.csv, summary.csv, report.md, the figures)
//!   universe.json   the universe's record, written last (super::record)
//! ```
//!
//! The calibration ([`crate::calibrate::calibrate`]) and the comparison
//! ([`usar_sweep::sweep::run_sweep`]) keep their own trace and journal, so a universe stopped
//! half-way continues where it stopped. Nothing that goes wrong in a universe stops the
//! multiverse: a scenario that breaks a rule, a calibration that errs, or failing trials are
//! written into its record.

use std::path::{Path, PathBuf};

use usar_sim::scenario::{ScenarioSpec, path_text};

use super::effect::claim_effect;
use super::emulator::Emulator;
use super::error::MultiverseError;
use super::plan::MultiversePlan;
use super::record::{CalibrationResult, ComparisonResult, MetricSummary, Status, UniverseRecord};
use super::setup::MultiverseSetup;
use super::universe::Universe;
use crate::calibrate::{CalibrationOutcome, Progress, Target, Targets, calibrate};
use usar_report::analysis::{Analysis, CellAnalysis, ReportOptions};
use usar_report::error::ReportError;
use usar_report::output::write_outputs;
use usar_sweep::atomic::{FileError, remove_stale_temps, write_atomic};
use usar_sweep::data::hooks::{Stopped, SweepHooks};
use usar_sweep::data::owner::sub_runs;
use usar_sweep::spec_ron::spec_to_ron;
use usar_sweep::sweep::{SweepConfig, SweepOutcome, run_sweep};
use usar_sweep::vary::{Override, apply_overrides, rule_error};

/// What the functions of this module return.
type Result<T, E = MultiverseError> = std::result::Result<T, E>;

/// The folder, under the output folder, that holds the universes' folders.
pub const UNIVERSES_DIR: &str = sub_runs::UNIVERSES;
/// The universe's scenario in its folder.
pub const SCENARIO_FILE: &str = "scenario.ron";
/// The calibration's folder in a universe's folder (a run of its own, claimed inside the
/// multiverse's folder: [`sub_runs`]).
pub const CALIBRATION_DIR: &str = sub_runs::CALIBRATION;
/// The comparison's folder in a universe's folder (as [`CALIBRATION_DIR`]).
pub const COMPARISON_DIR: &str = sub_runs::COMPARISON;

/// The folder of universe `id` under the output folder `root`.
pub fn universe_dir(root: &Path, id: &str) -> PathBuf {
    root.join(UNIVERSES_DIR).join(id)
}

/// What every universe of one multiverse run shares.
#[derive(Debug, Clone, Copy)]
pub struct UniverseRun<'a> {
    /// The multiverse.
    pub setup: &'a MultiverseSetup,
    /// Its plan (the command quoted in the universes' files, the factorial's size).
    pub plan: &'a MultiversePlan,
    /// [`MultiversePlan::identity_sum`], which the records are checksummed with.
    pub identity_sum: &'a str,
    /// The output folder.
    pub root: &'a Path,
    /// The emulator of the multiverse's design (`--design`): each calibration starts where
    /// it predicts the least loss ([`Emulator::start`]); `None`: at the scenario's values.
    pub emulator: Option<&'a Emulator>,
}

impl UniverseRun<'_> {
    /// Runs universe `u` (or continues it) and writes its record.
    ///
    /// # Errors
    /// An I/O error writing the universe's own files (its folder, `scenario.ron`,
    /// `universe.json`), or [`Stopped`] when the stop flag was set while it ran (no record is
    /// written: its calibration's trace and its comparison's journal keep what finished);
    /// everything else is in the record.
    pub fn run(&self, u: &Universe) -> Result<UniverseRecord> {
        let id = u.id(self.plan.factorial());
        let dir = universe_dir(self.root, &id);
        std::fs::create_dir_all(&dir).map_err(FileError::io(format!(
            "creating folder {}",
            path_text(&dir)
        )))?;
        remove_stale_temps(&dir)?;
        let mut record = UniverseRecord {
            index: u.index,
            id,
            choices: u.choices.clone(),
            status: Status::Ok,
            message: None,
            calibration: None,
            comparison: None,
        };
        let overrides = self.setup.axes.universe_overrides(&u.choices);
        let targets = self
            .setup
            .axes
            .universe_targets(&u.choices, &self.setup.targets);
        match (self.scenario(&overrides, &dir)?, targets) {
            (Err(message), _) => {
                record.status = Status::Invalid;
                record.message = Some(message);
            }
            (Ok(_), Err(e)) => {
                record.status = Status::Invalid;
                record.message = Some(format!("targets: {}", e.0.message));
            }
            (Ok(spec), Ok(targets)) => {
                self.calibrate_and_compare(spec, &targets, &dir, &mut record);
            }
        }
        if self.setup.hooks.stopped() {
            return Err(Stopped.into());
        }
        record.write(&dir, self.identity_sum)?;
        Ok(record)
    }

    /// The universe's spec, written as `scenario.ron` in `dir`; `Err(message)` when its
    /// choices do not apply or break a rule (`scenario.ron` is written then too, when they
    /// apply).
    fn scenario(&self, overrides: &[Override], dir: &Path) -> Result<Result<ScenarioSpec, String>> {
        let spec = match apply_overrides(&self.setup.base, overrides) {
            Ok(s) => s,
            Err((i, e)) => return Ok(Err(format!("set {}: {e}", overrides[i].brief()))),
        };
        let sets: Vec<String> = overrides.iter().map(|o| format!("--set '{o}'")).collect();
        let comments = [
            format!(
                "A universe of the multiverse in ../../multiverse.md: {} with {}.",
                self.plan.scenario_path,
                self.choice_text(overrides)
            ),
            format!(
                "The same scenario: usar check {} {} --print",
                self.plan.scenario_path,
                sets.join(" ")
            ),
        ];
        let path = dir.join(SCENARIO_FILE);
        let text = spec_to_ron(&spec, &comments).map_err(ReportError::from)?;
        write_atomic(&path, text.as_bytes())?;
        Ok(match spec.validate(&path_text(&path)) {
            Ok(_) => Ok(spec),
            Err(e) => Err(rule_error("set", overrides, &e)),
        })
    }

    /// `a=x, b=y` of the overrides, or `its own values` for none.
    fn choice_text(&self, overrides: &[Override]) -> String {
        if overrides.is_empty() {
            return "its own values".into();
        }
        overrides
            .iter()
            .map(ToString::to_string)
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Calibrates `spec` to the universe's `targets`, compares the methods on the calibrated
    /// scenario, and fills in `record`.
    fn calibrate_and_compare(
        &self,
        spec: ScenarioSpec,
        targets: &Targets,
        dir: &Path,
        record: &mut UniverseRecord,
    ) {
        let mut setup = self.setup.calibration_setup(
            spec,
            targets.clone(),
            path_text(&dir.join(SCENARIO_FILE)),
            format!("{} (universe {})", self.plan.command(None), record.id),
        );
        let start = self
            .emulator
            .and_then(|e| e.start(&record.choices, targets.targets(), self.setup.digits));
        if let Some(s) = &start {
            setup.start = Some(s.values.clone());
        }
        let progress = Progress {
            on_evaluated: self.setup.hooks.calibration.clone(),
            ..Progress::off()
        };
        let calibrated = match calibrate(&setup, &dir.join(CALIBRATION_DIR), progress) {
            Ok(c) => c,
            Err(e) => {
                record.status = Status::Failed;
                record.message = Some(one_line(&format!("calibration: {e:#}")));
                return;
            }
        };
        record.calibration = Some(CalibrationResult {
            predicted_loss: start.map_or(f64::NAN, |s| s.predicted_loss),
            ..calibration_result(&calibrated)
        });
        let cfg = SweepConfig {
            scenario_path: dir.join(CALIBRATION_DIR).join("calibrated.ron"),
            methods: self.setup.comparison.methods.clone(),
            method_factory: self.setup.comparison.method_factory.clone(),
            trials: self.setup.comparison.trials,
            base_seed: self.setup.comparison.base_seed,
            duration_s: self.setup.comparison.duration_s,
            threads: self.setup.threads,
            out_dir: dir.join(COMPARISON_DIR),
            progress: false,
            hooks: SweepHooks {
                stop: self.setup.hooks.stop.clone(),
                ..self.setup.hooks.sweep.clone()
            },
            ..SweepConfig::new(calibrated.best_scenario.clone(), dir)
        };
        let report = ReportOptions {
            targets: Some(targets.clone()),
            claims: self.setup.claims.clone(),
        };
        match compare(&cfg, report) {
            Ok((o, analysis)) => {
                record.comparison =
                    Some(comparison_result(&o, &analysis.cells[0], targets.targets()));
                let failures: Vec<String> = o
                    .failures()
                    .map(|f| format!("{} trial {}: {}", f.method, f.trial, f.message))
                    .collect();
                if !failures.is_empty() {
                    record.status = Status::Failed;
                    record.message = Some(one_line(&format!(
                        "comparison: {} of {} trials failed: {}",
                        failures.len(),
                        o.expected_trials(),
                        failures.join("; ")
                    )));
                }
            }
            Err(e) => {
                record.status = Status::Failed;
                record.message = Some(one_line(&format!("comparison: {e:#}")));
            }
        }
    }
}

/// Runs the comparison and writes its files, whose reports show `report`'s sections (a
/// universe's report checks its targets and the multiverse's claims).
fn compare(cfg: &SweepConfig, report: ReportOptions) -> Result<(SweepOutcome, Analysis)> {
    let o = run_sweep(cfg)?;
    if usar_sweep::data::hooks::is_set(cfg.hooks.stop.as_ref()) {
        // Some trials were skipped: no files of a partial comparison (its journal keeps the
        // trials that ran; a rerun continues it).
        return Err(Stopped.into());
    }
    let analysis = Analysis::with_report(&o, report);
    write_outputs(cfg, &o, &analysis, &[])?;
    Ok((o, analysis))
}

/// What the record keeps of a calibration.
fn calibration_result(c: &CalibrationOutcome) -> CalibrationResult {
    CalibrationResult {
        loss: c.loss,
        values: c.best_values().to_vec(),
        statistics: c.best().statistics.clone(),
        evaluations: c.evaluations.len(),
        stop: c.stop,
        predicted_loss: f64::NAN,
    }
}

/// What the record keeps of a comparison: every method x metric summary, every claim, and
/// each of `targets`' statistics over its trials.
fn comparison_result(o: &SweepOutcome, a: &CellAnalysis, targets: &[Target]) -> ComparisonResult {
    let metrics = a
        .methods
        .iter()
        .flat_map(|m| {
            a.metrics
                .iter()
                .zip(&m.metrics)
                .map(|(metric, s)| MetricSummary {
                    method: m.method.clone(),
                    metric: metric.name(&a.tasks),
                    n: s.n,
                    mean: s.mean,
                    sd: s.sd,
                })
        })
        .collect();
    ComparisonResult {
        trials_ok: o.cells[0].results.len(),
        trials_failed: o.cells[0].failures.len(),
        metrics,
        claims: a.claims.iter().map(claim_effect).collect(),
        targets: targets
            .iter()
            .map(|t| t.value_of(&o.cells[0].results))
            .collect(),
    }
}

/// `text` on one line: line breaks become spaces (a record's message is a table cell).
fn one_line(text: &str) -> String {
    text.split(['\n', '\r'])
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect::<Vec<_>>()
        .join(" ")
}
