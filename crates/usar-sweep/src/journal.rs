//! The sweep journal: `journal.jsonl` at the top of the output folder, one JSON object per
//! line.
//!
//! The first line is the [`SweepHeader`]: the sweep's parameters, including its grid (the
//! varied fields and, per cell, their values, the cell's scenario hash and trial length; a
//! sweep without `--vary` is a grid of one cell with no fields). Every later line is one
//! [`TrialRecord`], appended and flushed as soon as its trial ends, in completion order.
//!
//! Every line carries a checksum of its content, `{"header":{..},"sum":"<hex>"}` and
//! `{"trial":{..},"sum":"<hex>"}` ([`crate::checked_log`], the plumbing the journal shares
//! with a calibration's trace): [`header_sum`] of the header's JSON, and [`record_sum`] of
//! the header's sum and the record's JSON (as written, compact, fields in declaration order),
//! so a record verifies only in the journal of its own sweep. A header that does not verify
//! makes the journal unusable; a record that does not verify is left out (listed in
//! [`JournalContents::rejected`]) and its trial runs again. The sums are FNV-1a 64: they catch
//! edits and damage, not a forger who recomputes them.
//!
//! A record is identified by its [`RecordKey`] `(cell, method, trial)`. A key may appear more
//! than once (a failed trial retried by `--resume`); the last record wins. Nothing else about
//! a record depends on the journal it is in, so [`crate::shard`] splits the job list into
//! shards that write journals of their own, and merges them by reading each with
//! [`read_journal`], checking their headers agree and keeping the last record per key. A kill
//! can leave a last line cut short; [`Journal::open_resume`] drops it.

use std::fs::{self, File};
use std::io::{BufRead, BufReader, Read};
use std::path::{Path, PathBuf};

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use usar_sim::mission::TrialResult;
use usar_sim::scenario::path_text;

use crate::atomic::FileError;
use crate::checked_log::{LogWriter, RecordLine, parse_line, read_records};
/// The checksums of the journal's lines (from [`crate::checked_log`], kept here for callers
/// that verify a journal by hand).
pub use crate::checked_log::{header_sum, record_sum};
pub use crate::journal_error::JournalError;

/// File name of the journal inside the output folder.
pub const JOURNAL_FILE: &str = "journal.jsonl";

/// Format version of the journal; bumped when its lines change shape. Format 2 added the
/// grid to the header and the cell index to every record; format 3 a checksum to every line;
/// format 4 the cell's task names and difficulty order to the header, and per-task results
/// (one entry per task, in the scenario's order) to every record; format 5 the build that
/// wrote the journal to the header ([`SweepHeader::build`]).
pub const JOURNAL_FORMAT: u32 = 5;

/// The parameters that determine a sweep's results. `--resume` continues a journal only if
/// its header equals the new sweep's header.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SweepHeader {
    /// [`JOURNAL_FORMAT`].
    pub format: u32,
    /// Version of the `experiments` crate that wrote the journal.
    pub version: String,
    /// The build of `usar` that wrote the journal (`usar_report::report::software_build`: the git
    /// commit, with a hash of the uncommitted changes when there are any; empty when built
    /// outside a git checkout). Another build may simulate differently, so its journal is
    /// neither continued nor merged: before format 5, a sweep rerun after the model's code
    /// changed silently reused the old code's trials.
    pub build: String,
    /// Name of the scenario the grid was built from.
    pub scenario: String,
    /// Grouping methods (display names, as written), in sweep order.
    pub methods: Vec<String>,
    /// Trials per method and cell.
    pub trials: u32,
    /// Base seed; trial `k` of every method and cell uses `trial_seed(base_seed, k)`.
    pub base_seed: u64,
    /// The cells the sweep runs.
    pub grid: GridHeader,
}

/// The grid of a sweep: varied fields and cells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct GridHeader {
    /// Varied field paths in `--vary` order; empty for a sweep without `--vary`.
    pub fields: Vec<String>,
    /// The cells, first field varying slowest; exactly one for a sweep without `--vary`.
    pub cells: Vec<CellHeader>,
}

