//! The trace of a calibration: `trace.jsonl` in its output folder, one JSON object per line,
//! checksummed as the sweep journal's lines are, by the same plumbing
//! ([`usar_sweep::checked_log`]: [`header_sum`], [`record_sum`](usar_sweep::checked_log::record_sum)).
//!
//! The first line is the [`TraceHeader`] (what identifies the calibration: scenario hash,
//! targets, free fields and ranges, methods, trials, seed, duration, digits, build), every
//! later line one [`Evaluation`], appended and flushed as it ends:
//!
//! ```text
//! {"header":{"format":1,...},"sum":"<16 hex digits>"}
//! {"eval":{"index":0,"values":[0.0055,14],...},"sum":"<16 hex digits>"}
//! ```
//!
//! Running the same calibration again reads the trace and replays the (deterministic)
//! search with the recorded evaluations as a cache keyed by the exact free values, so only
//! new points run. A last line cut short by a kill is dropped; a record that does not verify
//! is left out (its point runs again); a header that does not verify, or a damaged line
//! before the last, is refused.

use std::fs;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};
use serde_json::Value;
use usar_sim::scenario::path_text;

use super::evaluate::Evaluation;
use super::free::FreeField;
use super::trace_error::TraceError;
use usar_report::targets::file::Target;
use usar_sweep::atomic::FileError;
use usar_sweep::checked_log::{LogWriter, RecordLine, header_sum, parse_line, read_records};

/// File name of the trace in the output folder.
pub const TRACE_FILE: &str = usar_sweep::data::owner::evidence::TRACE;

/// Format of the trace's lines; bumped when they change shape.
pub const TRACE_FORMAT: u32 = 1;

/// What identifies a calibration: a trace is continued only by a calibration with an equal
/// header.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TraceHeader {
    /// [`TRACE_FORMAT`].
    pub format: u32,
    /// Version of the `experiments` crate.
    pub version: String,
    /// The build of `usar` ([`usar_report::report::software_build`]): another may simulate
    /// differently.
    pub build: String,
    /// The base scenario's name.
    pub scenario: String,
    /// [`usar_sweep::fingerprint::scenario_hash`] of the validated base scenario.
    pub scenario_hash: String,
    /// The targets, in order.
    pub targets: Vec<Target>,
    /// The free fields and their ranges, in order.
    pub free: Vec<FreeField>,
    /// The methods, canonical names, in order.
    pub methods: Vec<String>,
    /// Trials per method and evaluation.
    pub trials: u32,
    /// Base seed.
    pub base_seed: u64,
    /// Trial length, seconds; `None`: each point's `mission.duration_s`.
    pub duration_s: Option<f64>,
    /// Significant digits of the free values.
    pub digits: u32,
    /// The search and its constants (`super::optimizer`).
    pub search: String,
}

