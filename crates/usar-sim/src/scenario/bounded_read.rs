//! Reading a whole input file with a size limit, the one reader of every RON input (scenario
//! files here, and the targets, claims and axes files of `usar_report::targets::ron_file`).

use std::io::Read;
use std::path::Path;

/// Why a file was not read by [`read_bounded`].
#[derive(Debug, thiserror::Error)]
pub enum BoundedReadError {
    /// The file could not be opened or read.
    #[error(transparent)]
    Io(#[from] std::io::Error),
    /// The file is longer than the limit (it was read only up to one byte past it).
    #[error("longer than the limit of {max_bytes} bytes")]
    TooLong {
        /// The limit, bytes.
        max_bytes: u64,
    },
}

/// The bytes of the file at `path`, at most `max_bytes` of them: an endless input such as
/// `/dev/zero` is refused once it passes the limit, never read into memory.
///
/// # Errors
/// [`BoundedReadError::Io`] when the file cannot be opened or read,
/// [`BoundedReadError::TooLong`] when it holds more than `max_bytes` bytes.
pub fn read_bounded(path: &Path, max_bytes: u64) -> Result<Vec<u8>, BoundedReadError> {
    let mut bytes = Vec::new();
    std::fs::File::open(path)?
        .take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max_bytes {
        return Err(BoundedReadError::TooLong { max_bytes });
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_is_read_up_to_its_limit_and_refused_past_it() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("f.ron");
        std::fs::write(&path, b"12345").unwrap();
        assert_eq!(read_bounded(&path, 5).unwrap(), b"12345");
        assert!(matches!(
            read_bounded(&path, 4),
            Err(BoundedReadError::TooLong { max_bytes: 4 })
        ));
        let missing = read_bounded(&dir.path().join("none"), 5).unwrap_err();
        assert!(
            matches!(missing, BoundedReadError::Io(ref e) if e.kind() == std::io::ErrorKind::NotFound)
        );
    }

    #[cfg(unix)]
    #[test]
    fn an_endless_input_is_refused_at_the_limit() {
        let e = read_bounded(Path::new("/dev/zero"), 1 << 16).unwrap_err();
        assert_eq!(e.to_string(), "longer than the limit of 65536 bytes");
    }
}
