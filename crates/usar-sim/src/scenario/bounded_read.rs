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
    /// The path (after symbolic links) is a folder, FIFO, socket or device: refused before it
    /// is opened, since opening a FIFO without a writer, or reading a terminal, waits for ever.
    #[error("not a regular file (a folder, FIFO or device)")]
    NotAFile,
    /// The file is longer than the limit (it was read only up to one byte past it).
    #[error("longer than the limit of {max_bytes} bytes")]
    TooLong {
        /// The limit, bytes.
        max_bytes: u64,
    },
}

/// The bytes of the regular file at `path`, at most `max_bytes` of them: a file that grows
/// without end is refused once it passes the limit, never read into memory, and anything but
/// a regular file (a FIFO without a writer, `/dev/zero`, a folder) is refused before it is
/// opened, never waited on.
///
/// # Errors
/// [`BoundedReadError::Io`] when the file cannot be found, opened or read,
/// [`BoundedReadError::NotAFile`] when `path` is not a regular file (after symbolic links),
/// [`BoundedReadError::TooLong`] when it holds more than `max_bytes` bytes.
pub fn read_bounded(path: &Path, max_bytes: u64) -> Result<Vec<u8>, BoundedReadError> {
    if !std::fs::metadata(path)?.is_file() {
        return Err(BoundedReadError::NotAFile);
    }
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

    /// Regression (issue 70): a FIFO without a writer was opened, which waited for ever. The
    /// read runs in a thread, so that a regression fails here instead of hanging the tests.
    #[cfg(unix)]
    #[test]
    fn a_fifo_a_device_and_a_folder_are_refused_without_waiting() {
        let dir = tempfile::tempdir().unwrap();
        let fifo = dir.path().join("f.ron");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        assert!(made.is_ok_and(|s| s.success()), "mkfifo");
        for path in [fifo, "/dev/zero".into(), dir.path().to_path_buf()] {
            let (send, got) = std::sync::mpsc::channel();
            let p = path.clone();
            std::thread::spawn(move || send.send(read_bounded(&p, 1 << 16).map(|_| ())));
            let e = got
                .recv_timeout(std::time::Duration::from_secs(10))
                .unwrap_or_else(|_| panic!("{}: still waiting after 10 s", path.display()))
                .unwrap_err();
            assert!(matches!(e, BoundedReadError::NotAFile), "{e}");
            assert_eq!(
                e.to_string(),
                "not a regular file (a folder, FIFO or device)"
            );
        }
    }
}