/// One cell of the grid.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CellHeader {
    /// The value of each varied field, as written on the command line, in field order.
    pub values: Vec<String>,
    /// [`crate::fingerprint::scenario_hash`] of the cell's validated scenario.
    pub scenario_hash: String,
    /// Simulated length of each trial of the cell, seconds.
    pub duration_s: f64,
    /// The cell's task names, by task id (the outputs' per-task columns).
    pub tasks: Vec<String>,
    /// The cell's task ids from the hardest to the easiest.
    pub hardest_first: Vec<usize>,
}

/// How one trial ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The trial ran to its time limit.
    Ok(Box<TrialResult>),
    /// The trial returned an error or panicked; the message says which.
    Failed(String),
}

/// One journal line after the header.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct TrialRecord {
    /// Grid cell index, 0-based (into [`GridHeader::cells`]).
    pub cell: usize,
    /// Grouping method (display name, as written).
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

/// One line of `journal.jsonl` (and of each shard's journal, which `usar merge` reads), as
/// its published schema describes it (`docs/schema/journal-line.schema.json`): the header
/// line first, then one trial line per finished trial. `sum` is the line's checksum (see the
/// module doc: FNV-1a 64, 16 lower-case hex digits). The journal writes these lines itself,
/// field by field; this type exists for the schema.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(untagged)]
pub enum JournalLine {
    /// The first line: the sweep's parameters.
    Header {
        /// The sweep's parameters.
        header: SweepHeader,
        /// [`header_sum`] of the header's JSON.
        sum: String,
    },
    /// Every later line: one trial.
    Trial {
        /// The trial.
        trial: TrialRecord,
        /// [`record_sum`] of the header's sum and the record's JSON.
        sum: String,
    },
}

/// What identifies a record: `(cell, method, trial)`.
pub type RecordKey<'a> = (usize, &'a str, u32);

impl TrialRecord {
    /// The record's identity.
    pub fn key(&self) -> RecordKey<'_> {
        (self.cell, &self.method, self.trial)
    }
}

/// One line of the journal as read back: the header's or the record's JSON as written, and
/// the line's checksum.
/// A complete record line whose checksum does not verify (an edit, or damage that left valid
/// JSON): it is not used, nor are earlier records of its trial.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RejectedRecord {
    /// Line number in the journal, 1-based.
    pub line: usize,
    /// Grid cell index the line claims.
    pub cell: usize,
    /// Method the line claims.
    pub method: String,
    /// Trial index the line claims.
    pub trial: u32,
}

impl RejectedRecord {
    /// The identity of the trial the line claims, as [`TrialRecord::key`].
    pub fn key(&self) -> RecordKey<'_> {
        (self.cell, &self.method, self.trial)
    }
}

/// A journal read from a file.
#[derive(Debug, Clone, PartialEq)]
pub struct JournalContents {
    /// Its header.
    pub header: SweepHeader,
    /// The header's checksum ([`header_sum`]), which every record's checksum includes.
    pub header_sum: String,
    /// Its complete records that verify, in file order (a key may repeat: the last one wins).
    /// A record that does not verify removes the earlier records of its key.
    pub records: Vec<TrialRecord>,
    /// Complete record lines that do not verify, in file order.
    pub rejected: Vec<RejectedRecord>,
    /// Length in bytes of the header and complete records: what is left of the file once a
    /// last line cut short by a kill is dropped.
    pub complete_bytes: u64,
}

/// What the functions of this module return.
type Result<T> = std::result::Result<T, JournalError>;

/// The error for a damaged line (`line` is 1-based).
fn damaged(path: &Path, line: usize) -> JournalError {
    JournalError::DamagedLine {
        path: path_text(path),
        line,
    }
}

