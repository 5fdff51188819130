//! The axes file of `usar multiverse` (`AXES.ron`): the open choices of the paper, each with
//! the paper's own words and its alternatives, an alternative being a list of `FIELD=VALUE`
//! overrides as `usar check --set` takes them ([`usar_sweep::vary::Override`]).
//!
//! ```ron
//! Axes(
//!     axes: [
//!         (
//!             name: "hp effect",
//!             paper: "\"the lower its HP, the smaller its velocity, sensing, and observing range\" (VI.B)",
//!             alternatives: [
//!                 (name: "linear", set: ["mission.hp_effect=Linear"]),
//!                 (name: "none", set: ["mission.hp_effect=NoEffect"]),
//!             ],
//!         ),
//!     ],
//! )
//! ```
//!
//! [`Axes::parse`] checks what the file alone can tell: RON syntax and shape, at least one
//! axis and one alternative per axis, names that are not empty, unique and not a fixed
//! column of `multiverse.csv` ([`super::columns`]), overrides that parse, no field set twice
//! by one alternative, and no field set by two axes. What needs the scenario (a field that
//! does not exist, a value that breaks a rule) is checked by [`super::validate`]. Every error
//! is one line naming the file, line, column and field:
//! `axes.ron:12:21: axes[1].alternatives[0].set[1]: ...`.

use std::path::Path;

use serde::{Deserialize, Serialize};

use super::columns::is_fixed_column;
use usar_report::targets::ron_file::{self, Source, StudyFile, check_name};
use usar_sweep::vary::{FieldPath, Override};

/// Longest axes file read, bytes (1 MiB): a longer file is refused instead of read into
/// memory.
pub const MAX_AXES_BYTES: u64 = 1 << 20;

/// One alternative of an axis: its name and the overrides that make it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Alternative {
    /// Its name, unique within the axis, not empty, one line of at most
    /// [`ron_file::MAX_NAME_CHARS`] characters (`linear`); the value of the axis's column in
    /// `multiverse.csv`.
    pub name: String,
    /// `FIELD=VALUE` overrides applied to the base scenario, in order (`[]`: the base
    /// scenario's own values). FIELD is a path as `--vary` takes it, VALUE is RON.
    #[serde(default)]
    pub set: Vec<String>,
    /// Names of targets (of `--targets`) fitted in this alternative's universes although the
    /// file marks them `report_only`, as `usar calibrate --require NAME` (default none). For a
    /// choice that decides which targets a reading can be held to (the sheet's cost unit).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub require: Vec<String>,
    /// Names of targets left out of the loss in this alternative's universes, as `usar
    /// calibrate --report-only NAME` (default none).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub report_only: Vec<String>,
}

/// One open choice and its alternatives.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Axis {
    /// Its name, unique, not empty, one line of at most [`ron_file::MAX_NAME_CHARS`]
    /// characters (`hp effect`); the name of its column in `multiverse.csv`.
    pub name: String,
    /// What the paper says about it, quoted, and where (default empty).
    #[serde(default)]
    pub paper: String,
    /// Its alternatives, at least one.
    pub alternatives: Vec<Alternative>,
}

/// A checked axes file: at least one axis, names unique, overrides that parse, every field
/// set by one axis only.
#[derive(Debug, Clone, Serialize, Deserialize)]
#[serde(rename = "Axes", deny_unknown_fields)]
pub struct Axes {
    /// The axes, in file order (the first varies slowest in universe order).
    pub axes: Vec<Axis>,
    #[serde(skip)]
    source: Source,
}

impl PartialEq for Axes {
    /// The same axes, wherever they were read from.
    fn eq(&self, other: &Self) -> bool {
        self.axes == other.axes
    }
}

