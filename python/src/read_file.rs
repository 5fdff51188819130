//! Reading a scenario file so that Ctrl-C works while the read waits: opening a FIFO for
//! reading waits for a writer, and the kernel restarts that wait after Python's SIGINT
//! handler runs, so the calling thread would never see the signal.

use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, TryRecvError};
use std::time::Duration;

use pyo3::exceptions::PyRuntimeError;
use pyo3::prelude::*;
use usar_sim::scenario as sc;

use crate::detached::POLL;
use crate::errors::value_error;

/// How long, after Ctrl-C, a waiting read of a FIFO is offered a writer to end it.
const UNBLOCK_FOR: Duration = Duration::from_secs(2);

/// [`sc::read_source`] of `path` (the CLI's size bound and checks) on a thread of its own,
/// while the calling thread waits with the GIL released and checks for signals every
/// [`POLL`]. On Ctrl-C it returns `KeyboardInterrupt` at once; a read still waiting for a
/// FIFO's writer is then ended by opening the FIFO for writing and closing it (the reader sees
/// the end of the file), so no thread stays blocked.
///
/// # Errors
/// `ValueError` for a file that cannot be read (the path named), the signal's exception, or
/// `RuntimeError` if the reading thread panicked.
pub fn read_source_interruptibly(py: Python<'_>, path: &Path) -> PyResult<String> {
    let (tx, rx) = mpsc::channel();
    let done = Arc::new(AtomicBool::new(false));
    let (p, finished) = (path.to_path_buf(), done.clone());
    std::thread::spawn(move || {
        let read = sc::read_source(&p);
        finished.store(true, Ordering::SeqCst);
        let _ = tx.send(read);
    });
    loop {
        py.detach(|| std::thread::sleep(POLL));
        match rx.try_recv() {
            Ok(read) => return read.map_err(value_error),
            Err(TryRecvError::Empty) => {}
            Err(TryRecvError::Disconnected) => {
                return Err(PyRuntimeError::new_err(
                    "the thread reading the scenario panicked (a bug: please report it)",
                ));
            }
        }
        if let Err(e) = py.check_signals() {
            unblock_fifo_reader(path.to_path_buf(), done);
            return Err(e);
        }
    }
}

/// Offers the FIFO at `path` a writer (opened without waiting, closed at once) every
/// [`POLL`] until `done` or for [`UNBLOCK_FOR`], on a thread of its own; nothing for a path
/// that is not a FIFO.
fn unblock_fifo_reader(path: PathBuf, done: Arc<AtomicBool>) {
    #[cfg(unix)]
    {
        use std::os::unix::fs::{FileTypeExt, OpenOptionsExt};
        let is_fifo = std::fs::metadata(&path).is_ok_and(|m| m.file_type().is_fifo());
        if !is_fifo {
            return;
        }
        std::thread::spawn(move || {
            let mut waited = Duration::ZERO;
            while !done.load(Ordering::SeqCst) && waited < UNBLOCK_FOR {
                // Fails (ENXIO) until the reader waits in open(); then its open returns.
                let _ = std::fs::OpenOptions::new()
                    .write(true)
                    .custom_flags(libc::O_NONBLOCK)
                    .open(&path);
                std::thread::sleep(POLL);
                waited += POLL;
            }
        });
    }
    #[cfg(not(unix))]
    drop((path, done));
}
