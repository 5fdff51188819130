//! Checksummed JSON-lines logs, the plumbing of the sweep journal ([`crate::journal`]) and a
//! calibration's trace (`usar_study::calibrate::trace`); a multiverse's universe and design records
//! are single lines of the same shape.
//!
//! A log is a header line and record lines, each `{"<key>":<json>,"sum":"<hex>"}` and its
//! newline ([`checked_line`]): the header's sum is [`header_sum`] of its JSON as written, a
//! record's [`record_sum`] of the header's sum and its JSON, so a record verifies only in the
//! log of its own header. The sums are FNV-1a 64: they catch edits and damage, not a forger
//! who recomputes them.
//!
//! Reading ([`read_records`]) keeps complete lines only: a last line without its newline was
//! cut short by a kill (perhaps inside a multi-byte character) and is left out, and a blank
//! line holds nothing. Writing ([`LogWriter`]) appends one flushed line at a time; a line that
//! cannot be written whole (a full disk) is cut back off the file, so the log keeps only
//! complete lines.

use std::collections::BTreeMap;
use std::fs::{self, File, OpenOptions};
use std::io::{Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde_json::value::RawValue;
use usar_sim::scenario::path_text;

use crate::atomic::FileError;
use crate::fingerprint::fnv1a64_hex;

/// Why a log could not be written ([`LogWriter`]).
#[derive(Debug, thiserror::Error)]
pub enum LogError {
    /// An I/O error creating, opening, truncating or appending to the log (or making its
    /// folder), naming the path.
    #[error(transparent)]
    File(#[from] FileError),
    /// An earlier line could be neither written whole nor cut back off the file: the log may
    /// end with part of a line, so nothing more is appended.
    #[error("{path}: an earlier line could not be written nor removed; not appending")]
    Damaged {
        /// The log's path, as shown.
        path: String,
    },
    /// A header or record that cannot be written as JSON (`what`: `the journal header`, `an
    /// evaluation`; not expected).
    #[error("serialising {what}")]
    Serialise {
        /// What was being written.
        what: &'static str,
        /// The serialiser's error.
        #[source]
        source: serde_json::Error,
    },
}

/// `value` as compact JSON, or the [`LogError::Serialise`] of `what`.
fn json_of<T: Serialize>(value: &T, what: &'static str) -> Result<String> {
    serde_json::to_string(value).map_err(|source| LogError::Serialise { what, source })
}

/// What the writing functions of this module return.
type Result<T> = std::result::Result<T, LogError>;

/// The checksum of a header line: FNV-1a 64 ([`fnv1a64_hex`]) of the header's JSON as
/// written. Every record's checksum includes it ([`record_sum`]).
pub fn header_sum(header_json: &str) -> String {
    fnv1a64_hex(header_json.as_bytes())
}

/// The checksum of a record line in the log whose header has checksum `header_sum`: FNV-1a 64
/// of `<header_sum>:<record JSON as written>`.
pub fn record_sum(header_sum: &str, record_json: &str) -> String {
    fnv1a64_hex(format!("{header_sum}:{record_json}").as_bytes())
}

/// A log line: `{"<key>":<json>,"sum":"<sum>"}` and its newline.
pub fn checked_line(key: &str, json: &str, sum: &str) -> String {
    format!("{{\"{key}\":{json},\"sum\":\"{sum}\"}}\n")
}

/// One line as read back: the JSON under `key` as written, and the sum it carries (`None`
/// when it carries none). `None` unless the line is one JSON object holding `key` and at
/// most a string `sum` besides.
pub fn parse_line<'a>(line: &'a str, key: &str) -> Option<(&'a str, Option<String>)> {
    let map: BTreeMap<&str, &RawValue> = serde_json::from_str(line.trim_end()).ok()?;
    let json = map.get(key)?.get();
    let sum = match map.get("sum") {
        Some(raw) => Some(serde_json::from_str::<String>(raw.get()).ok()?),
        None => None,
    };
    (map.len() == 1 + usize::from(sum.is_some())).then_some((json, sum))
}

/// A record line on its own (a multiverse's universe or design record, one file each):
/// [`checked_line`] of `json` under `key` with [`record_sum`] of `identity_sum` (the checksum
/// of what the record belongs to) and `json`. (The multiverse's.)
pub fn record_line(key: &str, json: &str, identity_sum: &str) -> String {
    checked_line(key, json, &record_sum(identity_sum, json))
}

/// The JSON under `key` of the line `text` written by [`record_line`] with `identity_sum`:
/// `None` when it is not such a line or does not verify (edited, damaged, another identity's).
/// (The multiverse's.)
pub fn verified_record<'a>(text: &'a str, key: &str, identity_sum: &str) -> Option<&'a str> {
    let (json, sum) = parse_line(text, key)?;
    (sum? == record_sum(identity_sum, json)).then_some(json)
}

