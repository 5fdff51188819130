//! The calibration targets a sweep's reports compare with, and the paper's own.
//!
//! [`ReportOptions`] says what a sweep's reports say about a paper: the pooled statistics
//! against a targets file (`--targets FILE`) and the claims of a claims file (`--claims
//! FILE`); neither by default, so the report of a user's own scenario is about that scenario alone.
//! [`ReportOptions::resolve`] is the one place they are decided.
//!
//! The paper's targets are the method-independent statistics `scenarios/paper.ron` is
//! calibrated against, pooled over every trial of a sweep (all methods together): the authors'
//! results sheet (`RNE_experiments_for_paper.ods` of the public repository
//! RNE-Agent-Trust-Model-SMC2021, 4 methods x 10 trials x 600 s, pooled the same way). See
//! `docs/calibration.md`. They are defined once, in `scenarios/paper-targets.ron` (embedded
//! here as [`PAPER_TARGETS_RON`], the default of `usar calibrate`): eighteen statistics (nine
//! means and ratios of means, three pooled within-method standard deviations and six of the
//! trials' structure, [`crate::targets::Statistic`]) over the tasks named `easy` and `hard`; for a scenario
//! without them every statistic is NaN ([`applies_to`] says so).

use std::path::Path;
use std::sync::OnceLock;

use usar_sim::mission::TrialResult;
use usar_sim::scenario::{Scenario, path_text};
use usar_sweep::settings::Setting;

use crate::claims::{Claims, ClaimsError};
use crate::targets::TargetsError;
pub use crate::targets::{Target, Targets};

/// What a sweep's reports (`report.md`, `grid.md`, the terminal summary) say beyond the
/// scenario's own results. Default: nothing (no targets, no claims).
///
/// These are outputs, not inputs: they are not part of a sweep's journal header, so changing
/// them re-renders the reports of a journaled sweep without running a trial again.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ReportOptions {
    /// Targets to compare the statistics pooled over all trials with (the "Pooled statistics"
    /// section, and a line of the terminal summary); `None`: no such section. The paper's are
    /// `scenarios/paper-targets.ron` ([`paper_targets`]).
    pub targets: Option<Targets>,
    /// Claims to check the results against (the "Claims" section, and lines of the terminal
    /// summary); `None`: no such section. The paper's are `scenarios/paper-claims.ron`
    /// ([`crate::claims::paper_claims`]).
    pub claims: Option<Claims>,
}