/// Human-readable list of the fields where two headers differ: `trace has trials 2 vs 3,
/// digits 4 vs 5`.
pub fn header_diff(old: &TraceHeader, new: &TraceHeader) -> String {
    let list = |xs: Vec<String>| format!("[{}]", xs.join(", "));
    let targets = |h: &TraceHeader| {
        list(
            h.targets
                .iter()
                .map(|t| {
                    let reported = if t.report_only { " (reported)" } else { "" };
                    format!("{}: {} {}{reported}", t.name, t.statistic, t.describe())
                })
                .collect(),
        )
    };
    let free = |h: &TraceHeader| list(h.free.iter().map(|f| f.to_string()).collect());
    let build = |h: &TraceHeader| {
        if h.build.is_empty() {
            "unrecorded".to_owned()
        } else {
            h.build.clone()
        }
    };
    let duration = |h: &TraceHeader| {
        h.duration_s
            .map_or("(scenario's)".into(), |x| x.to_string())
    };
    let fields: [(&str, String, String); 13] = [
        ("format", old.format.to_string(), new.format.to_string()),
        ("version", old.version.clone(), new.version.clone()),
        ("build", build(old), build(new)),
        ("scenario", old.scenario.clone(), new.scenario.clone()),
        (
            "scenario hash",
            old.scenario_hash.clone(),
            new.scenario_hash.clone(),
        ),
        ("targets", targets(old), targets(new)),
        ("free fields", free(old), free(new)),
        (
            "methods",
            list(old.methods.clone()),
            list(new.methods.clone()),
        ),
        ("trials", old.trials.to_string(), new.trials.to_string()),
        ("seed", old.base_seed.to_string(), new.base_seed.to_string()),
        ("duration", duration(old), duration(new)),
        ("digits", old.digits.to_string(), new.digits.to_string()),
        ("search", old.search.clone(), new.search.clone()),
    ];
    let mut d: Vec<String> = fields
        .iter()
        .filter(|(_, a, b)| a != b)
        .map(|(name, a, b)| match *name {
            "build" => format!("build {a} vs {b} (another build of usar may simulate differently)"),
            _ => format!("{name} {a} vs {b}"),
        })
        .collect();
    if d.is_empty() {
        d = json_diff(old, new);
    }
    format!("trace has {}", d.join(", "))
}

/// The fields where two headers differ, compared as JSON (what the trace holds): the
/// fallback of [`header_diff`] for a difference its texts do not show.
fn json_diff(old: &TraceHeader, new: &TraceHeader) -> Vec<String> {
    let (Ok(Value::Object(a)), Ok(Value::Object(b))) =
        (serde_json::to_value(old), serde_json::to_value(new))
    else {
        return vec!["another header".into()];
    };
    let shown = |v: Option<&Value>| {
        let text = v.map_or_else(|| "nothing".to_owned(), Value::to_string);
        usar_sweep::vary::brief(&text)
    };
    let mut keys: Vec<&String> = a.keys().chain(b.keys()).collect();
    keys.sort();
    keys.dedup();
    let d: Vec<String> = keys
        .into_iter()
        .filter(|k| a.get(*k) != b.get(*k))
        .map(|k| format!("{k} {} vs {}", shown(a.get(k)), shown(b.get(k))))
        .collect();
    if d.is_empty() {
        vec!["the same fields in another form".into()]
    } else {
        d
    }
}

/// A trace read from a file.
#[derive(Debug, Clone, PartialEq)]
pub struct TraceContents {
    /// Its header.
    pub header: TraceHeader,
    /// Its complete evaluations that verify, in file order.
    pub evaluations: Vec<Evaluation>,
    /// Line numbers (1-based) of complete evaluation lines that do not verify.
    pub rejected: Vec<usize>,
    /// Bytes of the header and complete lines (what is left once a cut last line is dropped).
    pub complete_bytes: u64,
    header_sum: String,
}

/// What the functions of this module return.
type Result<T> = std::result::Result<T, TraceError>;

