//! The sweep journal: `journal.jsonl` at the top of the output folder, one JSON object per
//! line.
//!
//! The first line is the [`SweepHeader`]: the sweep's parameters, including its grid (the
//! varied fields and, per cell, their values, the cell's scenario hash and trial length; a
//! sweep without `--vary` is a grid of one cell with no fields). Every later line is one
//! [`TrialRecord`], appended and flushed as soon as its trial ends, in completion order.
//!
//! A record is identified by its [`RecordKey`] `(cell, method, trial)`. A key may appear more
//! than once (a failed trial retried by `--resume`); the last record wins. Nothing else about
//! a record depends on the journal it is in, so a later feature can split the job list into
//! shards that write journals of their own, and merge them by reading each with
//! [`read_journal`], checking their headers agree and keeping the last record per key. A kill
//! can leave a last line cut short; [`Journal::open_resume`] drops it.

use std::fs::{self, File, OpenOptions};
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use serde::{Deserialize, Serialize};
use usar_sim::mission::TrialResult;

/// File name of the journal inside the output folder.
pub const JOURNAL_FILE: &str = "journal.jsonl";

/// Format version of the journal; bumped when its lines change shape. Format 2 added the
/// grid to the header and the cell index to every record.
pub const JOURNAL_FORMAT: u32 = 2;

/// The parameters that determine a sweep's results. `--resume` continues a journal only if
/// its header equals the new sweep's header.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepHeader {
    /// [`JOURNAL_FORMAT`].
    pub format: u32,
    /// Version of the `experiments` crate that wrote the journal.
    pub version: String,
    /// Name of the scenario the grid was built from.
    pub scenario: String,
    /// Grouping methods, upper case, in sweep order.
    pub methods: Vec<String>,
    /// Trials per method and cell.
    pub trials: u32,
    /// Base seed; trial `k` of every method and cell uses `trial_seed(base_seed, k)`.
    pub base_seed: u64,
    /// The cells the sweep runs.
    pub grid: GridHeader,
}

/// The grid of a sweep: varied fields and cells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridHeader {
    /// Varied field paths in `--vary` order; empty for a sweep without `--vary`.
    pub fields: Vec<String>,
    /// The cells, first field varying slowest; exactly one for a sweep without `--vary`.
    pub cells: Vec<CellHeader>,
}

/// One cell of the grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CellHeader {
    /// The value of each varied field, as written on the command line, in field order.
    pub values: Vec<String>,
    /// [`crate::fingerprint::scenario_hash`] of the cell's validated scenario.
    pub scenario_hash: String,
    /// Simulated length of each trial of the cell, seconds.
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
    /// Grid cell index, 0-based (into [`GridHeader::cells`]).
    pub cell: usize,
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

/// What identifies a record: `(cell, method, trial)`.
pub type RecordKey<'a> = (usize, &'a str, u32);

impl TrialRecord {
    /// The record's identity.
    pub fn key(&self) -> RecordKey<'_> {
        (self.cell, &self.method, self.trial)
    }
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

/// A journal read from a file.
#[derive(Debug, Clone, PartialEq)]
pub struct JournalContents {
    /// Its header.
    pub header: SweepHeader,
    /// Its complete records, in file order (a key may repeat: the last one wins).
    pub records: Vec<TrialRecord>,
    /// Length in bytes of the header and complete records: what is left of the file once a
    /// last line cut short by a kill is dropped.
    pub complete_bytes: u64,
}