/// Why a sweep's report options could not be resolved: a targets file or a claims file that
/// cannot be read, parsed or used with the scenario (one line, naming the file, line and
/// field).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ReportOptionsError {
    /// The targets file ([`Targets::load`], [`Targets::check_tasks`]).
    #[error(transparent)]
    Targets(#[from] TargetsError),
    /// The claims file ([`Claims::load`], [`Claims::check_tasks`], [`Claims::check_methods`]).
    #[error(transparent)]
    Claims(#[from] ClaimsError),
}

impl ReportOptions {
    /// The report options of a sweep of `scenario` (loaded from `scenario_path`) with
    /// `methods` (as given or canonical; case and `-`/`_` ignored): the targets file
    /// `cli_targets` (`--targets FILE`) or else the one the scenario's `report` section names
    /// (`report: (targets: "paper-targets.ron")`, relative to the scenario file's folder), and
    /// likewise the claims file `cli_claims` (`--claims FILE`) or the scenario's
    /// `report: (claims: "paper-claims.ron")`; both read and checked now, before any trial
    /// runs. A file given on the command line overrides the scenario's; with neither flags
    /// nor a `report` section, the reports say nothing beyond the results. A file the
    /// scenario names that does not exist (a copy of paper.ron in another folder) is a
    /// warning on stderr, and the reports leave its section out; one given by a flag must
    /// exist.
    ///
    /// # Errors
    /// A targets or claims file that cannot be read or parsed ([`Targets::load`],
    /// [`Claims::load`]), one with a metric the scenario lacks (a task it does not have), or
    /// a claim naming a method that is neither built in nor one of `methods`.
    pub fn resolve(
        cli_targets: Option<&Path>,
        cli_claims: Option<&Path>,
        scenario: &Scenario,
        scenario_path: &Path,
        methods: &[String],
    ) -> Result<Self, ReportOptionsError> {
        let asked = scenario.report();
        let named = |file: &Option<String>, field: &str, flag: Setting, cli: bool| {
            let file = file.as_ref()?;
            let folder = scenario_path.parent().unwrap_or(Path::new(""));
            let path = folder.join(file);
            // A copy of paper.ron elsewhere still runs: its reports leave the section out.
            if !cli && !path.exists() {
                tracing::warn!(
                    "{}: report.{field}: {} not found (relative to the scenario's folder); the \
                     reports leave out its section ({flag} FILE gives it)",
                    path_text(scenario_path),
                    path_text(&path)
                );
                return None;
            }
            Some(path)
        };
        let tasks = scenario.task_names();
        let origin = path_text(scenario_path);
        let targets_path = named(
            &asked.targets,
            "targets",
            Setting::Targets,
            cli_targets.is_some(),
        );
        let targets = match cli_targets.or(targets_path.as_deref()) {
            None => None,
            Some(path) => {
                let t = Targets::load(path)?;
                t.check_tasks_of_scenario(&tasks, &origin)?;
                Some(t)
            }
        };
        let claims_path = named(
            &asked.claims,
            "claims",
            Setting::Claims,
            cli_claims.is_some(),
        );
        let claims = match cli_claims.or(claims_path.as_deref()) {
            None => None,
            Some(path) => {
                let c = Claims::load(path)?;
                c.check_tasks_of_scenario(&tasks, &origin)?;
                c.check_methods(methods)?;
                Some(c)
            }
        };
        Ok(Self { targets, claims })
    }

    /// The options of a report that checks the paper: `scenarios/paper-targets.ron`
    /// ([`paper_targets`]) and `scenarios/paper-claims.ron` ([`crate::claims::paper_claims`]).
    pub fn paper() -> Self {
        Self {
            targets: Some(paper_targets().clone()),
            claims: Some(crate::claims::paper_claims().clone()),
        }
    }

    /// The one line a report gives when it leaves out the targets or the claims: how to ask
    /// for what is left out; `None` when both are in.
    pub fn how_to_ask(&self) -> Option<String> {
        let missing: Vec<&str> = [
            (
                self.targets.is_none(),
                "`--targets FILE` compares the pooled statistics with a \
              targets file (the paper's: `scenarios/paper-targets.ron`)",
            ),
            (
                self.claims.is_none(),
                "`--claims FILE` checks the claims of a claims file (the paper's: \
                 `scenarios/paper-claims.ron`)",
            ),
        ]
        .into_iter()
        .filter_map(|(left_out, text)| left_out.then_some(text))
        .collect();
        (!missing.is_empty()).then(|| {
            format!(
                "Also available (`usar sweep`, `usar merge`, or the scenario's `report` \
                 section; see `docs/sweeps.md`): {}.",
                missing.join("; ")
            )
        })
    }
}

/// The text of `scenarios/paper-targets.ron` (read through the crate's
/// `data/paper-targets.ron`, a link to it, so the packaged crate carries the file).
pub const PAPER_TARGETS_RON: &str = include_str!("../data/paper-targets.ron");

/// The name [`paper_targets`] gives its origin: `scenarios/paper-targets.ron`.
pub const PAPER_TARGETS_ORIGIN: &str = "scenarios/paper-targets.ron";

/// The targets of `scenarios/paper.ron`, parsed once from [`PAPER_TARGETS_RON`].
///
/// # Panics
/// Never: the embedded file is checked by this module's tests.
pub fn paper_targets() -> &'static Targets {
    static TARGETS: OnceLock<Targets> = OnceLock::new();
    TARGETS.get_or_init(|| {
        Targets::parse(PAPER_TARGETS_RON, PAPER_TARGETS_ORIGIN)
            .unwrap_or_else(|e| panic!("the embedded paper targets do not parse: {e}"))
    })
}

/// The targets of the file at `path`, or, without one, the paper's eighteen as `usar
/// calibrate` uses them by default (named `scenarios/paper-targets.ron (built in)` in the
/// outputs).
///
/// # Errors
/// A targets file that cannot be read or parsed ([`Targets::load`]).
pub fn targets_or_paper(path: Option<&Path>) -> Result<Targets, TargetsError> {
    match path {
        Some(p) => Targets::load(p),
        None => Targets::parse(
            PAPER_TARGETS_RON,
            &format!("{PAPER_TARGETS_ORIGIN} (built in)"),
        ),
    }
}

/// Whether a scenario with these task names has the statistics: every metric of
/// [`paper_targets`] exists for it (tasks named `easy` and `hard`; without them every
/// statistic is NaN and the reports say so in one sentence).
pub fn applies_to(tasks: &[String]) -> bool {
    paper_targets().apply_to(tasks)
}

