//! Calibration targets and the `TARGETS.ron` file that holds them.
//!
//! ```ron
//! Targets(
//!     targets: [
//!         // Source: ... (a comment per target)
//!         (name: "rounds per trial", statistic: Mean("rounds"), value: 6.2, band: PlusMinus(0.6)),
//!         (name: "pooled SD of total rescuees", statistic: PooledSd("rescued_total"),
//!          value: 4.69, band: Between(3.0, 7.0)),
//!     ],
//! )
//! ```
//!
//! Each target names a [`Statistic`] of a set of trials (metrics by their `trials.csv`
//! column names), the value it should have and the [`Band`] it must fall in. Errors are one
//! line naming the file, line, column and field: `paper-targets.ron:12:9:
//! targets[3].statistic: unknown metric "rescued_eazy" (metrics: ...)`.

use std::path::Path;

use serde::{Deserialize, Serialize};
use usar_sim::mission::TrialResult;
use usar_sweep::settings::Setting;

use super::band::Band;
use super::ron_file::{self, Source, StudyFile, check_name};
use super::statistic::Statistic;

/// Longest targets file read, bytes (1 MiB): a longer file is refused instead of read into
/// memory.
pub const MAX_TARGETS_BYTES: u64 = 1 << 20;

/// One target: a statistic, the value it should have, and the band it must fall in.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Target {
    /// What it is, for tables (`rounds per trial`); unique within a file, not empty, one line
    /// of at most [`ron_file::MAX_NAME_CHARS`] characters.
    pub name: String,
    /// The statistic, computed over a set of trials pooled over methods.
    pub statistic: Statistic,
    /// The value it should have (finite; inside the band).
    pub value: f64,
    /// Where the statistic is accepted.
    pub band: Band,
    /// Computed and reported (with whether it lies in its band) but left out of the loss and
    /// so of admissibility: a target known to conflict with the others, or one watched only
    /// (`report_only: true` in the file, or `--report-only NAME`); default `false`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub report_only: bool,
}

impl Target {
    /// Whether `x` lies in the band (boundaries included; never for NaN).
    pub fn holds(&self, x: f64) -> bool {
        self.band.holds(self.value, x)
    }

    /// `in` or `OUT` for statistic `x` ([`Target::holds`]), followed by `(reported)` for a
    /// [`Target::report_only`] target: how the tables mark it.
    pub fn mark(&self, x: f64) -> &'static str {
        match (self.holds(x), self.report_only) {
            (true, false) => "in",
            (false, false) => "OUT",
            (true, true) => "in (reported)",
            (false, true) => "OUT (reported)",
        }
    }

    /// The value and band as a table shows them: `6.2 ± 0.6`, `4.69 in [3, 7]`, `6 in [5, ∞)`.
    pub fn describe(&self) -> String {
        match self.band {
            Band::PlusMinus(_) => format!("{} {}", self.value, self.band),
            Band::Between(..) | Band::AtLeast(_) | Band::AtMost(_) => {
                format!("{} in {}", self.value, self.band)
            }
        }
    }

    /// The statistic over `results` ([`Statistic::value`]).
    pub fn value_of(&self, results: &[TrialResult]) -> f64 {
        self.statistic.value(results)
    }
}