/// Reads and verifies the trace at `path`.
///
/// # Errors
/// An unreadable file, a missing header, a header that does not verify or is of another
/// format, or a damaged line other than the last; each names `--overwrite`.
pub fn read_trace(path: &Path) -> Result<TraceContents> {
    let bytes =
        fs::read(path).map_err(FileError::io(format!("cannot read {}", path_text(path))))?;
    let damaged = |line: usize| TraceError::DamagedLine {
        path: path_text(path),
        line,
    };
    let Some(first) = bytes
        .split_inclusive(|&b| b == b'\n')
        .next()
        .filter(|l| l.ends_with(b"\n"))
    else {
        return Err(TraceError::NoHeader {
            path: path_text(path),
        });
    };
    let not_header = || TraceError::NotAHeader {
        path: path_text(path),
    };
    let text = std::str::from_utf8(first).map_err(|_| not_header())?;
    let (raw, sum) = parse_line(text, "header").ok_or_else(not_header)?;
    let hsum = header_sum(raw);
    if sum.as_deref() != Some(hsum.as_str()) {
        return Err(TraceError::HeaderUnverified {
            path: path_text(path),
        });
    }
    let format = serde_json::from_str::<serde_json::Value>(raw)
        .ok()
        .and_then(|v| v.get("format")?.as_u64());
    if format != Some(u64::from(TRACE_FORMAT)) {
        return Err(TraceError::Format {
            path: path_text(path),
            found: format.map_or("unknown".into(), |f| f.to_string()),
            expected: TRACE_FORMAT,
        });
    }
    let header: TraceHeader = serde_json::from_str(raw).map_err(|_| not_header())?;
    let (mut evaluations, mut rejected) = (Vec::new(), Vec::new());
    let complete_bytes = read_records(&bytes, first.len(), &hsum, "eval", |line, r| {
        let not_a_line = || damaged(line);
        match r {
            RecordLine::Verified(json) => {
                evaluations.push(serde_json::from_str(json).map_err(|_| not_a_line())?);
            }
            RecordLine::Unverified(json) => {
                serde_json::from_str::<Evaluation>(json).map_err(|_| not_a_line())?;
                rejected.push(line);
            }
            RecordLine::Damaged => return Err(not_a_line()),
        }
        Ok(())
    })?;
    Ok(TraceContents {
        header,
        evaluations,
        rejected,
        complete_bytes,
        header_sum: hsum,
    })
}

/// An open trace, appending one flushed line per evaluation ([`LogWriter`]: a line that
/// cannot be written whole is cut back off the file).
#[derive(Debug)]
pub struct Trace {
    log: LogWriter,
}

impl Trace {
    /// The trace's path in `dir`.
    pub fn path_in(dir: &Path) -> PathBuf {
        dir.join(TRACE_FILE)
    }

    /// Starts a new trace in `dir` with `header` (refused if one is there).
    ///
    /// # Errors
    /// An existing trace, or an I/O error.
    pub fn create(dir: &Path, header: &TraceHeader) -> Result<Self> {
        let log = LogWriter::create_with(Self::path_in(dir), "header", header, "the trace header")?;
        Ok(Self { log })
    }

    /// Continues the trace `contents` was read from, at `path`: a last line cut short is cut
    /// off the file.
    ///
    /// # Errors
    /// An I/O error.
    pub fn resume(path: &Path, contents: &TraceContents) -> Result<Self> {
        let log = LogWriter::resume(path, contents.header_sum.clone(), contents.complete_bytes)?;
        Ok(Self { log })
    }

