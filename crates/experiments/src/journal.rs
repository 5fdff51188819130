//! The sweep journal: `journal.jsonl` in the output folder, one JSON object per line.
//!
//! The first line is the [`SweepHeader`] (the sweep's parameters); every later line is one
//! [`TrialRecord`], appended and flushed as soon as its trial ends, in completion order. A trial
//! may appear more than once (a failed trial retried by `--resume`); the last record wins.
//! A kill can leave a last line cut short; [`Journal::open_resume`] drops it.

use std::fs::{self, File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use serde::{Deserialize, Serialize};
use usar_sim::mission::TrialResult;

/// File name of the journal inside the output folder.
pub const JOURNAL_FILE: &str = "journal.jsonl";

/// Format version of the journal; bumped when its lines change shape.
pub const JOURNAL_FORMAT: u32 = 1;

/// The parameters that determine a sweep's results. `--resume` continues a journal only if
/// its header equals the new sweep's header.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepHeader {
    /// [`JOURNAL_FORMAT`].
    pub format: u32,
    /// Version of the `experiments` crate that wrote the journal.
    pub version: String,
    /// Scenario name.
    pub scenario: String,
    /// FNV-1a 64 hash (hex) of the validated scenario serialised as JSON: any change to the
    /// scenario file's meaning changes it.
    pub scenario_hash: String,
    /// Grouping methods, upper case, in sweep order.
    pub methods: Vec<String>,
    /// Trials per method.
    pub trials: u32,
    /// Base seed; trial `k` uses `trial_seed(base_seed, k)`.
    pub base_seed: u64,
    /// Simulated length of each trial, seconds.
    pub duration_s: f64,
}

/// How one trial ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The trial ran to its time limit.
    Ok(Box<TrialResult>),
    /// The trial returned an error or panicked; the message says which.
    Failed(String),
}

/// One journal line after the header.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TrialRecord {
    /// Grouping method, upper case.
    pub method: String,
    /// Trial index, 0-based.
    pub trial: u32,
    /// The trial's seed.
    pub seed: u64,
    /// Wall-clock time the trial took, seconds (for the report only).
    pub wall_s: f64,
    /// The result or the failure.
    pub outcome: Outcome,
}

/// One line of the journal, as read back.
#[derive(Debug, Clone, PartialEq, Deserialize)]
#[serde(rename_all = "snake_case")]
enum Line {
    Header(SweepHeader),
    Trial(TrialRecord),
}

