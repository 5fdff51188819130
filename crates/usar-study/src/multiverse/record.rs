//! What one universe produced ([`UniverseRecord`]), kept as `universes/<id>/universe.json`
//! once the universe is done: the data `multiverse.csv`, `multiverse.md` and the figures are
//! made from, so that a resumed, sharded or merged multiverse writes the same files as one
//! uninterrupted run.
//!
//! The file is one line, `{"universe":{...},"sum":"<16 hex digits>"}`, written atomically;
//! `sum` is [`usar_sweep::checked_log::record_sum`] of the multiverse's identity sum
//! ([`super::plan::MultiversePlan::identity_sum`]) and the record's JSON as written, so a
//! record verifies only for the multiverse that wrote it (an edited record, or one left by a
//! multiverse of other parameters, does not, and its universe runs again). Numbers that may
//! not be finite are written as `"NaN"`, `"inf"` ([`usar_report::targets::float_text`]).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use usar_sim::scenario::path_text;

use super::effect::ClaimEffect;
use super::error::MultiverseError;
use crate::calibrate::StopReason;
use usar_report::targets::float_text;
use usar_sweep::atomic::write_atomic;
use usar_sweep::bounded_file::{MAX_MULTIVERSE_PLAN_BYTES, read_small};
use usar_sweep::checked_log::{record_line, verified_record};

/// What the functions of this module return.
type Result<T, E = MultiverseError> = std::result::Result<T, E>;

/// The record's file name in a universe's folder.
pub const RECORD_FILE: &str = "universe.json";

/// How a universe ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Calibrated and compared, every trial run (admissible or not: see
    /// [`UniverseRecord::admissible`]).
    Ok,
    /// Its choices make a scenario that breaks a rule: nothing ran (not retried; the message
    /// says which rule).
    Invalid,
    /// The calibration stopped with an error, or comparison trials failed: run again, the
    /// universe is retried (its calibration trace and sweep journal keep what was done).
    Failed,
}

impl Status {
    /// The status as `multiverse.csv` and `multiverse.md` write it: `ok`, `invalid`,
    /// `failed`.
    pub fn word(self) -> &'static str {
        match self {
            Status::Ok => "ok",
            Status::Invalid => "invalid",
            Status::Failed => "failed",
        }
    }
}

/// What the calibration of a universe found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CalibrationResult {
    /// The best loss (0: every target's statistic in its band; +inf: every point failed).
    #[serde(with = "float_text")]
    pub loss: f64,
    /// The best values of the free fields, in `--free` order.
    pub values: Vec<f64>,
    /// Each target's statistic at the best values, in target order (NaN when undefined).
    #[serde(with = "float_text::vec")]
    pub statistics: Vec<f64>,
    /// Evaluations in the search's sequence.
    pub evaluations: usize,
    /// Why the search stopped.
    pub stop: StopReason,
    /// The loss the design's emulator predicted at the search's start (`--design`;
    /// [`super::emulator::Start`]); NaN without a design, and then absent from the record.
    #[serde(
        default = "float_text::nan",
        with = "float_text",
        skip_serializing_if = "float_text::is_nan"
    )]
    pub predicted_loss: f64,
}

/// One method's summary of one metric in a universe's comparison (as `summary.csv`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MetricSummary {
    /// The method's display name.
    pub method: String,
    /// The metric's name (`rescued_total`, `hp_per_hard_rescuee_pct`; summary.csv's).
    pub metric: String,
    /// Values (successful trials where the metric is defined).
    pub n: usize,
    /// Their mean (NaN without values).
    #[serde(with = "float_text")]
    pub mean: f64,
    /// Their sample standard deviation (NaN with fewer than two).
    #[serde(with = "float_text")]
    pub sd: f64,
}