/// Why an axes file cannot be used: one line, `origin[:line:col]: [field: ]message`, the
/// [`Located`](ron_file::Located) error it wraps (its field is
/// `axes[1].alternatives[0].set[1]` and the like).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(transparent)]
pub struct AxesError(#[from] pub ron_file::Located);

impl Axes {
    /// Checks `axes` (named `origin` in errors; no line numbers), as [`Axes::parse`] does
    /// after parsing.
    ///
    /// # Errors
    /// As [`Axes::parse`] for the checks after parsing.
    pub fn new(axes: Vec<Axis>, origin: &str) -> Result<Self, AxesError> {
        let a = Self {
            axes,
            source: Source::given(origin),
        };
        a.check_file()?;
        Ok(a)
    }

    /// Parses and checks the RON text `src` of an axes file named `origin` in errors (a
    /// leading byte-order mark is skipped).
    ///
    /// # Errors
    /// RON syntax or shape (an unknown or missing field), with ron's line and column; no
    /// axis; an axis without alternatives; an empty or repeated axis name, or one that names
    /// a fixed column of `multiverse.csv`; an empty or repeated alternative name within an
    /// axis; a name longer than [`ron_file::MAX_NAME_CHARS`] characters or holding a control
    /// character; an override that is not `FIELD=VALUE` (a bad path or RON value); one alternative
    /// setting a field twice; two axes setting the same field (or overlapping ones, such as
    /// `kinds[*].count` and `kinds[0].count`). Each names the line, column and field.
    pub fn parse(src: &str, origin: &str) -> Result<Self, AxesError> {
        Self::parse_checked(src, origin)
    }

    /// Reads and parses the axes file at `path` (named in errors as given).
    ///
    /// # Errors
    /// The file cannot be read, is longer than [`MAX_AXES_BYTES`] or is not UTF-8; else as
    /// [`Axes::parse`].
    pub fn load(path: &Path) -> Result<Self, AxesError> {
        Self::load_checked(path)
    }

    /// Where the axes were read from (a path as given, or the origin given to [`Axes::new`]).
    pub fn origin(&self) -> &str {
        self.source.origin()
    }

    /// The number of alternatives of each axis, in axis order.
    pub fn sizes(&self) -> Vec<usize> {
        self.axes.iter().map(|a| a.alternatives.len()).collect()
    }

    /// The overrides of alternative `alt` of axis `axis`, parsed (they parsed when the axes
    /// were checked).
    ///
    /// # Panics
    /// If `axis` or `alt` is out of range (a programming error).
    pub fn overrides(&self, axis: usize, alt: usize) -> Vec<Override> {
        self.axes[axis].alternatives[alt]
            .set
            .iter()
            .filter_map(|s| Override::parse(s).ok())
            .collect()
    }

    /// The overrides of a universe that takes alternative `choices[i]` of axis `i`, axis
    /// by axis.
    ///
    /// # Panics
    /// If `choices` does not have one valid index per axis (a programming error).
    pub fn universe_overrides(&self, choices: &[usize]) -> Vec<Override> {
        choices
            .iter()
            .enumerate()
            .flat_map(|(axis, &alt)| self.overrides(axis, alt))
            .collect()
    }

    /// An error about `field` (a path in the file, `axes[1].name`), placed where the field
    /// is in the file when known.
    pub fn error(&self, field: &str, message: String) -> AxesError {
        self.source.error(field, message).into()
    }

    /// One axis's names and overrides.
    fn check_axis(&self, i: usize, axis: &Axis) -> Result<(), AxesError> {
        let at = |f: &str| format!("axes[{i}].{f}");
        check_name(&axis.name, "axis").map_err(|m| self.error(&at("name"), m))?;
        if is_fixed_column(&axis.name) {
            return Err(self.error(
                &at("name"),
                format!(
                    "{:?} is a column of multiverse.csv already: name the axis otherwise",
                    axis.name
                ),
            ));
        }
        if let Some(j) = self.axes[..i].iter().position(|a| a.name == axis.name) {
            return Err(self.error(
                &at("name"),
                format!("axis {:?} is given twice (also axes[{j}])", axis.name),
            ));
        }
        if axis.alternatives.is_empty() {
            return Err(self.error(
                &at("alternatives"),
                format!("axis {:?} has no alternative: give at least one", axis.name),
            ));
        }
        for (k, alt) in axis.alternatives.iter().enumerate() {
            let at = |f: &str| format!("axes[{i}].alternatives[{k}].{f}");
            check_name(&alt.name, "alternative").map_err(|m| self.error(&at("name"), m))?;
            if let Some(m) = axis.alternatives[..k]
                .iter()
                .position(|a| a.name == alt.name)
            {
                return Err(self.error(
                    &at("name"),
                    format!(
                        "axis {:?}: alternative {:?} is given twice (also alternatives[{m}])",
                        axis.name, alt.name
                    ),
                ));
            }
            self.check_overrides(i, k)?;
            self.check_target_names(i, k)?;
        }
        Ok(())
    }

    /// The overrides of alternative `k` of axis `i` parse, and set each field once.
    fn check_overrides(&self, i: usize, k: usize) -> Result<(), AxesError> {
        let (axis, alt) = (&self.axes[i], &self.axes[i].alternatives[k]);
        let mut paths: Vec<FieldPath> = Vec::new();
        for (j, text) in alt.set.iter().enumerate() {
            let field = format!("axes[{i}].alternatives[{k}].set[{j}]");
            let who = format!("axis {:?}, alternative {:?}", axis.name, alt.name);
            let o = Override::parse(text).map_err(|e| {
                self.error(
                    &field,
                    format!("{who}: {}: {e}", usar_sweep::vary::brief(text.trim())),
                )
            })?;
            if let Some(p) = paths.iter().position(|p| p.overlaps(&o.path)) {
                return Err(self.error(
                    &field,
                    format!(
                        "{who}: {} is set twice (also set[{p}]): set each field once",
                        o.path
                    ),
                ));
            }
            paths.push(o.path);
        }
        Ok(())
    }

    /// No field (or overlapping pair of fields) is set by two axes.
    fn check_fields_belong_to_one_axis(&self) -> Result<(), AxesError> {
        // (axis, path) of every override seen so far.
        let mut seen: Vec<(usize, FieldPath)> = Vec::new();
        for (i, axis) in self.axes.iter().enumerate() {
            let mut own: Vec<(usize, FieldPath)> = Vec::new();
            for (k, alt) in axis.alternatives.iter().enumerate() {
                for (j, o) in self.overrides(i, k).into_iter().enumerate() {
                    if let Some((other, p)) = seen.iter().find(|(_, p)| p.overlaps(&o.path)) {
                        return Err(self.error(
                            &format!("axes[{i}].alternatives[{k}].set[{j}]"),
                            format!(
                                "axis {:?}, alternative {:?}: {} is set by axis {:?} too \
                                 ({p}): each field belongs to one axis",
                                axis.name, alt.name, o.path, self.axes[*other].name
                            ),
                        ));
                    }
                    own.push((i, o.path));
                }
            }
            seen.extend(own);
        }
        Ok(())
    }
}

impl StudyFile for Axes {
    type File = Axes;
    type Error = AxesError;
    const MAX_BYTES: u64 = MAX_AXES_BYTES;
    const KIND: &'static str = "an axes file";

    fn from_file(file: Axes, source: Source) -> Self {
        Self { source, ..file }
    }

    fn check_file(&self) -> Result<(), AxesError> {
        if self.axes.is_empty() {
            return Err(self.error("axes", "no axis: give at least one".into()));
        }
        for (i, axis) in self.axes.iter().enumerate() {
            self.check_axis(i, axis)?;
        }
        self.check_fields_belong_to_one_axis()?;
        self.check_targets_belong_to_one_axis()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"// Two axes.
Axes(
    axes: [
        (
            name: "hp effect",
            paper: "\"the lower its HP, the smaller its velocity\" (VI.B)",
            alternatives: [
                (name: "linear", set: ["mission.hp_effect=Linear"]),
                (name: "threshold", set: ["mission.hp_effect=Threshold(below_pct: 50.0, factor: 0.6)"]),
                (name: "none", set: ["mission.hp_effect=NoEffect"]),
            ],
        ),
        (
            name: "energy cost",
            alternatives: [
                (name: "per metre", set: ["mission.energy_pct_per_m=0.1", "mission.energy_pct_per_moving_step=0.0"]),
                (name: "base"),
            ],
        ),
    ],
)
"#;

    fn err(src: &str) -> String {
        Axes::parse(src, "a.ron").unwrap_err().to_string()
    }

    #[test]
    fn a_good_file_parses_with_defaults() {
        let a = Axes::parse(GOOD, "a.ron").unwrap();
        assert_eq!(a.sizes(), [3, 2]);
        assert_eq!(a.axes[1].paper, "");
        assert!(a.axes[1].alternatives[1].set.is_empty());
        assert!(a.axes[0].paper.starts_with("\"the lower"));
        let o = a.universe_overrides(&[1, 0]);
        let texts: Vec<String> = o.iter().map(ToString::to_string).collect();
        assert_eq!(
            texts,
            [
                "mission.hp_effect=Threshold(below_pct: 50.0, factor: 0.6)",
                "mission.energy_pct_per_m=0.1",
                "mission.energy_pct_per_moving_step=0.0",
            ]
        );
        assert_eq!(a.origin(), "a.ron");
        // The serialised form reads back (the plan keeps the axes as JSON).
        let json = serde_json::to_string(&a).unwrap();
        let back: Axes = serde_json::from_str(&json).unwrap();
        assert_eq!(back, a);
    }

    #[test]
    fn syntax_and_shape_errors_have_a_line_and_column() {
        let e = err("Axes(axes: [(name: \"a\", alternatives: [(name: \"x\" set: [])])])");
        assert!(e.starts_with("a.ron:1:"), "{e}");
        let e = err("Axes(\n    axes: [\n        (name: \"a\", alternative: []),\n    ],\n)");
        assert!(e.starts_with("a.ron:3:"), "{e}");
        assert!(e.contains("alternative"), "{e}");
        assert!(!e.contains('\n'), "{e}");
    }

    #[test]
    fn empty_and_repeated_things_are_refused_where_they_are() {
        assert_eq!(
            err("Axes(axes: [])"),
            "a.ron:1:6: axes: no axis: give at least one"
        );
        let e = err("Axes(axes: [\n  (name: \"a\", alternatives: []),\n])");
        assert_eq!(
            e,
            "a.ron:2:15: axes[0].alternatives: axis \"a\" has no alternative: give at least one"
        );
        let two = "Axes(axes: [\n  (name: \"a\", alternatives: [(name: \"x\")]),\n  (name: \"a\", \
                   alternatives: [(name: \"y\")]),\n])";
        assert_eq!(
            err(two),
            "a.ron:3:4: axes[1].name: axis \"a\" is given twice (also axes[0])"
        );
        let alts =
            "Axes(axes: [\n  (name: \"a\", alternatives: [(name: \"x\"), (name: \"x\")]),\n])";
        assert_eq!(
            err(alts),
            "a.ron:2:44: axes[0].alternatives[1].name: axis \"a\": alternative \"x\" is given \
             twice (also alternatives[0])"
        );
        let blank = "Axes(axes: [(name: \" \", alternatives: [(name: \"x\")])])";
        assert!(err(blank).contains("axes[0].name: empty axis name"));
        let tab = "Axes(axes: [(name: \"a\\tb\", alternatives: [(name: \"x\")])])";
        assert!(
            err(tab).contains("axes[0].name: axis name \"a\\tb\" holds a control character"),
            "{}",
            err(tab)
        );
        // Regression (issue 70): names of any length were read, and printed padded.
        let long = "x".repeat(201);
        let e = err(&format!(
            "Axes(axes: [(name: \"a\", alternatives: [(name: \"{long}\")])])"
        ));
        assert_eq!(
            e,
            "a.ron:1:41: axes[0].alternatives[0].name: alternative name of 201 characters, \
             longer than the limit of 200"
        );
        let e = err(&format!(
            "Axes(axes: [(name: \"{long}\", alternatives: [(name: \"x\")])])"
        ));
        assert!(
            e.contains("axes[0].name: axis name of 201 characters"),
            "{e}"
        );
        let most = "x".repeat(200);
        let fine = format!("Axes(axes: [(name: \"{most}\", alternatives: [(name: \"{most}\")])])");
        assert!(Axes::parse(&fine, "a.ron").is_ok());
        let column = "Axes(axes: [(name: \"loss\", alternatives: [(name: \"x\")])])";
        assert!(
            err(column).contains("\"loss\" is a column of multiverse.csv already"),
            "{}",
            err(column)
        );
    }

    #[test]
    fn overrides_must_parse_and_set_each_field_once() {
        let bad = "Axes(axes: [(name: \"a\", alternatives: [\n  (name: \"x\", set: [\"mission.pickup_s=1\", \"mission.pickup_s\"]),\n])])";
        assert_eq!(
            err(bad),
            "a.ron:2:43: axes[0].alternatives[0].set[1]: axis \"a\", alternative \"x\": \
             mission.pickup_s: expected FIELD=VALUE"
        );
        let twice = "Axes(axes: [(name: \"a\", alternatives: [\n  (name: \"x\", set: [\"kinds[*].count=1\", \"kinds[0].count=2\"]),\n])])";
        assert!(
            err(twice)
                .contains("set[1]: axis \"a\", alternative \"x\": kinds[0].count is set twice"),
            "{}",
            err(twice)
        );
        let shared = "Axes(axes: [\n  (name: \"a\", alternatives: [(name: \"x\", set: [\"mission.pickup_s=1\"])]),\n  (name: \"b\", alternatives: [(name: \"y\", set: [\"mission.recharge_s=1\", \"mission.pickup_s=2\"])]),\n])";
        assert_eq!(
            err(shared),
            "a.ron:3:72: axes[1].alternatives[0].set[1]: axis \"b\", alternative \"y\": \
             mission.pickup_s is set by axis \"a\" too (mission.pickup_s): each field belongs to \
             one axis"
        );
    }

    #[test]
    fn a_file_that_cannot_be_read_as_text_is_one_line() {
        let e = Axes::load(Path::new("/no/such/axes.ron"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("/no/such/axes.ron: cannot read axes file: "),
            "{e}"
        );
        let dir = tempfile::tempdir().unwrap();
        let bytes = dir.path().join("bytes.ron");
        std::fs::write(&bytes, [b'A', 0xff, b'(']).unwrap();
        let e = Axes::load(&bytes).unwrap_err().to_string();
        assert!(
            e.ends_with("bytes.ron: not UTF-8 text; an axes file is RON text"),
            "{e}"
        );
    }
}
