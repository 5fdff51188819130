//! The date written into outputs: `SOURCE_DATE_EPOCH` when set (reproducible builds), else the
//! system clock's.

use std::time::{Duration, SystemTime};

use crate::error::{ReportError, Result};

/// The date of the outputs: `SOURCE_DATE_EPOCH` (seconds since 1970, the reproducible-builds
/// convention) when set, else `None` (the system clock).
pub fn source_date() -> Result<Option<String>> {
    let Ok(text) = std::env::var("SOURCE_DATE_EPOCH") else {
        return Ok(None);
    };
    let secs: u64 = text
        .trim()
        .parse()
        .map_err(|source| ReportError::SourceDateEpoch {
            text: text.clone(),
            source,
        })?;
    let at = SystemTime::UNIX_EPOCH + Duration::from_secs(secs);
    Ok(Some(humantime::format_rfc3339_seconds(at).to_string()))
}
