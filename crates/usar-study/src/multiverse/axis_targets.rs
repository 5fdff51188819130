//! An axis alternative's target flags ([`Alternative::require`], [`Alternative::report_only`]):
//! a choice of the paper that decides which targets a reading can be held to. The sheet's cost
//! unit is one (`scenarios/paper-axes.ron`, "the sheet's cost unit"): read as percentage points
//! of a full level, the sheet's energy and HP per trial are targets; read as of unknown unit,
//! they are only reported (`docs/calibration.md`, "The eighteen targets").
//!
//! What the axes file alone can tell is checked here ([`Axes::parse`]): names not empty, none
//! in both lists of one alternative or twice in one list, and no target flagged by two axes.
//! That every name is a target is checked against the targets file
//! ([`super::validate::check_axis_targets`]).

use super::axes::{Alternative, Axes, AxesError};
use usar_report::targets::file::{Targets, TargetsError};

impl Axes {
    /// The targets of a universe that takes alternative `choices[i]` of axis `i`: `base` with
    /// every chosen alternative's [`Alternative::require`] fitted and
    /// [`Alternative::report_only`] left out (each target belongs to one axis, so the order
    /// does not matter), checked once.
    ///
    /// # Errors
    /// A name no target has, or every target left out of the loss (see
    /// [`Targets::set_report_only`]).
    ///
    /// # Panics
    /// If `choices` does not have one valid index per axis (a programming error).
    pub fn universe_targets(
        &self,
        choices: &[usize],
        base: &Targets,
    ) -> Result<Targets, TargetsError> {
        let mut targets = base.clone();
        let (mut required, mut report_only) = (Vec::new(), Vec::new());
        for (axis, &alt) in choices.iter().enumerate() {
            let a = &self.axes[axis].alternatives[alt];
            required.extend(a.require.iter().cloned());
            report_only.extend(a.report_only.iter().cloned());
        }
        targets.set_flags(&required, &report_only)?;
        Ok(targets)
    }

    /// Whether any alternative flags a target.
    pub fn flags_targets(&self) -> bool {
        self.axes
            .iter()
            .flat_map(|a| &a.alternatives)
            .any(|a| !a.require.is_empty() || !a.report_only.is_empty())
    }

    /// The target names of alternative `k` of axis `i`: not blank, none twice.
    pub(super) fn check_target_names(&self, i: usize, k: usize) -> Result<(), AxesError> {
        let (axis, alt) = (&self.axes[i], &self.axes[i].alternatives[k]);
        let who = format!("axis {:?}, alternative {:?}", axis.name, alt.name);
        let mut seen: Vec<(&str, String)> = Vec::new();
        for (field, j, name) in flagged(alt) {
            let at = format!("axes[{i}].alternatives[{k}].{field}[{j}]");
            if name.trim().is_empty() {
                return Err(self.error(&at, format!("{who}: an empty target name")));
            }
            if let Some((_, other)) = seen.iter().find(|(n, _)| *n == name) {
                return Err(self.error(
                    &at,
                    format!("{who}: target {name:?} is named twice (also {other})"),
                ));
            }
            seen.push((name, format!("{field}[{j}]")));
        }
        Ok(())
    }

    /// No target is flagged by two axes (the universe's flags would depend on axis order).
    pub(super) fn check_targets_belong_to_one_axis(&self) -> Result<(), AxesError> {
        let mut seen: Vec<(usize, &str)> = Vec::new();
        for (i, axis) in self.axes.iter().enumerate() {
            let mut own: Vec<(usize, &str)> = Vec::new();
            for (k, alt) in axis.alternatives.iter().enumerate() {
                for (field, j, name) in flagged(alt) {
                    if let Some((other, _)) = seen.iter().find(|(_, n)| *n == name) {
                        return Err(self.error(
                            &format!("axes[{i}].alternatives[{k}].{field}[{j}]"),
                            format!(
                                "axis {:?}, alternative {:?}: target {name:?} is flagged by \
                                 axis {:?} too: each target belongs to one axis",
                                axis.name, alt.name, self.axes[*other].name
                            ),
                        ));
                    }
                    own.push((i, name));
                }
            }
            seen.extend(own);
        }
        Ok(())
    }
}

/// `(list, index, name)` of every target name an alternative flags: `require` then
/// `report_only`.
fn flagged(alt: &Alternative) -> impl Iterator<Item = (&'static str, usize, &str)> {
    alt.require
        .iter()
        .enumerate()
        .map(|(j, n)| ("require", j, n.as_str()))
        .chain(
            alt.report_only
                .iter()
                .enumerate()
                .map(|(j, n)| ("report_only", j, n.as_str())),
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(axes: &str) -> Result<Axes, String> {
        Axes::parse(&format!("Axes(axes: [{axes}])"), "a.ron").map_err(|e| e.to_string())
    }

    #[test]
    fn a_target_is_named_once_per_alternative_and_by_one_axis() {
        let ok = parse(
            "(name: \"unit\", alternatives: [(name: \"unknown\"), (name: \"points\", require: \
             [\"energy\", \"hp\"])])",
        )
        .unwrap();
        assert!(ok.flags_targets());
        let e = parse(
            "(name: \"unit\", alternatives: [(name: \"p\", require: [\"energy\"], report_only: \
             [\"energy\"])])",
        )
        .unwrap_err();
        assert!(
            e.contains(
                "axes[0].alternatives[0].report_only[0]: axis \"unit\", alternative \"p\": target \
                 \"energy\" is named twice (also require[0])"
            ),
            "{e}"
        );
        let e =
            parse("(name: \"unit\", alternatives: [(name: \"p\", require: [\" \"])])").unwrap_err();
        assert!(
            e.contains("require[0]: axis \"unit\", alternative \"p\": an empty target name"),
            "{e}"
        );
        let e = parse(
            "(name: \"unit\", alternatives: [(name: \"p\", require: [\"energy\"])]), (name: \
             \"other\", alternatives: [(name: \"q\", report_only: [\"energy\"])])",
        )
        .unwrap_err();
        assert!(
            e.contains(
                "axes[1].alternatives[0].report_only[0]: axis \"other\", alternative \"q\": target \
                 \"energy\" is flagged by axis \"unit\" too"
            ),
            "{e}"
        );
        let plain = parse("(name: \"unit\", alternatives: [(name: \"p\")])").unwrap();
        assert!(!plain.flags_targets());
    }
}
