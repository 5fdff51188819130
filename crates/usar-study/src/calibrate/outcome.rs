//! What a calibration produced ([`CalibrationOutcome`]): data only; the files
//! (`super::outputs`) and the terminal summary (`super::summary`) are rendered from it.

use std::path::PathBuf;

use usar_sim::scenario::{Scenario, ScenarioSpec};

use super::evaluate::Evaluation;
use super::optimizer::StopReason;
use super::trace::TraceHeader;
use usar_report::targets::file::Target;

/// The calibrated scenario, written at the end.
pub const CALIBRATED_FILE: &str = "calibrated.ron";
/// Every evaluation, one row each.
pub const TRACE_CSV_FILE: &str = "trace.csv";
/// The report.
pub const REPORT_FILE: &str = "calibration.md";
/// The best loss against the evaluations.
pub const FIGURE_FILE: &str = "convergence.svg";
/// Each target's statistic against the evaluations, its band shaded.
pub const STATISTICS_FIGURE_FILE: &str = "statistics.svg";
/// The two targets farthest outside their bands at the best point, every evaluation, and
/// the Pareto front between them.
pub const TRADEOFF_FIGURE_FILE: &str = "tradeoff.svg";
/// The files `super::outputs::write_outputs` writes, in that order (`--overwrite` removes
/// them).
pub const OUTPUT_FILES: [&str; 6] = [
    CALIBRATED_FILE,
    TRACE_CSV_FILE,
    REPORT_FILE,
    FIGURE_FILE,
    STATISTICS_FIGURE_FILE,
    TRADEOFF_FIGURE_FILE,
];

/// One target with a statistic's value and whether it lies in the band.
#[derive(Debug, Clone, PartialEq)]
pub struct TargetCheck {
    /// The target.
    pub target: Target,
    /// The statistic (NaN when undefined).
    pub value: f64,
    /// Whether it lies in the band.
    pub holds: bool,
}

/// Each target of `targets` with its value in `values` (same order).
pub fn target_checks(targets: &[Target], values: &[f64]) -> Vec<TargetCheck> {
    targets
        .iter()
        .zip(values)
        .map(|(t, &x)| TargetCheck {
            target: t.clone(),
            value: x,
            holds: t.holds(x),
        })
        .collect()
}

/// The statistics of the calibrated scenario on trials the calibration never saw.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckOutcome {
    /// Their base seed.
    pub seed: u64,
    /// Trials per method.
    pub trials: u32,
    /// Each target's statistic over them.
    pub statistics: Vec<TargetCheck>,
    /// `METHOD trial K (seed S): message` per failed trial (left out of the statistics).
    pub failures: Vec<String>,
}

/// What a calibration produced.
#[derive(Debug, Clone)]
pub struct CalibrationOutcome {
    /// What identifies the calibration (as in its trace).
    pub header: TraceHeader,
    /// Where the base scenario came from.
    pub origin: String,
    /// Where the targets came from.
    pub targets_origin: String,
    /// How it was asked for ([`super::CalibrationSetup::command`]).
    pub command: String,
    /// When its outputs were written (UTC, RFC 3339, or the setup's date).
    pub date: String,
    /// Every evaluation of the search's sequence, in order (index = position).
    pub evaluations: Vec<Evaluation>,
    /// Index of the best evaluation: the lowest loss, the earliest of equals.
    pub best: usize,
    /// The base spec with the best values (what `calibrated.ron` holds).
    pub best_spec: ScenarioSpec,
    /// That spec, validated.
    pub best_scenario: Scenario,
    /// Every target with its statistic at the best values.
    pub statistics: Vec<TargetCheck>,
    /// The best loss.
    pub loss: f64,
    /// Whether the best values satisfy every target: loss 0 (every statistic in its band,
    /// every trial run to its end).
    pub admissible: bool,
    /// Why the search stopped.
    pub stop: StopReason,
    /// Evaluations run by this invocation.
    pub ran: usize,
    /// Evaluations taken from the trace of an earlier run.
    pub reused: usize,
    /// The evaluation budget of this run.
    pub max_evals: usize,
    /// The start values (the base scenario's, or the ranges' midpoints), in free-field order.
    pub starts: Vec<f64>,
    /// Worker threads used for the trials.
    pub threads: usize,
    /// Wall-clock time of this invocation, seconds.
    pub wall_s: f64,
    /// The statistics on unseen trials (`None` when skipped).
    pub check: Option<CheckOutcome>,
    /// The files written (trace.jsonl first).
    pub files: Vec<PathBuf>,
}

impl CalibrationOutcome {
    /// The best evaluation.
    pub fn best(&self) -> &Evaluation {
        &self.evaluations[self.best]
    }

    /// The best values, in free-field order.
    pub fn best_values(&self) -> &[f64] {
        &self.best().values
    }

    /// What the trials of each evaluation were: `RNE, DIS x 10 trials of 600 s, base seed
    /// 2021` (`the scenario's length` without a set duration).
    pub fn trials_text(&self) -> String {
        let h = &self.header;
        let length = h
            .duration_s
            .map_or("the scenario's length".into(), |d| format!("{d} s"));
        format!(
            "{} x {} trials of {length}, base seed {}",
            h.methods.join(", "),
            h.trials,
            h.base_seed
        )
    }
}

/// The index of the best of `evaluations` (lowest loss, the earliest of equals); `None` for
/// none.
pub fn best_index(evaluations: &[Evaluation]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (i, e) in evaluations.iter().enumerate() {
        if best.is_none_or(|b| e.search_loss() < evaluations[b].search_loss()) {
            best = Some(i);
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn eval(loss: f64, unseen_loss: f64) -> Evaluation {
        Evaluation {
            index: 0,
            values: vec![1.0],
            statistics: vec![],
            loss,
            message: None,
            trials_ok: 2,
            wall_s: 0.0,
            unseen_loss,
        }
    }

    #[test]
    fn a_point_in_band_that_fails_its_unseen_check_is_not_the_best_nor_admissible() {
        // In band on the search's trials, out on the unseen ones: its search loss is the
        // unseen check's; a point near the bands beats it, one in band on both beats all.
        let unconfirmed = eval(0.0, 3.0);
        assert_eq!(unconfirmed.search_loss(), 3.0);
        let near = eval(0.5, f64::NAN);
        assert_eq!(best_index(&[unconfirmed.clone(), near.clone()]), Some(1));
        let confirmed = eval(0.0, 0.0);
        assert_eq!(confirmed.search_loss(), 0.0);
        assert_eq!(best_index(&[unconfirmed, near, confirmed]), Some(2));
        assert_eq!(
            eval(0.0, f64::NAN).search_loss(),
            0.0,
            "not checked: its own loss"
        );
    }
}