/// What the comparison of a universe found.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ComparisonResult {
    /// Successful trials.
    pub trials_ok: usize,
    /// Failed trials.
    pub trials_failed: usize,
    /// Per method (in `--methods` order) and metric (in `summary.csv` order).
    pub metrics: Vec<MetricSummary>,
    /// Per claim of the plan's ([`super::plan::MultiverseIdentity::claims`]), in that order.
    pub claims: Vec<ClaimEffect>,
    /// Each target's statistic over the comparison's trials (more trials than a calibration
    /// evaluation holds), in target order (NaN when undefined).
    #[serde(with = "float_text::vec")]
    pub targets: Vec<f64>,
}

/// What one universe produced.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UniverseRecord {
    /// Index in the full factorial ([`super::universe::Universe::index`]).
    pub index: u64,
    /// The folder name (`u007`).
    pub id: String,
    /// The alternative taken on each axis, in axis order.
    pub choices: Vec<usize>,
    /// How it ended.
    pub status: Status,
    /// Why it is invalid or failed (one line per problem, `; `-joined); `None` when ok.
    pub message: Option<String>,
    /// The calibration's result, when it ran to its end.
    pub calibration: Option<CalibrationResult>,
    /// The comparison's result, when it ran.
    pub comparison: Option<ComparisonResult>,
}

impl UniverseRecord {
    /// Whether the universe is admissible: its calibration reached every band (loss 0).
    pub fn admissible(&self) -> bool {
        self.within_loss(0.0)
    }

    /// Whether the universe's calibration reached a loss of at most `max_loss` (0: admissible;
    /// a larger one: near-admissible, `--near-loss`).
    pub fn within_loss(&self, max_loss: f64) -> bool {
        self.calibration
            .as_ref()
            .is_some_and(|c| c.loss <= max_loss)
    }

    /// The effect of the claim with id `claim`, when the comparison ran.
    pub fn claim(&self, claim: &str) -> Option<&ClaimEffect> {
        self.comparison
            .as_ref()?
            .claims
            .iter()
            .find(|c| c.claim == claim)
    }

    /// The path of the record in the universe folder `dir`.
    pub fn path_in(dir: &Path) -> PathBuf {
        dir.join(RECORD_FILE)
    }

    /// Writes the record into the universe folder `dir`, atomically, checksummed with the
    /// multiverse's `identity_sum`.
    ///
    /// # Errors
    /// An I/O error.
    pub fn write(&self, dir: &Path, identity_sum: &str) -> Result<()> {
        let json = serde_json::to_string(self).map_err(|source| MultiverseError::Serialise {
            what: "a universe record",
            source,
        })?;
        let line = record_line("universe", &json, identity_sum);
        Ok(write_atomic(&Self::path_in(dir), line.as_bytes())?)
    }

    /// Reads the record of the universe folder `dir` for the multiverse with `identity_sum`.
    pub fn read(dir: &Path, identity_sum: &str) -> RecordRead {
        let path = Self::path_in(dir);
        // Bounded, and a FIFO or device is refused, not waited on (issue 70).
        let bytes = match std::fs::symlink_metadata(&path) {
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return RecordRead::Missing,
            _ => read_small(&path, MAX_MULTIVERSE_PLAN_BYTES),
        };
        let text = match bytes.map(String::from_utf8) {
            Ok(Ok(t)) => t,
            Ok(Err(_)) => {
                let path = path_text(&path);
                return RecordRead::Unusable(format!("{path}: not UTF-8 text"));
            }
            Err(e) => return RecordRead::Unusable(e.to_string()),
        };
        match parse(&text, identity_sum) {
            Some(r) => RecordRead::Done(Box::new(r)),
            None => RecordRead::Unusable(format!(
                "{} does not verify (edited, or written by another multiverse)",
                path_text(&path)
            )),
        }
    }
}

/// The record on one line `text`, when it verifies for `identity_sum`.
fn parse(text: &str, identity_sum: &str) -> Option<UniverseRecord> {
    serde_json::from_str(verified_record(text, "universe", identity_sum)?).ok()
}

