//! Reading a small RON file of the studies (targets, axes, claims): bounded in size, UTF-8,
//! parsed with its source map, every error one line placed at its file, line, column and
//! field ([`Located`], which each file's own error type is made from).

use std::io::Read;
use std::path::Path;
use std::sync::Arc;

use serde::de::DeserializeOwned;
use usar_sim::scenario::{SourceLocation, path_text};

use usar_sim::scenario::SourceMap;

/// A positioned error before it becomes a file type's own error (`TargetsError`, `AxesError`,
/// `ClaimsError`, which have these three fields).
#[derive(Debug)]
pub struct Located {
    /// The file (as given) and, when known, the line and column.
    pub location: SourceLocation,
    /// The field the error is about, when known.
    pub field: Option<String>,
    /// What is wrong.
    pub message: String,
}

/// The text of the file at `path` (and its name as errors give it), at most `max_bytes`
/// long. `kind` names the file for messages with its article: `a targets file`.
///
/// # Errors
/// The file cannot be read, is longer than `max_bytes` or is not UTF-8.
pub fn read_text(path: &Path, max_bytes: u64, kind: &str) -> Result<(String, String), Located> {
    let origin = path_text(path);
    let fail = |message: String| Located {
        location: SourceLocation {
            origin: origin.clone(),
            line_col: None,
        },
        field: None,
        message,
    };
    let bare = kind.split_once(' ').map_or(kind, |(_, k)| k);
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(max_bytes + 1).read_to_end(&mut bytes))
        .map_err(|e| fail(format!("cannot read {bare}: {e}")))?;
    if bytes.len() as u64 > max_bytes {
        return Err(fail(format!(
            "longer than the limit of {max_bytes} bytes for {kind}"
        )));
    }
    let text = String::from_utf8(bytes)
        .map_err(|_| fail(format!("not UTF-8 text; {kind} is RON text")))?;
    Ok((text, origin))
}

/// `src` (a leading byte-order mark skipped) parsed as a `T`, with its source map; a RON
/// error is placed at ron's line and column and at the field found there.
///
/// # Errors
/// RON syntax or shape (an unknown field or variant, a missing field).
pub fn parse<T: DeserializeOwned>(src: &str, origin: &str) -> Result<(T, Arc<SourceMap>), Located> {
    let src = src.strip_prefix('\u{feff}').unwrap_or(src);
    let map = Arc::new(SourceMap::build(src));
    let value = ron::Options::default().from_str(src).map_err(|e| {
        let offset = map.offset_of(e.span.start.line, e.span.start.col);
        Located {
            location: SourceLocation {
                origin: origin.to_owned(),
                line_col: Some((e.span.start.line, e.span.start.col)),
            },
            field: map.path_at(offset).map(str::to_owned),
            message: e.code.to_string(),
        }
    })?;
    Ok((value, map))
}