/// Parses and verifies the header line (the first line, as read) of the journal at `path`;
/// returns the header and its checksum.
fn parse_header_line(path: &Path, line: &[u8]) -> Result<(SweepHeader, String)> {
    let not_a_header = || JournalError::NotAHeader {
        path: path_text(path),
    };
    let line = std::str::from_utf8(line).map_err(|_| not_a_header())?;
    check_format(path, line)?;
    if !line.ends_with('\n') {
        return Err(JournalError::HeaderCut {
            path: path_text(path),
        });
    }
    let (json, sum) = parse_line(line, "header").ok_or_else(not_a_header)?;
    let expected = header_sum(json);
    if sum.as_deref() != Some(expected.as_str()) {
        return Err(JournalError::HeaderUnverified {
            path: path_text(path),
        });
    }
    let header = serde_json::from_str::<SweepHeader>(json).map_err(|_| not_a_header())?;
    Ok((header, expected))
}

/// Reads the journal at `path`: its header and every complete record, each verified against
/// its checksum. A last line without its newline was cut short by a kill, even when what was
/// written of it parses: it is left out (and redone by a resume). A complete record that does
/// not verify is listed in [`JournalContents::rejected`] and left out, with the earlier records
/// of its key.
///
/// # Errors
/// An unreadable file, a journal of another [`JOURNAL_FORMAT`], a missing header or one that
/// does not verify, or a damaged line other than the last (the message gives its line number
/// and names `--overwrite`).
pub fn read_journal(path: &Path) -> Result<JournalContents> {
    check_regular_file(path)?;
    let bytes =
        fs::read(path).map_err(FileError::io(format!("cannot read {}", path_text(path))))?;
    let Some(first) = bytes.split_inclusive(|&b| b == b'\n').next() else {
        return Err(JournalError::Empty {
            path: path_text(path),
        });
    };
    let (header, sum) = parse_header_line(path, first)?;
    let mut records: Vec<TrialRecord> = Vec::new();
    let mut rejected = Vec::new();
    let complete_bytes = read_records(&bytes, first.len(), &sum, "trial", |line, r| {
        let (json, verified) = match r {
            RecordLine::Verified(json) => (json, true),
            RecordLine::Unverified(json) => (json, false),
            RecordLine::Damaged => return Err(damaged(path, line)),
        };
        let record: TrialRecord = serde_json::from_str(json).map_err(|_| damaged(path, line))?;
        if verified {
            records.push(record);
        } else {
            records.retain(|r| r.key() != record.key());
            rejected.push(RejectedRecord {
                line,
                cell: record.cell,
                method: record.method,
                trial: record.trial,
            });
        }
        Ok(())
    })?;
    Ok(JournalContents {
        header,
        header_sum: sum,
        records,
        rejected,
        complete_bytes,
    })
}

/// Refuses a journal whose first line is the header of another format.
fn check_format(path: &Path, first_line: &str) -> Result<()> {
    let format = serde_json::from_str::<serde_json::Value>(first_line.trim_end())
        .ok()
        .and_then(|v| v.get("header")?.get("format")?.as_u64());
    match format {
        Some(found) if found != u64::from(JOURNAL_FORMAT) => Err(JournalError::Format {
            path: path_text(path),
            found,
            expected: JOURNAL_FORMAT,
        }),
        _ => Ok(()),
    }
}

/// The header of the journal at `path` (its first line only), verified.
///
/// # Errors
/// As [`read_journal`] for the first line.
pub fn read_header(path: &Path) -> Result<SweepHeader> {
    parse_header_line(path, &first_line(path)?).map(|(h, _)| h)
}

/// The first line of the regular file at `path`, with its newline if it has one.
fn first_line(path: &Path) -> Result<Vec<u8>> {
    check_regular_file(path)?;
    let file =
        File::open(path).map_err(FileError::io(format!("cannot read {}", path_text(path))))?;
    let mut first = Vec::new();
    BufReader::new(file)
        .read_until(b'\n', &mut first)
        .map_err(FileError::io(format!("reading {}", path_text(path))))?;
    Ok(first)
}

/// The header of the journal at `path` as written, without checking its checksum, its
/// format or that its line is complete: only to learn which files and cell folders its sweep
/// wrote (`--overwrite` removes them), never to trust a record. `None` when there is no
/// regular file at `path` or its first line holds no header of this format's shape.
pub fn read_header_unverified(path: &Path) -> Option<SweepHeader> {
    let line = first_line(path).ok()?;
    let (json, _) = parse_line(std::str::from_utf8(&line).ok()?, "header")?;
    serde_json::from_str(json).ok()
}