    /// Appends `e` as one checksummed line and flushes it.
    ///
    /// # Errors
    /// An I/O error.
    pub fn append(&mut self, e: &Evaluation) -> Result<()> {
        Ok(self.log.append_value("eval", e, "an evaluation")?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use usar_report::targets::band::Band;
    use usar_report::targets::metric_ref::MetricRef;
    use usar_report::targets::statistic::Statistic;

    pub(crate) fn header() -> TraceHeader {
        TraceHeader {
            format: TRACE_FORMAT,
            version: "0.1.0".into(),
            build: "abc".into(),
            scenario: "paper".into(),
            scenario_hash: "0123456789abcdef".into(),
            targets: vec![Target {
                name: "rounds".into(),
                statistic: Statistic::Mean(MetricRef("rounds".into())),
                value: 6.2,
                band: Band::PlusMinus(0.6),
                report_only: false,
            }],
            free: vec![FreeField::parse("mission.pickup_s=0.5..2").unwrap()],
            methods: vec!["RNE".into()],
            trials: 2,
            base_seed: 2021,
            duration_s: Some(20.0),
            digits: 4,
            search: "test".into(),
        }
    }

    fn eval(index: usize, x: f64) -> Evaluation {
        Evaluation {
            index,
            values: vec![x],
            statistics: vec![if index == 1 { f64::NAN } else { 6.0 }],
            loss: if index == 1 { f64::INFINITY } else { 0.0 },
            message: (index == 1).then(|| "failed".to_string()),
            trials_ok: 2,
            wall_s: 0.5,
            unseen_loss: if index == 2 { 1.5 } else { f64::NAN },
        }
    }

    fn same(a: &Evaluation, b: &Evaluation) -> bool {
        serde_json::to_string(a).unwrap() == serde_json::to_string(b).unwrap()
    }

    #[test]
    fn evaluations_come_back_and_a_cut_last_line_is_dropped() {
        let dir = tempfile::tempdir().unwrap();
        let mut t = Trace::create(dir.path(), &header()).unwrap();
        for i in 0..3 {
            t.append(&eval(i, 1.0 + i as f64)).unwrap();
        }
        drop(t);
        let path = Trace::path_in(dir.path());
        let whole = fs::read(&path).unwrap();
        let mut cut = whole.clone();
        cut.extend_from_slice(b"{\"eval\":{\"index\":3,\"val");
        fs::write(&path, &cut).unwrap();
        let c = read_trace(&path).unwrap();
        assert_eq!(c.header, header());
        assert_eq!(c.evaluations.len(), 3);
        assert!(same(&c.evaluations[1], &eval(1, 2.0)));
        assert_eq!(c.complete_bytes, whole.len() as u64);
        let mut t = Trace::resume(&path, &c).unwrap();
        assert_eq!(fs::read(&path).unwrap(), whole);
        t.append(&eval(3, 4.0)).unwrap();
        drop(t);
        assert_eq!(read_trace(&path).unwrap().evaluations.len(), 4);
    }

    #[test]
    fn edits_are_caught_by_the_sums() {
        let dir = tempfile::tempdir().unwrap();
        let mut t = Trace::create(dir.path(), &header()).unwrap();
        t.append(&eval(0, 1.0)).unwrap();
        t.append(&eval(2, 3.0)).unwrap();
        drop(t);
        let path = Trace::path_in(dir.path());
        let text = fs::read_to_string(&path).unwrap();
        // An edited loss: that evaluation is left out, the others stay.
        fs::write(&path, text.replacen("\"loss\":0.0", "\"loss\":0.5", 1)).unwrap();
        let c = read_trace(&path).unwrap();
        assert_eq!(c.rejected, vec![2]);
        assert_eq!(c.evaluations.len(), 1);
        // An edited header: refused.
        fs::write(&path, text.replace("\"trials\":2", "\"trials\":3")).unwrap();
        let e = format!("{:#}", read_trace(&path).unwrap_err());
        assert!(
            e.contains("trace.jsonl:1: the header does not verify (edited?)"),
            "{e}"
        );
        assert!(e.contains("--overwrite"), "{e}");
        // A damaged line in the middle: refused by line number.
        let mut lines: Vec<&str> = text.lines().collect();
        lines[1] = "garbage";
        fs::write(&path, lines.join("\n") + "\n").unwrap();
        let e = format!("{:#}", read_trace(&path).unwrap_err());
        assert!(e.contains("trace.jsonl:2: not a valid trace line"), "{e}");
    }

    #[test]
    fn headers_differ_in_words() {
        let mut other = header();
        other.trials = 3;
        other.free = vec![FreeField::parse("mission.pickup_s=0.5..3").unwrap()];
        assert_eq!(
            header_diff(&header(), &other),
            "trace has free fields [mission.pickup_s=0.5..2] vs [mission.pickup_s=0.5..3], \
             trials 2 vs 3"
        );
        // A target only reported in one of them: once "trace has " and nothing more.
        let mut reported = header();
        reported.targets[0].report_only = true;
        let d = header_diff(&header(), &reported);
        assert!(
            d.starts_with("trace has targets [") && d.contains(" (reported)]"),
            "{d}"
        );
        // What the texts do not show is named from the JSON.
        let d = json_diff(&header(), &reported);
        assert!(d.len() == 1 && d[0].starts_with("targets [{"), "{d:?}");
    }
}