/// Why targets could not be read or used: one line, `origin[:line:col]: [field: ]message`, the
/// [`Located`](ron_file::Located) error it wraps (its field is `targets[3].statistic` and the like).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(transparent)]
pub struct TargetsError(#[from] pub ron_file::Located);

/// A checked list of targets (at least one, names unique, every band usable, every metric
/// name a `trials.csv` column for some task names), with where it came from.
#[derive(Debug, Clone)]
pub struct Targets {
    source: Source,
    targets: Vec<Target>,
}

impl PartialEq for Targets {
    /// The same targets, wherever they were read from.
    fn eq(&self, other: &Self) -> bool {
        self.targets == other.targets
    }
}

/// The file's top level, `Targets(targets: [...])`, as read before [`Targets`] checks it.
#[derive(Deserialize)]
#[serde(rename = "Targets", deny_unknown_fields)]
pub struct TargetsFile {
    targets: Vec<Target>,
}

impl Targets {
    /// Checks `targets` (named `origin` in errors; no line numbers).
    ///
    /// # Errors
    /// As [`Targets::parse`] for the checks after parsing.
    pub fn new(targets: Vec<Target>, origin: &str) -> Result<Self, TargetsError> {
        let t = Self {
            source: Source::given(origin),
            targets,
        };
        t.check_file()?;
        Ok(t)
    }

    /// Parses and checks the RON text `src` of a targets file named `origin` in errors (a
    /// leading byte-order mark is skipped).
    ///
    /// # Errors
    /// RON syntax or shape (unknown field or statistic, missing field), with ron's line and
    /// column; no targets; a name that is empty, repeated, longer than
    /// [`ron_file::MAX_NAME_CHARS`] characters or holds a line break; an unknown metric (the message lists
    /// the metric names); a value that is not finite; a `PlusMinus` half-width that is not
    /// finite and > 0; a `Between` with bounds not finite or `low >= high`; a value outside
    /// its own `Between` band. Each names the line, column and field.
    pub fn parse(src: &str, origin: &str) -> Result<Self, TargetsError> {
        Self::parse_checked(src, origin)
    }

    /// Reads and parses the targets file at `path` (named in errors as given).
    ///
    /// # Errors
    /// The file cannot be read, is longer than [`MAX_TARGETS_BYTES`] or is not UTF-8; else as
    /// [`Targets::parse`].
    pub fn load(path: &Path) -> Result<Self, TargetsError> {
        Self::load_checked(path)
    }

    /// The targets, in file order.
    pub fn targets(&self) -> &[Target] {
        &self.targets
    }

    /// Marks the targets called `names` [`Target::report_only`] (`--report-only NAME`).
    ///
    /// # Errors
    /// A name no target has (the message lists the names there are), or every target left
    /// out of the loss (nothing would be fitted).
    pub fn set_report_only(&mut self, names: &[String]) -> Result<(), TargetsError> {
        self.mark(names, Setting::ReportOnly, true)?;
        self.check_some_fitted()
    }

    /// Fits the targets called `required` and leaves out those called `report_only`, then
    /// checks once that some target is fitted (a multiverse universe's flags, from every axis
    /// at once: `Axes::universe_targets` of the multiverse).
    ///
    /// # Errors
    /// As [`Targets::set_report_only`].
    pub fn set_flags(
        &mut self,
        required: &[String],
        report_only: &[String],
    ) -> Result<(), TargetsError> {
        self.mark(required, Setting::Require, false)?;
        self.mark(report_only, Setting::ReportOnly, true)?;
        self.check_some_fitted()
    }

    /// Puts the targets called `names` back into the loss although the file marks them
    /// `report_only: true` (`--require NAME`; e.g. the paper's energy and HP per trial under
    /// the reading that the sheet's costs are percentage points of a full level).
    ///
    /// # Errors
    /// A name no target has (the message lists the names there are).
    pub fn set_required(&mut self, names: &[String]) -> Result<(), TargetsError> {
        self.mark(names, Setting::Require, false)?;
        self.check_some_fitted()
    }

    fn mark(
        &mut self,
        names: &[String],
        flag: Setting,
        report_only: bool,
    ) -> Result<(), TargetsError> {
        let fail = |message: String| TargetsError::from(self.source.whole_error(message));
        for name in names {
            let Some(i) = self.targets.iter().position(|t| &t.name == name) else {
                let known: Vec<String> = self
                    .targets
                    .iter()
                    .map(|t| format!("{:?}", t.name))
                    .collect();
                return Err(fail(format!(
                    "{flag} {name:?}: no target has that name (targets: {})",
                    known.join(", ")
                )));
            };
            self.targets[i].report_only = report_only;
        }
        Ok(())
    }

    /// Refuses targets that are all report-only (nothing would be fitted).
    fn check_some_fitted(&self) -> Result<(), TargetsError> {
        if self.targets.iter().all(|t| t.report_only) {
            return Err(self
                .source
                .whole_error(format!(
                    "every target is report-only ({}): at least one must be fitted",
                    Setting::ReportOnly
                ))
                .into());
        }
        Ok(())
    }

    /// Where they were read from (a path as given, or the origin given to [`Targets::new`]).
    pub fn origin(&self) -> &str {
        self.source.origin()
    }

    /// Checks that every metric of every target exists for a scenario with task names
    /// `tasks` (a calibration does this before it runs anything).
    ///
    /// # Errors
    /// The first metric naming a task not in `tasks`, at the target's statistic, naming the
    /// target and the scenario's tasks.
    pub fn check_tasks(&self, tasks: &[String]) -> Result<(), TargetsError> {
        for (i, t) in self.targets.iter().enumerate() {
            for m in t.statistic.metrics() {
                m.resolve(tasks).map_err(|e| {
                    self.error(
                        &format!("targets[{i}].statistic"),
                        format!("target {:?}: {e}", t.name),
                    )
                })?;
            }
        }
        Ok(())
    }

    /// [`Targets::check_tasks`] against the task names `tasks` of the scenario read from
    /// `scenario` (a path as given), which the error names (`...; scenario: PATH`).
    ///
    /// # Errors
    /// As [`Targets::check_tasks`], with the scenario after the message
    /// ([`ron_file::Located::in_scenario`]).
    pub fn check_tasks_of_scenario(
        &self,
        tasks: &[String],
        scenario: &str,
    ) -> Result<(), TargetsError> {
        self.check_tasks(tasks)
            .map_err(|e| TargetsError(e.0.in_scenario(scenario)))
    }

    /// Whether every metric of every target exists for task names `tasks`.
    pub fn apply_to(&self, tasks: &[String]) -> bool {
        self.check_tasks(tasks).is_ok()
    }

    /// Each target's statistic over `results`, in target order.
    pub fn values(&self, results: &[TrialResult]) -> Vec<f64> {
        self.targets.iter().map(|t| t.value_of(results)).collect()
    }

    /// An error about `field`, placed where the field is in the file when known.
    fn error(&self, field: &str, message: String) -> TargetsError {
        self.source.error(field, message).into()
    }
}

impl StudyFile for Targets {
    type File = TargetsFile;
    type Error = TargetsError;
    const MAX_BYTES: u64 = MAX_TARGETS_BYTES;
    const KIND: &'static str = "a targets file";

    fn from_file(file: TargetsFile, source: Source) -> Self {
        Self {
            source,
            targets: file.targets,
        }
    }

    fn check_file(&self) -> Result<(), TargetsError> {
        if self.targets.is_empty() {
            return Err(self.error("targets", "no targets: give at least one".into()));
        }
        for (i, t) in self.targets.iter().enumerate() {
            let at = |field: &str| format!("targets[{i}].{field}");
            check_name(&t.name, "target").map_err(|m| self.error(&at("name"), m))?;
            if let Some(j) = self.targets[..i].iter().position(|o| o.name == t.name) {
                return Err(self.error(
                    &at("name"),
                    format!("duplicate name {:?} (targets[{j}] has it too)", t.name),
                ));
            }
            for m in t.statistic.metrics() {
                m.task().map_err(|e| self.error(&at("statistic"), e))?;
            }
            if !t.value.is_finite() {
                return Err(self.error(
                    &at("value"),
                    format!("expected a finite number, found {}", t.value),
                ));
            }
            if let Some(p) = t.band.problem(t.value) {
                return Err(self.error(&at("band"), p));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = "// Targets of a test\nTargets(\n    targets: [\n        \
        (name: \"rounds\", statistic: Mean(\"rounds\"), value: 6.2, band: PlusMinus(0.6)),\n        \
        (name: \"easy / hard\", statistic: RatioOfMeans(\"rescued_easy\", \"rescued_hard\"),\n         \
        value: 1.36, band: PlusMinus(0.2)),\n        \
        (name: \"sd\", statistic: PooledSd(\"rescued_total\"), value: 4.69, band: Between(3.0, 7.0)),\n    \
        ],\n)\n";

    fn err(src: &str) -> String {
        Targets::parse(src, "t.ron").unwrap_err().to_string()
    }

    #[test]
    fn a_good_file_parses_in_order() {
        let t = Targets::parse(GOOD, "t.ron").unwrap();
        let names: Vec<&str> = t.targets().iter().map(|t| t.name.as_str()).collect();
        assert_eq!(names, ["rounds", "easy / hard", "sd"]);
        assert_eq!(t.targets()[2].band, Band::Between(3.0, 7.0));
        assert_eq!(t.targets()[0].describe(), "6.2 ± 0.6");
        assert_eq!(t.targets()[2].describe(), "4.69 in [3, 7]");
        assert!(t.targets()[0].holds(6.8) && !t.targets()[0].holds(6.81));
        assert_eq!(t.origin(), "t.ron");
        // The struct name is optional, as in any RON file, and a byte-order mark is skipped.
        let bare = GOOD.replace("Targets(", "(");
        assert_eq!(Targets::parse(&format!("\u{feff}{bare}"), "u").unwrap(), t);
        let tasks = vec!["hard".to_string(), "easy".to_string()];
        assert!(t.apply_to(&tasks));
    }

    #[test]
    fn every_error_names_line_column_and_field() {
        let cases = [
            (
                GOOD.replace("Mean(\"rounds\")", "Median(\"rounds\")"),
                "t.ron:4:37: targets[0].statistic: Unexpected variant named `Median` in enum \
                 `Statistic`",
            ),
            (
                GOOD.replace("value: 6.2,", "value: 6.2, weight: 2,"),
                "t.ron:4:65: targets[0].weight: Unexpected field named `weight` in `Target`",
            ),
            (
                GOOD.replace("\"rescued_easy\"", "\"rescuedeasy\""),
                "t.ron:5:31: targets[1].statistic: unknown metric \"rescuedeasy\"",
            ),
            (
                GOOD.replace("\"rounds\")", "\"round\")"),
                "t.ron:4:26: targets[0].statistic: unknown metric \"round\" (metrics: \
                 rescued_total, rescued_<task>,",
            ),
            (
                GOOD.replace("PlusMinus(0.6)", "PlusMinus(0.0)"),
                "t.ron:4:65: targets[0].band: PlusMinus(0): the half-width must be a finite \
                 number > 0",
            ),
            (
                GOOD.replace("PlusMinus(0.6)", "PlusMinus(inf)"),
                "t.ron:4:65: targets[0].band: PlusMinus(inf): the half-width must be",
            ),
            (
                GOOD.replace("Between(3.0, 7.0)", "Between(7.0, 3.0)"),
                "t.ron:7:73: targets[2].band: Between(7, 3): the low bound must be below the \
                 high one",
            ),
            (
                GOOD.replace("Between(3.0, 7.0)", "Between(5.0, 7.0)"),
                "t.ron:7:73: targets[2].band: the target's value 4.69 lies outside its own band",
            ),
            (
                GOOD.replace("value: 6.2", "value: NaN"),
                "t.ron:4:53: targets[0].value: expected a finite number, found NaN",
            ),
            (
                GOOD.replace("name: \"sd\"", "name: \"rounds\""),
                "t.ron:7:10: targets[2].name: duplicate name \"rounds\" (targets[0] has it too)",
            ),
            (
                GOOD.replace("name: \"sd\"", "name: \" \""),
                "t.ron:7:10: targets[2].name: empty target name",
            ),
            // Regression (issue 70): a name of 65,536 characters was read, and its padding
            // in the calibration's summary panicked; a line break split its table row.
            (
                GOOD.replace("name: \"sd\"", &format!("name: \"{}\"", "s".repeat(201))),
                "t.ron:7:10: targets[2].name: target name of 201 characters, longer than the \
                 limit of 200",
            ),
            (
                GOOD.replace("name: \"sd\"", "name: \"s\\nd\""),
                "t.ron:7:10: targets[2].name: target name \"s\\nd\" holds a control character",
            ),
            // Regression (issue 70): numbers were written in full, 309 digits for 1e308.
            (
                GOOD.replace("value: 4.69", "value: 1e308"),
                "t.ron:7:74: targets[2].band: the target's value 1e308 lies outside its own \
                 band Between(3, 7)",
            ),
            (
                GOOD.replace("PlusMinus(0.6)", "PlusMinus(1e308)")
                    .replace("6.2", "1e308"),
                "t.ron:4:67: targets[0].band: PlusMinus(1e308): the band around 1e308 reaches \
                 past the largest number",
            ),
            // Regression (issue 70): reported at the target's last field.
            (
                GOOD.replace("value: 6.2, ", ""),
                "t.ron:4:9: targets[0]: missing field `value`",
            ),
            (
                "Targets(targets: [])".to_string(),
                "t.ron:1:9: targets: no targets: give at least one",
            ),
            (
                GOOD.replace("],\n)", "],\n"),
                "t.ron:8:7: Unexpected end of RON",
            ),
        ];
        for (src, says) in cases {
            let e = err(&src);
            assert!(
                e.starts_with(says),
                "{e}\nexpected it to start with\n{says}"
            );
            assert!(!e.contains('\n'), "{e}");
        }
    }

    #[test]
    fn targets_are_made_report_only_by_name_or_in_the_file() {
        let mut t = Targets::parse(GOOD, "t.ron").unwrap();
        t.set_report_only(&["sd".into()]).unwrap();
        let only: Vec<bool> = t.targets().iter().map(|t| t.report_only).collect();
        assert_eq!(only, [false, false, true]);
        assert_eq!(t.targets()[2].mark(9.0), "OUT (reported)");
        assert_eq!(t.targets()[0].mark(6.2), "in");
        let e = t.set_report_only(&["SD".into()]).unwrap_err().to_string();
        assert_eq!(
            e,
            "t.ron: --report-only \"SD\": no target has that name (targets: \"rounds\", \
             \"easy / hard\", \"sd\")"
        );
        let e = t
            .set_report_only(&["rounds".into(), "easy / hard".into()])
            .unwrap_err()
            .to_string();
        assert!(e.contains("at least one must be fitted"), "{e}");
        let in_file = GOOD.replace(
            "Between(3.0, 7.0))",
            "Between(3.0, 7.0), report_only: true)",
        );
        let t = Targets::parse(&in_file, "t.ron").unwrap();
        assert!(t.targets()[2].report_only && !t.targets()[0].report_only);
    }

    #[test]
    fn a_missing_task_names_the_target() {
        let t = Targets::parse(GOOD, "t.ron").unwrap();
        let tasks = vec!["hard".to_string(), "medium".to_string()];
        let e = t.check_tasks(&tasks).unwrap_err().to_string();
        assert_eq!(
            e,
            "t.ron:5:31: targets[1].statistic: target \"easy / hard\": metric \"rescued_easy\" \
             is about task \"easy\", which the scenario does not have (its tasks: hard, medium)"
        );
        assert!(!t.apply_to(&tasks));
        // Targets made in code have no line numbers.
        let made = Targets::new(t.targets().to_vec(), "<code>").unwrap();
        let e = made.check_tasks(&tasks).unwrap_err().to_string();
        assert!(e.starts_with("<code>: targets[1].statistic: target"), "{e}");
        assert!(Targets::new(vec![], "<code>").is_err());
    }

    #[test]
    fn an_unreadable_or_huge_file_is_one_line() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("none.ron");
        let e = Targets::load(&missing).unwrap_err().to_string();
        assert!(e.contains("none.ron: cannot read targets file: "), "{e}");
        let path = dir.path().join("t.ron");
        std::fs::write(&path, GOOD).unwrap();
        assert_eq!(Targets::load(&path).unwrap().targets().len(), 3);
        std::fs::write(&path, b"\xff\xfe").unwrap();
        let e = Targets::load(&path).unwrap_err().to_string();
        assert!(
            e.ends_with("t.ron: not UTF-8 text; a targets file is RON text"),
            "{e}"
        );
    }
}