/// Whether the regular file at `path` holds no complete line and nothing but the start of a
/// journal header (empty, or a sweep killed while it wrote its header): no trial to lose.
pub fn holds_no_line(path: &Path) -> bool {
    const HEADER_START: &[u8] = b"{\"header\":";
    // Checked before opening: opening a FIFO to read waits for a writer.
    let Some(file) = check_regular_file(path)
        .ok()
        .and_then(|()| File::open(path).ok())
    else {
        return false;
    };
    let mut start = Vec::new();
    let read = BufReader::new(file)
        .take(1 << 20)
        .read_until(b'\n', &mut start);
    read.is_ok()
        && !start.ends_with(b"\n")
        && start.len() < 1 << 20
        && (start.starts_with(HEADER_START) || HEADER_START.starts_with(&start))
}

/// Why the journal at `path` is another sweep's than the one with `header`: the differences
/// ([`header_diff`]), or that its header cannot be read. `None` when nothing is at `path`,
/// it holds no line ([`holds_no_line`]), or its header (not verified:
/// [`read_header_unverified`]) is `header`.
pub fn other_sweeps(path: &Path, header: &SweepHeader) -> Option<String> {
    if !something_at(path) || holds_no_line(path) {
        return None;
    }
    match read_header_unverified(path) {
        Some(found) if &found == header => None,
        Some(found) => Some(header_diff(&found, header)),
        None => Some("its header cannot be read".to_string()),
    }
}

/// Whether anything, even a symbolic link to a missing file, is at `path`.
pub fn something_at(path: &Path) -> bool {
    path.symlink_metadata().is_ok()
}

/// Refuses a journal path that is not a regular file (after symbolic links): a folder, a FIFO
/// (reading one would wait for a writer for ever), a device, or a link to a missing file.
fn check_regular_file(path: &Path) -> Result<()> {
    match fs::metadata(path) {
        Ok(m) if m.is_file() => Ok(()),
        Ok(m) if m.is_dir() => Err(JournalError::Folder {
            path: path_text(path),
        }),
        Ok(_) => Err(JournalError::NotAFile {
            path: path_text(path),
        }),
        Err(_) if something_at(path) => Err(JournalError::DanglingLink {
            path: path_text(path),
        }),
        Err(e) => Err(FileError::io(format!("cannot read {}", path_text(path)))(e).into()),
    }
}