/// A universe's record as found in its folder.
#[derive(Debug, Clone, PartialEq)]
pub enum RecordRead {
    /// No record: the universe has not finished.
    Missing,
    /// A record that verifies.
    Done(Box<UniverseRecord>),
    /// A record that cannot be used (unreadable, damaged, edited, another multiverse's):
    /// why, in one line. The universe runs again.
    Unusable(String),
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// A finished, admissible universe with one metric and one claim.
    pub(crate) fn record(index: u64, choices: &[usize], loss: f64) -> UniverseRecord {
        UniverseRecord {
            index,
            id: format!("u{index:03}"),
            choices: choices.to_vec(),
            status: Status::Ok,
            message: None,
            calibration: Some(CalibrationResult {
                loss,
                values: vec![1.25, 0.003],
                statistics: vec![6.0, f64::NAN],
                evaluations: 4,
                stop: StopReason::TargetReached,
                predicted_loss: f64::NAN,
            }),
            comparison: Some(ComparisonResult {
                trials_ok: 4,
                trials_failed: 0,
                metrics: vec![MetricSummary {
                    method: "RNE".into(),
                    metric: "rescued_total".into(),
                    n: 2,
                    mean: 150.5,
                    sd: f64::NAN,
                }],
                claims: vec![ClaimEffect {
                    claim: "1".into(),
                    verdict: "holds".into(),
                    rival: Some("DIS".into()),
                    effect: 2.5,
                    ci_low: 0.5,
                    ci_high: 4.5,
                    p: 0.01,
                }],
                targets: vec![148.0],
            }),
        }
    }

    #[test]
    fn a_record_reads_back_exactly_and_only_for_its_multiverse() {
        let dir = tempfile::tempdir().unwrap();
        assert_eq!(UniverseRecord::read(dir.path(), "abc"), RecordRead::Missing);
        let r = record(3, &[1, 0], f64::INFINITY);
        r.write(dir.path(), "abc").unwrap();
        match UniverseRecord::read(dir.path(), "abc") {
            RecordRead::Done(back) => {
                assert_eq!(back.choices, r.choices);
                assert!(back.calibration.as_ref().unwrap().loss.is_infinite());
                assert!(back.calibration.as_ref().unwrap().statistics[1].is_nan());
                assert!(!back.admissible());
            }
            other => panic!("{other:?}"),
        }
        assert!(matches!(
            UniverseRecord::read(dir.path(), "abd"),
            RecordRead::Unusable(m) if m.contains("does not verify")
        ));
        // An edited number no longer verifies.
        let path = UniverseRecord::path_in(dir.path());
        let text = std::fs::read_to_string(&path)
            .unwrap()
            .replace("150.5", "160.5");
        std::fs::write(&path, text).unwrap();
        assert!(matches!(
            UniverseRecord::read(dir.path(), "abc"),
            RecordRead::Unusable(_)
        ));
    }

    #[test]
    fn a_record_that_is_a_fifo_is_unusable_at_once_not_waited_on() {
        let dir = tempfile::tempdir().unwrap();
        let path = UniverseRecord::path_in(dir.path());
        let made = std::process::Command::new("mkfifo").arg(&path).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo");
        let (tx, rx) = std::sync::mpsc::channel();
        let root = dir.path().to_path_buf();
        // A reader that opened the FIFO would wait for a writer for ever: the test waits 20 s.
        std::thread::spawn(move || tx.send(UniverseRecord::read(&root, "abc")));
        let read = rx.recv_timeout(std::time::Duration::from_secs(20));
        assert!(
            matches!(&read, Ok(RecordRead::Unusable(m)) if m.contains("not a regular file")),
            "{read:?}"
        );
    }

    #[test]
    fn admissible_means_loss_zero() {
        assert!(record(0, &[0], 0.0).admissible());
        assert!(!record(0, &[0], 0.5).admissible());
        let mut r = record(0, &[0], 0.0);
        r.calibration = None;
        assert!(!r.admissible());
        assert_eq!(record(0, &[0], 0.0).claim("1").unwrap().effect, 2.5);
        assert!(record(0, &[0], 0.0).claim("2").is_none());
    }
}