/// Every target of [`paper_targets`] with its statistic pooled over `results` (every trial
/// weighs the same, whatever its method), in file order. NaN for no results, results without
/// the task a target's metric names, or a pooled standard deviation with fewer than 2 trials of a
/// method; a ratio with a zero denominator is infinite or NaN, as IEEE division gives.
pub fn check(results: &[TrialResult]) -> Vec<(Target, f64)> {
    paper_targets()
        .targets()
        .iter()
        .map(|t| (t.clone(), t.value_of(results)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::trial;

    #[test]
    fn the_paper_targets_are_the_eighteen_of_the_sheet() {
        let t = paper_targets().targets();
        let rows: Vec<(String, String, f64)> = t
            .iter()
            .map(|t| (t.name.clone(), t.statistic.to_string(), t.value))
            .collect();
        let expected = [
            ("rounds per trial", "Mean(rounds)", 6.2),
            (
                "easy / hard rescuees",
                "RatioOfMeans(rescued_easy, rescued_hard)",
                1.36,
            ),
            ("rescuees per trial", "Mean(rescued_total)", 152.0),
            (
                "easy rescuees per round",
                "RatioOfMeans(rescued_easy, rounds)",
                14.2,
            ),
            (
                "hard rescuees per round",
                "RatioOfMeans(rescued_hard, rounds)",
                10.42,
            ),
            (
                "hard HP / hard energy",
                "RatioOfMeans(hp_hard_pct, energy_hard_pct)",
                0.62,
            ),
            (
                "easy HP / easy energy",
                "RatioOfMeans(hp_easy_pct, energy_easy_pct)",
                0.09,
            ),
            (
                "hard / easy energy",
                "RatioOfMeans(energy_hard_pct, energy_easy_pct)",
                1.18,
            ),
            (
                "hard / easy HP",
                "RatioOfMeans(hp_hard_pct, hp_easy_pct)",
                8.16,
            ),
            (
                "pooled SD of total rescuees",
                "PooledSd(rescued_total)",
                4.69,
            ),
            (
                "pooled SD of hard-task rescuees",
                "PooledSd(rescued_hard)",
                4.14,
            ),
            (
                "pooled SD of easy-task rescuees",
                "PooledSd(rescued_easy)",
                5.2,
            ),
            ("energy per trial", "Mean(energy_total_pct)", 4275.8),
            ("HP lost per trial", "Mean(hp_total_pct)", 1601.9),
            (
                "energy CV within a method, %",
                "PooledCv(energy_total_pct)",
                2.71,
            ),
            ("pooled SD of rounds", "PooledSd(rounds)", 0.24),
            (
                "hard-easy correlation within a method",
                "WithinMethodCorrelation(rescued_hard, rescued_easy)",
                -0.48,
            ),
            (
                "cross-method correlation of trial totals",
                "CrossMethodCorrelation(rescued_total)",
                -0.19,
            ),
        ];
        assert_eq!(rows.len(), expected.len());
        for (row, (name, stat, value)) in rows.iter().zip(expected) {
            assert_eq!((row.0.as_str(), row.1.as_str(), row.2), (name, stat, value));
        }
    }

    #[test]
    fn the_paper_targets_have_their_bands_and_tasks() {
        let t = paper_targets().targets();
        let bands: Vec<String> = t.iter().map(|t| t.band.to_string()).collect();
        assert_eq!(
            bands,
            [
                "± 0.6",
                "± 0.2",
                "± 15",
                "± 2",
                "± 2",
                "± 0.12",
                "± 0.04",
                "± 0.12",
                "± 3",
                "[3, 7]",
                "[2.5, 6.5]",
                "[3, 8]",
                "[3420, 5130]",
                "[1280, 1920]",
                "(-∞, 5]",
                "(-∞, 0.35]",
                "(-∞, -0.1]",
                "(-∞, 0.2]"
            ]
        );
        // The sheet's cost unit is an open choice: S1 and S2 are reported, not fitted, under
        // today's reading.
        let reported: Vec<&str> = t
            .iter()
            .filter(|t| t.report_only)
            .map(|t| t.name.as_str())
            .collect();
        assert_eq!(reported, ["energy per trial", "HP lost per trial"]);
        let paper = ["hard".to_string(), "easy".to_string()];
        assert!(applies_to(&paper));
        assert!(!applies_to(&["a".to_string()]));
    }

    #[test]
    fn statistics_are_pooled_over_methods() {
        let r = [
            trial("A", 6, (90, 60), (400.0, 500.0), (40.0, 300.0)),
            trial("A", 4, (70, 40), (300.0, 400.0), (20.0, 200.0)),
        ];
        let checked = check(&r);
        let value = |name: &str| checked.iter().find(|(t, _)| t.name == name).unwrap().1;
        let close = |a: f64, b: f64| (a - b).abs() < 1e-12;
        assert!(close(value("rounds per trial"), 5.0));
        assert!(close(value("easy / hard rescuees"), 80.0 / 50.0));
        assert!(close(value("rescuees per trial"), 130.0));
        assert!(close(value("easy rescuees per round"), 16.0));
        assert!(close(value("hard rescuees per round"), 10.0));
        assert!(close(value("hard HP / hard energy"), 250.0 / 450.0));
        assert!(close(value("easy HP / easy energy"), 30.0 / 350.0));
        assert!(close(value("hard / easy energy"), 450.0 / 350.0));
        assert!(close(value("hard / easy HP"), 250.0 / 30.0));
        // Totals 150 and 110: sample variance 800 within the one method.
        assert!(close(value("pooled SD of total rescuees"), 800f64.sqrt()));
        assert!(check(&[]).iter().all(|(_, x)| x.is_nan()));
        let mut other = r[0].clone();
        other.tasks = vec!["a".into(), "b".into()];
        // Without the tasks, every statistic that names one is undefined (and a pooled SD,
        // CV or correlation of one trial); rounds, total rescuees and total costs are not.
        for (t, x) in check(&[other]) {
            let defined = [
                "rounds per trial",
                "rescuees per trial",
                "energy per trial",
                "HP lost per trial",
            ]
            .contains(&t.name.as_str());
            assert_eq!(x.is_nan(), !defined, "{}", t.name);
        }
        assert!(checked[0].0.holds(6.8) && !checked[0].0.holds(6.81));
    }
}