/// An open journal, appending one flushed line per record ([`LogWriter`]: a line that cannot
/// be written whole is cut back off the file).
#[derive(Debug)]
pub struct Journal {
    log: LogWriter,
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
        let log =
            LogWriter::create_with(Self::path_in(dir), "header", header, "the journal header")?;
        Ok(Self { log })
    }

    /// Opens the journal in `dir` to continue it: checks that its header verifies and equals
    /// `header` and returns the journal with what it already holds ([`read_journal`]: the
    /// records that verify, and those that do not). A last line cut short by a kill is removed
    /// from the file.
    ///
    /// # Errors
    /// No journal, a journal written with other parameters (the message lists the
    /// differences), a header that does not verify, a damaged line other than the last, or an
    /// I/O error.
    pub fn open_resume(dir: &Path, header: &SweepHeader) -> Result<(Self, JournalContents)> {
        let path = Self::path_in(dir);
        let contents = read_journal(&path)?;
        if &contents.header != header {
            return Err(JournalError::OtherParameters {
                path: path_text(&path),
                diff: header_diff(&contents.header, header),
            });
        }
        let log = LogWriter::resume(&path, contents.header_sum.clone(), contents.complete_bytes)?;
        Ok((Self { log }, contents))
    }

    /// Appends `record` as one line with its checksum ([`record_sum`]) and flushes it to the
    /// operating system.
    ///
    /// # Errors
    /// An I/O error.
    pub fn append(&mut self, record: &TrialRecord) -> Result<()> {
        Ok(self.log.append_value("trial", record, "a journal record")?)
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
    if old.build != new.build {
        let name = |b: &str| {
            if b.is_empty() {
                "unrecorded".to_owned()
            } else {
                b.to_owned()
            }
        };
        d.push(format!(
            "build {} vs {} (another build of usar may simulate differently)",
            name(&old.build),
            name(&new.build)
        ));
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

/// What a changed scenario hash means ([`crate::fingerprint::scenario_hash`]).
const EDITED: &str =
    "the scenario changed: a value or its description, in its file or set on top of it";

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
    // An edit of the scenario file changes every cell's hash: said once.
    let every_hash = old.cells.len() > 1
        && old
            .cells
            .iter()
            .zip(&new.cells)
            .all(|(a, b)| a.values == b.values && a.scenario_hash != b.scenario_hash);
    if every_hash {
        d.push(format!("another scenario in every cell ({EDITED})"));
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
        // Other values give another hash: that is said by the values.
        if a.scenario_hash != b.scenario_hash && a.values == b.values && !every_hash {
            d.push(format!(
                "{cell}scenario hash {} vs {} ({EDITED})",
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
pub(crate) mod tests {
    use std::fs::OpenOptions;
    use std::io::Write;

    use super::*;
    use crate::checked_log::checked_line;
    use crate::fingerprint::fnv1a64_hex;

    /// A header of a 2-cell grid over `mission.duration_s` (values `10` and `20`).
    pub(crate) fn header() -> SweepHeader {
        SweepHeader {
            format: JOURNAL_FORMAT,
            version: "0".into(),
            build: "abc1234".into(),
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
                        tasks: vec!["hard".into(), "easy".into()],
                        hardest_first: vec![0, 1],
                    },
                    CellHeader {
                        values: vec!["20".into()],
                        scenario_hash: fnv1a64_hex(b"t"),
                        duration_s: 20.0,
                        tasks: vec!["hard".into(), "easy".into()],
                        hardest_first: vec![0, 1],
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
            lines[0].starts_with(&format!("{{\"header\":{{\"format\":{JOURNAL_FORMAT},")),
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
        let (mut j, c) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(c.records, vec![record(0, 0)]);
        j.append(&record(1, 1)).unwrap();
        drop(j);
        let (_, c) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(c.records, vec![record(0, 0), record(1, 1)]);
        assert!(c.rejected.is_empty());
        // A kill after the record but before its newline: the record parses but is redone.
        let json = serde_json::to_string(&record(0, 2)).unwrap();
        let whole = checked_line("trial", &json, &record_sum(&c.header_sum, &json));
        let whole = whole.trim_end();
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(whole.as_bytes()).unwrap();
        drop(f);
        let read = read_journal(&path).unwrap();
        assert_eq!(read.records, vec![record(0, 0), record(1, 1)]);
        assert!(read.complete_bytes < fs::metadata(&path).unwrap().len());
        let (_, c) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(c.records, vec![record(0, 0), record(1, 1)]);
        assert!(fs::read_to_string(&path).unwrap().ends_with('\n'));
    }

    #[test]
    fn nul_bytes_a_crash_left_at_the_end_are_dropped_as_a_cut_line() {
        let dir = tempfile::tempdir().unwrap();
        let mut j = Journal::create(dir.path(), &header()).unwrap();
        j.append(&record(0, 0)).unwrap();
        let whole = fs::metadata(Journal::path_in(dir.path())).unwrap().len();
        drop(j);
        // A system crash after the file grew but before its last block was written.
        let mut f = OpenOptions::new()
            .append(true)
            .open(Journal::path_in(dir.path()))
            .unwrap();
        f.write_all(&[0; 4096]).unwrap();
        drop(f);
        let (mut j, c) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!((c.records, c.complete_bytes), (vec![record(0, 0)], whole));
        j.append(&record(1, 1)).unwrap();
        drop(j);
        let c = read_journal(&Journal::path_in(dir.path())).unwrap();
        assert_eq!(c.records, vec![record(0, 0), record(1, 1)]);
    }

    /// A journal of `header()` with records (0, 0) failed, (0, 0) ok... as `record` makes them,
    /// then (1, 1); returns its path and lines.
    fn journal_of_three(dir: &Path) -> (PathBuf, Vec<String>) {
        let mut j = Journal::create(dir, &header()).unwrap();
        for r in [record(0, 0), record(0, 1), record(1, 1)] {
            j.append(&r).unwrap();
        }
        let path = Journal::path_in(dir);
        let lines = fs::read_to_string(&path)
            .unwrap()
            .lines()
            .map(String::from)
            .collect();
        (path, lines)
    }

    fn write_lines(path: &Path, lines: &[String]) {
        fs::write(path, lines.join("\n") + "\n").unwrap();
    }

    #[test]
    fn every_line_carries_a_checksum() {
        let dir = tempfile::tempdir().unwrap();
        let (path, lines) = journal_of_three(dir.path());
        let c = read_journal(&path).unwrap();
        let header_json = serde_json::to_string(&header()).unwrap();
        assert_eq!(c.header_sum, header_sum(&header_json));
        assert_eq!(
            lines[0],
            format!("{{\"header\":{header_json},\"sum\":\"{}\"}}", c.header_sum)
        );
        let rec_json = serde_json::to_string(&record(0, 1)).unwrap();
        assert!(
            lines[2].ends_with(&format!(
                ",\"sum\":\"{}\"}}",
                record_sum(&c.header_sum, &rec_json)
            )),
            "{}",
            lines[2]
        );
        assert_eq!(c.records.len(), 3);
        assert!(c.rejected.is_empty());
    }

    #[test]
    fn an_edited_record_is_rejected_by_line_with_the_earlier_records_of_its_trial() {
        let dir = tempfile::tempdir().unwrap();
        let (path, mut lines) = journal_of_three(dir.path());
        // A retry of trial (0, 0), then an edit of it that stays valid JSON.
        let mut j = Journal::open_resume(dir.path(), &header()).unwrap().0;
        j.append(&record(0, 0)).unwrap();
        drop(j);
        lines.push(
            fs::read_to_string(&path)
                .unwrap()
                .lines()
                .last()
                .unwrap()
                .into(),
        );
        lines[4] = lines[4].replace("\"wall_s\":0.5", "\"wall_s\":0.25");
        write_lines(&path, &lines);
        let c = read_journal(&path).unwrap();
        assert_eq!(c.records, vec![record(0, 1), record(1, 1)]);
        assert_eq!(
            c.rejected,
            vec![RejectedRecord {
                line: 5,
                cell: 0,
                method: "RNE".into(),
                trial: 0
            }]
        );
        // A missing sum does not verify either, nor does a record from another sweep's journal.
        let mut other = header();
        other.base_seed = 2;
        let other_dir = tempfile::tempdir().unwrap();
        let mut j = Journal::create(other_dir.path(), &other).unwrap();
        j.append(&record(1, 0)).unwrap();
        drop(j);
        let foreign = fs::read_to_string(Journal::path_in(other_dir.path())).unwrap();
        lines[4] = foreign.lines().nth(1).unwrap().into();
        lines[2] = lines[2][..lines[2].rfind(",\"sum\"").unwrap()].to_string() + "}";
        write_lines(&path, &lines);
        let c = read_journal(&path).unwrap();
        assert_eq!(c.records, vec![record(0, 0), record(1, 1)]);
        let rejected: Vec<_> = c
            .rejected
            .iter()
            .map(|r| (r.line, r.cell, r.trial))
            .collect();
        assert_eq!(rejected, [(3, 0, 1), (5, 1, 0)]);
    }

    #[test]
    fn an_edited_header_is_refused_naming_overwrite() {
        let dir = tempfile::tempdir().unwrap();
        let (path, mut lines) = journal_of_three(dir.path());
        lines[0] = lines[0].replace("\"trials\":2", "\"trials\":3");
        write_lines(&path, &lines);
        let mut edited = header();
        edited.trials = 3;
        for e in [
            read_journal(&path).unwrap_err(),
            read_header(&path).unwrap_err(),
            Journal::open_resume(dir.path(), &edited).unwrap_err(),
        ] {
            let msg = format!("{e:#}");
            assert!(
                msg.contains(":1: the header does not verify (edited?)")
                    && msg.contains("--overwrite"),
                "{msg}"
            );
        }
    }

    #[test]
    fn a_damaged_line_names_overwrite() {
        let dir = tempfile::tempdir().unwrap();
        let (path, mut lines) = journal_of_three(dir.path());
        lines[2] = lines[2][..40].to_string();
        write_lines(&path, &lines);
        let e = Journal::open_resume(dir.path(), &header()).unwrap_err();
        let msg = format!("{e:#}");
        assert!(
            msg.contains("journal.jsonl:3: not a valid journal line")
                && msg.contains("--overwrite (in place of --resume)"),
            "{msg}"
        );
        assert!(!msg.contains("run the sweep again"), "{msg}");
    }

    #[test]
    fn an_edited_scenario_is_said_once_for_every_cell() {
        let mut edited = header();
        for c in &mut edited.grid.cells {
            c.scenario_hash = fnv1a64_hex(c.scenario_hash.as_bytes());
        }
        assert_eq!(
            header_diff(&header(), &edited),
            "journal has another scenario in every cell (the scenario changed: a value or its \
             description, in its file or set on top of it)"
        );
        edited.grid.cells[0] = header().grid.cells[0].clone();
        let one = header_diff(&header(), &edited);
        assert!(
            one.starts_with("journal has cell 1 scenario hash "),
            "{one}"
        );
        assert!(one.ends_with(
            " (the scenario changed: a value or its description, in its file or set on top of it)"
        ));
        // Another value of the varied field gives another hash: the value says it.
        edited.grid.cells[1].values = vec!["30".into()];
        assert_eq!(
            header_diff(&header(), &edited),
            "journal has cell 1 values 20 vs 30"
        );
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
                msg.contains(&format!(
                    "journal format 1, but this usar reads format {JOURNAL_FORMAT}"
                )),
                "{msg}"
            );
        }
    }

    #[test]
    fn a_last_line_cut_inside_a_character_is_dropped_and_a_bad_byte_is_placed() {
        let dir = tempfile::tempdir().unwrap();
        let mut j = Journal::create(dir.path(), &header()).unwrap();
        j.append(&record(0, 0)).unwrap();
        drop(j);
        let path = Journal::path_in(dir.path());
        let whole = fs::read(&path).unwrap();
        // A kill one byte into a two-byte character ("\u{fc}" is C3 BC in UTF-8).
        let mut cut = whole.clone();
        cut.extend_from_slice(b"{\"trial\":{\"scenario\":\"Pr\xc3");
        fs::write(&path, &cut).unwrap();
        let (_, c) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(c.records, vec![record(0, 0)]);
        assert_eq!(fs::read(&path).unwrap(), whole);
        // A complete line that is not UTF-8 is damaged, by its line number.
        let mut bad = whole.clone();
        bad.extend_from_slice(b"{\"trial\":\xff}\n");
        bad.extend_from_slice(&whole[whole.iter().position(|&b| b == b'\n').unwrap() + 1..]);
        fs::write(&path, &bad).unwrap();
        let msg = format!("{:#}", read_journal(&path).unwrap_err());
        assert!(
            msg.contains("journal.jsonl:3: not a valid journal line"),
            "{msg}"
        );
        // And a header that is not UTF-8.
        fs::write(&path, b"{\"header\":\xff}\n").unwrap();
        for e in [
            read_journal(&path).unwrap_err(),
            read_header(&path).unwrap_err(),
        ] {
            let msg = format!("{e:#}");
            assert!(
                msg.contains("journal.jsonl:1: not a journal header"),
                "{msg}"
            );
        }
    }

    #[cfg(unix)]
    #[test]
    fn a_journal_that_is_a_fifo_or_a_dangling_link_is_refused_without_waiting() {
        let dir = tempfile::tempdir().unwrap();
        let path = Journal::path_in(dir.path());
        let made = std::process::Command::new("mkfifo").arg(&path).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo");
        for e in [
            read_journal(&path).unwrap_err(),
            read_header(&path).unwrap_err(),
            Journal::open_resume(dir.path(), &header()).unwrap_err(),
        ] {
            let msg = format!("{e:#}");
            assert!(msg.contains("journal.jsonl: not a regular file"), "{msg}");
            assert!(msg.contains("--overwrite"), "{msg}");
        }
        fs::remove_file(&path).unwrap();
        std::os::unix::fs::symlink(dir.path().join("gone"), &path).unwrap();
        assert!(something_at(&path) && !path.exists());
        let msg = format!("{:#}", read_journal(&path).unwrap_err());
        assert!(
            msg.contains("journal.jsonl: a symbolic link to a missing file"),
            "{msg}"
        );
    }

    #[test]
    fn a_line_that_cannot_be_written_whole_is_cut_back_off() {
        let dir = tempfile::tempdir().unwrap();
        let path = Journal::path_in(dir.path());
        let mut j = Journal::create(dir.path(), &header()).unwrap();
        j.append(&record(0, 0)).unwrap();
        let before = fs::read(&path).unwrap();
        // A full disk cuts the next line after 40 bytes; another thread's record follows
        // once space is back.
        j.log.fail_after_bytes = Some(40);
        let msg = rne_core::error_line(&j.append(&record(1, 1)).unwrap_err());
        assert!(
            msg.contains("appending to") && msg.contains("no space left"),
            "{msg}"
        );
        assert_eq!(fs::read(&path).unwrap(), before);
        j.append(&record(0, 2)).unwrap();
        drop(j);
        let (_, c) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(c.records, vec![record(0, 0), record(0, 2)]);
        assert!(c.rejected.is_empty());
        // The same in a resumed journal (opened to append).
        let (mut j, _) = Journal::open_resume(dir.path(), &header()).unwrap();
        j.log.fail_after_bytes = Some(30);
        assert!(j.append(&record(1, 0)).is_err());
        j.append(&record(1, 1)).unwrap();
        drop(j);
        let c = read_journal(&path).unwrap();
        assert_eq!(c.records, vec![record(0, 0), record(0, 2), record(1, 1)]);
        // If the cut fails too, nothing more is appended after the partial line.
        let (mut j, _) = Journal::open_resume(dir.path(), &header()).unwrap();
        j.log.replace_file(File::open(&path).unwrap());
        j.log.fail_after_bytes = Some(0);
        assert!(j.append(&record(1, 1)).is_err());
        j.log
            .replace_file(OpenOptions::new().append(true).open(&path).unwrap());
        let msg = format!("{:#}", j.append(&record(1, 2)).unwrap_err());
        assert!(msg.contains("could not be written nor removed"), "{msg}");
        assert_eq!(read_journal(&path).unwrap().records.len(), 3);
    }

    #[test]
    fn blank_lines_hold_nothing_and_a_cut_header_holds_no_line() {
        let dir = tempfile::tempdir().unwrap();
        let path = Journal::path_in(dir.path());
        let mut j = Journal::create(dir.path(), &header()).unwrap();
        j.append(&record(0, 0)).unwrap();
        drop(j);
        assert!(!holds_no_line(&path));
        let whole = fs::read_to_string(&path).unwrap();
        fs::write(&path, format!("{whole}\n  \n")).unwrap();
        let (mut j, c) = Journal::open_resume(dir.path(), &header()).unwrap();
        assert_eq!(c.records, vec![record(0, 0)]);
        j.append(&record(0, 1)).unwrap();
        drop(j);
        assert_eq!(read_journal(&path).unwrap().records.len(), 2);
        // A header cut short (or nothing) holds no trial; other text is not taken for one.
        let first = whole.lines().next().unwrap();
        for (text, none) in [
            ("", true),
            ("{\"hea", true),
            (&first[..first.len() / 2], true),
            ("notes", false),
            (&whole[..], false),
        ] {
            fs::write(&path, text).unwrap();
            assert_eq!(holds_no_line(&path), none, "{text:?}");
        }
        // The message for a damaged line says which line to delete.
        fs::write(&path, format!("{whole}garbage\n{whole}")).unwrap();
        let msg = format!("{:#}", read_journal(&path).unwrap_err());
        assert!(
            msg.contains(
                "journal.jsonl:3: not a valid journal line; the journal is damaged: \
                          delete that line"
            ),
            "{msg}"
        );
    }
}