/// One line of the journal, as written: the same JSON as [`Line`], borrowing its content.
#[derive(Serialize)]
#[serde(rename_all = "snake_case")]
enum LineRef<'a> {
    Header(&'a SweepHeader),
    Trial(&'a TrialRecord),
}

/// An open journal, appending one flushed line per record.
#[derive(Debug)]
pub struct Journal {
    path: PathBuf,
    file: File,
}

impl Journal {
    /// Path of the journal in `dir`.
    pub fn path_in(dir: &Path) -> PathBuf {
        dir.join(JOURNAL_FILE)
    }

    /// Starts a new journal in `dir` with `header`. Fails if one already exists there (use
    /// [`Journal::open_resume`], or remove it first).
    ///
    /// # Errors
    /// An existing journal, or an I/O error.
    pub fn create(dir: &Path, header: &SweepHeader) -> Result<Self> {
        fs::create_dir_all(dir).with_context(|| format!("creating folder {}", dir.display()))?;
        let path = Self::path_in(dir);
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
            .with_context(|| format!("creating {}", path.display()))?;
        let mut j = Self { path, file };
        j.append_line(&LineRef::Header(header))?;
        Ok(j)
    }

    /// Opens the journal in `dir` to continue it: checks that its header equals `header` and
    /// returns the journal with the records it already holds. A last line cut short by a kill
    /// is removed from the file.
    ///
    /// # Errors
    /// No journal, a journal written with other parameters (the message lists the
    /// differences), a corrupt line other than the last, or an I/O error.
    pub fn open_resume(dir: &Path, header: &SweepHeader) -> Result<(Self, Vec<TrialRecord>)> {
        let path = Self::path_in(dir);
        let text = fs::read_to_string(&path).with_context(|| {
            format!(
                "--resume: cannot read {} (run without --resume to start the sweep)",
                path.display()
            )
        })?;
        let mut records = Vec::new();
        let mut found: Option<SweepHeader> = None;
        let mut keep_bytes = 0usize;
        let n_lines = text.split_inclusive('\n').count();
        for (i, line) in text.split_inclusive('\n').enumerate() {
            let complete = line.ends_with('\n');
            let parsed = serde_json::from_str::<Line>(line.trim_end());
            match parsed {
                // A last line without its newline was cut short by a kill, even when what
                // was written of it happens to parse: the record is redone.
                _ if i > 0 && i + 1 == n_lines && !complete => break,
                Ok(Line::Header(h)) if i == 0 => found = Some(h),
                Ok(Line::Trial(r)) if i > 0 && complete => records.push(r),
                Ok(_) | Err(_) => bail!(
                    "{}:{}: not a valid journal line; the journal is damaged (move it away \
                     and run the sweep again without --resume)",
                    path.display(),
                    i + 1
                ),
            }
            keep_bytes += line.len();
        }
        let Some(found) = found else {
            bail!("{}: empty journal (no header line)", path.display());
        };
        if &found != header {
            bail!(
                "--resume: {} was written by a sweep with other parameters ({}); run with \
                 another --out, or without --resume and --overwrite to start afresh",
                path.display(),
                header_diff(&found, header)
            );
        }
        let file = OpenOptions::new()
            .write(true)
            .open(&path)
            .with_context(|| format!("opening {}", path.display()))?;
        file.set_len(keep_bytes as u64)
            .with_context(|| format!("truncating {}", path.display()))?;
        let file = OpenOptions::new()
            .append(true)
            .open(&path)
            .with_context(|| format!("opening {}", path.display()))?;
        Ok((Self { path, file }, records))
    }

    /// Appends `record` as one line and flushes it to the operating system.
    ///
    /// # Errors
    /// An I/O error.
    pub fn append(&mut self, record: &TrialRecord) -> Result<()> {
        self.append_line(&LineRef::Trial(record))
    }

    fn append_line(&mut self, line: &LineRef<'_>) -> Result<()> {
        let mut s = serde_json::to_string(line).context("serialising a journal line")?;
        s.push('\n');
        self.file
            .write_all(s.as_bytes())
            .and_then(|()| self.file.flush())
            .with_context(|| format!("appending to {}", self.path.display()))
    }
}

/// Human-readable list of the fields where two headers differ.
fn header_diff(old: &SweepHeader, new: &SweepHeader) -> String {
    let mut d = Vec::new();
    if old.format != new.format {
        d.push(format!("journal format {} vs {}", old.format, new.format));
    }
    if old.version != new.version {
        d.push(format!("version {} vs {}", old.version, new.version));
    }
    if old.scenario != new.scenario || old.scenario_hash != new.scenario_hash {
        d.push(format!(
            "scenario {} ({}) vs {} ({})",
            old.scenario, old.scenario_hash, new.scenario, new.scenario_hash
        ));
    }
    if old.methods != new.methods {
        d.push(format!(
            "methods {} vs {}",
            old.methods.join(","),
            new.methods.join(",")
        ));
    }
    if old.trials != new.trials {
        d.push(format!("trials {} vs {}", old.trials, new.trials));
    }
    if old.base_seed != new.base_seed {
        d.push(format!("seed {} vs {}", old.base_seed, new.base_seed));
    }
    if old.duration_s != new.duration_s {
        d.push(format!(
            "duration {} s vs {} s",
            old.duration_s, new.duration_s
        ));
    }
    format!("journal has {}", d.join(", "))
}

/// FNV-1a 64-bit hash of `bytes`, as 16 hex digits (stable across platforms and releases).
pub fn fnv1a64_hex(bytes: &[u8]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for b in bytes {
        h ^= u64::from(*b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    format!("{h:016x}")
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header() -> SweepHeader {
        SweepHeader {
            format: JOURNAL_FORMAT,
            version: "0".into(),
            scenario: "s".into(),
            scenario_hash: fnv1a64_hex(b"s"),
            methods: vec!["RNE".into()],
            trials: 2,
            base_seed: 1,
            duration_s: 10.0,
        }
    }

    fn record(k: u32) -> TrialRecord {
        TrialRecord {
            method: "RNE".into(),
            trial: k,
            seed: 9,
            wall_s: 0.5,
            outcome: Outcome::Failed("boom".into()),
        }
    }

    #[test]
    fn floats_survive_the_journal_exactly() {
        // Resumed sweeps rebuild trials.csv from the journal: every f64 must parse back to
        // the same bits (serde_json's `float_roundtrip` feature).
        let mut x = 0.1f64;
        for _ in 0..10_000 {
            x = (x * 1.618_033_988_749_895 + 0.000_123_456_789).fract() * 731.0;
            let text = serde_json::to_string(&x).unwrap();
            let back: f64 = serde_json::from_str(&text).unwrap();
            assert_eq!(back.to_bits(), x.to_bits(), "{text}");
        }
    }

    #[test]
    fn fnv_known_values() {
        assert_eq!(fnv1a64_hex(b""), "cbf29ce484222325");
        assert_eq!(fnv1a64_hex(b"a"), "af63dc4c8601ec8c");
    }

    #[test]
    fn resume_reads_records_and_drops_a_cut_line() {
        let dir = tempfile::tempdir().unwrap();
        let mut j = Journal::create(dir.path(), &header()).unwrap();
        j.append(&record(0)).unwrap();
        drop(j);
        assert!(Journal::create(dir.path(), &header()).is_err());
        let path = Journal::path_in(dir.path());
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(b"{\"trial\":{\"meth").unwrap();
        drop(f);
        let (mut j, recs) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(recs, vec![record(0)]);
        j.append(&record(1)).unwrap();
        drop(j);
        let (_, recs) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(recs, vec![record(0), record(1)]);
        // A kill after the record but before its newline: the record parses but is redone.
        let whole = serde_json::to_string(&LineRef::Trial(&record(2))).unwrap();
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(whole.as_bytes()).unwrap();
        drop(f);
        let (_, recs) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(recs, vec![record(0), record(1)]);
        assert!(fs::read_to_string(&path).unwrap().ends_with('\n'));
    }

    #[test]
    fn resume_refuses_other_parameters() {
        let dir = tempfile::tempdir().unwrap();
        Journal::create(dir.path(), &header()).unwrap();
        let mut other = header();
        other.trials = 3;
        other.base_seed = 7;
        let e = Journal::open_resume(dir.path(), &other).unwrap_err();
        let msg = format!("{e:#}");
        assert!(msg.contains("trials 2 vs 3"), "{msg}");
        assert!(msg.contains("seed 1 vs 7"), "{msg}");
    }
}