/// Reads the journal at `path`: its header and every complete record. A last line without
/// its newline was cut short by a kill, even when what was written of it parses: it is left
/// out (and redone by a resume).
///
/// # Errors
/// An unreadable file, a journal of another [`JOURNAL_FORMAT`], a missing header, or a
/// damaged line other than the last (the message gives its line number).
pub fn read_journal(path: &Path) -> Result<JournalContents> {
    let text =
        fs::read_to_string(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut records = Vec::new();
    let mut header: Option<SweepHeader> = None;
    let mut complete_bytes = 0usize;
    let n_lines = text.split_inclusive('\n').count();
    for (i, line) in text.split_inclusive('\n').enumerate() {
        let complete = line.ends_with('\n');
        if i == 0 {
            check_format(path, line)?;
        }
        match serde_json::from_str::<Line>(line.trim_end()) {
            _ if i > 0 && i + 1 == n_lines && !complete => break,
            Ok(Line::Header(h)) if i == 0 => header = Some(h),
            Ok(Line::Trial(r)) if i > 0 && complete => records.push(r),
            Ok(_) | Err(_) => bail!(
                "{}:{}: not a valid journal line; the journal is damaged (move it away and run \
                 the sweep again)",
                path.display(),
                i + 1
            ),
        }
        complete_bytes += line.len();
    }
    let Some(header) = header else {
        bail!("{}: empty journal (no header line)", path.display());
    };
    Ok(JournalContents {
        header,
        records,
        complete_bytes: complete_bytes as u64,
    })
}

/// Refuses a journal whose first line is the header of another format.
fn check_format(path: &Path, first_line: &str) -> Result<()> {
    let format = serde_json::from_str::<serde_json::Value>(first_line.trim_end())
        .ok()
        .and_then(|v| v.get("header")?.get("format")?.as_u64());
    match format {
        Some(f) if f != u64::from(JOURNAL_FORMAT) => bail!(
            "{}: journal format {f}, but this usar reads format {JOURNAL_FORMAT}; start afresh \
             with --overwrite, or choose another --out",
            path.display()
        ),
        _ => Ok(()),
    }
}

/// The header of the journal at `path` (its first line only).
///
/// # Errors
/// As [`read_journal`] for the first line.
pub fn read_header(path: &Path) -> Result<SweepHeader> {
    let file = File::open(path).with_context(|| format!("cannot read {}", path.display()))?;
    let mut first = String::new();
    BufReader::new(file)
        .read_line(&mut first)
        .with_context(|| format!("reading {}", path.display()))?;
    check_format(path, &first)?;
    match serde_json::from_str::<Line>(first.trim_end()) {
        Ok(Line::Header(h)) => Ok(h),
        _ => bail!("{}:1: not a journal header", path.display()),
    }
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
        let contents = read_journal(&path).context("--resume")?;
        if &contents.header != header {
            bail!(
                "--resume: {} was written by a sweep with other parameters ({}); run with \
                 another --out, or without --resume and --overwrite to start afresh",
                path.display(),
                header_diff(&contents.header, header)
            );
        }
        let file = OpenOptions::new()
            .write(true)
            .open(&path)
            .with_context(|| format!("opening {}", path.display()))?;
        file.set_len(contents.complete_bytes)
            .with_context(|| format!("truncating {}", path.display()))?;
        let file = OpenOptions::new()
            .append(true)
            .open(&path)
            .with_context(|| format!("opening {}", path.display()))?;
        Ok((Self { path, file }, contents.records))
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

/// Human-readable list of the fields where two headers differ, e.g. `journal has trials 2
/// vs 3, seed 1 vs 7`.
pub fn header_diff(old: &SweepHeader, new: &SweepHeader) -> String {
    let mut d = Vec::new();
    if old.format != new.format {
        d.push(format!("journal format {} vs {}", old.format, new.format));
    }
    if old.version != new.version {
        d.push(format!("version {} vs {}", old.version, new.version));
    }
    if old.scenario != new.scenario {
        d.push(format!("scenario {} vs {}", old.scenario, new.scenario));
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
    grid_diff(&old.grid, &new.grid, &mut d);
    format!("journal has {}", d.join(", "))
}

fn grid_diff(old: &GridHeader, new: &GridHeader, d: &mut Vec<String>) {
    if old.fields != new.fields {
        d.push(format!(
            "varied fields [{}] vs [{}]",
            old.fields.join(", "),
            new.fields.join(", ")
        ));
        return;
    }
    if old.cells.len() != new.cells.len() {
        d.push(format!("{} cells vs {}", old.cells.len(), new.cells.len()));
        return;
    }
    for (i, (a, b)) in old.cells.iter().zip(&new.cells).enumerate() {
        let cell = if old.fields.is_empty() {
            String::new()
        } else {
            format!("cell {i} ")
        };
        if a.values != b.values {
            d.push(format!(
                "{cell}values {} vs {}",
                a.values.join(", "),
                b.values.join(", ")
            ));
        }
        if a.scenario_hash != b.scenario_hash {
            d.push(format!(
                "{cell}scenario hash {} vs {}",
                a.scenario_hash, b.scenario_hash
            ));
        }
        if a.duration_s != b.duration_s {
            d.push(format!(
                "{cell}duration {} s vs {} s",
                a.duration_s, b.duration_s
            ));
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fingerprint::fnv1a64_hex;

    fn header() -> SweepHeader {
        SweepHeader {
            format: JOURNAL_FORMAT,
            version: "0".into(),
            scenario: "s".into(),
            methods: vec!["RNE".into()],
            trials: 2,
            base_seed: 1,
            grid: GridHeader {
                fields: vec!["mission.duration_s".into()],
                cells: vec![
                    CellHeader {
                        values: vec!["10".into()],
                        scenario_hash: fnv1a64_hex(b"s"),
                        duration_s: 10.0,
                    },
                    CellHeader {
                        values: vec!["20".into()],
                        scenario_hash: fnv1a64_hex(b"t"),
                        duration_s: 20.0,
                    },
                ],
            },
        }
    }

    fn record(cell: usize, k: u32) -> TrialRecord {
        TrialRecord {
            cell,
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
    fn lines_carry_the_grid_and_the_cell() {
        let dir = tempfile::tempdir().unwrap();
        let mut j = Journal::create(dir.path(), &header()).unwrap();
        j.append(&record(1, 0)).unwrap();
        drop(j);
        let text = fs::read_to_string(Journal::path_in(dir.path())).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert!(
            lines[0].starts_with("{\"header\":{\"format\":2,"),
            "{}",
            lines[0]
        );
        assert!(
            lines[0].contains(
                "\"grid\":{\"fields\":[\"mission.duration_s\"],\"cells\":[{\"values\":[\"10\"],"
            ),
            "{}",
            lines[0]
        );
        assert!(
            lines[1].starts_with("{\"trial\":{\"cell\":1,\"method\":\"RNE\",\"trial\":0,"),
            "{}",
            lines[1]
        );
        assert_eq!(
            read_header(&Journal::path_in(dir.path())).unwrap(),
            header()
        );
        assert_eq!(record(1, 0).key(), (1, "RNE", 0));
    }

    #[test]
    fn resume_reads_records_and_drops_a_cut_line() {
        let dir = tempfile::tempdir().unwrap();
        let mut j = Journal::create(dir.path(), &header()).unwrap();
        j.append(&record(0, 0)).unwrap();
        drop(j);
        assert!(Journal::create(dir.path(), &header()).is_err());
        let path = Journal::path_in(dir.path());
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(b"{\"trial\":{\"meth").unwrap();
        drop(f);
        let (mut j, recs) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(recs, vec![record(0, 0)]);
        j.append(&record(1, 1)).unwrap();
        drop(j);
        let (_, recs) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(recs, vec![record(0, 0), record(1, 1)]);
        // A kill after the record but before its newline: the record parses but is redone.
        let whole = serde_json::to_string(&LineRef::Trial(&record(0, 2))).unwrap();
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(whole.as_bytes()).unwrap();
        drop(f);
        let read = read_journal(&path).unwrap();
        assert_eq!(read.records, vec![record(0, 0), record(1, 1)]);
        assert!(read.complete_bytes < fs::metadata(&path).unwrap().len());
        let (_, recs) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(recs, vec![record(0, 0), record(1, 1)]);
        assert!(fs::read_to_string(&path).unwrap().ends_with('\n'));
    }

    #[test]
    fn resume_refuses_other_parameters() {
        let dir = tempfile::tempdir().unwrap();
        Journal::create(dir.path(), &header()).unwrap();
        let mut other = header();
        other.trials = 3;
        other.base_seed = 7;
        other.grid.cells[1].scenario_hash = fnv1a64_hex(b"u");
        let e = Journal::open_resume(dir.path(), &other).unwrap_err();
        let msg = format!("{e:#}");
        assert!(msg.contains("trials 2 vs 3"), "{msg}");
        assert!(msg.contains("seed 1 vs 7"), "{msg}");
        assert!(msg.contains("cell 1 scenario hash"), "{msg}");
        other.grid.fields = vec!["sim.dt_s".into()];
        assert!(
            header_diff(&header(), &other)
                .contains("varied fields [mission.duration_s] vs [sim.dt_s]")
        );
    }

    #[test]
    fn a_journal_of_another_format_is_named_as_such() {
        let dir = tempfile::tempdir().unwrap();
        let path = Journal::path_in(dir.path());
        fs::write(
            &path,
            "{\"header\":{\"format\":1,\"version\":\"0.1.0\",\"scenario\":\"paper\"}}\n",
        )
        .unwrap();
        for e in [
            read_header(&path).unwrap_err(),
            Journal::open_resume(dir.path(), &header()).unwrap_err(),
        ] {
            let msg = format!("{e:#}");
            assert!(
                msg.contains("journal format 1, but this usar reads format 2"),
                "{msg}"
            );
        }
    }
}