/// A record line after the header, as [`read_records`] hands it over.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RecordLine<'a> {
    /// The record's JSON, its sum verified.
    Verified(&'a str),
    /// The record's JSON, its sum missing or wrong (an edit, or damage that left valid JSON).
    Unverified(&'a str),
    /// Not UTF-8, or not a line of the record's shape: the log is damaged at this line.
    Damaged,
}

/// Walks the record lines of a log whose header line (with its newline) is the first
/// `header_len` bytes of `bytes` and has checksum `header_sum`: calls `each(line, record)`
/// for every complete, non-blank line (`line` 1-based) holding `key`, in file order, and stops
/// at the first error `each` returns. Returns the length of the header and the complete lines,
/// bytes: what is left of the file once a last line cut short by a kill is dropped.
///
/// # Errors
/// The first error of `each`.
pub fn read_records<'a, E>(
    bytes: &'a [u8],
    header_len: usize,
    header_sum: &str,
    key: &str,
    mut each: impl FnMut(usize, RecordLine<'a>) -> std::result::Result<(), E>,
) -> std::result::Result<u64, E> {
    let mut complete = header_len as u64;
    let mut lines = bytes[header_len..]
        .split_inclusive(|&b| b == b'\n')
        .enumerate()
        .peekable();
    while let Some((i, line)) = lines.next() {
        if lines.peek().is_none() && !line.ends_with(b"\n") {
            break; // cut short by a kill, possibly inside a multi-byte character
        }
        let number = i + 2;
        let Ok(text) = std::str::from_utf8(line) else {
            each(number, RecordLine::Damaged)?;
            continue;
        };
        complete += line.len() as u64;
        if text.trim().is_empty() {
            continue; // a blank line (an editor's final newline) holds nothing
        }
        let record = match parse_line(text, key) {
            Some((json, sum)) if sum.as_deref() == Some(record_sum(header_sum, json).as_str()) => {
                RecordLine::Verified(json)
            }
            Some((json, _)) => RecordLine::Unverified(json),
            None => RecordLine::Damaged,
        };
        each(number, record)?;
    }
    Ok(complete)
}

/// An open log, appending one flushed, checksummed line per record.
///
/// A line that cannot be written whole (a full disk) is cut back off the file, so the log
/// keeps only complete lines and a later append, or a resume, finds it intact; if even that
/// fails, every later append is refused without writing.
#[derive(Debug)]
pub struct LogWriter {
    path: PathBuf,
    file: File,
    /// The header's checksum, part of every record's.
    header_sum: String,
    /// Length of the file up to the end of its last complete line, bytes.
    complete_bytes: u64,
    /// Set when a failed append could not be cut back off the file.
    damaged: bool,
    /// Tests: the next line is written only up to this many bytes, then fails.
    #[cfg(test)]
    pub(crate) fail_after_bytes: Option<usize>,
}

impl LogWriter {
    /// Starts a new log at `path` (its folder made if missing; refused if a file is there)
    /// with the header `header_json` under `key`.
    ///
    /// # Errors
    /// An existing file at `path`, or an I/O error.
    pub fn create(path: PathBuf, key: &str, header_json: &str) -> Result<Self> {
        if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
            fs::create_dir_all(dir)
                .map_err(FileError::io(format!("creating folder {}", path_text(dir))))?;
        }
        let file = OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&path)
            .map_err(FileError::io(format!("creating {}", path_text(&path))))?;
        let mut log = Self::at(path, file, header_sum(header_json), 0);
        let line = checked_line(key, header_json, &log.header_sum);
        log.write_line(&line)?;
        Ok(log)
    }

    /// Continues the log at `path` whose header has checksum `header_sum` and whose header
    /// and complete lines take `complete_bytes` bytes ([`read_records`]): whatever follows
    /// (a last line cut short by a kill) is cut off the file.
    ///
    /// # Errors
    /// An I/O error.
    pub fn resume(path: &Path, header_sum: String, complete_bytes: u64) -> Result<Self> {
        let file = OpenOptions::new()
            .write(true)
            .open(path)
            .map_err(FileError::io(format!("opening {}", path_text(path))))?;
        file.set_len(complete_bytes)
            .map_err(FileError::io(format!("truncating {}", path_text(path))))?;
        let file = OpenOptions::new()
            .append(true)
            .open(path)
            .map_err(FileError::io(format!("opening {}", path_text(path))))?;
        Ok(Self::at(path.to_owned(), file, header_sum, complete_bytes))
    }

    /// Starts a new log at `path` as [`LogWriter::create`] does, with `header` (`what` names
    /// it in an error: `the journal header`) written as JSON under `key`.
    ///
    /// # Errors
    /// As [`LogWriter::create`], or a header serde_json cannot write.
    pub fn create_with<H: Serialize>(
        path: PathBuf,
        key: &str,
        header: &H,
        what: &'static str,
    ) -> Result<Self> {
        Self::create(path, key, &json_of(header, what)?)
    }

    /// Appends `record` written as JSON under `key` ([`LogWriter::append`]); `what` names it
    /// in an error (`a journal record`).
    ///
    /// # Errors
    /// As [`LogWriter::append`], or a record serde_json cannot write.
    pub fn append_value<T: Serialize>(
        &mut self,
        key: &str,
        record: &T,
        what: &'static str,
    ) -> Result<()> {
        self.append(key, &json_of(record, what)?)
    }

    /// Tests: writes go to `file` from now on (a file opened read-only makes them fail).
    #[cfg(test)]
    pub(crate) fn replace_file(&mut self, file: File) {
        self.file = file;
    }

    fn at(path: PathBuf, file: File, header_sum: String, complete_bytes: u64) -> Self {
        Self {
            path,
            file,
            header_sum,
            complete_bytes,
            damaged: false,
            #[cfg(test)]
            fail_after_bytes: None,
        }
    }

    /// Appends the record `json` under `key` as one line with its checksum ([`record_sum`])
    /// and flushes it to the operating system.
    ///
    /// # Errors
    /// An I/O error, or an earlier line that could not be cut back off the file.
    pub fn append(&mut self, key: &str, json: &str) -> Result<()> {
        let line = checked_line(key, json, &record_sum(&self.header_sum, json));
        self.write_line(&line)
    }

    fn write_line(&mut self, s: &str) -> Result<()> {
        if self.damaged {
            return Err(LogError::Damaged {
                path: path_text(&self.path),
            });
        }
        if let Err(e) = self.write_bytes(s.as_bytes()) {
            // Cut the part of the line that was written back off, so that the log ends with a
            // complete line, and write the next line where it ended.
            let end = self.complete_bytes;
            let cut = self.file.set_len(end);
            if cut
                .and_then(|()| self.file.seek(SeekFrom::Start(end)))
                .is_err()
            {
                self.damaged = true;
            }
            return Err(FileError::io(format!("appending to {}", path_text(&self.path)))(e).into());
        }
        self.complete_bytes += s.len() as u64;
        Ok(())
    }

    fn write_bytes(&mut self, bytes: &[u8]) -> std::io::Result<()> {
        #[cfg(test)]
        if let Some(n) = self.fail_after_bytes.take() {
            self.file.write_all(&bytes[..n.min(bytes.len())])?;
            return Err(std::io::Error::new(
                std::io::ErrorKind::StorageFull,
                "no space left on device (test)",
            ));
        }
        self.file.write_all(bytes).and_then(|()| self.file.flush())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_parses_back_to_its_json_and_sum() {
        let line = checked_line("eval", r#"{"a":[1,2.5]}"#, "00ff");
        assert_eq!(line, "{\"eval\":{\"a\":[1,2.5]},\"sum\":\"00ff\"}\n");
        assert_eq!(
            parse_line(&line, "eval"),
            Some((r#"{"a":[1,2.5]}"#, Some("00ff".to_string())))
        );
        assert_eq!(parse_line(&line, "trial"), None, "another key");
        assert_eq!(
            parse_line(r#"{"eval":1}"#, "eval"),
            Some(("1", None)),
            "no sum"
        );
        for bad in [
            r#"{"eval":1,"sum":2}"#,
            r#"{"eval":1,"sum":"0","x":3}"#,
            r#"{"eval":1,"header":2}"#,
            r#"[1]"#,
            "{\"eval\":1",
        ] {
            assert_eq!(parse_line(bad, "eval"), None, "{bad}");
        }
    }

    #[test]
    fn a_record_on_its_own_verifies_only_for_its_identity() {
        let line = record_line("universe", r#"{"u":3}"#, "abcd");
        assert_eq!(
            verified_record(&line, "universe", "abcd"),
            Some(r#"{"u":3}"#)
        );
        assert_eq!(verified_record(&line, "universe", "abce"), None);
        assert_eq!(verified_record(&line, "design", "abcd"), None);
        let edited = line.replace('3', "4");
        assert_eq!(verified_record(&edited, "universe", "abcd"), None);
        let unsummed = r#"{"universe":{"u":3}}"#;
        assert_eq!(verified_record(unsummed, "universe", "abcd"), None);
    }

    /// A log of a header and three records read back; a cut last line and a blank line hold
    /// nothing, an edited record is unverified, a line of another shape damaged, and a record
    /// verifies only under its own header.
    #[test]
    fn records_are_read_back_verified_and_a_cut_last_line_is_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("sub").join("log.jsonl");
        let mut w = LogWriter::create(path.clone(), "header", r#"{"n":1}"#).unwrap();
        for k in 0..3 {
            w.append("rec", &format!(r#"{{"k":{k}}}"#)).unwrap();
        }
        let mut bytes = fs::read(&path).unwrap();
        let whole = bytes.len() as u64;
        let header_len = bytes.iter().position(|&b| b == b'\n').unwrap() + 1;
        let sum = header_sum(r#"{"n":1}"#);
        bytes.extend_from_slice(b"\n{\"rec\":{\"k\":3},\"su");
        let mut seen = Vec::new();
        let complete = read_records(&bytes, header_len, &sum, "rec", |i, r| {
            seen.push((i, r));
            Ok::<(), ()>(())
        })
        .unwrap();
        assert_eq!(
            complete,
            whole + 1,
            "the blank line counts, the cut one does not"
        );
        assert_eq!(
            seen,
            [
                (2, RecordLine::Verified(r#"{"k":0}"#)),
                (3, RecordLine::Verified(r#"{"k":1}"#)),
                (4, RecordLine::Verified(r#"{"k":2}"#)),
            ]
        );
        let edited = String::from_utf8(bytes)
            .unwrap()
            .replace("\"k\":1", "\"k\":9");
        let other = header_sum(r#"{"n":2}"#);
        let mut kinds = Vec::new();
        read_records(edited.as_bytes(), header_len, &other, "rec", |_, r| {
            kinds.push(matches!(r, RecordLine::Unverified(_)));
            Ok::<(), ()>(())
        })
        .unwrap();
        assert_eq!(kinds, [true; 3], "another header's sum verifies nothing");
        let damaged = format!("{}not json\n", &edited[..header_len]);
        let mut got = Vec::new();
        read_records(damaged.as_bytes(), header_len, &sum, "rec", |i, r| {
            got.push((i, r));
            Ok::<(), ()>(())
        })
        .unwrap();
        assert_eq!(got, [(2, RecordLine::Damaged)]);
    }

    /// Resuming cuts a partial last line off; a failed write is cut back off so the next
    /// append lands after the last complete line; a second log at the same path is refused.
    #[test]
    fn resume_and_a_failed_write_leave_only_complete_lines() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("log.jsonl");
        let mut w = LogWriter::create(path.clone(), "header", "{}").unwrap();
        w.append("rec", "1").unwrap();
        let complete = fs::metadata(&path).unwrap().len();
        fs::OpenOptions::new()
            .append(true)
            .open(&path)
            .unwrap()
            .write_all(b"{\"rec\":2")
            .unwrap();
        drop(w);
        assert!(LogWriter::create(path.clone(), "header", "{}").is_err());
        let mut w = LogWriter::resume(&path, header_sum("{}"), complete).unwrap();
        w.fail_after_bytes = Some(5);
        let err = w.append("rec", "2").unwrap_err();
        let line = rne_core::error_line(&err);
        assert!(line.contains("no space left"), "{line}");
        assert_eq!(fs::metadata(&path).unwrap().len(), complete);
        w.append("rec", "3").unwrap();
        let text = fs::read_to_string(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3, "{text}");
        assert_eq!(
            parse_line(lines[2], "rec"),
            Some(("3", Some(record_sum(&header_sum("{}"), "3"))))
        );
    }
}
